// Scene configuration errors (docs/interfaces.md): one test per kind, each message naming the file, the key, the
// value and the allowed range.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "test_util.hpp"

namespace {

using namespace top_sim;
using top_sim_test::scene_from;

// Parses `yaml` as file `source` and returns the SceneError's message ("" and a test failure if none is thrown).
std::string error_of(const std::string& yaml, const std::string& source) {
  try {
    scene_from(yaml, source);
  } catch (const SceneError& e) {
    EXPECT_EQ(e.file, source);
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "not a SceneError: " << e.what();
    return "";
  }
  ADD_FAILURE() << "accepted a bad scene:\n" << yaml;
  return "";
}

// The message names the file, "key: value" together, and the allowed range.
void expect_error(const std::string& yaml, const std::string& key, const std::string& value, const std::string& range) {
  const std::string source = "bad_" + key + ".yaml";
  const std::string msg = error_of(yaml, source);
  SCOPED_TRACE(msg);
  EXPECT_EQ(msg.rfind(source + ": ", 0), 0u) << "file first";
  EXPECT_NE(msg.find(key + ": " + value), std::string::npos) << "key and value";
  EXPECT_NE(msg.find(range), std::string::npos) << "allowed range";
}

const std::string kTop = "top: aluminium\n";

TEST(SceneErrors, UnknownKeyAtTopLevel) {
  // The "value" of an unknown key is the key itself; the allowed range is the list of known keys.
  expect_error(kTop + "duraton: 5\n", "duraton", "unknown key", "duration");
}

TEST(SceneErrors, UnknownKeyNested) {
  expect_error(kTop + "plane: {inclinaton: 0.1}\n", "plane.inclinaton", "unknown key", "inclination");
  expect_error("top: {mass: 0.025, rotor: {inertia_axial: 1.0e-6, spinn: 10}}\n", "top.rotor.spinn", "unknown key",
               "spin");
  expect_error(kTop + "integrator: {method: dopri5, rtoll: 1.0e-6}\n", "integrator.rtoll", "unknown key", "rtol");
}

TEST(SceneErrors, WrongType) {
  expect_error(kTop + "plane: {inclination: steep}\n", "plane.inclination", "'steep' is not a number",
               "in (-pi/2, pi/2)");
  expect_error("top: {mass: [1, 2]}\n", "top.mass", "a list is not a number", "> 0");
  expect_error(kTop + "model: {normal_force: 3}\n", "model.normal_force", "'3'", "constrained | static");
  expect_error(kTop + "initial: {position: 0.5}\n", "initial.position", "'0.5'", "list of 2 numbers");
  expect_error(kTop + "plane: 0.1\n", "plane", "'0.1'", "not a mapping");
}

TEST(SceneErrors, OutOfRangeValues) {
  expect_error("top: {mass: -1}\n", "top.mass", "-1", "> 0");
  expect_error("top: {max_tilt: 4}\n", "top.max_tilt", "4", "(0, pi]");
  expect_error("top: {tip_radius: -0.001}\n", "top.tip_radius", "-0.001", ">= 0");
  // A rigid axisymmetric body has I_f <= 2 I_d.
  expect_error("top: {inertia_axial: 7.0e-6, inertia_transverse: 3.0e-6}\n", "top.inertia_axial", "7e-06",
               "<= 2 * inertia_transverse");
  expect_error("top: {rotor: {inertia_axial: 6.0e-6}}\n", "top.rotor.inertia_axial", "6e-06", "(0, top.inertia_axial");
  expect_error(kTop + "plane: {inclination: 2.0}\n", "plane.inclination", "2", "(-pi/2, pi/2)");
  expect_error(kTop + "plane: {gravity: 0}\n", "plane.gravity", "0", "> 0");
  expect_error(kTop + "friction: {law: paper, s_c: 1.5}\n", "friction.s_c", "1.5", "(0, 1]");
  expect_error(kTop + "friction: {law: paper, mu_c: -0.2}\n", "friction.mu_c", "-0.2", "> 0");
  expect_error(kTop + "friction: {law: coulomb, mu: -1}\n", "friction.mu", "-1", ">= 0");
  expect_error(kTop + "friction: {regularization_speed: 0}\n", "friction.regularization_speed", "0", "> 0");
  expect_error(kTop + "friction: {law: dry}\n", "friction.law", "'dry'", "paper | linearized | coulomb | table");
  expect_error(kTop + "initial: {tilt: -0.1}\n", "initial.tilt", "-0.1", "[0, pi)");
  expect_error(kTop + "initial: {start: sleeping}\n", "initial.start", "'sleeping'", "tilted | stationary");
  expect_error(kTop + "integrator: {rtol: 2}\n", "integrator.rtol", "2", "(0, 1)");
  expect_error(kTop + "integrator: {dt: 0}\n", "integrator.dt", "0", "[1e-12, 10]");
  expect_error(kTop + "integrator: {method: rk45}\n", "integrator.method", "'rk45'", "dopri5");
  expect_error(kTop + "duration: -5\n", "duration", "-5", "> 0");
}

TEST(SceneErrors, MissingTop) {
  const std::string msg = error_of("plane: {inclination: 0.1}\n", "no_top.yaml");
  EXPECT_NE(msg.find("no_top.yaml: top: required"), std::string::npos) << msg;
  EXPECT_NE(msg.find("config/tops/"), std::string::npos) << msg;  // what is allowed instead
}

TEST(SceneErrors, UnknownTopOrPlaneFile) {
  const std::string top = error_of("top: titanium\n", "titanium.yaml");
  EXPECT_NE(top.find("titanium.yaml: top: 'titanium' names no file"), std::string::npos) << top;
  EXPECT_NE(top.find("/tops/"), std::string::npos) << top;  // where names are looked up
  const std::string plane = error_of(kTop + "friction: teflon\n", "teflon.yaml");
  EXPECT_NE(plane.find("teflon.yaml: friction: 'teflon' names no file"), std::string::npos) << plane;
  EXPECT_NE(plane.find("/planes/"), std::string::npos) << plane;
}

TEST(SceneErrors, ParameterOfAnotherFrictionLaw) {
  const std::string msg = error_of(kTop + "friction: {law: coulomb, mu: 0.3, mu_c: 0.25}\n", "mixed_law.yaml");
  EXPECT_EQ(msg.rfind("mixed_law.yaml: friction.mu_c: ", 0), 0u) << msg;
  EXPECT_NE(msg.find("law coulomb"), std::string::npos) << msg;
  EXPECT_NE(msg.find("law paper"), std::string::npos) << msg;
  // docs/interfaces.md: the message names the value too, and the keys the chosen law does take.
  EXPECT_NE(msg.find("0.25"), std::string::npos) << msg;
  EXPECT_NE(msg.find("takes: mu,"), std::string::npos) << msg;
}

TEST(SceneErrors, BadTablePoints) {
  // Unsorted s.
  std::string msg = error_of(kTop + "friction: {law: table, points: [[0.0, 0.0], [0.6, 0.3], [0.4, 0.2]]}\n",
                             "unsorted.yaml");
  EXPECT_NE(msg.find("unsorted.yaml: "), std::string::npos) << msg;
  EXPECT_NE(msg.find("friction.points[2].s = 0.4"), std::string::npos) << msg;
  EXPECT_NE(msg.find("greater than the previous s (0.6"), std::string::npos) << msg;
  // s outside [0, 1].
  msg = error_of(kTop + "friction: {law: table, points: [[0.0, 0.0], [1.5, 0.3]]}\n", "outside.yaml");
  EXPECT_NE(msg.find("outside.yaml: "), std::string::npos) << msg;
  EXPECT_NE(msg.find("friction.points[1].s = 1.5"), std::string::npos) << msg;
  EXPECT_NE(msg.find("[0, 1]"), std::string::npos) << msg;
  // Not a number, and a point that is not a pair.
  expect_error(kTop + "friction: {law: table, points: [[0.0, x], [1.0, 0.3]]}\n", "friction.points[0][1]", "'x'",
               "finite number");
  expect_error(kTop + "friction: {law: table, points: [[0.0, 0.1, 2], [1.0, 0.3]]}\n", "friction.points[0]",
               "a list", "[s, mu]");
  // Missing points.
  msg = error_of(kTop + "friction: {law: table}\n", "no_points.yaml");
  EXPECT_NE(msg.find("no_points.yaml: friction.points: required"), std::string::npos) << msg;
}

TEST(SceneErrors, EventsOutOfOrder) {
  expect_error(kTop + "events:\n  - {t: 5.0, inclination: 0.15}\n  - {t: 3.0, spin: 100.0}\n", "events[1].t", "3",
               ">= the previous event's t = 5");
  expect_error(kTop + "events:\n  - {t: -1.0, spin: 100.0}\n", "events[0].t", "-1", ">= 0");
  expect_error(kTop + "events:\n  - {t: 1.0, inclination: 3.0}\n", "events[0].inclination", "3", "|alpha| < pi/2");
}

TEST(SceneErrors, AdiabaticModelAboveAlphaC) {
  // alpha 0.3 > alpha_c = atan(0.25) = 0.245: no stationary state for the reduced model to follow.
  const std::string msg = error_of(kTop + "plane: {inclination: 0.3}\nmodel: {kind: adiabatic}\n", "adiabatic.yaml");
  EXPECT_EQ(msg.rfind("adiabatic.yaml: model.kind: ", 0), 0u) << msg;
  EXPECT_NE(msg.find("adiabatic"), std::string::npos) << msg;
  EXPECT_NE(msg.find("tan(alpha) = 0.309"), std::string::npos) << msg;  // the value that is out of range
  EXPECT_NE(msg.find("alpha_c = 0.24"), std::string::npos) << msg;      // the limit
}

TEST(SceneErrors, StationaryStartImpossible) {
  const std::string msg =
      error_of(kTop + "plane: {inclination: 0.3}\ninitial: {start: stationary, spin: 200.0}\n", "stationary.yaml");
  EXPECT_EQ(msg.rfind("stationary.yaml: initial.start: 'stationary' is impossible", 0), 0u) << msg;
  EXPECT_NE(msg.find("tan(alpha) = 0.309"), std::string::npos) << msg;
  EXPECT_NE(msg.find("alpha_c = 0.24"), std::string::npos) << msg;
}

TEST(SceneErrors, FilesThatCannotBeReadOrParsed) {
  try {
    load_scene(top_sim_test::fixture_path("bad_yaml"));
    ADD_FAILURE() << "invalid YAML accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("bad_yaml.yaml: not valid YAML"), std::string::npos) << e.what();
  }
  try {
    load_scene(top_sim_test::fixture_path("does_not_exist"));
    ADD_FAILURE() << "missing file accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("does_not_exist.yaml: cannot open"), std::string::npos) << e.what();
  }
  // A scene file's error names that file (the path as given).
  try {
    load_scene(top_sim_test::fixture_path("bad_inclination"));
    ADD_FAILURE() << "bad inclination accepted";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.file, top_sim_test::fixture_path("bad_inclination"));
    EXPECT_NE(std::string(e.what()).find("plane.inclination: 2 is out of range"), std::string::npos) << e.what();
  }
}

