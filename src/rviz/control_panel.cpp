#include "control_panel.hpp"

#include <QComboBox>
#include <QEvent>
#include <QFormLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QPushButton>
#include <QScrollArea>
#include <QTimer>
#include <QStackedWidget>
#include <QVBoxLayout>
#include <fstream>
#include <sstream>

#include <dynamic_reconfigure/Reconfigure.h>
#include <pluginlib/class_list_macros.hpp>
#include <ros/package.h>
#include <ros/param.h>
#include <rviz/properties/property.h>
#include <rviz/properties/vector_property.h>
#include <rviz/render_panel.h>
#include <rviz/view_controller.h>
#include <rviz/view_manager.h>
#include <rviz/visualization_manager.h>
#include <std_msgs/String.h>
#include <std_srvs/SetBool.h>
#include <std_srvs/Trigger.h>

#include "panel_logic.hpp"
#include "top_sim/Kill.h"
#include "top_sim/Spawn.h"
#include "top_sim/TopCommand.h"
#include "top_sim/data_path.hpp"
#include "top_sim/scene.hpp"

namespace top_sim_rviz {

namespace {

QPushButton* button(const char* text, QWidget* parent) { return new QPushButton(QString::fromUtf8(text), parent); }

std::string text_of(const QLineEdit* field) { return field->text().trimmed().toStdString(); }

// A service call's outcome as one sentence: its answer, or why the call did not happen.
template <class Srv>
std::string call(const std::string& name, Srv& srv) {
  const bool answered = ros::service::call(name, srv);
  return service_message(name, answered, srv.response.success, srv.response.message);
}

// A form that fits a narrow dock: labels beside their fields, fields as wide as the dock, small margins.
QFormLayout* form_of(QWidget* box) {
  auto* form = new QFormLayout(box);
  form->setFieldGrowthPolicy(QFormLayout::AllNonFixedFieldsGrow);
  form->setRowWrapPolicy(QFormLayout::DontWrapRows);
  form->setContentsMargins(6, 4, 6, 4);
  form->setVerticalSpacing(4);
  return form;
}

// A field and its button on one row, the field taking the width the button leaves.
QHBoxLayout* field_with_button(QLineEdit* field, QPushButton* b) {
  auto* row = new QHBoxLayout();
  row->addWidget(field, 1);
  row->addWidget(b);
  return row;
}

}  // namespace

// The dock of rviz/top_sim.rviz leaves the widget about 330 x 620 px: the groups are stacked so that every field
// is wider than its text and inclination, spin and Apply come right after the top's state. The groups scroll in a
// smaller dock (never sideways); the answer stays below them, in view whatever the dock's height.
ControlWidget::ControlWidget(QWidget* parent) : QWidget(parent) {
  auto* groups = new QWidget(this);
  auto* stack = new QVBoxLayout(groups);
  stack->setContentsMargins(0, 0, 0, 0);
  stack->setSpacing(4);
  stack->addWidget(build_top());
  stack->addWidget(build_change());
  stack->addWidget(build_run());
  stack->addWidget(build_spawn());
  stack->addStretch();
  scroll_ = new QScrollArea(this);
  scroll_->setWidget(groups);
  scroll_->setWidgetResizable(true);
  scroll_->setFrameShape(QFrame::NoFrame);
  scroll_->setHorizontalScrollBarPolicy(Qt::ScrollBarAlwaysOff);
  message_label_ = new QLabel(this);
  message_label_->setWordWrap(true);  // a long answer wraps inside the dock
  message_label_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  message_label_->setSizePolicy(QSizePolicy::Preferred, QSizePolicy::Minimum);  // never squeezed by the groups
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->setSpacing(4);
  layout->addWidget(scroll_, 1);
  layout->addWidget(message_label_);
  subscribe();
}

// A field that shows the picked top's value until the user types in it (FollowedField).
QLineEdit* ControlWidget::followed_field(FollowedField& follow, const char* placeholder, QWidget* parent) {
  auto* field = new QLineEdit(parent);
  field->setPlaceholderText(placeholder);
  connect(field, &QLineEdit::textEdited, this, [&follow](const QString& text) { follow.typed(text.toStdString()); });
  return field;
}

QWidget* ControlWidget::build_top() {
  auto* box = new QGroupBox("Top", this);
  auto* form = form_of(box);
  tops_ = new QComboBox(box);
  tops_->addItem(kLaunchTopName);
  status_ = new QLabel("No state received yet.", box);
  status_->setWordWrap(true);
  // At most three lines (a fault's description is longer; its whole text is the tooltip): the fields stay in view.
  status_->setMaximumHeight(3 * status_->fontMetrics().lineSpacing());
  status_->setAlignment(Qt::AlignLeft | Qt::AlignTop);
  form->addRow("top", tops_);
  form->addRow("state", status_);
  connect(tops_, QOverload<int>::of(&QComboBox::activated), this, &ControlWidget::pick_top);
  return box;
}

// Inclination, spin and friction law of the picked top: the fields show its values; what the user typed is sent.
QWidget* ControlWidget::build_change() {
  auto* box = new QGroupBox("Change the picked top", this);
  auto* form = form_of(box);
  inclination_ = followed_field(inclination_follow_, ("alpha, " + field_range("inclination")).c_str(), box);
  spin_ = followed_field(spin_follow_, "shell spin", box);
  form->addRow("inclination [rad]", inclination_);
  form->addRow("spin [rad/s]", spin_);
  law_ = new QComboBox(box);
  law_->addItem("in force");  // keep the law in force (show_state names it); the others: change to that law
  for (const std::string& law : law_names()) law_->addItem(QString::fromStdString(law));
  form->addRow("friction law", law_);
  form->addRow(build_friction_parameters(box));
  form->addRow(build_contact_fields(box));
  QPushButton* apply_button = button("Apply to the picked top", box);
  form->addRow(apply_button);
  connect(law_, QOverload<int>::of(&QComboBox::currentIndexChanged), this, &ControlWidget::show_law);
  connect(apply_button, &QPushButton::clicked, this, &ControlWidget::apply);
  connect(inclination_, &QLineEdit::returnPressed, this, &ControlWidget::apply);
  connect(spin_, &QLineEdit::returnPressed, this, &ControlWidget::apply);
  show_law(0);
  return box;
}

// One page per entry of the law box: its parameters side by side (empty: the value in force is kept).
QWidget* ControlWidget::build_friction_parameters(QWidget* parent) {
  law_pages_ = new QStackedWidget(parent);
  law_pages_->addWidget(new QWidget(law_pages_));  // the law in force is kept: no parameters (the page is hidden)
  for (const std::string& law : law_names()) {
    auto* page = new QWidget(law_pages_);
    auto* row = new QHBoxLayout(page);
    row->setContentsMargins(0, 0, 0, 0);
    for (const std::string& p : law_parameters(law)) {
      auto* field = new QLineEdit(page);
      field->setPlaceholderText("in force");
      field->setMinimumWidth(50);
      parameters_[p] = field;
      row->addWidget(new QLabel(QString::fromStdString(p), page));
      row->addWidget(field, 1);
    }
    law_pages_->addWidget(page);
  }
  return law_pages_;
}

// Patch radius, rolling resistance and air, two to a row (the dock is narrow); empty: the value in force is kept.
// TopState does not carry them, so they show what was typed, not the top's values.
QWidget* ControlWidget::build_contact_fields(QWidget* parent) {
  auto* grid = new QWidget(parent);
  auto* rows = new QVBoxLayout(grid);
  rows->setContentsMargins(0, 0, 0, 0);
  QHBoxLayout* row = nullptr;
  for (const ContactField& f : kContactFields) {
    if (row == nullptr || row->count() == 4) {
      row = new QHBoxLayout();
      rows->addLayout(row);
    }
    auto* field = new QLineEdit(grid);
    field->setPlaceholderText("in force");
    const std::string unit = field_unit(f.name);
    field->setToolTip(QString::fromStdString(std::string(f.name) + " " + f.symbol + " [" + unit + "], " +
                                             field_range(f.name)));
    field->setMinimumWidth(50);
    contact_[f.name] = field;
    row->addWidget(new QLabel(QString::fromStdString(std::string(f.symbol) + " [" + unit + "]"), grid));
    row->addWidget(field, 1);
    connect(field, &QLineEdit::returnPressed, this, &ControlWidget::apply);
  }
  return grid;
}

QWidget* ControlWidget::build_run() {
  auto* box = new QGroupBox("Run", this);
  auto* form = form_of(box);
  pause_ = button("Pause", box);
  QPushButton* reset_button = button("Reset", box);
  auto* buttons = new QHBoxLayout();
  buttons->addWidget(pause_);
  buttons->addWidget(reset_button);
  form->addRow(buttons);
  rtf_ = followed_field(rtf_follow_, "0 = fast as possible", box);
  QPushButton* rtf_button = button("Set", box);
  form->addRow("real-time factor", field_with_button(rtf_, rtf_button));
  connect(pause_, &QPushButton::clicked, this, &ControlWidget::toggle_pause);
  connect(reset_button, &QPushButton::clicked, this, &ControlWidget::reset);
  connect(rtf_button, &QPushButton::clicked, this, &ControlWidget::set_real_time_factor);
  connect(rtf_, &QLineEdit::returnPressed, this, &ControlWidget::set_real_time_factor);
  return box;
}

QWidget* ControlWidget::build_spawn() {
  auto* box = new QGroupBox("Spawn and kill", this);
  auto* form = form_of(box);
  spawn_name_ = new QLineEdit(box);
  spawn_name_->setPlaceholderText("name of the new top");
  spawn_file_ = new QLineEdit(box);
  spawn_file_->setPlaceholderText("empty: the node's scene");
  spawn_file_->setToolTip("A shipped scene's name (e.g. tippe_top) or a scene file's path; empty: the node's scene.");
  auto* row = new QHBoxLayout();
  QPushButton* spawn_button = button("Spawn", box);
  QPushButton* kill_button = button("Kill picked", box);
  row->addWidget(spawn_button);
  row->addWidget(kill_button);
  form->addRow("new top", spawn_name_);
  form->addRow("scene", spawn_file_);
  form->addRow(row);
  connect(spawn_button, &QPushButton::clicked, this, &ControlWidget::spawn);
  connect(kill_button, &QPushButton::clicked, this, &ControlWidget::kill);
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

QLineEdit* ControlWidget::contact_field(const std::string& name) const {
  auto it = contact_.find(name);
  return it == contact_.end() ? nullptr : it->second;
}

void ControlWidget::show_message(const std::string& text) {
  message_ = text;
  message_label_->setText(QString::fromStdString(text));
}

void ControlWidget::show_law(int index) {
  law_pages_->setCurrentIndex(index);
  law_pages_->setVisible(index > 0);  // the law in force kept: no row of parameters
}

// Only what the user typed is sent (the other fields show the top's values); what was sent follows the top again.
void ControlWidget::apply() {
  PanelFields f;
  if (inclination_follow_.edited()) f.inclination = text_of(inclination_);
  if (spin_follow_.edited()) f.spin = text_of(spin_);
  f.friction_law = law_->currentIndex() > 0 ? law_->currentText().toStdString() : "";  // 0: keep the law in force
  for (const std::string& p : law_parameters(f.friction_law)) f.friction[p] = text_of(parameters_[p]);
  for (const auto& [name, field] : contact_) f.contact[name] = text_of(field);
  top_sim::TopCommand c;
  const std::string error = fields_to_message(f, c);
  if (!error.empty()) return show_message(refused_message(error));  // nothing is sent
  c.name = top();  // ~tops/command steers any top, with or without its own topics (~per_top_topics)
  const std::string topic = top_name_of(node_, "", "tops/command");
  auto it = commands_.find(topic);
  if (it == commands_.end()) {
    it = commands_.emplace(topic, nh_.advertise<top_sim::TopCommand>(topic, 10, true)).first;
    ros::WallDuration(0.3).sleep();  // let the node connect before the first (latched) message
  }
  it->second.publish(c);
  if (c.set_inclination) inclination_follow_.applied();
  if (c.set_spin) spin_follow_.applied();
  show_message(sent_message(c, top()));
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
  if (!error.empty()) return show_message(sentence("The real-time factor was not set: " + error));
  dynamic_reconfigure::Reconfigure srv;
  dynamic_reconfigure::DoubleParameter p;
  p.name = "real_time_factor";
  p.value = factor;
  srv.request.config.doubles.push_back(p);
  const std::string name = node_ + "/set_parameters";
  if (!ros::service::call(name, srv)) return show_message(service_message(name, false, false, ""));
  rtf_follow_.applied();
  show_message("The real-time factor is set to " + field_text(factor, -1) +
               (factor == 0.0 ? " (as fast as possible)." : "."));
}

// The scene field takes what top_sim_run and scene:= take: a shipped scene's name or a file (the core's rule).
void ControlWidget::spawn() {
  top_sim::Spawn srv;
  srv.request.name = text_of(spawn_name_);
  const std::string given = text_of(spawn_file_);
  if (!given.empty()) {
    std::string file;
    try {
      file = top_sim::scene_path(given, ros::package::getPath("top_sim") + "/config");
    } catch (const top_sim::SceneError& e) {
      return show_message(sentence(std::string("Nothing was spawned: ") + e.what()));
    }
    std::ifstream in(file);
    if (!in) return show_message("Nothing was spawned: the scene file " + file + " cannot be read.");
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
    if (states->names[i] == top()) show_state(states->states[i]);
}

void ControlWidget::show_state(const top_sim::TopState& s) {
  paused_ = s.paused;
  pause_->setText(paused_ ? "Resume" : "Pause");
  status_->setText(QString::fromStdString(status_line(s)));
  status_->setToolTip(status_->text());
  const QString in_force = QString::fromStdString(s.friction_law.empty() ? "in force" : "in force: " + s.friction_law);
  if (law_->itemText(0) != in_force) law_->setItemText(0, in_force);
  const auto follow = [](QLineEdit* field, const FollowedField& f, double value) {
    const std::optional<std::string> text = f.follow(value, field->hasFocus());
    if (text && field->text().toStdString() != *text) field->setText(QString::fromStdString(*text));
  };
  follow(inclination_, inclination_follow_, s.alpha);
  follow(spin_, spin_follow_, s.spin);
  follow(rtf_, rtf_follow_, s.requested_real_time_factor);
}

ControlPanel::ControlPanel(QWidget* parent) : rviz::Panel(parent) {
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(4, 4, 4, 4);
  auto* row = new QHBoxLayout();
  node_ = new QLineEdit("/top_sim", this);
  row->addWidget(new QLabel("node", this));
  row->addWidget(node_);
  layout->addLayout(row);
  widget_ = new ControlWidget(this);  // it scrolls its groups in a dock shorter than they are
  layout->addWidget(widget_, 1);
  connect(node_, &QLineEdit::editingFinished, this, [this] {
    widget_->set_node(node_->text().trimmed().toStdString());
    Q_EMIT configChanged();
  });
}

// rviz 1.14 goes on rendering into its main window for a few frames after closing it at shutdown (SIGINT, Ctrl-C,
// File > Quit); under Mesa's llvmpipe the framebuffer is then 0 x 0 and the clear writes past its 0-byte tile
// arrays, corrupting the heap: rviz died with -11 or -6 in most runs with this config and a node (issue 46). While
// the window is hidden nothing is drawn, so rendering stops with it and starts again when it shows.
void ControlPanel::onInitialize() {
  view_timer_ = new QTimer(this);
  connect(view_timer_, &QTimer::timeout, this, &ControlPanel::apply_view_hint);
  view_timer_->start(500);  // until the node has set its view (it may start after rviz)
  frame_ = vis_manager_->getRenderPanel() ? vis_manager_->getRenderPanel()->window() : nullptr;
  if (!frame_) return;
  frame_->installEventFilter(this);
  connect(vis_manager_, &QObject::destroyed, this, [this] {  // rviz deletes its manager before the panels
    frame_->removeEventFilter(this);
    frame_ = nullptr;
  });
}

bool ControlPanel::eventFilter(QObject* watched, QEvent* event) {
  if (frame_ && watched == frame_ && event->type() == QEvent::Hide) vis_manager_->stopUpdate();
  if (frame_ && watched == frame_ && event->type() == QEvent::Show) vis_manager_->startUpdate();
  return rviz::Panel::eventFilter(watched, event);
}

void ControlPanel::apply_view_hint() {
  const std::string node = node_->text().trimmed().toStdString();
  std::string camera;
  double distance = 0.0;
  double reach = 0.0;
  if (!ros::param::get(node + "/view/camera", camera)) return;
  ros::param::get(node + "/view/distance", distance);
  ros::param::get(node + "/view/reach", reach);
  view_timer_->stop();
  rviz::ViewController* view = vis_manager_->getViewManager()->getCurrent();
  if (!view || view->getClassId() != "rviz/Orbit") return;  // another camera is the user's choice: it stays
  const double now = view->subProp("Distance")->getValue().toDouble();
  const std::optional<OrbitView> pose = orbit_view(camera, distance, now, reach);
  if (!pose) return;
  view->subProp("Pitch")->setValue(pose->pitch);
  view->subProp("Distance")->setValue(pose->distance);
  // Over the top, not beside it (the shipped config looks 5 cm to its side), at the height that shows the label.
  if (auto* focal = dynamic_cast<rviz::VectorProperty*>(view->subProp("Focal Point")))
    focal->setVector(Ogre::Vector3(0.0f, 0.0f, static_cast<float>(pose->focal_z)));
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
