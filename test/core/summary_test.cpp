// The summary of a stream of Snapshots (SummaryAccumulator, src/output/run.hpp): what top_sim_run's samples and
// top_sim_bag's TopStates both feed. Synthetic streams with known answers, then a sampled run.
#include <gtest/gtest.h>

#include <boost/property_tree/json_parser.hpp>
#include <boost/property_tree/ptree.hpp>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iomanip>
#include <limits>
#include <sstream>
#include <utility>

#include "test_util.hpp"
#include "top_sim/plane.hpp"
#include "top_sim/trajectory.hpp"

namespace pt = boost::property_tree;
using top_sim::ContactMode;
using top_sim::Regime;
using top_sim::Snapshot;

namespace {

Snapshot at(double t, double x, double y, Regime regime, ContactMode mode, double residual = 0.0) {
  Snapshot s;
  s.t = t;
  s.contact_point = Eigen::Vector3d(x, y, 0.0);
  s.regime = regime;
  s.contact_mode = mode;
  s.energy_balance_residual = residual;
  return s;
}

pt::ptree parse(const std::string& json) {
  pt::ptree j;
  std::istringstream in(json);
  pt::read_json(in, j);
  return j;
}

}  // namespace

// Intervals count for the earlier sample's regime and mode; a change is seen at the first sample in the new mode.
TEST(SummaryAccumulator, DurationsAndChangesFollowTheSamples) {
  top_sim::SummaryAccumulator acc(top_sim::mark_time(0.0, 1.0));
  acc.add(at(0.0, 0, 0, Regime::nutating, ContactMode::slipping, 1e-9));
  acc.add(at(0.25, 0, 0, Regime::nutating, ContactMode::flight, 3e-9));
  acc.add(at(0.5, 0, 0, Regime::precessing, ContactMode::slipping, 2e-9));
  acc.add(at(1.0, 0, 0, Regime::sleeping, ContactMode::slipping));
  const top_sim::SampledSummary s = acc.result();
  EXPECT_EQ(s.samples, 4u);
  EXPECT_EQ(s.t_first, 0.0);
  EXPECT_EQ(s.t_last, 1.0);
  EXPECT_EQ(s.regime_seconds[top_sim::code(Regime::nutating)], 0.5);
  EXPECT_EQ(s.regime_seconds[top_sim::code(Regime::precessing)], 0.5);
  EXPECT_EQ(s.regime_seconds[top_sim::code(Regime::sleeping)], 0.0);  // the last sample closes no interval
  EXPECT_EQ(s.mode_seconds[top_sim::code(ContactMode::slipping)], 0.75);
  EXPECT_EQ(s.mode_seconds[top_sim::code(ContactMode::flight)], 0.25);
  ASSERT_EQ(s.mode_changes.size(), 2u);
  EXPECT_EQ(s.mode_change_count, 2u);
  EXPECT_EQ(s.mode_changes[0].t, 0.25);
  EXPECT_EQ(s.mode_changes[0].to, ContactMode::flight);
  EXPECT_EQ(s.mode_changes[1].t, 0.5);
  EXPECT_EQ(s.mode_changes[1].from, ContactMode::flight);
  EXPECT_EQ(s.max_energy_residual, 3e-9);
  EXPECT_EQ(s.last.regime, Regime::sleeping);
}

// The mark (t = 0.8 of [0, 1]) falls between samples at 0.7 and 0.9 on the second leg of a bent path: the
// interpolated point lies on that leg, so phi_measured is the leg's direction; the first leg's is another.
TEST(SummaryAccumulator, PhiMeasuredStartsAtTheInterpolatedMark) {
  const double phi = 0.3;  // travel direction of the second leg: from h (+x) towards downhill (-y)
  const Eigen::Vector2d corner(0.5, 0.0), dir(std::cos(phi), -std::sin(phi));
  top_sim::SummaryAccumulator acc(top_sim::mark_time(0.0, 1.0));
  for (double t : {0.0, 0.3, 0.5, 0.7, 0.9, 1.0}) {
    const Eigen::Vector2d p = t <= 0.5 ? Eigen::Vector2d(t, 0.0) : Eigen::Vector2d(corner + (t - 0.5) * dir);
    acc.add(at(t, p.x(), p.y(), Regime::precessing, ContactMode::slipping));
  }
  const top_sim::SampledSummary s = acc.result();
  ASSERT_TRUE(s.phi_measured);
  EXPECT_NEAR(*s.phi_measured, phi, 1e-14);

  Snapshot faulted = s.last;  // a recorded fault (its text only) leaves phi_measured out, as a run's does
  faulted.fault_message = "t = 1 s: fallen";
  EXPECT_FALSE(top_sim::travel_since(corner, faulted));
  EXPECT_FALSE(top_sim::travel_since(s.last.contact_point.head<2>(), s.last)) << "no displacement, no direction";
}

