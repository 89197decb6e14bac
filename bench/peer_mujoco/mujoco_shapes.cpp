// peer_mujoco --tippe-top: MuJoCo's tutorial tippe top (python/tutorial.ipynb of google-deepmind/mujoco), written
// from its facts: a free body of a sphere (radius 20 mm, origin 20 mm above the floor), a cylindrical stem (radius
// 4 mm, half-length 8 mm, centre 20 mm above the ball's centre) and a non-colliding ballast box (half-sizes 23, 23,
// 5 mm, centre 15 mm below the ball's centre) that lowers the centre of mass; geoms of density 1000 (MuJoCo's
// default) give the inertia; RK4 at MuJoCo's default timestep 2 ms (the tutorial sets none); default contact
// (condim 3, friction 1, solref 0.02 1); keyframe: upright at rest, angular velocity (0, 1, 200) rad/s in the body
// frame. Left out: the texture, material, light and camera (rendering only).
// Measured: the stem's first touch of the floor, the tilt's time course, CPU per simulated second; and the same
// body in top_sim's terms, read from MuJoCo's compiled model.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <vector>

#include "mujoco_shapes.hpp"
#include "mujoco_top.hpp"

namespace peer {

MjInstance::MjInstance(const std::string& xml) : m(compile(xml)), d(mj_makeData(m)) {}

MjInstance::~MjInstance() {
  mj_deleteData(d);
  mj_deleteModel(m);
}

Eigen::Quaterniond body_orientation(const mjData* d) {
  return Eigen::Quaterniond(d->qpos[3], d->qpos[4], d->qpos[5], d->qpos[6]).normalized();
}

Eigen::Vector3d body_axis(const mjData* d) { return body_orientation(d) * Eigen::Vector3d::UnitZ(); }

double tilt_from_vertical(const mjData* d) { return std::acos(std::clamp(body_axis(d).z(), -1.0, 1.0)); }

bool in_contact(const mjModel* m, const mjData* d, mjData* scratch, int g1, int g2) {
  std::copy(d->qpos, d->qpos + m->nq, scratch->qpos);
  mj_fwdPosition(m, scratch);
  for (int i = 0; i < scratch->ncon; ++i) {
    const mjContact& c = scratch->contact[i];
    if ((c.geom1 == g1 && c.geom2 == g2) || (c.geom1 == g2 && c.geom2 == g1)) return true;
  }
  return false;
}

bool expect(bool ok, const std::string& what) {
  std::cout << (ok ? "ok    " : "FAIL  ") << what << "\n";
  return ok;
}

std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

namespace {

// The tutorial's geometry [m].
constexpr double kBallRadius = 0.02;
constexpr double kStemRadius = 0.004, kStemHalfLength = 0.008, kStemZ = 0.02;  // stem centre above the ball's
constexpr double kBallastHalfXY = 0.023, kBallastHalfZ = 0.005, kBallastZ = -0.015;
constexpr double kTutorialDt = 0.002;  // MuJoCo's default timestep: the tutorial sets none
constexpr double kTutorialT = 7.0;     // the tutorial's video and plot [s]
const std::vector<double> kTippeDt = {2e-3, 1e-3, 5e-4, 2.5e-4, 1e-4};
constexpr double kCourseInterval = 0.25;  // the tilt's time course in the table [s]
constexpr double kCsvInterval = 0.01;     // and in the CSV [s]: a multiple of every dt above

std::string tippe_mjcf(double dt) {
  return "<mujoco model=\"tippe top\">\n"
         "  <option timestep=\"" + num(dt) + "\" integrator=\"RK4\"/>\n"
         "  <worldbody>\n"
         "    <geom name=\"floor\" type=\"plane\" size=\".2 .2 .01\"/>\n"
         "    <body name=\"top\" pos=\"0 0 " + num(kBallRadius) + "\">\n"
         "      <freejoint/>\n"
         "      <geom name=\"ball\" type=\"sphere\" size=\"" + num(kBallRadius) + "\"/>\n"
         "      <geom name=\"stem\" type=\"cylinder\" pos=\"0 0 " + num(kStemZ) + "\" size=\"" + num(kStemRadius) +
         " " + num(kStemHalfLength) + "\"/>\n"
         "      <geom name=\"ballast\" type=\"box\" size=\"" + num(kBallastHalfXY) + " " + num(kBallastHalfXY) + " " +
         num(kBallastHalfZ) + "\" pos=\"0 0 " + num(kBallastZ) + "\" contype=\"0\" conaffinity=\"0\" group=\"3\"/>\n"
         "    </body>\n"
         "  </worldbody>\n"
         "  <keyframe>\n"
         "    <key name=\"spinning\" qpos=\"0 0 " + num(kBallRadius) + " 1 0 0 0\" qvel=\"0 0 0 0 1 200\"/>\n"
         "  </keyframe>\n"
         "</mujoco>\n";
}

// Height of the stem's lowest point above the floor (its end discs' rims; negative: penetrating) [m].
double stem_gap(const mjData* d) {
  const Eigen::Vector3d axis = body_axis(d);
  const double cz = d->qpos[2] + kStemZ * axis.z();
  const double rim = kStemRadius * std::sqrt(std::max(0.0, 1.0 - axis.z() * axis.z()));
  return std::min(cz + kStemHalfLength * axis.z(), cz - kStemHalfLength * axis.z()) - rim;
}

struct TippeRun {
  double dt = 0.0;
  double touch_geometry = NAN;   // first step end with the stem's lowest point at or below the floor [s]
  double touch_collision = NAN;  // first step end at which MuJoCo's collision finds a stem-floor contact [s]
  double half_pi = NAN;          // first step end with the tilt past pi/2 [s]
  double ball_leaves = NAN;      // first step end after the stem's touch with the ball clear of the floor [s]
  double tilt_end = NAN, tilt_max = 0.0, spin_end = NAN;  // at kTutorialT: tilt [rad], omega . axis [rad/s]
  std::vector<double> t, tilt;   // every kCsvInterval
  Eigen::VectorXd qpos_end;
};

void reset_keyframe(const MjInstance& mj, double dt) {
  mj.m->opt.timestep = dt;
  mj_resetDataKeyframe(mj.m, mj.d, 0);
}

// The untimed run with its probes; `probe` false: the bare run (for the check that probing changes nothing).
TippeRun tippe_run(MjInstance& mj, double dt, bool probe = true) {
  TippeRun r;
  r.dt = dt;
  const int stem = mj_name2id(mj.m, mjOBJ_GEOM, "stem"), floor = mj_name2id(mj.m, mjOBJ_GEOM, "floor");
  reset_keyframe(mj, dt);
  std::unique_ptr<mjData, void (*)(mjData*)> scratch(mj_makeData(mj.m), mj_deleteData);
  const long steps = std::lround(kTutorialT / dt), every = std::lround(kCsvInterval / dt);
  r.t.push_back(0.0);
  r.tilt.push_back(tilt_from_vertical(mj.d));
  for (long k = 1; k <= steps && probe; ++k) {
    mj_step(mj.m, mj.d);
    const double t = static_cast<double>(k) * dt, tilt = tilt_from_vertical(mj.d);
    r.tilt_max = std::max(r.tilt_max, tilt);
    if (std::isnan(r.touch_geometry) && stem_gap(mj.d) <= 0.0) r.touch_geometry = t;
    if (std::isnan(r.touch_collision) && in_contact(mj.m, mj.d, scratch.get(), stem, floor)) r.touch_collision = t;
    if (std::isnan(r.half_pi) && tilt > M_PI / 2) r.half_pi = t;
    if (!std::isnan(r.touch_geometry) && std::isnan(r.ball_leaves) && mj.d->qpos[2] > kBallRadius) r.ball_leaves = t;
    if (k % every == 0) {
      r.t.push_back(t);
      r.tilt.push_back(tilt);
    }
  }
  for (long k = 1; k <= steps && !probe; ++k) mj_step(mj.m, mj.d);
  r.tilt_end = tilt_from_vertical(mj.d);
  r.spin_end = Eigen::Vector3d(mj.d->qvel[3], mj.d->qvel[4], mj.d->qvel[5]).z();  // body frame: z is the axis
  r.qpos_end = Eigen::Map<const Eigen::VectorXd>(mj.d->qpos, mj.m->nq);
  return r;
}

// CPU seconds per simulated second of the bare run to kTutorialT, one sample per dt per repetition, interleaved.
std::vector<std::vector<double>> tippe_cpu(MjInstance& mj, int reps) {
  std::vector<std::vector<double>> cpu(kTippeDt.size());
  for (int rep = 0; rep < reps; ++rep)
    for (std::size_t i = 0; i < kTippeDt.size(); ++i) {
      reset_keyframe(mj, kTippeDt[i]);
      const long steps = std::lround(kTutorialT / kTippeDt[i]);
      const double c0 = thread_cpu();
      for (long k = 0; k < steps; ++k) mj_step(mj.m, mj.d);
      cpu[i].push_back((thread_cpu() - c0) / kTutorialT);
    }
  return cpu;
}

// The body in top_sim's terms (docs/physics.md section 13: shapes at distance d from the centre of mass along
// f_hat, here the body z axis, ball to stem), read from MuJoCo's compiled model.
struct TopSimTerms {
  double mass, com_below_ball, inertia_transverse, inertia_axial, off_diagonal, transverse_split;
};

TopSimTerms top_sim_terms(const mjModel* m) {
  const int body = mj_name2id(m, mjOBJ_BODY, "top");
  const Eigen::Quaterniond iq(m->body_iquat[4 * body], m->body_iquat[4 * body + 1], m->body_iquat[4 * body + 2],
                              m->body_iquat[4 * body + 3]);
  const Eigen::Matrix3d R = iq.normalized().toRotationMatrix();
  const Eigen::Vector3d principal(m->body_inertia + 3 * body);
  const Eigen::Matrix3d I = R * principal.asDiagonal() * R.transpose();  // body frame, about the centre of mass
  TopSimTerms t;
  t.mass = m->body_mass[body];
  t.com_below_ball = -m->body_ipos[3 * body + 2];
  t.inertia_transverse = 0.5 * (I(0, 0) + I(1, 1));
  t.inertia_axial = I(2, 2);
  t.off_diagonal = std::max({std::abs(I(0, 1)), std::abs(I(0, 2)), std::abs(I(1, 2)),
                             std::abs(m->body_ipos[3 * body]), std::abs(m->body_ipos[3 * body + 1])});
  t.transverse_split = std::abs(I(0, 0) - I(1, 1));
  return t;
}

void print_top_sim_terms(MjInstance& mj) {
  const TopSimTerms t = top_sim_terms(mj.m);
  const double stem_end = kStemZ + kStemHalfLength + t.com_below_ball;  // the stem's end face from the COM
  reset_keyframe(mj, kTutorialDt);
  mj_forward(mj.m, mj.d);
  mjtNum v[6];
  mj_objectVelocity(mj.m, mj.d, mjOBJ_BODY, mj_name2id(mj.m, mjOBJ_BODY, "top"), v, 0);
  std::printf("\n**The same body in top_sim's terms** (MuJoCo's compiled model: body_mass, body_ipos, body_iquat, "
              "body_inertia; f_hat = the body z axis, from the ball towards the stem):\n\n"
              "| quantity | value |\n|---|---|\n");
  std::printf("| mass m | %.6g kg |\n| centre of mass below the ball's centre | %.6g m (top.com_offset = %.6g) |\n",
              t.mass, t.com_below_ball, -t.com_below_ball);
  std::printf("| I_d (transverse, about the centre of mass) | %.6g kg m^2 |\n| I_f (axial) | %.6g kg m^2 |\n",
              t.inertia_transverse, t.inertia_axial);
  std::printf("| largest off-diagonal / off-axis term; I_xx - I_yy | %.2g; %.2g |\n", t.off_diagonal,
              t.transverse_split);
  std::printf("| ball: sphere radius, centre at d | %.6g m, d = %+.6g m |\n", kBallRadius, t.com_below_ball);
  std::printf("| stem end as a sphere (its hemispherical cap reaches the end face) | radius %.6g m, d = %+.6g m |\n",
              kStemRadius, stem_end - kStemRadius);
  std::printf("| stem end as MuJoCo has it (a flat end face): rim | radius %.6g m, d = %+.6g m |\n", kStemRadius,
              stem_end);
  std::printf("| initial state | upright (tilt 0), spin 200 rad/s, angular_velocity_transverse [0, 1] rad/s; "
              "centre-of-mass velocity (%.3g, %.3g, %.3g) m/s (MuJoCo's free-joint velocity is the body origin's, "
              "the ball's centre: at rest) |\n", v[3], v[4], v[5]);
}

void print_tippe_runs(const std::vector<TippeRun>& runs, const std::vector<std::vector<double>>& cpu) {
  std::printf("| dt [s] | stem first touch: geometry / MuJoCo collision [s] | tilt past pi/2 [s] | ball leaves the "
              "floor [s] | tilt at 7 s [rad] | max tilt [rad] | spin at 7 s [rad/s] | CPU per simulated s [s] "
              "(median, min-max) |\n|---|---|---|---|---|---|---|---|\n");
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const TippeRun& r = runs[i];
    const auto [lo, hi] = std::minmax_element(cpu[i].begin(), cpu[i].end());
    std::printf("| %g | %.4f / %.4f | %.4f | %.4f | %.4f | %.4f | %.2f | %.3g (%.3g-%.3g) |\n", r.dt,
                r.touch_geometry, r.touch_collision, r.half_pi, r.ball_leaves, r.tilt_end, r.tilt_max, r.spin_end,
                median(cpu[i]), *lo, *hi);
  }
}

// The tilt every kCourseInterval for the tutorial's dt and the finest.
void print_course(const TippeRun& coarse, const TippeRun& fine) {
  std::printf("\n| t [s] | tilt, dt %g [rad] | tilt, dt %g [rad] |\n|---|---|---|\n", coarse.dt, fine.dt);
  const long every = std::lround(kCourseInterval / kCsvInterval);
  for (std::size_t k = 0; k < coarse.t.size() && k < fine.t.size(); k += static_cast<std::size_t>(every)) {
    if (std::abs(coarse.t[k] - fine.t[k]) > 1e-9) throw std::logic_error("tippe top: the runs' samples differ in time");
    std::printf("| %.2f | %.4f | %.4f |\n", coarse.t[k], coarse.tilt[k], fine.tilt[k]);
  }
}

void write_tippe_csv(const std::string& file, const std::vector<TippeRun>& runs) {
  std::ofstream csv(file);
  csv << "dt,t,tilt\n";
  for (const TippeRun& r : runs)
    for (std::size_t k = 0; k < r.t.size(); ++k) csv << r.dt << "," << r.t[k] << "," << r.tilt[k] << "\n";
}

// The ctest: the top inverts (tilt past pi/2, the stem touches, MuJoCo's collision agrees with the geometry within
// a step) at the tutorial's dt and at 0.5 ms; the probes leave the run unchanged to the bit; the composite's
// centre of mass from the three geoms' volumes (density 1000) against MuJoCo's.
int tippe_check(MjInstance& mj) {
  bool ok = true;
  for (double dt : {kTutorialDt, 5e-4}) {
    const TippeRun r = tippe_run(mj, dt), bare = tippe_run(mj, dt, false);
    const std::string at = "dt " + fmt("%g", dt) + ": ";
    ok &= expect(r.half_pi < kTutorialT && r.tilt_end > 2.0,
                 at + "the top inverts: tilt past pi/2 at " + fmt("%.3f", r.half_pi) + " s, " +
                     fmt("%.3f", r.tilt_end) + " rad at 7 s (> 2)");
    ok &= expect(r.touch_geometry < kTutorialT && std::abs(r.touch_collision - r.touch_geometry) <= 1.5 * dt,
                 at + "the stem touches at " + fmt("%.4f", r.touch_geometry) + " s; MuJoCo's collision finds it at " +
                     fmt("%.4f", r.touch_collision) + " s (within a step)");
    ok &= expect(r.qpos_end == bare.qpos_end, at + "the probed run ends where the bare run does, to the bit");
  }
  const double v_ball = 4.0 / 3.0 * M_PI * std::pow(kBallRadius, 3);
  const double v_stem = M_PI * kStemRadius * kStemRadius * 2 * kStemHalfLength;
  const double v_box = 8 * kBallastHalfXY * kBallastHalfXY * kBallastHalfZ;
  const double z = (v_stem * kStemZ + v_box * kBallastZ) / (v_ball + v_stem + v_box);
  const TopSimTerms t = top_sim_terms(mj.m);
  ok &= expect(std::abs(t.mass - 1000 * (v_ball + v_stem + v_box)) < 1e-12 && std::abs(-t.com_below_ball - z) < 1e-12,
               "MuJoCo's mass " + fmt("%.6g", t.mass) + " kg and centre of mass " + fmt("%.6g", -t.com_below_ball) +
                   " m are the geoms' at density 1000 (within 1e-12)");
  ok &= expect(t.off_diagonal < 1e-15 && t.transverse_split < 1e-12 * t.inertia_transverse,
               "the inertia is axisymmetric about the body z axis through the centre of mass");
  return ok ? 0 : 1;
}

}  // namespace

int tippe_top(const ShapesOptions& o) {
  if (o.print_mjcf) {
    std::cout << tippe_mjcf(kTutorialDt);
    return 0;
  }
  MjInstance mj(tippe_mjcf(kTutorialDt));
  if (o.check) return tippe_check(mj);
  std::vector<TippeRun> runs;
  for (double dt : kTippeDt) runs.push_back(tippe_run(mj, dt));
  const std::vector<std::vector<double>> cpu = tippe_cpu(mj, o.reps);
  std::printf("MuJoCo %s, the tutorial's tippe top (RK4, contact solref 0.02 1), 7 s; CPU: thread time of the run "
              "without probes, %d repetitions interleaved\n\n", mj_versionString(), o.reps);
  print_tippe_runs(runs, cpu);
  print_course(runs.front(), runs.back());
  print_top_sim_terms(mj);
  if (!o.csv.empty()) write_tippe_csv(o.csv, runs);
  return 0;
}

}  // namespace peer