TEST(SceneWarnings, FrictionClampIsSaidOnce) {
  const Scene s = scene_from(kTop + "friction: {law: paper, mu_c: 0.25, s_c: 0.4}\n", "clamped.yaml");
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_NE(s.warnings[0].find("clamped to 0"), std::string::npos) << s.warnings[0];
  EXPECT_TRUE(scene_from(kTop + "friction: {law: paper, mu_c: 0.25, s_c: 0.6}\n").warnings.empty());
}

// Control for all of the above: every shipped scene loads, so the errors come from the bad values alone.
TEST(SceneErrors, EveryShippedSceneLoads) {
  int n = 0;
  for (const auto& entry : std::filesystem::directory_iterator(top_sim_test::config_dir() + "/scenes")) {
    if (entry.path().extension() != ".yaml") continue;
    ++n;
    EXPECT_NO_THROW(load_scene(entry.path().string())) << entry.path();
  }
  EXPECT_GE(n, 5);  // default, supercritical, reversed_spin, upright, gyro_reversal at least
}

}  // namespace

namespace {

// Issue 11: inputs that used to abort, pass silently or print rounded values.
TEST(SceneErrors, KeysMustBeWordsGivenOnce) {
  std::string msg = error_of("top: {[]: 0}\n", "nonscalar.yaml");
  EXPECT_NE(msg.find("top: a list is not a valid key"), std::string::npos) << msg;
  msg = error_of("top: aluminium\nfriction: pmma\ntop: steel\n", "dup.yaml");
  EXPECT_NE(msg.find("dup.yaml: top: given twice"), std::string::npos) << msg;
  msg = error_of(kTop + "plane: {inclination: 0.1, inclination: 0.2}\n", "dup_nested.yaml");
  EXPECT_NE(msg.find("plane.inclination: given twice"), std::string::npos) << msg;
}

TEST(SceneErrors, SubnormalNumbersAreRefused) {
  const std::string msg = error_of(
      "top: {mass: 1.0e-310, tip_radius: 0.005, com_offset: 0.01, inertia_axial: 1.0e-5, "
      "inertia_transverse: 2.0e-5}\n",
      "subnormal.yaml");
  EXPECT_NE(msg.find("top.mass: 1e-310 is subnormal"), std::string::npos) << msg;  // a mass that made N = 0
}

TEST(SceneErrors, ValuesArePrintedAtFullPrecision) {
  expect_error(kTop + "plane: {inclination: 1.5707963267948966}\n", "plane.inclination", "1.5707963267948966",
               "(-pi/2, pi/2)");
}

TEST(SceneErrors, ADirectoryIsNotASceneFile) {
  try {
    load_scene(top_sim_test::config_dir());
    ADD_FAILURE() << "a directory accepted as a scene";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("is a directory, not a scene file"), std::string::npos) << e.what();
  }
}

}  // namespace

