// Unit tests of the node's parts that need no master: the parameter reader (scene sources, strict types, unknown
// keys), the top set (names, the sharing of a tick's budget), the contact-point trail, ~cpu_affinity and the
// background opener of the tops' topics (without roscpp: its build step is the test's).
#include <gtest/gtest.h>

#include <sched.h>
#include <sys/mman.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <atomic>
#include <condition_variable>
#include <mutex>
#include <chrono>
#include <cstdint>
#include <fstream>
#include <limits>
#include <map>
#include <string>
#include <thread>
#include <vector>

#include "cpu_affinity.hpp"
#include "node_parameters.hpp"
#include "param_yaml.hpp"
#include "top_set.hpp"
#include "topic_opener.hpp"
#include "marker_stream.hpp"
#include "markers.hpp"
#include "trail.hpp"
#include "top_sim/scene.hpp"
#include "top_sim/simulator.hpp"
#include "top_sim/state.hpp"

namespace {

using top_sim_ros::ParamReader;
using top_sim_ros::ParameterError;

std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

TEST(NodeParameters, SceneMapBecomesSceneTheCoreAccepts) {
  XmlRpc::XmlRpcValue tree;
  tree["scene"]["top"] = std::string("aluminium");
  tree["scene"]["friction"] = std::string("pmma");
  tree["scene"]["plane"]["inclination"] = 0.17;
  tree["scene"]["initial"]["spin"] = 150;  // an int on the server must still read as a double
  tree["scene"]["initial"]["position"][0] = 0.5;
  tree["scene"]["initial"]["position"][1] = -0.25;
  tree["publish_rate"] = 1000;
  ParamReader p(tree, "/top_sim");
  const top_sim_ros::NodeParameters n = top_sim_ros::read_node_parameters(p);
  EXPECT_EQ(n.publish_rate, 1000.0);
  const top_sim::Scene s = top_sim_ros::read_node_scene(p, TOP_SIM_TEST_CONFIG_DIR);
  EXPECT_EQ(s.model.plane.inclination, 0.17);
  EXPECT_EQ(s.initial.spin, 150.0);
  EXPECT_EQ(s.initial.position.x(), 0.5);
  EXPECT_EQ(s.initial.position.y(), -0.25);
  EXPECT_NO_THROW(p.check_unknown());
}

TEST(NodeParameters, SceneTextGetsTheFileChecks) {
  XmlRpc::XmlRpcValue tree;
  tree["scene"] = std::string("top: aluminium\ntop: steel\nfriction: pmma\n");
  ParamReader p(tree, "/top_sim");
  const std::string m = message_of([&] { top_sim_ros::read_node_scene(p, TOP_SIM_TEST_CONFIG_DIR); });
  EXPECT_NE(m.find("/top_sim/scene"), std::string::npos) << m;
  EXPECT_NE(m.find("top: given twice"), std::string::npos) << m;
}

TEST(NodeParameters, UnknownKeysTyposAndWrongTypesAreErrors) {
  XmlRpc::XmlRpcValue tree;
  tree["scene_file"] = std::string("x.yaml");
  tree["publish_rte"] = 100.0;  // typo
  ParamReader p(tree, "/top_sim");
  top_sim_ros::read_node_parameters(p);
  p.text("scene_file", "");
  const std::string unknown = message_of([&] { p.check_unknown(); });
  EXPECT_NE(unknown.find("/top_sim/publish_rte: unknown parameter"), std::string::npos) << unknown;

  XmlRpc::XmlRpcValue spin;  // a scene key outside ~scene is named as unknown, with where it belongs
  spin["top"] = std::string("aluminium");
  ParamReader q(spin, "/n");
  EXPECT_NE(message_of([&] { q.check_unknown(); }).find("go under /n/scene"), std::string::npos);

  XmlRpc::XmlRpcValue typed;
  typed["publish_rate"] = std::string("fast");
  ParamReader r(typed, "/n");
  const std::string wrong = message_of([&] { top_sim_ros::read_node_parameters(r); });
  EXPECT_NE(wrong.find("/n/publish_rate"), std::string::npos) << wrong;
  EXPECT_NE(wrong.find("must be a number"), std::string::npos) << wrong;
  EXPECT_NE(wrong.find("/n/publish_rate = 'fast': must be"), std::string::npos) << "as typed, not XML-RPC: " << wrong;
  EXPECT_EQ(wrong.find("<value>"), std::string::npos) << wrong;

  XmlRpc::XmlRpcValue range;
  range["publish_rate"] = 0.0;
  ParamReader s(range, "/n");
  EXPECT_NE(message_of([&] { top_sim_ros::read_node_parameters(s); }).find("in (0, 10000] Hz"), std::string::npos);
}

TEST(NodeParameters, SceneFromOnePlaceOnly) {
  XmlRpc::XmlRpcValue both;
  both["scene_file"] = std::string("a.yaml");
  both["scene"]["top"] = std::string("aluminium");
  ParamReader p(both, "/n");
  EXPECT_NE(message_of([&] { top_sim_ros::read_node_scene(p, ""); }).find("one place"), std::string::npos);
  XmlRpc::XmlRpcValue none;
  ParamReader q(none, "/n");
  EXPECT_NE(message_of([&] { top_sim_ros::read_node_scene(q, ""); }).find("no scene"), std::string::npos);
  // Neither, with a config directory (rosrun top_sim top_sim_node): its default scene, as turtlesim's one turtle.
  const top_sim::Scene fallback = top_sim_ros::read_node_scene(q, TOP_SIM_TEST_CONFIG_DIR);
  const top_sim::Scene scene = top_sim::load_scene(std::string(TOP_SIM_TEST_CONFIG_DIR) + "/scenes/default.yaml");
  EXPECT_EQ(fallback.initial.spin, scene.initial.spin);
  EXPECT_EQ(fallback.model.plane.inclination, scene.model.plane.inclination);
}

TEST(NodeParameters, StartTopsInNameOrderEmptyMeansTheNodesScene) {
  XmlRpc::XmlRpcValue tree;
  tree["tops"]["b"] = std::string("");
  tree["tops"]["a"] = std::string("top: aluminium\nfriction: pmma\ninitial: {spin: 321}\n");
  ParamReader p(tree, "/n");
  top_sim::Scene node_scene;
  node_scene.initial.spin = 42.0;
  const auto tops = top_sim_ros::read_start_tops(p, TOP_SIM_TEST_CONFIG_DIR, node_scene);
  ASSERT_EQ(tops.size(), 2u);
  EXPECT_EQ(tops[0].first, "a");
  EXPECT_EQ(tops[0].second.initial.spin, 321.0);
  EXPECT_EQ(tops[1].first, "b");
  EXPECT_EQ(tops[1].second.initial.spin, 42.0);
}

top_sim::Scene default_scene() { return top_sim::load_scene(std::string(TOP_SIM_TEST_CONFIG_DIR) + "/scenes/default.yaml"); }

TEST(TopSet, NamesMustBeNewBaseNames) {
  top_sim_ros::TopSet set;
  set.add(std::make_unique<top_sim_ros::NodeTop>("top", true, default_scene(), top_sim_ros::Frames{}, 0.0, 1.0,
                                                 200.0, 0.0));
  EXPECT_EQ(set.check_new_name("a_1"), "");
  EXPECT_NE(set.check_new_name("").find("empty"), std::string::npos);
  EXPECT_NE(set.check_new_name("top").find("taken"), std::string::npos);
  EXPECT_NE(set.check_new_name("1a").find("not a base ROS name"), std::string::npos);
  EXPECT_NE(set.check_new_name("a/b").find("not a base ROS name"), std::string::npos);
  EXPECT_NE(set.check_new_name("a b").find("not a base ROS name"), std::string::npos);
  EXPECT_NE(set.check_new_name(std::string(101, 'a')).find("at most 100"), std::string::npos);
  const top_sim_ros::Frames f = top_sim_ros::spawned_frames(top_sim_ros::Frames{}, "a_1");
  EXPECT_EQ(f.plane, "a_1/plane");
  EXPECT_EQ(f.top, "a_1/top");
  EXPECT_EQ(f.world, "world");
}

// A costly top (rk4 at dt 1e-8) next to cheap ones: the cheap tops keep up with the ticks' targets; the costly one
// falls behind alone, and the tick stays near its budget. The budget (20 ms) is generous and the cheap tops may
// end one tick short, so a descheduled test process on a loaded CI machine does not fail it.
TEST(TopSet, ACostlyTopDoesNotSlowTheOthers) {
  top_sim_ros::TopSet set;
  const double rate = 200.0;
  set.add(std::make_unique<top_sim_ros::NodeTop>("top", true, default_scene(), top_sim_ros::Frames{}, 0.0, 1.0, rate,
                                                 0.0));
  top_sim::Scene slow = default_scene();
  slow.integrator.method = top_sim::Method::rk4;
  slow.integrator.dt = 1e-8;
  set.add(std::make_unique<top_sim_ros::NodeTop>("slow", false, slow, top_sim_ros::Frames{}, 0.0, 1.0, rate, 0.0));
  set.add(std::make_unique<top_sim_ros::NodeTop>("b", false, default_scene(), top_sim_ros::Frames{}, 0.0, 1.0, rate,
                                                 0.0));
  const double budget = 0.02;
  double worst_tick = 0.0;
  const int ticks = 40;
  for (int k = 1; k <= ticks; ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    set.advance(k / rate, budget, false);  // a fake wall clock one period per tick
    worst_tick = std::max(worst_tick, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  const double target = ticks / rate;
  EXPECT_GE(set.find("top")->sim().time(), target - 1.0 / rate - 1e-9);
  EXPECT_GE(set.find("b")->sim().time(), target - 1.0 / rate - 1e-9);
  EXPECT_LT(set.find("slow")->sim().time(), 0.1 * target);  // 1e-8 s steps: far behind
  // The budget is checked between steps; one rk4 step is far below a millisecond. Generous for a loaded CI machine.
  EXPECT_LT(worst_tick, budget + 0.05) << "worst tick " << worst_tick << " s";
}

// The node's parameters under /top_sim from a tree holding only `key` = `v` (key "": publish_rate alone).
top_sim_ros::NodeParameters parameters_with(const std::string& key, XmlRpc::XmlRpcValue v = XmlRpc::XmlRpcValue()) {
  XmlRpc::XmlRpcValue tree;
  if (key.empty())
    tree["publish_rate"] = 100;
  else
    tree[key] = v;
  ParamReader p(tree, "/top_sim");
  return top_sim_ros::read_node_parameters(p);
}

// ~per_top_topics: a strict bool; unset, on while the node holds at most 100 tops (issue 49).
TEST(NodeParameters, PerTopTopicsIsABoolOrTheRuleByCount) {
  using top_sim_ros::PerTopTopics;
  auto read = [](XmlRpc::XmlRpcValue v) { return parameters_with("per_top_topics", v).per_top_topics; };
  EXPECT_EQ(parameters_with("").per_top_topics, PerTopTopics::by_count);
  EXPECT_EQ(read(XmlRpc::XmlRpcValue(true)), PerTopTopics::on);
  EXPECT_EQ(read(XmlRpc::XmlRpcValue(false)), PerTopTopics::off);
  for (XmlRpc::XmlRpcValue bad : {XmlRpc::XmlRpcValue(std::string("maybe")), XmlRpc::XmlRpcValue(1)}) {
    const std::string m = message_of([&] { read(bad); });
    EXPECT_NE(m.find("/top_sim/per_top_topics"), std::string::npos) << m;
    EXPECT_NE(m.find("must be true or false"), std::string::npos) << m;
  }
  EXPECT_TRUE(top_sim_ros::own_topics(PerTopTopics::by_count, 100));
  EXPECT_FALSE(top_sim_ros::own_topics(PerTopTopics::by_count, 101));
  EXPECT_TRUE(top_sim_ros::own_topics(PerTopTopics::on, 10000));
  EXPECT_FALSE(top_sim_ros::own_topics(PerTopTopics::off, 1));
}

// A TopCommand on one top (NodeTop::command, what ~tops/command and ~NAME/command apply): checked as a whole
// first; reset, then pause, then the fields; pause of one top leaves the other running.
TEST(NodeTop, CommandIsCheckedWholeThenResetPauseFields) {
  top_sim_ros::TopSet set;
  const double rate = 200.0;
  set.add(std::make_unique<top_sim_ros::NodeTop>("top", true, default_scene(), top_sim_ros::Frames{}, 0.0, 1.0, rate,
                                                 0.0));
  set.add(std::make_unique<top_sim_ros::NodeTop>("b", false, default_scene(), top_sim_ros::Frames{}, 0.0, 1.0, rate,
                                                 0.0));
  top_sim_ros::NodeTop& b = *set.find("b");
  const double alpha0 = b.sim().model().plane.inclination;
  top_sim::Command applied;
  top_sim::TopCommand m;
  m.set_inclination = true;
  m.inclination = 0.2;
  m.set_spin = true;
  m.spin = std::numeric_limits<double>::quiet_NaN();  // one bad field: nothing applied, the field named
  const std::string error = b.command(m, 0.0, applied);
  EXPECT_NE(error.find("spin"), std::string::npos) << error;
  set.advance(1.0 / rate, 0.02, false);
  EXPECT_EQ(b.sim().model().plane.inclination, alpha0);
  EXPECT_TRUE(applied.empty());
  m.set_spin = false;
  EXPECT_EQ(b.command(m, 1.0 / rate, applied), "");
  set.advance(2.0 / rate, 0.02, false);
  EXPECT_EQ(b.sim().model().plane.inclination, 0.2);
  EXPECT_TRUE(applied.inclination.has_value());
  top_sim::TopCommand pause;
  pause.set_paused = pause.paused = true;
  EXPECT_EQ(b.command(pause, 2.0 / rate, applied), "");
  const double tb = b.sim().time(), ttop = set.find("top")->sim().time();
  for (int k = 3; k <= 10; ++k) set.advance(k / rate, 0.02, false);
  EXPECT_TRUE(b.paused());
  EXPECT_EQ(b.sim().time(), tb);
  EXPECT_GT(set.find("top")->sim().time(), ttop);
  top_sim::TopCommand reset;  // reset with a field: the field applies to the reset top
  reset.reset = true;
  reset.set_paused = true;  // and resume
  reset.set_spin = true;
  reset.spin = 150.0;
  EXPECT_EQ(b.command(reset, 10.0 / rate, applied), "");
  set.advance(11.0 / rate, 0.02, false);
  EXPECT_FALSE(b.paused());
  EXPECT_EQ(b.sim().model().plane.inclination, alpha0);
  EXPECT_NEAR(b.sim().snapshot().spin, 150.0, 1.0);
  top_sim::TopCommand nothing;
  EXPECT_NE(b.command(nothing, 0.0, applied).find("no field is set"), std::string::npos);
}

// Every point of a trail once, oldest first (a chunk starts at its predecessor's last point).
std::vector<top_sim_ros::Trail::Point> trail_points(const top_sim_ros::Trail& trail) {
  std::vector<top_sim_ros::Trail::Point> out;
  for (const auto& c : trail.chunks())
    for (std::size_t i = out.empty() ? 0 : 1; i < c.points.size(); ++i) out.push_back(c.points[i]);
  return out;
}

// A point is kept when it is path_resolution or more from the newest kept point; steps of 0.1 mm at a resolution of
// 0.25 mm keep every third point (0, 0.3, 0.6 mm...).
TEST(Trail, KeepsAPointOnlyWhenTheContactPointMovedTheResolution) {
  top_sim_ros::Trail trail;
  for (int i = 0; i < 10; ++i) trail.add(Eigen::Vector3d(1e-4 * i, 0.0, 0.0), ros::Time(i), 2.5e-4, 100);
  const auto points = trail_points(trail);
  ASSERT_EQ(points.size(), 4u);
  for (std::size_t k = 0; k < 4; ++k) EXPECT_NEAR(points[k].position.x(), 3e-4 * k, 1e-15);
}

// The trail's head moves between the contact frame (a fast top) and the plane frame; it is frame-locked in both, since
// rviz 1.14 aborts (SIGTRAP) when a marker it got frame-locked comes again with the same (ns, id, type) unlocked.
TEST(Trail, HeadIsFrameLockedInTheContactAndThePlaneFrame) {
  top_sim_ros::Trail trail;
  for (int i = 0; i < 5; ++i) trail.add(Eigen::Vector3d(1e-3 * i, 0.0, 0.0), ros::Time(i), 2.5e-4, 100);
  const top_sim_ros::Frames frames;
  for (const bool attached : {true, false}) {
    const visualization_msgs::Marker m =
        top_sim_ros::trail_head_marker(trail, Eigen::Vector3d(5e-3, 0.0, 0.0), ros::Time(5), frames, attached);
    EXPECT_EQ(m.header.frame_id, attached ? frames.contact : frames.plane);
    EXPECT_EQ(m.action, visualization_msgs::Marker::ADD);
    EXPECT_TRUE(m.frame_locked) << (attached ? "contact" : "plane") << " frame";
  }
}

// Chunks close at kChunkPoints points and join up: each starts at its predecessor's last point, ids increase, and a
// closed chunk does not change (same version) while points are added after it.
TEST(Trail, ChunksCloseAtTheirSizeJoinUpAndStayUnchanged) {
  using top_sim_ros::Trail;
  Trail trail;
  const int n = 5 * static_cast<int>(Trail::kChunkPoints);
  std::vector<std::pair<std::uint64_t, std::uint64_t>> first_seen;  // (id, version) of each chunk when it closed
  for (int i = 0; i < n; ++i) {
    trail.add(Eigen::Vector3d(1e-3 * i, 0.0, 0.0), ros::Time(1.0 + i), 1e-4, 100000);
    const auto& chunks = trail.chunks();
    if (chunks.size() >= 2 && first_seen.size() < chunks.size() - 1)
      first_seen.emplace_back(chunks[chunks.size() - 2].id, chunks[chunks.size() - 2].version);
  }
  const auto& chunks = trail.chunks();
  ASSERT_GE(chunks.size(), 5u);
  for (std::size_t c = 0; c + 1 < chunks.size(); ++c) {
    EXPECT_EQ(chunks[c].points.size(), Trail::kChunkPoints) << "chunk " << c;
    EXPECT_LT(chunks[c].id, chunks[c + 1].id);
    EXPECT_EQ(chunks[c].points.back().stamp, chunks[c + 1].points.front().stamp);
    EXPECT_EQ(chunks[c].points.back().position, chunks[c + 1].points.front().position);
    EXPECT_EQ(chunks[c].id, first_seen[c].first);
    EXPECT_EQ(chunks[c].version, first_seen[c].second) << "a closed chunk changed";
  }
  EXPECT_EQ(trail_points(trail).size(), static_cast<std::size_t>(n));
  EXPECT_EQ(trail.size(), n + chunks.size() - 1) << "size counts the joints twice";
}

// Beyond `length` points the oldest chunks are merged (every other point kept): the trail stays within
// length + one chunk, keeps its first and newest points (it still covers its time), its points stay in time
// order, and its newest chunks keep every point (level 0).
TEST(Trail, StaysWithinItsLengthKeepsItsEndsAndItsNewestPoints) {
  using top_sim_ros::Trail;
  Trail trail;
  const std::size_t length = 200;
  for (int i = 0; i < 5000; ++i) {
    trail.add(Eigen::Vector3d(1e-3 * i, 0.0, 0.0), ros::Time(1.0 + i), 1e-4, length);
    ASSERT_LE(trail.size(), length + Trail::kChunkPoints);
  }
  const auto points = trail_points(trail);
  EXPECT_EQ(points.front().stamp, ros::Time(1.0));
  EXPECT_EQ(points.back().stamp, ros::Time(5000.0));
  for (std::size_t i = 1; i < points.size(); ++i) ASSERT_LT(points[i - 1].stamp, points[i].stamp);
  const auto& chunks = trail.chunks();
  EXPECT_EQ(chunks.back().level, 0);
  EXPECT_EQ(chunks[chunks.size() - 2].level, 0);
  for (std::size_t c = 1; c < chunks.size(); ++c) EXPECT_GE(chunks[c - 1].level, chunks[c].level) << "older is coarser";
}

// trim(seconds) drops whole chunks whose newest point is older than `seconds` before the trail's newest point: the
// trail covers at least `seconds` and at most one chunk more; clear() empties it.
TEST(Trail, TrimDropsWholeChunksOlderThanItsTime) {
  using top_sim_ros::Trail;
  Trail trail;
  for (int i = 0; i < 200; ++i) trail.add(Eigen::Vector3d(1e-3 * i, 0.0, 0.0), ros::Time(1.0 + i), 1e-4, 100000);
  trail.trim(50.0);
  const auto points = trail_points(trail);
  const double newest = points.back().stamp.toSec(), oldest = points.front().stamp.toSec();
  EXPECT_LE(oldest, newest - 50.0);
  EXPECT_GT(oldest, newest - 50.0 - Trail::kChunkPoints);
  EXPECT_GE(trail.chunks().front().points.back().stamp.toSec(), newest - 50.0);
  trail.clear();
  EXPECT_TRUE(trail.empty());
  EXPECT_EQ(trail.size(), 0u);
}

// What one marker tick of a top sends: {namespace: (ADDs, DELETEs)}.
using Sent = std::map<std::string, std::pair<int, int>>;
Sent sent_by(const visualization_msgs::MarkerArray& a) {
  Sent out;
  for (const auto& m : a.markers) {
    auto& [adds, deletes] = out[m.ns];
    (m.action == visualization_msgs::Marker::DELETE ? deletes : adds) += 1;
  }
  return out;
}

struct StreamFixture {
  top_sim::Scene scene = top_sim::load_scene(std::string(TOP_SIM_TEST_CONFIG_DIR) + "/scenes/default.yaml");
  top_sim::Snapshot snapshot;
  top_sim_ros::Trail trail;
  top_sim_ros::MarkerStream stream;
  top_sim_ros::MarkerTick tick;
  int points = 0;
  StreamFixture() {
    tick.period = 0.1;
    tick.refresh = 10.0;
  }
  void add(int n) {
    for (int i = 0; i < n; ++i, ++points)
      trail.add(Eigen::Vector3d(1e-3 * points, 0.0, 0.0), ros::Time(1.0 + 0.01 * points), 1e-4, 1000);
  }
  Sent next() {
    tick.wall += tick.period;
    tick.stamp = ros::Time(1.0 + tick.wall);
    visualization_msgs::MarkerArray a;
    stream.collect(snapshot, scene.model.top, trail, top_sim_ros::Frames(), top_sim_ros::MarkerStyle(), "", tick, a);
    return sent_by(a);
  }
};

// The first tick sends everything: the fixed markers, the moving ones, every closed chunk of the trail and its
// open head. After that a tick sends only what changed: a chunk once when it closes, nothing fixed, the head.
TEST(MarkerStream, SendsEverythingOnceThenWhatChanged) {
  using top_sim_ros::Trail;
  StreamFixture f;
  f.add(3 * Trail::kChunkPoints);  // three closed chunks and a head of 4 points
  Sent first = f.next();
  for (const char* ns : {"plane", "grid", "body", "stripe", "stem", "tip", "spin", "velocity", "label", "trail_head"})
    EXPECT_EQ(first[ns].first, 1) << ns;
  EXPECT_EQ(first["trail"].first, 3);
  Sent quiet = f.next();
  for (const char* ns : {"plane", "grid", "body", "stripe", "stem", "tip", "spin", "velocity", "label", "trail"})
    EXPECT_EQ(quiet.count(ns), 0u) << ns << " sent again unchanged";
  EXPECT_EQ(quiet["trail_head"].first, 1);
  f.add(Trail::kChunkPoints - 2);  // the head (a joint and 2 points) fills up and closes at the next point
  EXPECT_EQ(f.next()["trail"], std::make_pair(1, 0));
  f.snapshot.regime = top_sim::Regime::sliding;  // another colour: the fixed markers again
  Sent recoloured = f.next();
  EXPECT_EQ(recoloured["body"].first, 1);
  EXPECT_EQ(recoloured["label"].first, 1);
}

// A body with shapes (the disc of test/ros/scenes/disc_rolling.yaml): the stream draws it from the shapes it was
// given (set_shapes), sends the touching highlight, and the fixed markers again when what touches changes (a lift-off,
// a touchdown), and deletes the highlight with the rest when the top goes.
TEST(MarkerStream, ShapesAreDrawnAndTheHighlightFollowsWhatTouches) {
  StreamFixture f;
  f.scene = top_sim::load_scene(std::string(TOP_SIM_TEST_CONFIG_DIR) + "/../test/ros/scenes/disc_rolling.yaml");
  ASSERT_TRUE(f.scene.model.shapes.active);
  f.stream.set_shapes(f.scene.model.shapes);
  f.snapshot.touching = 1;
  Sent first = f.next();
  for (const char* ns : {"body", "touching", "stripe"}) EXPECT_EQ(first[ns], std::make_pair(1, 0)) << ns;
  for (const char* ns : {"tip", "stem"}) EXPECT_EQ(first[ns], std::make_pair(0, 1)) << ns << ": not on a disc";
  EXPECT_EQ(f.next().count("touching"), 0u) << "sent again unchanged";
  f.snapshot.touching = 0;  // in flight
  Sent flying = f.next();
  EXPECT_EQ(flying["touching"], std::make_pair(0, 1));
  EXPECT_EQ(flying["body"], std::make_pair(1, 0));
  f.snapshot.touching = 1;
  EXPECT_EQ(f.next()["touching"], std::make_pair(1, 0));
  visualization_msgs::MarkerArray gone;
  f.stream.remove_all(f.snapshot, f.scene.model.top, top_sim_ros::Frames(), top_sim_ros::MarkerStyle(), "b/",
                      ros::Time(2.0), gone);
  EXPECT_EQ(sent_by(gone)["b/touching"], std::make_pair(0, 1));
}

// Beyond path_length a merge rewrites a chunk and removes its neighbour: one ADD, one DELETE; a cleared trail (a
// reset) DELETEs every chunk sent; a new subscriber (resend_all) gets every chunk again.
TEST(MarkerStream, MergedAndClearedChunksAreReplacedAndDeleted) {
  using top_sim_ros::Trail;
  StreamFixture f;
  f.add(1000 + 2);  // 1000 points held at most: the next closes merge
  f.next();
  int adds = 0, deletes = 0;
  for (int k = 0; k < 20; ++k) {
    f.add(Trail::kChunkPoints - 1);  // one chunk closes per tick
    const auto trail = f.next()["trail"];
    adds += trail.first;
    deletes += trail.second;
  }
  EXPECT_NEAR(deletes, 20, 1) << "one chunk merged away per chunk closed";
  EXPECT_GE(adds, 2 * deletes) << "the new chunk and the merged one";
  const double refreshes = 20 * f.trail.chunks().size() * f.tick.period / f.tick.refresh;
  EXPECT_LE(adds, 2 * deletes + 2 + refreshes + 1) << "and a share of the refresh";
  const std::size_t closed = f.trail.chunks().size() - 1;
  f.stream.resend_all();
  Sent again = f.next();
  EXPECT_EQ(again["trail"].first, static_cast<int>(closed));
  EXPECT_EQ(again["body"].first, 1);
  f.trail.clear();
  EXPECT_EQ(f.next()["trail"].second, static_cast<int>(closed));
}

// Every closed chunk is sent again within `refresh` seconds (a bag played from any moment shows the whole trail),
// spread over the ticks: over one refresh period each chunk once, about closed * period / refresh per tick.
TEST(MarkerStream, RefreshesEveryChunkWithinItsPeriod) {
  using top_sim_ros::Trail;
  StreamFixture f;
  f.add(40 * Trail::kChunkPoints);
  f.next();
  const int closed = static_cast<int>(f.trail.chunks().size()) - 1;
  const int ticks = static_cast<int>(f.tick.refresh / f.tick.period);
  int most = 0, total = 0;
  for (int k = 0; k < ticks; ++k) {
    const int n = f.next()["trail"].first;
    most = std::max(most, n);
    total += n;
  }
  EXPECT_NEAR(total, closed, 1);
  EXPECT_LE(most, 1);
}

// What rviz holds after applying every marker tick (ADD replaces the marker of its namespace and id, DELETE removes
// it) is the trail itself, tick after tick, through merges, trims and a clear: the closed chunks' points by id and
// the head's points, joined up to the contact point. The same holds for a bag replayed from its start.
TEST(MarkerStream, WhatRvizHoldsIsTheTrail) {
  using top_sim_ros::Trail;
  StreamFixture f;
  std::map<std::pair<std::string, int>, visualization_msgs::Marker> held;
  for (int tick = 0; tick < 400; ++tick) {
    f.add(tick % 7 == 0 ? 40 : tick % 3);  // bursts and pauses
    if (tick % 50 == 49) f.trail.trim(0.5);
    if (tick == 300) f.trail.clear();
    f.tick.wall += f.tick.period;
    f.tick.stamp = ros::Time(1.0 + f.tick.wall);
    visualization_msgs::MarkerArray a;
    f.stream.collect(f.snapshot, f.scene.model.top, f.trail, top_sim_ros::Frames(), top_sim_ros::MarkerStyle(), "",
                     f.tick, a);
    for (const auto& m : a.markers) {
      if (m.action == visualization_msgs::Marker::DELETE) held.erase({m.ns, m.id});
      else held[{m.ns, m.id}] = m;
    }
    const auto& chunks = f.trail.chunks();
    std::size_t trail_markers = 0;
    for (const auto& [key, m] : held) trail_markers += key.first == "trail";
    ASSERT_EQ(trail_markers, chunks.empty() ? 0 : chunks.size() - 1) << "tick " << tick;
    for (std::size_t c = 0; c + 1 < chunks.size(); ++c) {
      const auto it = held.find({"trail", static_cast<int>(chunks[c].id)});
      ASSERT_NE(it, held.end()) << "tick " << tick << ", chunk " << chunks[c].id;
      ASSERT_EQ(it->second.points.size(), chunks[c].points.size());
      for (std::size_t i = 0; i < chunks[c].points.size(); ++i)
        ASSERT_EQ(it->second.points[i].x, chunks[c].points[i].position.x()) << "tick " << tick;
    }
    const auto head = held.find({"trail_head", 9});
    if (!chunks.empty() && chunks.back().points.size() >= 2) {
      ASSERT_NE(head, held.end()) << "tick " << tick;
      ASSERT_EQ(head->second.points.size(), chunks.back().points.size() + 1);
      EXPECT_EQ(head->second.points.front().x, chunks.back().points.front().position.x());
    }
  }
}

// -1 (not pinned) or a CPU online; anything else names the parameter, its value and the range.
TEST(NodeParameters, CpuAffinityIsMinusOneOrACpuOnline) {
  const int cpus = top_sim_ros::online_cpus();
  auto read = [](XmlRpc::XmlRpcValue v) { return parameters_with("cpu_affinity", v).cpu_affinity; };
  EXPECT_EQ(parameters_with("").cpu_affinity, -1);
  EXPECT_EQ(read(XmlRpc::XmlRpcValue(cpus - 1)), cpus - 1);
  EXPECT_EQ(read(XmlRpc::XmlRpcValue(0)), 0);
  const std::string range = "[0, " + std::to_string(cpus - 1) + "]";
  for (int bad : {cpus, -2, 4096}) {
    const std::string m = message_of([&] { read(XmlRpc::XmlRpcValue(bad)); });
    EXPECT_NE(m.find("/top_sim/cpu_affinity"), std::string::npos) << m;
    EXPECT_NE(m.find(std::to_string(bad)), std::string::npos) << m;
    EXPECT_NE(m.find(range), std::string::npos) << m;
  }
  const std::string m = message_of([&] { read(XmlRpc::XmlRpcValue(std::string("1"))); });
  EXPECT_NE(m.find("/top_sim/cpu_affinity = '1': must be an integer"), std::string::npos) << m;
}

// The kernel's own account of a thread's CPUs (the independent reference for the masks set here).
std::string proc_cpus(pid_t tid) {
  std::ifstream in("/proc/self/task/" + std::to_string(tid) + "/status");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("Cpus_allowed_list:", 0) == 0) return line.substr(line.find_first_not_of(" \t", 18));
  return "?";
}

pid_t this_tid() { return static_cast<pid_t>(syscall(SYS_gettid)); }

// A thread that runs before the pinning is pinned with the main thread, and a thread started after inherits it.
TEST(CpuAffinity, PinsEveryThreadOfTheProcess) {
  EXPECT_EQ(top_sim_ros::allowed_cpus(), proc_cpus(this_tid()));
  cpu_set_t before;
  ASSERT_EQ(sched_getaffinity(0, sizeof(before), &before), 0);
  int cpu = -1;
  for (int c = 0; c < CPU_SETSIZE; ++c)
    if (CPU_ISSET(c, &before)) cpu = c;  // the last CPU this test may use
  ASSERT_GE(cpu, 0);
  std::atomic<pid_t> early_tid{0};
  std::atomic<bool> pinned{false};
  std::string early_cpus, late_cpus;
  std::thread early([&] {
    early_tid = this_tid();
    while (!pinned) std::this_thread::yield();
    early_cpus = proc_cpus(this_tid());
  });
  while (early_tid == 0) std::this_thread::yield();
  const std::string error = top_sim_ros::pin_process_to_cpu(cpu);
  pinned = true;
  early.join();
  std::thread late([&] { late_cpus = proc_cpus(this_tid()); });
  late.join();
  const std::string main_cpus = proc_cpus(this_tid());
  ASSERT_EQ(sched_setaffinity(0, sizeof(before), &before), 0);  // the other tests run where they did
  EXPECT_EQ(error, "");
  EXPECT_EQ(main_cpus, std::to_string(cpu));
  EXPECT_EQ(early_cpus, std::to_string(cpu));
  EXPECT_EQ(late_cpus, std::to_string(cpu));
}

// The other threads become SCHED_BATCH (woken, they no longer preempt the caller); the caller keeps its policy.
// The kernel's answer (sched_getscheduler) is the reference.
TEST(CpuAffinity, OtherThreadsYieldToTheCaller) {
  std::atomic<pid_t> other_tid{0};
  std::atomic<bool> done{false};
  int other_policy = -1;
  std::thread other([&] {
    other_tid = this_tid();
    while (!done) std::this_thread::yield();
    other_policy = sched_getscheduler(0);
  });
  while (other_tid == 0) std::this_thread::yield();
  const int before = sched_getscheduler(0);
  const std::string error = top_sim_ros::yield_other_threads();
  done = true;
  other.join();
  EXPECT_EQ(error, "");
  EXPECT_EQ(other_policy, SCHED_BATCH);
  EXPECT_EQ(sched_getscheduler(0), before);
  EXPECT_NE(before, SCHED_BATCH);
}

}  // namespace

namespace {

// A gate the opener's build step waits at, so the test decides which top is in hand and when it is done.
struct Gate {
  std::mutex m;
  std::condition_variable cv;
  std::vector<std::string> entered, finished;
  std::string open_for;  // the top whose build may return

