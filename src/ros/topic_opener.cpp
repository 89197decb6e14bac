#include "topic_opener.hpp"

#include <algorithm>
#include <exception>
#include <utility>

namespace top_sim_ros {

TopicOpener::TopicOpener(Build build) : build_(std::move(build)), worker_([this] { work(); }) {}

TopicOpener::~TopicOpener() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
    queue_.clear();
  }
  wake_.notify_all();
  worker_.join();
}

void TopicOpener::add(NodeTop& top) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    queue_.push_back(&top);
  }
  wake_.notify_one();
}

void TopicOpener::forget(NodeTop& top) {
  std::vector<std::pair<NodeTop*, TopTopics>> dropped;  // destroyed after the lock is released
  std::unique_lock<std::mutex> lock(mutex_);
  queue_.erase(std::remove(queue_.begin(), queue_.end(), &top), queue_.end());
  done_with_.wait(lock, [&] { return in_hand_ != &top; });  // its callbacks hold references to the top
  for (auto it = done_.begin(); it != done_.end();) {
    if (it->first == &top) {
      dropped.push_back(std::move(*it));
      it = done_.erase(it);
    } else {
      ++it;
    }
  }
}

std::size_t TopicOpener::install() {
  std::vector<std::pair<NodeTop*, TopTopics>> ready;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (done_.empty()) return 0;
    ready.swap(done_);
  }
  for (auto& [top, topics] : ready) {
    top->install(std::move(topics));
  }
  return ready.size();
}

std::size_t TopicOpener::pending() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return queue_.size() + (in_hand_ ? 1 : 0) + done_.size();
}

void TopicOpener::work() {
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    wake_.wait(lock, [this] { return stop_ || !queue_.empty(); });
    if (stop_) return;
    NodeTop* top = in_hand_ = queue_.front();
    queue_.pop_front();
    lock.unlock();
    TopTopics topics;
    try {
      topics = build_(*top);  // the roscpp calls, without the lock: forget() and install() go on
    } catch (const std::exception& e) {  // e.g. roscpp shutting down: the top keeps running without its topics
      ROS_ERROR("top_sim_node: top %s: its topics could not be opened: %s", top->name().c_str(), e.what());
    }
    lock.lock();
    done_.emplace_back(top, std::move(topics));
    in_hand_ = nullptr;
    done_with_.notify_all();
  }
}

}  // namespace top_sim_ros
