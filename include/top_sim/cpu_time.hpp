// CPU time of the calling thread: what tools and the node report as a simulation's cost.
#pragma once

namespace top_sim {

// CPU seconds of the calling thread (tools run simulations in parallel threads; std::clock counts them all).
double thread_cpu_seconds();

}  // namespace top_sim
