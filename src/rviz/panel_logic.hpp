// The rviz control panel's logic, without Qt (docs/ros.md, "Control in rviz"): topic and service names of a top,
// field text -> the node's TopCommand with the core's validation, a top's state -> the status line. The widget
// (control_panel.hpp) only moves text between these functions and the node's topics and services.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "top_sim/TopCommand.h"
#include "top_sim/TopState.h"

namespace top_sim_rviz {

constexpr const char* kLaunchTopName = "top";  // the node's name for its launch-time top

// A top's topic or service: "/top_sim" + "top" + "inclination" -> "/top_sim/inclination" (the launch-time top
// keeps the node's names), "/top_sim" + "b" -> "/top_sim/b/inclination".
std::string top_name_of(const std::string& node, const std::string& top, const std::string& leaf);

// What the panel's motion and friction fields hold, as typed; an empty field is not sent.
struct PanelFields {
  std::string inclination, spin;               // [rad], [rad/s]
  std::string friction_law;                    // "" = keep the law; else one of law_names()
  std::map<std::string, std::string> friction;  // parameter name -> text; empty texts keep the law in force's
  std::map<std::string, std::string> contact;   // kContactFields' name -> text; an empty text is not sent
};

// The finite contact's and air's fields (TopCommand's names, physics.md section 12); their units and ranges are
// the command schema's (field_unit, field_range).
struct ContactField {
  const char* name;
  const char* symbol;  // physics.md's: short enough for two fields side by side in the dock
};
constexpr ContactField kContactFields[] = {
    {"patch_radius", "a"}, {"rolling_resistance", "delta"}, {"spin_drag", "k"}, {"drag", "c"}};

// A command field's unit and allowed range as the command schema gives them (top_sim::command_fields), for the
// panel's labels and tool tips.
std::string field_unit(const std::string& name);
std::string field_range(const std::string& name);

// The fields as one TopCommand, checked with the core's rules (top_sim::validate of a Command and of a friction
// law); "" or an error naming the field, the text and the allowed range. Law parameters left empty are not given:
// the node keeps their values in force (TopCommand.friction_given).
std::string fields_to_message(const PanelFields& fields, top_sim::TopCommand& out);

// The laws a panel offers and the parameters each reads (the core's tables; the table law needs points, which a
// panel field cannot carry, so it is not offered).
std::vector<std::string> law_names();
std::vector<std::string> law_parameters(const std::string& law);

// "sleeping, slipping, phi 0.270 / phi* 0.270 | real time x0.98 of 1" (paused, fault shown when so).
std::string status_line(const top_sim::TopState& s);

// A real-time factor typed in the panel: "" or the error (>= 0 and finite, 0 = as fast as possible).
std::string parse_real_time_factor(const std::string& text, double& value);

// ---- What the panel says: plain sentences, word-wrapped under the fields ----------------------------------------
// `text` as a sentence: first letter capitalised, a full stop at the end ("paused" -> "Paused.").
std::string sentence(const std::string& text);
// After Apply: "Sent to top 'b': inclination 0.2 rad, spin 150 rad/s and friction law coulomb with mu 0.35."
std::string sent_message(const top_sim::TopCommand& c, const std::string& top);
// Apply refused by the panel's checks: "Nothing was sent: inclination = 'abc': must be a number."
std::string refused_message(const std::string& error);
// A service call's outcome: its answer as a sentence ("Done." or "Refused." when it gave none), or that the
// service did not answer.
std::string service_message(const std::string& service, bool answered, bool success, const std::string& answer);

// ---- Fields that follow the picked top -----------------------------------------------------------------------
// A value as a field shows it: `decimals` < 0 the shortest text that reads back as the same double (an alpha
// sent as 0.15 shows "0.15"), else fixed with that many decimals (a spin that keeps changing).
std::string field_text(double value, int decimals);

// A field that shows the picked top's value (alpha, spin, requested real-time factor) unless the user is editing
// it: while it has the keyboard focus, and while it holds text typed and not yet applied. The widget reports
// focus and edits and shows what follow() returns; only edited fields are sent.
class FollowedField {
 public:
  explicit FollowedField(int decimals = -1) : decimals_(decimals) {}
  void typed(const std::string& text);  // the user changed the text (not the panel); blank = follow again
  void applied() { edited_ = false; }   // its value was sent: show the top's again
  bool edited() const { return edited_; }
  // The text to show for the top's `value`, or nothing: keep the field's text (the user's).
  std::optional<std::string> follow(double value, bool has_focus) const;

 private:
  int decimals_;
  bool edited_ = false;
};

// The interactive markers (top_sim_interactive): a ring about the plane's x axis tilts the plane, a handle along
// the plane's normal sets the spin. Both return "" or the core's error for the resulting value (nothing is sent).
constexpr double kSpinPerMetre = 2000.0;  // spin handle: 1 cm of drag changes the spin by 20 rad/s

// The ring turned by the unit quaternion (w, x, y, z) from its rest pose: alpha = alpha_now + its angle about x
// (the part of the turn about the plane's x axis; a turn about other axes does not tilt the plane).
std::string inclination_from_ring(double alpha_now, double w, double x, double y, double z, double& alpha);
// The handle dragged `drag` metres along the normal: spin = spin_now + kSpinPerMetre * drag.
std::string spin_from_handle(double spin_now, double drag, double& spin);

// rviz's orbit camera for a scene's view hint (docs/interfaces.md, `view`), which the node sets as ~view/camera and
// ~view/distance: `low` looks from the side just above the plane, `top` from above, `follow` as the shipped config
// does; a distance of 0 keeps `current_distance`. None for the camera "unset" (or a word the panel does not know).
// `low` also aims halfway up from the plane to the label over a body reaching `reach` (~view/reach) and backs off
// until that whole band is in the vertical field of view: a close side view must not cut the label off.
struct OrbitView {
  double pitch = 0.0;     // [rad] above the plane
  double distance = 0.0;  // [m] from the follow frame
  double focal_z = kShippedFocalZ;  // [m] the point looked at, above the follow frame
  static constexpr double kShippedFocalZ = 0.012;  // rviz/top_sim.rviz's
};
constexpr double kFieldOfView = 0.785398;  // [rad] vertical, rviz/top_sim.rviz's
// [m] the top of the label above the contact point of a body reaching `reach` (markers.cpp places it, two lines).
double label_top(double reach);
std::optional<OrbitView> orbit_view(const std::string& camera, double distance, double current_distance,
                                    double reach = 0.0);

}  // namespace top_sim_rviz
