// The control panel (docs/ros.md, "Control in rviz"): a thin client of the node's topics and services. The widget
// works without rviz (a test drives it under QT_QPA_PLATFORM=offscreen); ControlPanel is its rviz::Panel shell.
#pragma once

#include <QWidget>
#include <optional>
#include <map>
#include <string>

#include <ros/ros.h>
#include <rviz/panel.h>

#include "panel_logic.hpp"
#include "top_sim/TopStateArray.h"

class QComboBox;
class QLabel;
class QLineEdit;
class QPushButton;
class QScrollArea;
class QStackedWidget;
class QTimer;

namespace top_sim_rviz {

class ControlWidget : public QWidget {
  Q_OBJECT

 public:
  explicit ControlWidget(QWidget* parent = nullptr);

  void set_node(const std::string& node);  // "/top_sim": the node whose tops the panel steers
  const std::string& node() const { return node_; }
  std::string top() const;                 // the picked top
  const std::string& message() const { return message_; }  // the last error or answer shown

  // The fields, for a test or a saved config.
  QComboBox* top_field() const { return tops_; }
  QLineEdit* inclination_field() const { return inclination_; }
  QLineEdit* spin_field() const { return spin_; }
  QComboBox* law_field() const { return law_; }
  QLineEdit* parameter_field(const std::string& name) const;
  QLineEdit* contact_field(const std::string& name) const;  // kContactFields' names
  QLineEdit* real_time_factor_field() const { return rtf_; }
  QLineEdit* spawn_name_field() const { return spawn_name_; }
  QLineEdit* spawn_file_field() const { return spawn_file_; }
  QScrollArea* groups_area() const { return scroll_; }  // the groups of fields (they scroll in a short dock)
  QLabel* answer_label() const { return message_label_; }  // the last answer, below the groups, always in view

  void show_message(const std::string& text);  // the answer line

 public Q_SLOTS:
  void apply();          // inclination, spin, friction law, contact and air -> the picked top's ~command
  void toggle_pause();   // ~pause
  void reset();          // ~reset
  void set_real_time_factor();  // dynamic_reconfigure's real_time_factor
  void spawn();          // ~spawn: the name, the text of a scene file or shipped scene ("" = the node's scene)
  void kill();           // ~kill the picked top
  void pick_top(int index);  // follow it with the camera (~follow)
  void show_law(int index);  // enable the picked law's parameter fields

 private:
  void on_states(const top_sim::TopStateArray::ConstPtr& states);
  void show_state(const top_sim::TopState& state);  // the picked top's: status line and followed fields
  void subscribe();
  QLineEdit* followed_field(FollowedField& follow, const char* placeholder, QWidget* parent);
  QWidget* build_top();
  QWidget* build_change();
  QWidget* build_friction_parameters(QWidget* parent);
  QWidget* build_contact_fields(QWidget* parent);
  QWidget* build_run();
  QWidget* build_spawn();

  std::string node_ = "/top_sim";
  std::string message_;
  bool paused_ = false;
  ros::NodeHandle nh_;
  ros::Subscriber states_;
  ros::Publisher follow_;
  std::map<std::string, ros::Publisher> commands_;  // per top
  QComboBox* tops_ = nullptr;
  QLineEdit *inclination_ = nullptr, *spin_ = nullptr, *rtf_ = nullptr, *spawn_name_ = nullptr,
            *spawn_file_ = nullptr;
  QComboBox* law_ = nullptr;
  QStackedWidget* law_pages_ = nullptr;  // the picked law's parameters only: one row, not one row per parameter
  std::map<std::string, QLineEdit*> parameters_;
  std::map<std::string, QLineEdit*> contact_;  // patch, rolling resistance, air: sent when not empty
  FollowedField inclination_follow_, spin_follow_{1}, rtf_follow_;
  QPushButton* pause_ = nullptr;
  QLabel *status_ = nullptr, *message_label_ = nullptr;
  QScrollArea* scroll_ = nullptr;
};

class ControlPanel : public rviz::Panel {
  Q_OBJECT

 public:
  explicit ControlPanel(QWidget* parent = nullptr);
  void onInitialize() override;
  void load(const rviz::Config& config) override;
  void save(rviz::Config config) const override;
  bool eventFilter(QObject* watched, QEvent* event) override;  // rviz's window hidden: no rendering (onInitialize)

 private:
  // Turns rviz's camera to the node's scene's view hint (~view/camera, ~view/distance), once, when the node is up.
  void apply_view_hint();

  ControlWidget* widget_;
  QLineEdit* node_;
  QTimer* view_timer_ = nullptr;
  QWidget* frame_ = nullptr;  // rviz's main window
};

}  // namespace top_sim_rviz
