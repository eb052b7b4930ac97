// libFuzzer target: a random scene built from the input bytes (scene_builder.hpp),
// stepped 30 times. Built by -DSPOOK_BUILD_FUZZ=ON with clang
// (tools/run-fuzz.sh). The float scenes are instantiated in
// fuzz_scene_float.cpp, so that the two halves compile in parallel.
#include "scene_builder.hpp"

namespace spook::fuzz {
void runFloatScene(Reader& in);
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  spook::fuzz::Reader in(data, size);
  if (in.choice(2) == 0) {
    spook::fuzz::Builder<double>{in, {}, {}, -1, {}}.run();
  } else {
    spook::fuzz::runFloatScene(in);
  }
  return 0;
}