// The recorded summary: what a bag cannot give is null and "unavailable" says why; phi_star with its source.
TEST(SummaryAccumulator, RecordedSummaryMarksWhatABagCannotGive) {
  top_sim::SummaryAccumulator acc(top_sim::mark_time(2.0, 3.0));
  acc.add(at(2.0, 0, 0, Regime::sleeping, ContactMode::slipping));
  acc.add(at(3.0, 1e-3, -1e-3, Regime::sleeping, ContactMode::rolling));
  top_sim::RecordedSource src;
  src.bag = "x.bag";
  src.topic = "/top_sim/top_state";
  src.top = "top_sim";
  src.phi_star = 0.5;
  src.phi_star_source = "the last TopState's phi_star";
  const pt::ptree j = parse(top_sim::summary_json(src, acc.result()));
  EXPECT_EQ(j.get<std::string>("top"), "top_sim");
  EXPECT_EQ(j.get<double>("sim_seconds"), 1.0);
  EXPECT_EQ(j.get<double>("regime_seconds.sleeping"), 1.0);
  EXPECT_EQ(j.get<double>("mode_seconds.slipping"), 1.0);
  EXPECT_NEAR(j.get<double>("phi_measured"), M_PI / 4, 1e-15);
  EXPECT_EQ(j.get<double>("phi_star"), 0.5);
  EXPECT_EQ(j.get<std::string>("phi_star_source"), "the last TopState's phi_star");
  EXPECT_EQ(j.get<int>("mode_change_count"), 1);
  for (const char* key : {"cpu_seconds", "steps", "rhs_evaluations", "real_time_factor", "method", "mode_switches",
                          "mode_switch_count"}) {
    EXPECT_EQ(j.get<std::string>(key), "null") << key;
    EXPECT_FALSE(j.get<std::string>(std::string("unavailable.") + key, "").empty()) << key;
  }
  EXPECT_EQ(j.get<std::string>("contact_fault"), "null");
  EXPECT_EQ(j.get<std::string>("contact_fault_kind"), "null");
  EXPECT_EQ(j.get<std::string>("end_state"), "null");  // the recording says no end state: known, not unavailable
  EXPECT_EQ(j.get<std::string>("end_state_message"), "null");
  EXPECT_FALSE(j.get_child_optional("unavailable.end_state"));
  EXPECT_EQ(j.get<int>("final.touching"), 0);
}

// A recording whose last state has an end state (TopState's end_state and end_state_message, read back by
// to_snapshot) reports them as top_sim_run does, with the last state's touching.
TEST(SummaryAccumulator, RecordedSummaryReportsTheRecordedEndState) {
  top_sim::SummaryAccumulator acc(top_sim::mark_time(0.0, 1.0));
  acc.add(at(0.0, 0, 0, Regime::nutating, ContactMode::flight));
  Snapshot flat = at(1.0, 0, 0, Regime::nutating, ContactMode::rolling);
  flat.touching = 2;  // shape 1 of top.shapes
  flat.end_state = top_sim::EndState::lying_flat;
  flat.end_message = top_sim::describe(top_sim::EndState::lying_flat, -1e-5, 1.0);
  acc.add(flat);
  top_sim::RecordedSource src;
  src.bag = "disc.bag";
  const pt::ptree j = parse(top_sim::summary_json(src, acc.result()));
  EXPECT_EQ(j.get<std::string>("end_state"), "lying_flat");
  EXPECT_EQ(j.get<std::string>("end_state_message"), flat.end_message);
  EXPECT_FALSE(j.get_child_optional("unavailable.end_state"));
  EXPECT_FALSE(j.get_child_optional("unavailable.end_state_message"));
  EXPECT_EQ(j.get<std::string>("contact_fault"), "null") << "an end state is no fault";
  EXPECT_EQ(j.get<int>("final.touching"), 2);
}

