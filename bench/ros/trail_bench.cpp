// What a node's trails cost per tick (issue 31): TOPS trails fed in turn, one contact point per top per tick as
// StateOutput::publish_top adds them, trimmed at every 20th tick as a 10 Hz marker tick would. The contact points
// come from a CSV of top_sim_run (columns contact_x, contact_y, contact_z), each top offset in time. Prints the CPU
// time per add; under valgrind --tool=callgrind the instruction counts compare builds exactly (the catkin build has
// it as devel/lib/top_sim/trail_bench; another commit's trail by hand, its trail.{hpp,cpp} from git show in DIR):
//   g++ -O2 -DNDEBUG -I DIR -I/usr/include/eigen3 bench/ros/trail_bench.cpp DIR/trail.cpp -lrostime -o /tmp/tb
//   top_sim_run config/scenes/default.yaml --duration 60 --rate 200 --csv /tmp/contact.csv
//   valgrind --tool=callgrind /tmp/tb /tmp/contact.csv 100 [RESOLUTION=2e-4] [LENGTH=1000]   (and 200 tops: the
//   difference of the two counts over 100 x the rows is the instructions per add)
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "trail.hpp"

namespace {

double cpu() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// The contact point of every row of a top_sim_run CSV.
std::vector<Eigen::Vector3d> read_contacts(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> names;
  std::stringstream header(line);
  for (std::string name; std::getline(header, name, ',');) names.push_back(name);
  int cx = -1;
  for (std::size_t i = 0; i < names.size(); ++i)
    if (names[i] == "contact_x") cx = static_cast<int>(i);
  std::vector<Eigen::Vector3d> out;
  if (cx < 0) return out;
  while (std::getline(in, line)) {
    std::stringstream row(line);
    std::vector<double> v;
    for (std::string cell; std::getline(row, cell, ',');) v.push_back(std::atof(cell.c_str()));
    if (static_cast<int>(v.size()) > cx + 2) out.emplace_back(v[cx], v[cx + 1], v[cx + 2]);
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: trail_bench CONTACTS.csv TOPS [RESOLUTION=2e-4] [LENGTH=1000]\n");
    return 2;
  }
  const std::vector<Eigen::Vector3d> contacts = read_contacts(argv[1]);
  const int tops = std::atoi(argv[2]);
  const double resolution = argc > 3 ? std::atof(argv[3]) : 2e-4;
  const std::size_t length = argc > 4 ? std::strtoul(argv[4], nullptr, 10) : 1000;
  if (contacts.empty() || tops < 1) {
    std::fprintf(stderr, "trail_bench: no contact_x column in %s, or TOPS < 1\n", argv[1]);
    return 2;
  }
  std::vector<top_sim_ros::Trail> trails(static_cast<std::size_t>(tops));
  const double start = cpu();
  for (std::size_t tick = 0; tick < contacts.size(); ++tick) {
    const ros::Time stamp(1.0 + 0.005 * static_cast<double>(tick));
    for (std::size_t k = 0; k < trails.size(); ++k) {
      const Eigen::Vector3d& p = contacts[(tick + 37 * k) % contacts.size()];
      trails[k].add(p + Eigen::Vector3d(0.01 * static_cast<double>(k), 0.0, 0.0), stamp, resolution, length);
      if (tick % 20 == 0) trails[k].trim(60.0);
    }
  }
  const double adds = static_cast<double>(contacts.size()) * tops;
  std::printf("%zu ticks x %d tops: %.1f ns per add (CPU)\n", contacts.size(), tops, 1e9 * (cpu() - start) / adds);
  return 0;
}
