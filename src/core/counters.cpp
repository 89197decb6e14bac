// Work counters of the core (counters.hpp).
#include "counters.hpp"

namespace top_sim {

WorkCounters& work_counters() {
  static WorkCounters counters;
  return counters;
}

}  // namespace top_sim
