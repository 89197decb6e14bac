// top_sim_lcm_echo: prints the top_sim.top_state_t stream of an LCM channel as `rostopic echo` prints TopState
// (Debian's lcm-spy does not start). docs/interfaces.md, "LCM".
#include <lcm/lcm-cpp.hpp>

#include <chrono>
#include <cstdint>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>

#include "top_sim/format.hpp"
#include "top_state_t.hpp"

namespace {

const char* kUsage =
    "usage: top_sim_lcm_echo [--url URL] [--channel NAME] [-n COUNT] [--timeout SECONDS]\n"
    "  --url URL          LCM URL (default udpm://239.255.76.67:7667?ttl=0, as top_sim_run --lcm and the node)\n"
    "  --channel NAME     channel (default TOP_STATE)\n"
    "  -n COUNT           stop after COUNT messages (default: run until interrupted)\n"
    "  --timeout SECONDS  exit 1 when no message arrives for this long (default: wait for ever)\n";

struct Arguments {
  std::string url = "udpm://239.255.76.67:7667?ttl=0", channel = "TOP_STATE";
  long count = -1;
  double timeout = -1.0;
};

struct BadArgument {
  std::string message;
};

double positive(const std::string& flag, const std::string& text) {
  const std::optional<double> v = top_sim::parse_number(text);
  if (!v || !(*v > 0.0)) throw BadArgument{flag + " = '" + text + "': must be a number > 0"};
  return *v;
}

Arguments parse(int argc, char** argv) {
  Arguments a;
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    if (flag == "-h" || flag == "--help") throw BadArgument{""};
    if (i + 1 >= argc) throw BadArgument{flag + ": unknown option or missing value"};
    const std::string value = argv[++i];
    if (flag == "--url") a.url = value;
    else if (flag == "--channel") a.channel = value;
    else if (flag == "-n") {
      const double n = positive("-n", value);
      if (n != static_cast<double>(static_cast<long>(n))) throw BadArgument{"-n = '" + value + "': must be a whole number > 0"};
      a.count = static_cast<long>(n);
    } else if (flag == "--timeout") a.timeout = positive("--timeout", value);
    else throw BadArgument{flag + ": unknown option"};
  }
  return a;
}

std::string vec(const double* v, int n) {
  std::string s = "[";
  for (int i = 0; i < n; ++i) s += (i ? ", " : "") + top_sim::format_number(v[i]);
  return s + "]";
}

std::string flag(bool b) { return b ? "True" : "False"; }

// Every field of lcm/top_state_t.lcm, in its order, one per line.
void print(const top_sim::top_state_t& m, std::ostream& out) {
  using top_sim::format_number;
  out << "utime: " << m.utime << "\nalpha: " << format_number(m.alpha) << "\nposition: " << vec(m.position, 3)
      << "\norientation: " << vec(m.orientation, 4) << "\nvelocity: " << vec(m.velocity, 3)
      << "\nangular_velocity: " << vec(m.angular_velocity, 3) << "\ntip_center: " << vec(m.tip_center, 3)
      << "\ntip_velocity: " << vec(m.tip_velocity, 3) << "\ncontact_point: " << vec(m.contact_point, 3)
      << "\nfigure_axis: " << vec(m.figure_axis, 3) << "\nspin: " << format_number(m.spin)
      << "\nhas_rotor: " << flag(m.has_rotor) << "\nrotor_spin: " << format_number(m.rotor_spin)
      << "\nslip: " << format_number(m.slip) << "\nmu: " << format_number(m.mu)
      << "\nfriction_law: \"" << m.friction_law << "\""
      << "\nnormal_force: " << format_number(m.normal_force) << "\nfriction_force: " << vec(m.friction_force, 3)
      << "\ndrilling_torque: " << format_number(m.drilling_torque)
      << "\npatch_radius: " << format_number(m.patch_radius)
      << "\nphi: " << format_number(m.phi) << "\nhas_stationary_state: " << flag(m.has_stationary_state)
      << "\nphi_star: " << format_number(m.phi_star) << "\nregime: " << int(m.regime)
      << "\nregime_name: \"" << m.regime_name << "\"\ncontact_mode: " << int(m.contact_mode)
      << "\ncontact_mode_name: \"" << m.contact_mode_name << "\"\ngap: " << format_number(m.gap)
      << "\ntouching: " << m.touching
      << "\nenergy: " << format_number(m.energy) << "\ndissipated_work: " << format_number(m.dissipated_work)
      << "\nenergy_balance_residual: " << format_number(m.energy_balance_residual)
      << "\nreal_time_factor: " << format_number(m.real_time_factor)
      << "\nrequested_real_time_factor: " << format_number(m.requested_real_time_factor)
      << "\npaused: " << flag(m.paused) << "\nfault: \"" << m.fault << "\"\nend_state: \"" << m.end_state
      << "\"\nend_state_message: \"" << m.end_state_message << "\"\n---" << std::endl;
}

class Echo {
 public:
  explicit Echo(long count) : left_(count) {}
  void on_message(const lcm::ReceiveBuffer*, const std::string&, const top_sim::top_state_t* m) {
    print(*m, std::cout);
    if (left_ > 0) --left_;
  }
  bool done() const { return left_ == 0; }

 private:
  long left_;
};

}  // namespace

int main(int argc, char** argv) {
  Arguments a;
  try {
    a = parse(argc, argv);
  } catch (const BadArgument& e) {
    if (!e.message.empty()) std::cerr << "top_sim_lcm_echo: " << e.message << "\n";
    std::cerr << kUsage;
    return e.message.empty() ? 0 : 2;
  }
  lcm::LCM lcm(a.url);
  if (!lcm.good()) {
    std::cerr << "top_sim_lcm_echo: --url = '" << a.url
              << "': LCM cannot open it (udpm:// on one machine needs a multicast route: ip route add 224.0.0.0/4 "
                 "dev lo)\n";
    return 2;
  }
  Echo echo(a.count);
  lcm.subscribe(a.channel, &Echo::on_message, &echo);
  const int wait_ms = a.timeout > 0.0 ? static_cast<int>(a.timeout * 1000.0) : 1000;
  while (!echo.done()) {
    const int r = lcm.handleTimeout(wait_ms);
    if (r < 0) {
      std::cerr << "top_sim_lcm_echo: LCM receive failed on " << a.url << "\n";
      return 1;
    }
    if (r == 0 && a.timeout > 0.0) {
      std::cerr << "top_sim_lcm_echo: no message on channel " << a.channel << " for " << a.timeout << " s\n";
      return 1;
    }
  }
  return 0;
}
