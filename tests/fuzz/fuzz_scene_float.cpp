// The float half of the fuzz target (fuzz_scene.cpp).
#include "scene_builder.hpp"

namespace spook::fuzz {
void runFloatScene(Reader& in) { Builder<float>{in, {}, {}, -1, {}}.run(); }
}  // namespace spook::fuzz
