// libFuzzer entry of the command target (fuzz_targets.hpp); built with -DTOP_SIM_FUZZ=ON, run by scripts/fuzz.sh.
#include "fuzz_targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  top_sim::fuzz::require("command", top_sim::fuzz::command(data, size));
  return 0;
}
