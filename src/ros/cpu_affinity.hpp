// ~cpu_affinity (docs/ros.md, "Parameters"): the node pins all its threads to one CPU. The main loop and roscpp's
// I/O threads hand every tick's messages to each other; on two cores those wake-ups cross cores and cost about
// 30 % of the node's CPU with 1000 tops (docs/node_benchmark.md, "Many tops per node").
#pragma once

#include <string>

namespace top_sim_ros {

constexpr int kNoCpuAffinity = -1;  // the default: the node does not pin itself

// "" or why `cpu` cannot be ~cpu_affinity on a machine with `cpus` CPUs (-1, or 0 to cpus - 1); `where` names it.
std::string check_cpu_affinity(const std::string& where, int cpu, int cpus);

int online_cpus();  // CPUs online (sysconf), the range ~cpu_affinity is checked against

// Pins every thread of this process, and so every thread it starts later, to `cpu`: "" or why not.
std::string pin_process_to_cpu(int cpu);

// Every thread but the caller becomes SCHED_BATCH: a thread it wakes (roscpp's I/O thread, at each publish) no
// longer preempts it, so on one CPU the tick's messages go out together after the tick. "" or why not.
std::string yield_other_threads();

// The CPUs the calling thread may run on, as /proc lists them ("1", "0-1", "0,2").
std::string allowed_cpus();

}  // namespace top_sim_ros
