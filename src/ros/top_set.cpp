#include "top_set.hpp"

#include <algorithm>
#include <chrono>

namespace top_sim_ros {

namespace {

constexpr std::size_t kMaxNameLength = 100;

bool is_base_name(const std::string& name) {
  auto letter = [](char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); };
  auto digit = [](char c) { return c >= '0' && c <= '9'; };
  if (name.empty() || !letter(name[0])) return false;
  return std::all_of(name.begin(), name.end(), [&](char c) { return letter(c) || digit(c) || c == '_'; });
}

}  // namespace

std::string TopSet::check_new_name(const std::string& name) const {
  if (name.empty()) return "name is empty: give a base ROS name (a letter, then letters, digits or '_')";
  if (name.size() > kMaxNameLength)
    return "name '" + name.substr(0, 20) + "...' is " + std::to_string(name.size()) + " characters long: at most " +
           std::to_string(kMaxNameLength);
  if (!is_base_name(name))
    return "name '" + name + "' is not a base ROS name: a letter, then letters, digits or '_' (no '/', no spaces)";
  if (by_name_.count(name)) return "name '" + name + "' is taken: a top of that name exists (~list)";
  return "";
}

NodeTop& TopSet::add(std::unique_ptr<NodeTop> top) {
  by_name_[top->name()] = top.get();
  tops_.push_back(std::move(top));
  return *tops_.back();
}

std::unique_ptr<NodeTop> TopSet::remove(const std::string& name) {
  for (auto it = tops_.begin(); it != tops_.end(); ++it) {
    if ((*it)->name() != name) continue;
    std::unique_ptr<NodeTop> top = std::move(*it);
    tops_.erase(it);
    by_name_.erase(name);
    return top;
  }
  return nullptr;
}

NodeTop* TopSet::find(const std::string& name) {
  const auto it = by_name_.find(name);
  return it == by_name_.end() ? nullptr : it->second;
}

std::vector<std::string> TopSet::names() const {
  std::vector<std::string> n;
  n.reserve(tops_.size());
  for (const auto& t : tops_) n.push_back(t->name());
  return n;
}

void TopSet::advance(double wall, double budget, bool paused, const std::function<void(NodeTop&)>& after) {
  const std::size_t n = tops_.size();
  if (n == 0) return;
  first_ %= n;
  using Clock = std::chrono::steady_clock;
  const Clock::time_point start = Clock::now();
  for (std::size_t k = 0; k < n; ++k) {
    const Clock::time_point now = Clock::now();  // the one clock read for this top's share and its physics
    const double left = std::max(0.0, budget - std::chrono::duration<double>(now - start).count());
    NodeTop& top = *tops_[(first_ + k) % n];
    top.advance(wall, left / static_cast<double>(n - k), paused, now);
    if (after) after(top);
  }
  first_ = (first_ + 1) % n;
}

}  // namespace top_sim_ros
