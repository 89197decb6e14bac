// Unit tests of the node's parts that need no master: the parameter reader (scene sources, strict types, unknown
// keys), the top set (names, the sharing of a tick's budget) and the contact-point trail.
#include <gtest/gtest.h>

#include <chrono>
#include <string>

#include "node_parameters.hpp"
#include "top_set.hpp"
#include "trail.hpp"

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

// A point is kept when it is path_resolution or more from the newest kept point; steps of 0.1 mm at a resolution of
// 0.25 mm keep every third point (0, 0.3, 0.6 mm...).
TEST(Trail, KeepsAPointOnlyWhenTheContactPointMovedTheResolution) {
  top_sim_ros::Trail trail;
  for (int i = 0; i < 10; ++i) trail.add(Eigen::Vector3d(1e-4 * i, 0.0, 0.0), ros::Time(i), 2.5e-4, 100);
  ASSERT_EQ(trail.points().size(), 4u);
  for (std::size_t k = 0; k < 4; ++k) EXPECT_NEAR(trail.points()[k].position.x(), 3e-4 * k, 1e-15);
}

// Beyond `length` points the older half is thinned: the oldest point stays, the trail never holds more than
// length + 1 points, and its storage is the one reserved at the first point (no copy as it grows).
TEST(Trail, StaysWithinItsLengthKeepsItsStartAndItsStorage) {
  top_sim_ros::Trail trail;
  const std::size_t length = 50;
  trail.add(Eigen::Vector3d::Zero(), ros::Time(1.0), 1e-4, length);
  const top_sim_ros::Trail::Point* storage = trail.points().data();
  for (int i = 1; i < 1000; ++i) {
    trail.add(Eigen::Vector3d(1e-3 * i, 0.0, 0.0), ros::Time(1.0 + i), 1e-4, length);
    ASSERT_LE(trail.points().size(), length + 1);
    ASSERT_EQ(trail.points().data(), storage);
  }
  EXPECT_EQ(trail.points().front().stamp, ros::Time(1.0));
  EXPECT_EQ(trail.points().back().stamp, ros::Time(1000.0));
}

}  // namespace
