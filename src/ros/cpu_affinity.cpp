#include "cpu_affinity.hpp"

#include <dirent.h>
#include <sched.h>
#include <sys/syscall.h>
#include <sys/types.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "node_parameters.hpp"

namespace top_sim_ros {

std::string check_cpu_affinity(const std::string& where, int cpu, int cpus) {
  if (cpu == kNoCpuAffinity || (cpu >= 0 && cpu < cpus)) return "";
  return range_error(where, cpu, "-1 (do not pin) or a CPU in [0, " + std::to_string(cpus - 1) + "] (" +
                                     std::to_string(cpus) + " CPUs online)");
}

int online_cpus() {
  const long n = sysconf(_SC_NPROCESSORS_ONLN);
  return n > 0 ? static_cast<int>(n) : 1;
}

namespace {

std::vector<pid_t> process_threads() {
  std::vector<pid_t> tids;
  DIR* dir = opendir("/proc/self/task");
  if (!dir) return tids;
  while (const dirent* e = readdir(dir))
    if (e->d_name[0] != '.') tids.push_back(static_cast<pid_t>(std::atoi(e->d_name)));
  closedir(dir);
  return tids;
}

}  // namespace

// Each thread has its own mask: the ones already running are set one by one (new threads inherit their creator's).
std::string pin_process_to_cpu(int cpu) {
  cpu_set_t set;
  CPU_ZERO(&set);
  CPU_SET(cpu, &set);
  if (sched_setaffinity(0, sizeof(set), &set) != 0)
    return "sched_setaffinity to CPU " + std::to_string(cpu) + ": " + std::strerror(errno);
  for (pid_t tid : process_threads())
    if (sched_setaffinity(tid, sizeof(set), &set) != 0 && errno != ESRCH)  // ESRCH: the thread has ended
      return "sched_setaffinity of thread " + std::to_string(tid) + " to CPU " + std::to_string(cpu) + ": " +
             std::strerror(errno);
  return "";
}

std::string yield_other_threads() {
  const auto self = static_cast<pid_t>(syscall(SYS_gettid));
  sched_param none{};
  for (pid_t tid : process_threads())
    if (tid != self && sched_setscheduler(tid, SCHED_BATCH, &none) != 0 && errno != ESRCH)
      return "sched_setscheduler of thread " + std::to_string(tid) + " to SCHED_BATCH: " + std::strerror(errno);
  return "";
}

std::string allowed_cpus() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof(set), &set) != 0) return std::string("sched_getaffinity: ") + std::strerror(errno);
  std::string out;
  for (int c = 0; c < CPU_SETSIZE; ++c) {
    if (!CPU_ISSET(c, &set)) continue;
    int last = c;
    while (last + 1 < CPU_SETSIZE && CPU_ISSET(last + 1, &set)) ++last;
    out += (out.empty() ? "" : ",") + std::to_string(c) + (last > c ? "-" + std::to_string(last) : "");
    c = last;
  }
  return out;
}

}  // namespace top_sim_ros