// A sampled run feeds the same accumulator: its regime_seconds cover the whole run and its phi_measured (from the
// interpolated mark) agrees with the run's own (from the exact state at the mark).
TEST(SummaryAccumulator, SampledRunCoversTheRunAndAgreesWithTheExactMark) {
  top_sim::Simulator sim(top_sim_test::scene_from(top_sim_test::standard_scene(0.1, 200.0)));
  top_sim::RunOptions opt;
  opt.duration = 2.0;
  opt.sample_rate = 137.0;  // the mark (1.6 s = 219.2 samples) falls between two samples
  const top_sim::RunResult r = top_sim::run(sim, opt);
  double total = 0.0;
  for (double s : r.sampled.regime_seconds) total += s;
  EXPECT_NEAR(total, r.sim_seconds, 1e-12);
  EXPECT_GE(r.sampled.samples, 275u);  // t = 0, 1/137 s, ..., 2 s, and the end once more if 274/137 rounds below
  EXPECT_LE(r.sampled.samples, 276u);
  ASSERT_TRUE(r.phi_measured && r.sampled.phi_measured);
  // The mark's point interpolated over 7.3 ms of a path curving at the nutation frequency: far below the 1e-3 rad
  // of the phi criterion.
  EXPECT_NEAR(*r.sampled.phi_measured, *r.phi_measured, 1e-4);
  EXPECT_NE(*r.sampled.phi_measured, *r.phi_measured) << "the mark was not interpolated";
  top_sim_test::note("sampled vs exact phi_measured (137 Hz, 2 s)",
                     std::abs(*r.sampled.phi_measured - *r.phi_measured));
  const pt::ptree j = parse(top_sim::summary_json(sim.scene(), r));
  EXPECT_NEAR(j.get<double>("regime_seconds.nutating") + j.get<double>("regime_seconds.precessing") +
                  j.get<double>("regime_seconds.sleeping") + j.get<double>("regime_seconds.sliding") +
                  j.get<double>("regime_seconds.contact_fault"),
              2.0, 1e-12);
  EXPECT_EQ(j.get<std::uint64_t>("samples"), r.sampled.samples);
  EXPECT_FALSE(j.get_child_optional("unavailable"));

  // regime_seconds are the simulator's (its regime cadence), not the samples': an unsampled run has the same.
  top_sim::Simulator unsampled(sim.scene());
  opt.sample_rate = 0.0;
  const pt::ptree k = parse(top_sim::summary_json(sim.scene(), top_sim::run(unsampled, opt)));
  for (const char* regime : {"nutating", "precessing", "sleeping", "sliding", "contact_fault"}) {
    const std::string key = std::string("regime_seconds.") + regime;
    EXPECT_EQ(k.get<double>(key), j.get<double>(key)) << key;
  }
  EXPECT_FALSE(k.get_child_optional("unavailable"));
}

// Who reads how often changes no result: the regime's hysteresis and its seconds live on the simulator's cadence.
// One top read at 1 kHz through 60 s of the default scene (nutating, then precessing) against one advanced in a
// single call and read once: the same regime seconds to the bit, summing to the 60 s, and the same final regime.
TEST(RegimeCadence, ReadsAndSlicingChangeNoRegime) {
  const top_sim::Scene scene = top_sim::load_scene(std::string(TOP_SIM_TEST_CONFIG_DIR) + "/scenes/default.yaml");
  top_sim::Simulator read(scene), unread(scene);
  std::array<int, top_sim::kRegimeCount> seen{};
  for (int k = 1; k <= 60000; ++k) {
    ASSERT_TRUE(read.advance_to(1e-3 * k));
    ++seen[top_sim::code(read.snapshot().regime)];
  }
  ASSERT_TRUE(unread.advance_to(60.0));
  const auto a = read.regime_seconds(), b = unread.regime_seconds();
  double total = 0.0;
  for (int r = 0; r < top_sim::kRegimeCount; ++r) {
    EXPECT_EQ(a[r], b[r]) << top_sim::to_string(static_cast<Regime>(r));
    total += b[r];
  }
  EXPECT_NEAR(total, 60.0, 1e-9);
  EXPECT_GT(seen[top_sim::code(Regime::nutating)], 0);
  EXPECT_GT(seen[top_sim::code(Regime::precessing)], 0);
  EXPECT_EQ(read.snapshot().regime, unread.snapshot().regime);
  EXPECT_EQ(read.state(), unread.state());
}

