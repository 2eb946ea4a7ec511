// The libFuzzer entry point of every target: HBA_FUZZ_HARNESS (set by the
// build) names the harness function that reads the input.
#include <cstddef>
#include <cstdint>

#include "harness.hpp"
#include "memory_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  hba::fuzz::HBA_FUZZ_HARNESS(hba::fuzz::sharedMemoryFile().hold(data, size));
  return 0;
}