namespace {

// parse_scene_text (the node's ~scene parameter and spawn requests) applies the file loader's checks.
TEST(SceneText, SameChecksAsAFile) {
  const std::string dup = "top: aluminium\ntop: steel\n";
  try {
    top_sim::parse_scene_text(dup, "spawn a");
    ADD_FAILURE() << "a key given twice was accepted";
  } catch (const top_sim::SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("given twice"), std::string::npos) << e.what();
    EXPECT_EQ(e.file, "spawn a");
  }
  EXPECT_THROW(top_sim::parse_scene_text("top: [unclosed", "spawn b"), top_sim::SceneError);
  EXPECT_THROW(top_sim::parse_scene_text("spin: 300\n", "spawn c"), top_sim::SceneError);  // unknown key
  try {  // no text: the keys' defaults, and `top` has none
    top_sim::parse_scene_text("", "spawn d");
    ADD_FAILURE() << "an empty scene was accepted";
  } catch (const top_sim::SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("top: required"), std::string::npos) << e.what();
  }
  const top_sim::Scene spun = top_sim::parse_scene_text("top: aluminium\nfriction: pmma\ninitial: {spin: 123.5}\n",
                                                        "spawn e", top_sim_test::config_dir());
  EXPECT_EQ(spun.initial.spin, 123.5);
  EXPECT_EQ(spun.source, "spawn e");
}

}  // namespace

