// The node's tops and the sharing of one tick's physics budget among them (docs/ros.md, "Many tops").
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include "node_top.hpp"

namespace top_sim_ros {

class TopSet {
 public:
  using Tops = std::vector<std::unique_ptr<NodeTop>>;

  // "" or why `name` cannot name a new top: a base ROS name (a letter, then letters, digits or '_'), unused.
  std::string check_new_name(const std::string& name) const;
  NodeTop& add(std::unique_ptr<NodeTop> top);
  std::unique_ptr<NodeTop> remove(const std::string& name);  // nullptr when there is no such top
  NodeTop* find(const std::string& name);  // by an index: ~tops/command looks a top up among thousands
  NodeTop& launch_top() { return *tops_.front(); }  // added first, never removed
  std::vector<std::string> names() const;
  std::size_t size() const { return tops_.size(); }
  Tops::iterator begin() { return tops_.begin(); }
  Tops::iterator end() { return tops_.end(); }

  // One tick of physics for every top, within `budget` wall seconds in all: each top in turn may spend what is
  // left over the number of tops still to go, so time a cheap top leaves unused goes to the ones after it. The
  // first top of the round rotates each tick, so no top is always last when a costly one eats the budget. A top
  // that gets too little falls behind on its own (its own Pacer drops its debt); the others keep real time.
  // `after` sees each top right after its physics, while its data is still in cache.
  void advance(double wall, double budget, bool paused, const std::function<void(NodeTop&)>& after = {});

 private:
  Tops tops_;
  std::unordered_map<std::string, NodeTop*> by_name_;
  std::size_t first_ = 0;
};

}  // namespace top_sim_ros