  void enter_and_wait(const std::string& name) {
    std::unique_lock<std::mutex> lock(m);
    entered.push_back(name);
    cv.notify_all();
    cv.wait(lock, [&] { return open_for == name; });
    finished.push_back(name);
  }
  void wait_entered(std::size_t n) {
    std::unique_lock<std::mutex> lock(m);
    cv.wait(lock, [&] { return entered.size() >= n; });
  }
  void open(const std::string& name) {
    std::lock_guard<std::mutex> lock(m);
    open_for = name;
    cv.notify_all();
  }
};

}  // namespace

// Tops are opened in the order added; one forgotten while queued is never built, one forgotten while in hand is
// waited for; finished tops are handed over only by install(), on the caller's thread; pending() counts all three.
TEST(TopicOpener, OpensInOrderForgetsQueuedWaitsForTheTopInHand) {
  std::vector<std::unique_ptr<top_sim_ros::NodeTop>> tops;
  for (const char* name : {"a", "b", "c", "d"})
    tops.push_back(std::make_unique<top_sim_ros::NodeTop>(name, false, default_scene(), top_sim_ros::Frames{}, 0.0,
                                                          1.0, 200.0, 0.0));
  Gate gate;
  top_sim_ros::TopicOpener opener([&](top_sim_ros::NodeTop& t) {
    gate.enter_and_wait(t.name());
    return top_sim_ros::TopTopics{};
  });
  for (auto& t : tops) opener.add(*t);
  gate.wait_entered(1);  // a in hand, b c d queued
  EXPECT_EQ(opener.pending(), 4u);
  opener.forget(*tops[1]);  // b: out of the queue at once
  EXPECT_EQ(opener.pending(), 3u);
  gate.open("a");
  gate.wait_entered(2);  // a done (not installed), c in hand
  EXPECT_EQ(opener.pending(), 3u);
  EXPECT_EQ(opener.install(), 1u);
  EXPECT_EQ(opener.pending(), 2u);
  std::atomic<bool> forgotten{false};
  std::thread killer([&] {
    opener.forget(*tops[2]);  // c is in hand: returns only after its build returned
    forgotten = true;
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  EXPECT_FALSE(forgotten) << "forget() returned while the top was still being built";
  gate.open("c");
  killer.join();
  {
    std::lock_guard<std::mutex> lock(gate.m);
    EXPECT_EQ(gate.finished, (std::vector<std::string>{"a", "c"}));
  }
  gate.wait_entered(3);  // d in hand
  gate.open("d");
  while (opener.pending() > 0) {
    opener.install();
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  std::lock_guard<std::mutex> lock(gate.m);
  EXPECT_EQ(gate.entered, (std::vector<std::string>{"a", "c", "d"}));  // b never built
}

// ~topics_at_start: 100 by default, -1 (all) and any count >= 0; below -1 a ParameterError naming it.
TEST(NodeParameters, TopicsAtStartIsACountOrMinusOne) {
  auto read = [](int v) {
    XmlRpc::XmlRpcValue tree;
    tree["topics_at_start"] = v;
    ParamReader p(tree, "/top_sim");
    return top_sim_ros::read_node_parameters(p).topics_at_start;
  };
  XmlRpc::XmlRpcValue none;
  none["publish_rate"] = 100;
  ParamReader p(none, "/top_sim");
  EXPECT_EQ(top_sim_ros::read_node_parameters(p).topics_at_start, 100);
  EXPECT_EQ(read(-1), -1);
  EXPECT_EQ(read(0), 0);
  EXPECT_EQ(read(20000), 20000);
  const std::string m = message_of([&] { read(-2); });
  EXPECT_NE(m.find("/top_sim/topics_at_start = -2"), std::string::npos) << m;
}

// The launch arguments (alpha:=, spin:=, dynamic_reconfigure keys at start) are part of the launch-time top's scene:
// it starts there and a reset returns there with no command; a friction change keeps what it does not name.
TEST(StartScene, LaunchValuesAreFoldedIntoTheScene) {
  const top_sim::Scene scene = default_scene();
  top_sim::Command start;
  start.inclination = 0.2;
  start.spin = 150.0;
  start.friction = top_sim::FrictionChange{};
  start.friction->given.emplace_back(top_sim::find_friction_parameter("mu_c"), 0.3);
  ASSERT_EQ(top_sim::validate(start, scene.model), "");
  const top_sim::Scene launch = top_sim_ros::start_scene(scene, start);
  EXPECT_EQ(launch.model.plane.inclination, 0.2);
  EXPECT_EQ(launch.initial.spin, 150.0);
  EXPECT_EQ(launch.model.friction.mu_c, 0.3);
  EXPECT_EQ(launch.model.friction.s_c, scene.model.friction.s_c) << "not named: the scene's";
  EXPECT_EQ(launch.initial.tilt, scene.initial.tilt);
  top_sim::Simulator sim(launch);
  EXPECT_NEAR(top_sim::shell_spin(sim.state()), 150.0, 1e-12);
  top_sim::Command tilt;
  tilt.inclination = 0.05;
  ASSERT_EQ(sim.submit(tilt), "");
  sim.advance_to(0.01);
  ASSERT_EQ(sim.model().plane.inclination, 0.05);
  sim.reset();
  EXPECT_EQ(sim.model().plane.inclination, 0.2);
  EXPECT_NEAR(top_sim::shell_spin(sim.state()), 150.0, 1e-12);
  EXPECT_EQ(top_sim_ros::start_scene(scene, top_sim::Command{}).model.plane.inclination,
            scene.model.plane.inclination) << "no start values: the scene as read";
}

// A stationary start is computed at the folded values; where it has no sleeping state the start is refused.
TEST(StartScene, StationaryStartWithoutASleepingStateIsRefused) {
  const top_sim::Scene gyro = top_sim::load_scene(std::string(TOP_SIM_TEST_CONFIG_DIR) + "/scenes/gyro_reversal.yaml");
  ASSERT_EQ(gyro.initial.start, top_sim::StartKind::stationary);
  top_sim::Command steep;
  steep.inclination = 1.2;  // tan(1.2) = 2.6: far above any mu of pmma, no sleeping state
  EXPECT_THROW(top_sim_ros::start_scene(gyro, steep), std::runtime_error);
}
