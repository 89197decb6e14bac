#include "control_panel.hpp"

#include <QComboBox>
#include <algorithm>
#include <QFormLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QPushButton>
#include <QScrollArea>
#include <QVBoxLayout>
#include <fstream>
#include <sstream>

#include <dynamic_reconfigure/Reconfigure.h>
#include <pluginlib/class_list_macros.hpp>
#include <std_msgs/String.h>
#include <std_srvs/SetBool.h>
#include <std_srvs/Trigger.h>

#include "panel_logic.hpp"
#include "top_sim/Kill.h"
#include "top_sim/Spawn.h"
#include "top_sim/TopCommand.h"

namespace top_sim_rviz {

namespace {

QPushButton* button(const char* text, QWidget* parent) { return new QPushButton(QString::fromUtf8(text), parent); }

std::string text_of(const QLineEdit* field) { return field->text().trimmed().toStdString(); }

// A service call's outcome as one line: its message, or why the call did not happen.
template <class Srv>
std::string call(const std::string& name, Srv& srv) {
  if (!ros::service::call(name, srv)) return "service " + name + " did not answer (is the node running?)";
  return srv.response.message.empty() ? std::string(srv.response.success ? "done" : "refused")
                                      : srv.response.message;
}

}  // namespace

ControlWidget::ControlWidget(QWidget* parent) : QWidget(parent) {
  auto* layout = new QVBoxLayout(this);
  layout->addWidget(build_tops());
  layout->addWidget(build_motion());
  layout->addWidget(build_friction());
  layout->addWidget(build_run());
  message_label_ = new QLabel(this);
  message_label_->setWordWrap(true);
  layout->addWidget(message_label_);
  layout->addStretch();
  subscribe();
}

QWidget* ControlWidget::build_tops() {
  auto* box = new QGroupBox("Top", this);
  auto* form = new QFormLayout(box);
  tops_ = new QComboBox(box);
  tops_->addItem(kLaunchTopName);
  status_ = new QLabel("no state yet", box);
  status_->setWordWrap(true);
  form->addRow("top", tops_);
  form->addRow("state", status_);
  spawn_name_ = new QLineEdit(box);
  spawn_file_ = new QLineEdit(box);
  spawn_file_->setPlaceholderText("scene file (empty: the node's scene)");
  auto* row = new QHBoxLayout();
  QPushButton* spawn_button = button("Spawn", box);
  QPushButton* kill_button = button("Kill picked", box);
  row->addWidget(spawn_button);
  row->addWidget(kill_button);
  form->addRow("new top", spawn_name_);
  form->addRow("scene", spawn_file_);
  form->addRow(row);
  connect(tops_, QOverload<int>::of(&QComboBox::activated), this, &ControlWidget::pick_top);
  connect(spawn_button, &QPushButton::clicked, this, &ControlWidget::spawn);
  connect(kill_button, &QPushButton::clicked, this, &ControlWidget::kill);
  return box;
}

QWidget* ControlWidget::build_motion() {
  auto* box = new QGroupBox("Inclination and spin", this);
  auto* form = new QFormLayout(box);
  inclination_ = new QLineEdit(box);
  inclination_->setPlaceholderText("alpha [rad], |alpha| < pi/2");
  spin_ = new QLineEdit(box);
  spin_->setPlaceholderText("shell spin [rad/s]");
  form->addRow("inclination", inclination_);
  form->addRow("spin", spin_);
  return box;
}

QWidget* ControlWidget::build_friction() {
  auto* box = new QGroupBox("Friction law", this);
  auto* form = new QFormLayout(box);
  law_ = new QComboBox(box);
  law_->addItem("");  // keep the law in force
  for (const std::string& law : law_names()) law_->addItem(QString::fromStdString(law));
  form->addRow("law", law_);
  for (const std::string& law : law_names())
    for (const std::string& p : law_parameters(law)) {
      auto* field = new QLineEdit(box);
      field->setPlaceholderText("in force");
      parameters_[p] = field;
      form->addRow(QString::fromStdString(p), field);
    }
  QPushButton* apply_button = button("Apply to the picked top", box);
  form->addRow(apply_button);
  connect(law_, QOverload<int>::of(&QComboBox::currentIndexChanged), this, &ControlWidget::show_law);
  connect(apply_button, &QPushButton::clicked, this, &ControlWidget::apply);
  show_law(0);
  return box;
}

QWidget* ControlWidget::build_run() {
  auto* box = new QGroupBox("Run", this);
  auto* row = new QHBoxLayout(box);
  pause_ = button("Pause", box);
  QPushButton* reset_button = button("Reset", box);
  rtf_ = new QLineEdit(box);
  rtf_->setPlaceholderText("real-time factor");
  QPushButton* rtf_button = button("Set", box);
  row->addWidget(pause_);
  row->addWidget(reset_button);
  row->addWidget(rtf_);
  row->addWidget(rtf_button);
  connect(pause_, &QPushButton::clicked, this, &ControlWidget::toggle_pause);
  connect(reset_button, &QPushButton::clicked, this, &ControlWidget::reset);
  connect(rtf_button, &QPushButton::clicked, this, &ControlWidget::set_real_time_factor);
  return box;
}

void ControlWidget::set_node(const std::string& node) {
  node_ = node;
  commands_.clear();
  subscribe();
}

void ControlWidget::subscribe() {
  states_ = nh_.subscribe(node_ + "/top_states", 1, &ControlWidget::on_states, this);
  follow_ = nh_.advertise<std_msgs::String>(node_ + "/follow", 1, true);
}

std::string ControlWidget::top() const { return tops_->currentText().toStdString(); }

QLineEdit* ControlWidget::parameter_field(const std::string& name) const {
  auto it = parameters_.find(name);
  return it == parameters_.end() ? nullptr : it->second;
}

void ControlWidget::show_message(const std::string& text) {
  message_ = text;
  message_label_->setText(QString::fromStdString(text));
}

void ControlWidget::show_law(int) {
  const std::vector<std::string> used = law_parameters(law_->currentText().toStdString());
  for (auto& [name, field] : parameters_)
    field->setEnabled(std::find(used.begin(), used.end(), name) != used.end());
}

void ControlWidget::apply() {
  PanelFields f;
  f.inclination = text_of(inclination_);
  f.spin = text_of(spin_);
  f.friction_law = law_->currentText().toStdString();
  for (const std::string& p : law_parameters(f.friction_law)) f.friction[p] = text_of(parameters_[p]);
  top_sim::TopCommand c;
  const std::string error = to_command(f, c);
  if (!error.empty()) return show_message(error);  // nothing is sent
  const std::string topic = top_name_of(node_, top(), "command");
  auto it = commands_.find(topic);
  if (it == commands_.end()) {
    it = commands_.emplace(topic, nh_.advertise<top_sim::TopCommand>(topic, 10, true)).first;
    ros::WallDuration(0.3).sleep();  // let the node connect before the first (latched) message
  }
  it->second.publish(c);
  show_message("sent to " + topic);
}

void ControlWidget::toggle_pause() {
  std_srvs::SetBool srv;
  srv.request.data = !paused_;
  const std::string answer = call(node_ + "/pause", srv);
  if (srv.response.success) paused_ = !paused_;
  pause_->setText(paused_ ? "Resume" : "Pause");
  show_message(answer);
}

void ControlWidget::reset() {
  std_srvs::Trigger srv;
  show_message(call(node_ + "/reset", srv));
}

void ControlWidget::set_real_time_factor() {
  double factor = 0.0;
  const std::string error = parse_real_time_factor(text_of(rtf_), factor);
  if (!error.empty()) return show_message(error);
  dynamic_reconfigure::Reconfigure srv;
  dynamic_reconfigure::DoubleParameter p;
  p.name = "real_time_factor";
  p.value = factor;
  srv.request.config.doubles.push_back(p);
  const std::string name = node_ + "/set_parameters";
  show_message(ros::service::call(name, srv) ? "real_time_factor set" : "service " + name + " did not answer");
}

void ControlWidget::spawn() {
  top_sim::Spawn srv;
  srv.request.name = text_of(spawn_name_);
  const std::string file = text_of(spawn_file_);
  if (!file.empty()) {
    std::ifstream in(file);
    if (!in) return show_message("scene file = '" + file + "': cannot be read");
    std::ostringstream text;
    text << in.rdbuf();
    srv.request.scene = text.str();
  }
  show_message(call(node_ + "/spawn", srv));
}

void ControlWidget::kill() {
  top_sim::Kill srv;
  srv.request.name = top();
  show_message(call(node_ + "/kill", srv));
}

void ControlWidget::pick_top(int) {
  std_msgs::String name;
  name.data = top();
  follow_.publish(name);
}

// The tops the node has (its order) and the picked top's state.
void ControlWidget::on_states(const top_sim::TopStateArray::ConstPtr& states) {
  const std::string picked = top();
  QStringList names;
  for (const std::string& n : states->names) names << QString::fromStdString(n);
  QStringList shown;
  for (int i = 0; i < tops_->count(); ++i) shown << tops_->itemText(i);
  if (names != shown && !names.empty()) {
    tops_->clear();
    tops_->addItems(names);
    const int keep = tops_->findText(QString::fromStdString(picked));
    tops_->setCurrentIndex(keep >= 0 ? keep : 0);
  }
  for (std::size_t i = 0; i < states->names.size() && i < states->states.size(); ++i)
    if (states->names[i] == top()) {
      paused_ = states->states[i].paused;
      pause_->setText(paused_ ? "Resume" : "Pause");
      status_->setText(QString::fromStdString(status_line(states->states[i])));
    }
}

ControlPanel::ControlPanel(QWidget* parent) : rviz::Panel(parent) {
  auto* layout = new QVBoxLayout(this);
  auto* row = new QHBoxLayout();
  node_ = new QLineEdit("/top_sim", this);
  row->addWidget(new QLabel("node", this));
  row->addWidget(node_);
  layout->addLayout(row);
  widget_ = new ControlWidget(this);
  auto* scroll = new QScrollArea(this);  // the dock may be shorter than the panel: scroll, do not grow the window
  scroll->setWidget(widget_);
  scroll->setWidgetResizable(true);
  layout->addWidget(scroll);
  connect(node_, &QLineEdit::editingFinished, this, [this] {
    widget_->set_node(node_->text().trimmed().toStdString());
    Q_EMIT configChanged();
  });
}

void ControlPanel::load(const rviz::Config& config) {
  rviz::Panel::load(config);
  QString node;
  if (config.mapGetString("Node", &node) && !node.isEmpty()) {
    node_->setText(node);
    widget_->set_node(node.toStdString());
  }
}

void ControlPanel::save(rviz::Config config) const {
  rviz::Panel::save(config);
  config.mapSetValue("Node", node_->text());
}

}  // namespace top_sim_rviz

PLUGINLIB_EXPORT_CLASS(top_sim_rviz::ControlPanel, rviz::Panel)
