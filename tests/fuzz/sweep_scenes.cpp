// Random scenes of the fuzz target's builder (scene_builder.hpp) from a
// seeded generator, without libFuzzer or sanitizers: thousands a minute in
// an optimized build, where the fuzz target makes ten a second. It prints
// each finding with the run that made it and goes on.
//   cmake --build build --target spook_scene_sweep
//   build/tests/spook_scene_sweep [runs = 20000] [seed = 1] [only this run]
// Bytes are uniform in 0..223 (reals within their typical ranges, no
// extremes: those the fuzz target explores). Finite blow-ups count as
// findings here (scene_builder.hpp, blowUpIsFinding; SPOOK_SWEEP_NO_BLOWUPS=1
// counts only the fuzz target's findings).
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

#include "scene_builder.hpp"

int main(int argc, char** argv) {
  const int runs = argc > 1 ? std::atoi(argv[1]) : 20000;
  std::mt19937 random(argc > 2 ? static_cast<unsigned>(std::atoi(argv[2])) : 1u);
  const int only = argc > 3 ? std::atoi(argv[3]) : -1;
  spook::fuzz::findingThrows = true;
  spook::fuzz::blowUpIsFinding = std::getenv("SPOOK_SWEEP_NO_BLOWUPS") == nullptr;
  int findings = 0, withWires = 0;
  for (int run = 0; run < runs; ++run) {
    std::vector<std::uint8_t> bytes(60 + random() % 200);
    for (auto& b : bytes) b = static_cast<std::uint8_t>(random() % 224);
    if (only >= 0 && run != only) continue;
    spook::fuzz::Reader in(bytes.data(), bytes.size());
    try {
      if (in.choice(2) == 0) {
        spook::fuzz::Builder<double> scene{in, {}, {}, -1, {}};
        scene.run();
        withWires += scene.wires.empty() ? 0 : 1;
      } else {
        spook::fuzz::Builder<float> scene{in, {}, {}, -1, {}};
        scene.run();
        withWires += scene.wires.empty() ? 0 : 1;
      }
    } catch (const spook::fuzz::Finding&) {
      std::fprintf(stderr, "  in run %d\n", run);
      ++findings;
    }
  }
  std::printf("%d runs (%d with wires), %d findings\n", runs, withWires, findings);
  return findings == 0 ? 0 : 1;
}
