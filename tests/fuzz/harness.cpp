// One libFuzzer harness; MEDAX_FUZZ_TARGET names the reader (see fuzz_input.hpp).
#include "fuzz_input.hpp"

#include <cstddef>
#include <cstdint>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  medax::fuzz::feed(MEDAX_FUZZ_TARGET, {reinterpret_cast<const char*>(data), size});
  return 0;
}
