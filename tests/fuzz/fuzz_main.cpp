// libFuzzer glue for one target, chosen at compile time (PMSIM_FUZZ_TARGET=<entry name>).
// PMSIM_FUZZ_MAKE_SEEDS=<folder> makes the binary write its seed corpus (from PMSIM_ASSETS or the
// source assets/) and exit, so scripts/fuzz.sh needs nothing but the fuzz build.
#include <cstdlib>
#include <string>

#include "core/base/asset_locator.h"
#include "tests/fuzz/fuzz_targets.h"

#define PMSIM_CAT2(a, b) a##b
#define PMSIM_CAT(a, b) PMSIM_CAT2(a, b)

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  if (const char* out = std::getenv("PMSIM_FUZZ_MAKE_SEEDS"); out && *out) {
    pmsim::fuzz::PMSIM_CAT(PMSIM_FUZZ_TARGET, _seeds)(pmsim::asset_dir(), out);
    std::exit(0);
  }
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return pmsim::fuzz::PMSIM_FUZZ_TARGET(data, size);
}
