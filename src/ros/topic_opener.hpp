// A top's own topics (NAME/top_state, NAME/path, NAME/inclination, NAME/spin, NAME/command) advertised and
// subscribed on a background thread (docs/ros.md, "Many tops: start-up"). roscpp looks every new topic up among all
// of the node's topics and registers it with the master one call at a time, so the five topics of each of 10,000
// tops take minutes; the loop publishes `top_states` and answers services meanwhile.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>
#include <utility>
#include <vector>

#include <ros/ros.h>

#include "node_top.hpp"
#include "top_input.hpp"

namespace top_sim_ros {

class TopicOpener {
 public:
  using Build = std::function<TopTopics(NodeTop&)>;  // thread-safe: only reads the top's constant parts

  explicit TopicOpener(Build build);
  ~TopicOpener();  // finishes the top in hand, drops the others

  void add(NodeTop& top);       // queued, opened in the order added
  void forget(NodeTop& top);    // before the top is destroyed: dropped, or waited for while the worker holds it
  std::size_t install();        // on the loop's thread: hands finished tops their topics; returns how many
  std::size_t pending() const;  // tops still without their topics (queued, in hand or not yet installed)

 private:
  void work();

  Build build_;
  mutable std::mutex mutex_;
  std::condition_variable wake_, done_with_;
  std::deque<NodeTop*> queue_;
  NodeTop* in_hand_ = nullptr;
  std::vector<std::pair<NodeTop*, TopTopics>> done_;
  bool stop_ = false;
  std::thread worker_;  // last: started once everything above exists
};

}  // namespace top_sim_ros