namespace {

// The fewest significant digits p for which printf's %.{p}g reads back as v: the definition of "shortest round
// trip", independent of std::to_chars.
int shortest_digits(double v) {
  for (int p = 1; p < 17; ++p) {
    char text[64];
    std::snprintf(text, sizeof text, "%.*g", p, v);
    if (std::strtod(text, nullptr) == v) return p;
  }
  return 17;
}

// Significant digits a decimal text spells: its mantissa's digits without leading and trailing zeros.
int significant_digits(const std::string& text) {
  std::string digits;
  for (char c : text.substr(0, text.find_first_of("eE"))) {
    if (std::isdigit(static_cast<unsigned char>(c))) digits += c;
  }
  const auto first = digits.find_first_not_of('0');
  if (first == std::string::npos) return 1;
  return static_cast<int>(digits.find_last_not_of('0') - first + 1);
}

std::vector<std::string> split_fields(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream in(line);
  for (std::string f; std::getline(in, f, ',');) fields.push_back(f);
  return fields;
}

}  // namespace

// Every CSV number reads back as the snapshot's double, bit for bit, in the fewest digits that do (printf's %.{p}g
// as the reference); enumerations are their names; NaN is "nan"; over ordinary, tiny, huge, negative, NaN and
// infinite values and more rows than one block.
TEST(CsvWriter, NumbersAreTheShortestTextThatReadsBack) {
  using namespace top_sim;
  std::vector<Snapshot> rows;
  Simulator sim(load_scene(std::string(TOP_SIM_TEST_CONFIG_DIR) + "/scenes/default.yaml"));
  for (int k = 0; k < 3000; ++k) {
    ASSERT_TRUE(sim.advance_to(1e-3 * (k + 1)));
    rows.push_back(sim.snapshot());
  }
  rows[7].gap = 1e-300;
  rows[8].energy = -1.5e300;
  rows[9].slip = std::numeric_limits<double>::quiet_NaN();
  rows[10].mu = -std::numeric_limits<double>::infinity();
  rows[11].normal_force = std::numeric_limits<double>::denorm_min();
  std::ostringstream written;
  {
    CsvWriter w(written);
    w.header();
    for (const Snapshot& s : rows) w.row(s);
  }
  EXPECT_GT(written.str().size(), 65536u) << "more than one block";
  std::istringstream in(written.str());
  std::string line;
  ASSERT_TRUE(std::getline(in, line));
  const auto& columns = trajectory_columns();
  const auto names = split_fields(line);
  ASSERT_EQ(names.size(), columns.size());
  for (std::size_t c = 0; c < columns.size(); ++c) EXPECT_EQ(names[c], columns[c].name);
  std::size_t r = 0;
  for (; std::getline(in, line); ++r) {
    ASSERT_LT(r, rows.size());
    const auto fields = split_fields(line);
    ASSERT_EQ(fields.size(), columns.size()) << "row " << r;
    for (std::size_t c = 0; c < columns.size(); ++c) {
      if (columns[c].text) {
        EXPECT_EQ(fields[c], columns[c].text(rows[r]));
        continue;
      }
      const double v = columns[c].value(rows[r]);
      if (std::isnan(v)) {
        EXPECT_EQ(fields[c], "nan");
        continue;
      }
      EXPECT_EQ(std::strtod(fields[c].c_str(), nullptr), v) << "row " << r << " " << columns[c].name << " " << fields[c];
      if (std::isfinite(v)) {
        EXPECT_EQ(significant_digits(fields[c]), shortest_digits(v)) << fields[c];
      }
    }
  }
  EXPECT_EQ(r, rows.size());
}