namespace {

// scene_path: the one rule for a scene argument (top_sim_run, the node's ~scene_file, top_sim.launch's scene:=).
TEST(ScenePath, NamesArePathsInConfigScenesAndPathsStayPaths) {
  const std::string config = top_sim_test::config_dir();
  const std::vector<std::string> shipped = top_sim::shipped_scene_names(config);
  ASSERT_FALSE(shipped.empty());
  for (const std::string& name : shipped) {
    const std::string path = top_sim::scene_path(name, config);
    EXPECT_EQ(path, config + "/scenes/" + name + ".yaml");
    EXPECT_TRUE(std::filesystem::is_regular_file(path)) << path;
  }
  EXPECT_TRUE(std::is_sorted(shipped.begin(), shipped.end()));
  // A path: contains '/' or ends in .yaml / .yml; relative ones are taken from the caller's directory if given.
  EXPECT_EQ(top_sim::scene_path("/abs/x.yaml", config, "/caller"), "/abs/x.yaml");
  EXPECT_EQ(top_sim::scene_path("sub/x", config, "/caller"), "/caller/sub/x");
  EXPECT_EQ(top_sim::scene_path("x.yml", config, "/caller"), "/caller/x.yml");
  EXPECT_EQ(top_sim::scene_path("x.yaml", config), "x.yaml");
}

TEST(ScenePath, AnUnknownNameListsEveryShippedScene) {
  const std::string config = top_sim_test::config_dir();
  try {
    top_sim::scene_path("no_such_scene", config);
    ADD_FAILURE() << "an unknown scene name was accepted";
  } catch (const top_sim::SceneError& e) {
    const std::string message = e.what();
    EXPECT_EQ(e.file, "no_such_scene");
    std::size_t listed = 0;
    for (const auto& entry : std::filesystem::directory_iterator(config + "/scenes")) {
      if (entry.path().extension() != ".yaml") continue;
      ++listed;
      EXPECT_NE(message.find(entry.path().stem().string()), std::string::npos) << entry.path() << ": " << message;
    }
    EXPECT_GE(listed, 1u);
  }
}

}  // namespace

