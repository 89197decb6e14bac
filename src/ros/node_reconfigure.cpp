#include "node_reconfigure.hpp"

#include <cmath>
#include <optional>
#include <utility>

#include "node_parameters.hpp"

namespace top_sim_ros {

namespace {

// dynamic_reconfigure's friction fields are named like the core's parameters.
void friction_to_config(const top_sim::FrictionLaw& law, top_sim::TopSimConfig& cfg) {
  cfg.friction_law = top_sim::to_string(law.kind);
#define TOP_SIM_COPY_TO_CONFIG(kind, name, range) cfg.name = law.name;
  TOP_SIM_FRICTION_PARAMETERS(TOP_SIM_COPY_TO_CONFIG)
#undef TOP_SIM_COPY_TO_CONFIG
}

// The law the config shows (it mirrors the law in force but for a table's points, which it cannot carry).
top_sim::FrictionLaw law_of_config(const top_sim::TopSimConfig& cfg) {
  top_sim::FrictionLaw law;
  top_sim::parse_friction_law_kind(cfg.friction_law, law.kind);
#define TOP_SIM_COPY_FROM_CONFIG(kind, name, range) law.name = cfg.name;
  TOP_SIM_FRICTION_PARAMETERS(TOP_SIM_COPY_FROM_CONFIG)
#undef TOP_SIM_COPY_FROM_CONFIG
  return law;
}

// The config's fields of law `kind` as a change over the law in force (top_sim::changed_law, the rule of every
// adapter); the other laws' fields stay as they are in force.
top_sim::FrictionChange friction_from_config(const top_sim::TopSimConfig& cfg, top_sim::FrictionLawKind kind) {
  top_sim::FrictionChange change;
  change.kind = kind;
  for (const top_sim::FrictionParameter& p : top_sim::kFrictionParameters) {
    if (p.law != kind) continue;
#define TOP_SIM_FIELD_OF_CONFIG(kind_, field, range_) \
    if (std::string(p.name) == #field) change.given.emplace_back(&p, cfg.field);
    TOP_SIM_FRICTION_PARAMETERS(TOP_SIM_FIELD_OF_CONFIG)
#undef TOP_SIM_FIELD_OF_CONFIG
  }
  return change;
}

// The finite-contact and air fields (level 32): the config's, the Command's and the model's, named alike.
struct FiniteField {
  double top_sim::TopSimConfig::*config;
  std::optional<double> top_sim::Command::*command;
  double (*in_model)(const top_sim::Model&);
};
const FiniteField kFiniteFields[] = {
    {&top_sim::TopSimConfig::patch_radius, &top_sim::Command::patch_radius,
     [](const top_sim::Model& m) { return m.finite_contact.patch_radius; }},
    {&top_sim::TopSimConfig::rolling_resistance, &top_sim::Command::rolling_resistance,
     [](const top_sim::Model& m) { return m.finite_contact.rolling_resistance; }},
    {&top_sim::TopSimConfig::spin_drag, &top_sim::Command::spin_drag,
     [](const top_sim::Model& m) { return m.air.spin_drag; }},
    {&top_sim::TopSimConfig::drag, &top_sim::Command::drag, [](const top_sim::Model& m) { return m.air.drag; }}};

}  // namespace

NodeReconfigure::NodeReconfigure(ros::NodeHandle& nh, ros::NodeHandle& pnh, const top_sim::Scene& scene,
                                 double real_time_factor, double publish_rate, ReconfigureHooks hooks)
    : hooks_(std::move(hooks)) {
  server_ = std::make_unique<dynamic_reconfigure::Server<top_sim::TopSimConfig>>(mutex_, pnh);
  config_.real_time_factor = real_time_factor;
  config_.publish_rate = publish_rate;
  record_scene_for_push(scene);
  dirty_ = false;  // pushed now
  server_->updateConfig(config_);
  server_->setCallback([this](top_sim::TopSimConfig& cfg, uint32_t level) { on_reconfigure(cfg, level); });
  // updateConfig() sets each parameter on the master (milliseconds): never on a command's path.
  timer_ = nh.createWallTimer(ros::WallDuration(0.5), [this](const ros::WallTimerEvent&) {
    if (!dirty_) return;
    dirty_ = false;
    server_->updateConfig(config_);
  });
}

void NodeReconfigure::record_for_push(const top_sim::Command& c) {
  if (c.inclination) config_.alpha = *c.inclination;
  if (c.spin) config_.spin = *c.spin;
  if (c.friction) friction_to_config(top_sim::changed_law(law_of_config(config_), *c.friction), config_);
  bool finite = false;
  for (const FiniteField& f : kFiniteFields)
    if (c.*f.command) {
      config_.*f.config = *(c.*f.command);
      finite = true;
    }
  if (c.inclination || c.spin || c.friction || finite) dirty_ = true;  // pushed by the slow timer
}

void NodeReconfigure::record_scene_for_push(const top_sim::Scene& scene) {
  config_.alpha = scene.model.plane.inclination;
  config_.spin = scene.initial.spin;
  friction_to_config(scene.model.friction, config_);
  for (const FiniteField& f : kFiniteFields) config_.*f.config = f.in_model(scene.model);
  dirty_ = true;
}

void NodeReconfigure::on_reconfigure(top_sim::TopSimConfig& cfg, uint32_t level) {
  if (!ready_) {  // the first call only echoes the values set at start
    ready_ = true;
    cfg = config_;
    return;
  }
  top_sim::Command c;
  if ((level & 1) && cfg.alpha != config_.alpha) c.inclination = cfg.alpha;
  if ((level & 2) && cfg.spin != config_.spin) c.spin = cfg.spin;
  if (level & 16) {
    top_sim::FrictionChange change;
    if (!reconfigured_friction(cfg, change)) {
      cfg = config_;
      return;
    }
    c.friction = std::move(change);
  }
  if (level & 32)
    for (const FiniteField& f : kFiniteFields)
      if (cfg.*f.config != config_.*f.config) c.*f.command = cfg.*f.config;  // the core validates (>= 0)
  if (!c.empty() && !hooks_.submit(c).empty()) {
    const double rtf = cfg.real_time_factor, rate = cfg.publish_rate;
    cfg = config_;  // show the values in force
    cfg.real_time_factor = rtf;
    cfg.publish_rate = rate;
  }
  reconfigure_pacing(cfg, level);
  cfg.alpha = config_.alpha;  // applied or refused above; either way config_ holds the value in force
  cfg.spin = config_.spin;
  for (const FiniteField& f : kFiniteFields) cfg.*f.config = config_.*f.config;
}

// The change dynamic_reconfigure asks for (the core applies it over the law in force, which config_ shows); false
// (after a warning) when it names no law or switches to a table, whose points it cannot carry.
bool NodeReconfigure::reconfigured_friction(const top_sim::TopSimConfig& cfg, top_sim::FrictionChange& change) {
  top_sim::FrictionLawKind kind;
  if (!top_sim::parse_friction_law_kind(cfg.friction_law, kind)) {
    ROS_WARN("top_sim_node: dynamic_reconfigure friction_law = '%s': must be one of %s", cfg.friction_law.c_str(),
             top_sim::friction_law_names(", ").c_str());
    return false;
  }
  if (kind == top_sim::kFrictionPointsLaw && config_.friction_law != cfg.friction_law) {
    ROS_WARN("top_sim_node: dynamic_reconfigure friction_law = 'table': the points come only from the scene or a "
             "TopCommand; kept the %s law", config_.friction_law.c_str());
    return false;
  }
  change = friction_from_config(cfg, kind);
  return true;
}

// real_time_factor (level 4) and publish_rate (level 8): applied when valid, else warned; cfg shows what holds.
void NodeReconfigure::reconfigure_pacing(top_sim::TopSimConfig& cfg, uint32_t level) {
  if (level & 4) {
    if (std::isfinite(cfg.real_time_factor) && cfg.real_time_factor >= 0.0) {
      config_.real_time_factor = cfg.real_time_factor;
      hooks_.set_real_time_factor(cfg.real_time_factor);
    } else {
      ROS_WARN("top_sim_node: %s", range_error("real_time_factor", cfg.real_time_factor, ">= 0").c_str());
    }
    cfg.real_time_factor = config_.real_time_factor;
  }
  if (level & 8) {
    if (std::isfinite(cfg.publish_rate) && cfg.publish_rate > 0.0 && cfg.publish_rate <= kMaxPublishRate) {
      config_.publish_rate = cfg.publish_rate;
      hooks_.set_publish_rate(cfg.publish_rate);
    } else {
      ROS_WARN("top_sim_node: %s", range_error("publish_rate", cfg.publish_rate, "in (0, 10000] Hz").c_str());
    }
    cfg.publish_rate = config_.publish_rate;
  }
}

}  // namespace top_sim_ros
