// The libFuzzer entry point of one target; BODYREC_FUZZ_TARGET names its function (see fuzz/CMakeLists.txt).
#include "fuzz_targets.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return bodyrec::fuzz::BODYREC_FUZZ_TARGET(data, size);
}