// top.shapes (physics.md section 13): each bad shape named by its index and key, with the value and the range.
TEST(SceneErrors, ContactShapes) {
  const std::string inertia = "inertia_axial: 5.0e-6, inertia_transverse: 3.0e-6, ";
  expect_error("top: {shapes: []}\n", "top.shapes", "a list of 0 shapes is out of range", "1 to 4 shapes");
  expect_error("top: {shapes: 3}\n", "top.shapes", "'3' is out of range", "{sphere: {offset, radius}}");
  expect_error("top: {shapes: [{box: {offset: 0, radius: 1}}]}\n", "top.shapes[0].box", "unknown shape kind",
               "sphere, rim");
  expect_error("top: {shapes: [{sphere: {offset: -0.01, radius: 1e-3}, rim: {offset: 0, radius: 0.02}}]}\n",
               "top.shapes[0]", "a mapping", "one key, sphere or rim");
  expect_error("top: {shapes: [{sphere: {offset: -0.01, radius: 0}}]}\n", "top.shapes[0].sphere.radius", "0", "> 0");
  expect_error("top: {shapes: [{sphere: {offset: -0.01, radius: 1e-3}}, {rim: {offset: .nan, radius: 0.02}}]}\n",
               "top.shapes[1].rim.offset", "nan", "a finite number");
  expect_error("top: {shapes: [{sphere: {offset: -0.01, radius: 1e-3}}, {rim: {offset: 0.004}}]}\n",
               "top.shapes[1].rim.radius", "required", "required");
  expect_error("top: {shapes: [{sphere: {offset: -0.01, radius: 1e-3, colour: red}}]}\n", "top.shapes[0].sphere.colour",
               "unknown key", "offset, radius");
  expect_error("top: {tip_radius: 1e-3, shapes: [{sphere: {offset: -0.01, radius: 1e-3}}]}\n", "top.tip_radius",
               "not with top.shapes", "replace tip_radius and com_offset");
  // A rim 5 mm from the axis bounds I_f by m rho^2 = 6.25e-7 kg m^2.
  expect_error("top: {mass: 0.025, " + inertia + "shapes: [{sphere: {offset: -0.01, radius: 1e-3}}, "
               "{rim: {offset: 0.004, radius: 0.005}}]}\n", "top.inertia_axial", "5e-06 is out of range",
               "mass * rho_max^2 = 6.25e-07");
  // At a 1.2 rad start the crown (20 mm, 4 mm above the centre of mass) is below the plane when the tip touches.
  expect_error("top: {mass: 0.025, " + inertia + "max_tilt: 3, shapes: [{sphere: {offset: -0.01, radius: 1.5e-3}}, "
               "{rim: {offset: 0.004, radius: 0.02}}]}\nplane: {inclination: 0}\ninitial: {tilt: 1.2}\n", "top.shapes[1]",
               "the rim starts", "below the plane at the initial tilt 1.2 rad");
}

