// MuJoCo side of bench/peer_mujoco: the same top, plane and initial state as the top_sim scene.
//
// Parameter mapping (top_sim -> MJCF):
//   top.mass m, inertia_transverse I_d, inertia_axial I_f -> <inertial pos="0 0 0" mass=m diaginertia="I_d I_d I_f">
//     at the body origin = the centre of mass, body z = the figure axis f_hat (inertiafromgeom="false")
//   tip_radius R, com_offset f -> sphere geom of radius R at body (0, 0, -f) (the tip sphere's centre r_m)
//   plane.inclination alpha -> plane geom through the world origin, euler="alpha 0 0" (R_WP = Rot_x(alpha), radians)
//   plane.gravity g -> <option gravity="0 0 -g">
//   friction coulomb mu 0 -> condim 1 on both geoms (normal force only)
//   the rigid contact -> MuJoCo's soft contact at its stiffest: solref (2 dt, 1), default solimp
//   initial state -> free joint qpos (com, quaternion taking z to f_hat) and qvel (v_cm world, omega body frame)
#include "mujoco_top.hpp"

#include <mujoco/mujoco.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <memory>
#include <stdexcept>

#include "top_sim/plane.hpp"
#include "top_sim/state.hpp"

namespace peer {

std::string num(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

double thread_cpu() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

double median(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

namespace {

Eigen::Quaterniond quaternion(const double* q) { return Eigen::Quaterniond(q[0], q[1], q[2], q[3]); }

}  // namespace

// mj_loadXML reads files only: the text goes through a virtual file system (2 MB, so on the heap).
mjModel* compile(const std::string& xml) {
  auto vfs = std::make_unique<mjVFS>();
  mj_defaultVFS(vfs.get());
  const char* name = "peer_mujoco.xml";
  if (mj_makeEmptyFileVFS(vfs.get(), name, static_cast<int>(xml.size())) != 0)
    throw std::runtime_error("MuJoCo: cannot make the in-memory MJCF file");
  std::memcpy(vfs->filedata[mj_findFileVFS(vfs.get(), name)], xml.data(), xml.size());
  char error[1000] = "";
  mjModel* m = mj_loadXML(name, vfs.get(), error, sizeof error);
  mj_deleteVFS(vfs.get());
  if (!m) throw std::runtime_error(std::string("MuJoCo: the MJCF does not compile: ") + error);
  return m;
}

std::string mjcf(const top_sim::Scene& scene, double dt) {
  const top_sim::Top& top = scene.model.top;
  const std::string solref = num(2.0 * dt) + " 1";
  return "<mujoco model=\"top_sim_peer\">\n"
         "  <compiler angle=\"radian\" inertiafromgeom=\"false\"/>\n"
         "  <option timestep=\"" + num(dt) + "\" integrator=\"RK4\" gravity=\"0 0 " +
         num(-scene.model.plane.gravity) + "\"/>\n"
         "  <default><geom condim=\"1\" solref=\"" + solref + "\"/></default>\n"
         "  <worldbody>\n"
         "    <geom name=\"plane\" type=\"plane\" size=\"0 0 1\" euler=\"" + num(scene.model.plane.inclination) +
         " 0 0\"/>\n"
         "    <body name=\"top\">\n"
         "      <joint name=\"free\" type=\"free\"/>\n"
         "      <inertial pos=\"0 0 0\" mass=\"" + num(top.mass) + "\" diaginertia=\"" + num(top.inertia_transverse) +
         " " + num(top.inertia_transverse) + " " + num(top.inertia_axial) + "\"/>\n"
         "      <geom name=\"tip\" type=\"sphere\" size=\"" + num(top.tip_radius) + "\" pos=\"0 0 " +
         num(-top.com_offset) + "\"/>\n"
         "    </body>\n"
         "  </worldbody>\n"
         "</mujoco>\n";
}

FreeBodyState initial_free_body(const top_sim::Scene& scene) {
  using namespace top_sim;
  const double alpha = scene.model.plane.inclination, f = scene.model.top.com_offset;
  const StateVector y = initial_state(scene);
  const Eigen::Vector3d f_hat = figure_axis(y), omega = angular_velocity(y);
  const Eigen::Vector3d tip_center(y[idx::x], y[idx::x + 1], scene.model.top.tip_radius + y[idx::gap]);
  const Eigen::Vector3d v_cm = velocity3(y) + omega.cross(f * f_hat);  // physics.md section 3
  const Eigen::Vector3d f_world = plane_to_world(alpha, f_hat);
  const Eigen::Quaterniond q = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), f_world);
  FreeBodyState s;
  s.com = plane_to_world(alpha, tip_center + f * f_hat);
  s.quat = Eigen::Vector4d(q.w(), q.x(), q.y(), q.z());
  s.com_velocity = plane_to_world(alpha, v_cm);
  s.omega_body = q.conjugate() * plane_to_world(alpha, omega);
  return s;
}

MujocoTop::MujocoTop(const top_sim::Scene& scene) : scene_(scene) {
  m_ = compile(mjcf(scene, 1e-3));
  d_ = mj_makeData(m_);
  if (m_->nq != 7 || m_->nv != 6 || m_->ngeom != 2)
    throw std::logic_error("MuJoCo: not the one free body and two geoms");
  set_timestep(1e-3);
}

MujocoTop::~MujocoTop() {
  mj_deleteData(d_);
  mj_deleteModel(m_);
}

void MujocoTop::set_timestep(double dt, double time_constant) {
  m_->opt.timestep = dt;
  for (int i = 0; i < m_->ngeom; ++i) {
    m_->geom_solref[mjNREF * i] = std::max(2.0 * dt, time_constant);
    m_->geom_solref[mjNREF * i + 1] = 1.0;
  }
}

void MujocoTop::reset() {
  mj_resetData(m_, d_);
  const FreeBodyState s = initial_free_body(scene_);
  for (int i = 0; i < 3; ++i) {
    d_->qpos[i] = s.com[i];
    d_->qvel[i] = s.com_velocity[i];
    d_->qvel[3 + i] = s.omega_body[i];
  }
  for (int i = 0; i < 4; ++i) d_->qpos[3 + i] = s.quat[i];
}

// From qpos itself (after mj_step the kinematics in mjData belong to the last RK4 stage, not the new state).
Eigen::Vector3d MujocoTop::tip_center_plane() const {
  const Eigen::Vector3d com(d_->qpos[0], d_->qpos[1], d_->qpos[2]);
  const Eigen::Vector3d axis = quaternion(d_->qpos + 3).normalized() * Eigen::Vector3d::UnitZ();
  return top_sim::world_to_plane(scene_.model.plane.inclination, com - scene_.model.top.com_offset * axis);
}

double MujocoTop::tilt() const {
  const Eigen::Vector3d axis = quaternion(d_->qpos + 3).normalized() * Eigen::Vector3d::UnitZ();
  const double z = top_sim::world_to_plane(scene_.model.plane.inclination, axis).z();
  return std::acos(std::clamp(z, -1.0, 1.0));
}

std::vector<double> MujocoTop::tilt_run(double T, double from) {
  const double dt = m_->opt.timestep;
  const long steps = std::lround(T / dt);
  std::vector<double> tilts;
  reset();
  for (long k = 1; k <= steps; ++k) {
    mj_step(m_, d_);
    if (static_cast<double>(k) * dt >= from - 1e-12) tilts.push_back(tilt());
  }
  return tilts;
}

std::vector<Eigen::Vector2d> MujocoTop::run(double T, double interval) {
  const double dt = m_->opt.timestep;
  const long steps = std::lround(T / dt), per_sample = std::max(1L, std::lround(interval / dt));
  std::vector<Eigen::Vector2d> samples;
  samples.reserve(static_cast<std::size_t>(steps / per_sample + 1));
  reset();
  samples.push_back(tip_center_plane().head<2>());  // the contact point r_m - R n, in-plane
  max_penetration_ = 0.0;
  for (long k = 1; k <= steps; ++k) {
    mj_step(m_, d_);
    if (k % per_sample != 0) continue;
    const Eigen::Vector3d tip = tip_center_plane();
    samples.push_back(tip.head<2>());
    max_penetration_ = std::max(max_penetration_, scene_.model.top.tip_radius - tip.z());
  }
  return samples;
}

InitialReport MujocoTop::initial_report() {
  reset();
  mj_forward(m_, d_);
  const int tip = mj_name2id(m_, mjOBJ_GEOM, "tip"), body = mj_name2id(m_, mjOBJ_BODY, "top");
  InitialReport r;
  r.tip_center_plane = top_sim::world_to_plane(scene_.model.plane.inclination,
                                               Eigen::Vector3d(d_->geom_xpos + 3 * tip));
  r.figure_axis_world = Eigen::Vector3d(d_->xmat[9 * body + 2], d_->xmat[9 * body + 5], d_->xmat[9 * body + 8]);
  mjtNum v[6];
  mj_objectVelocity(m_, d_, mjOBJ_BODY, body, v, 0);  // (angular, linear) at the body's centre of mass, world axes
  r.omega_world = Eigen::Vector3d(v[0], v[1], v[2]);
  r.com_velocity_world = Eigen::Vector3d(v[3], v[4], v[5]);
  return r;
}

}  // namespace peer