// One sphere in top.shapes is the tip sphere: the same scene as tip_radius and com_offset. A rim runs the point
// contact's full model; more than two shapes, and shapes with the tip sphere's other models, are refused for now.
TEST(SceneShapes, OneSphereIsTheTipSphereAndARimRunsThePointContact) {
  const top_sim::Scene listed = scene_from("top: {shapes: [{sphere: {offset: -0.012, radius: 2.0e-3}}]}\n");
  const top_sim::Scene keyed = scene_from("top: {tip_radius: 2.0e-3, com_offset: 0.012}\n");
  EXPECT_EQ(listed.model.top.tip_radius, keyed.model.top.tip_radius);
  EXPECT_EQ(listed.model.top.com_offset, keyed.model.top.com_offset);
  EXPECT_EQ(listed.model.shapes.count, 1u);
  EXPECT_EQ(keyed.model.shapes.count, 0u);
  EXPECT_FALSE(top_sim::has_shapes(listed.model));
  expect_error("top: {shapes: [{sphere: {offset: -0.01, radius: 1.5e-3}}, {rim: {offset: 0.004, radius: 0.02}}, "
               "{sphere: {offset: 0.01, radius: 1e-3}}]}\n",
               "top.shapes", "3 shapes: at most 2 are simulated", "two in contact at once");
  const std::string disc = "top: {mass: 0.4, inertia_axial: 3.2e-4, inertia_transverse: 1.6e-4, "
                           "shapes: [{rim: {offset: 0, radius: 0.04}}]";
  const top_sim::Scene rim = scene_from(disc + "}\n");
  EXPECT_TRUE(top_sim::has_shapes(rim.model));
  EXPECT_EQ(rim.model.top.tip_radius, 0.0);  // the state's reference point is the centre of mass
  EXPECT_EQ(rim.model.top.com_offset, 0.0);
  expect_error(disc + ", rotor: {inertia_axial: 1e-5}}\n", "top.rotor", "not with top.shapes yet", "full model");
  EXPECT_TRUE(scene_from(disc + "}\nfriction: {law: coulomb, mu: 0.3}\ncontact: {patch_radius: 1e-4}\n")
                  .model.finite_contact.has_patch());  // a patch on shapes, also with a law that sticks
  expect_error(disc + "}\nplane: {inclination: 0}\ninitial: {tilt: 0}\n", "initial.tilt",
               "top.shapes[0], a rim, starts lying flat", "must be >= 1e-04");
  expect_error(disc + "}\nmodel: {normal_force: static}\n", "model.normal_force", "not with top.shapes yet",
               "constrained normal force");
}

namespace {

// A view hint (issue 46): a camera the viewer knows, a positive distance and pace; anything else names the key, the
// value and the allowed values.
TEST(SceneErrors, ViewHintOutOfRange) {
  expect_error(kTop + "view: {camera: side}\n", "view.camera", "'side' is not one of", "low | top | follow");
  expect_error(kTop + "view: {distance: 0.0}\n", "view.distance", "0 is out of range", "in (0, 100] [m]");
  expect_error(kTop + "view: {distance: -1}\n", "view.distance", "-1 is out of range", "in (0, 100] [m]");
  expect_error(kTop + "view: {real_time_factor: 0}\n", "view.real_time_factor", "0 is out of range", "in (0, 1000]");
  expect_error(kTop + "view: {zoom: 2}\n", "view.zoom", "unknown key", "camera");
  const Scene s = scene_from(kTop + "view: {camera: low, distance: 0.2, real_time_factor: 0.25}\n");
  EXPECT_EQ(s.view.camera, ViewCamera::low);
  EXPECT_EQ(s.view.distance, 0.2);
  EXPECT_EQ(s.view.real_time_factor, 0.25);
  EXPECT_EQ(scene_from(kTop).view.camera, ViewCamera::unset);
}

// A shape's name is a plain identifier (issue 46): what a label can say.
TEST(SceneErrors, ShapeNameNotAPlainIdentifier) {
  const std::string body = "top: {mass: 0.025, inertia_axial: 5.0e-6, inertia_transverse: 3.0e-6, shapes: [";
  const std::string rest = "{rim: {offset: 0.004, radius: 0.02}}]}\n";
  for (const char* bad : {"'2nd'", "'tip top'", "'a-b'", "''", "averyveryverylongname", "[a]"}) {
    const std::string msg =
        error_of(body + "{sphere: {offset: -0.01, radius: 1.5e-3, name: " + bad + "}}, " + rest, "bad_name.yaml");
    EXPECT_NE(msg.find("top.shapes[0].sphere.name: "), std::string::npos) << msg;
    EXPECT_NE(msg.find("is not a plain identifier"), std::string::npos) << msg;
  }
  const Scene s = scene_from(body + "{sphere: {offset: -0.01, radius: 1.5e-3, name: tip_1}}, " + rest);
  EXPECT_EQ(shape_name(s.model.shapes, 0), "tip_1");
  EXPECT_EQ(shape_name(s.model.shapes, 1), "shape 1");
  EXPECT_EQ(touching_names(s.model.shapes, 0b11), "tip_1 and shape 1");
}

}  // namespace
