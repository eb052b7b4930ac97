#!/usr/bin/env bash
# Builds the libFuzzer scene target (tests/fuzz) with clang into its own
# build directory and runs it for N seconds (default 60) from the committed
# seed corpus tests/fuzz/corpus. Exits non-zero on any finding; the input
# that caused it is left in <build>/findings/.
#   tools/run-fuzz.sh [seconds]
# Environment: SPOOK_FUZZ_BUILD_DIR (default build-fuzz; a build configured
# with -DSPOOK_BUILD_FUZZ=ON is reused), SPOOK_FUZZ_SKIP
# (comma-separated known findings the target steers around, see
# tests/fuzz/fuzz_scene.cpp), CMAKE_CXX_COMPILER_LAUNCHER (e.g. ccache).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

seconds=${1:-60}
build=${SPOOK_FUZZ_BUILD_DIR:-build-fuzz}
clangxx=$(command -v clang++ || command -v clang++-14 || true)
if [ -z "$clangxx" ]; then
  echo "run-fuzz: clang++ not found (tools/install-deps.sh installs it)" >&2
  exit 1
fi

# A build directory configured with the target already (CI's sanitized
# build, -DSPOOK_BUILD_FUZZ=ON) is reused as it is. Otherwise: Debug keeps
# spook's assertions; -O1 -g1 as the sanitized CI build.
if ! grep -q '^SPOOK_BUILD_FUZZ:BOOL=ON' "$build/CMakeCache.txt" 2>/dev/null; then
  cmake -S . -B "$build" -DCMAKE_CXX_COMPILER="$clangxx" -DCMAKE_BUILD_TYPE=Debug "-DCMAKE_CXX_FLAGS_DEBUG=-O1 -g1" \
    -DSPOOK_BUILD_TESTS=OFF -DSPOOK_BUILD_EXAMPLES=OFF -DSPOOK_BUILD_BENCH=OFF -DSPOOK_BUILD_FUZZ=ON
fi
cmake --build "$build" -j2 --target spook_fuzz_scene

# New inputs go to <build>/corpus (the first directory); the committed seeds
# are only read. -timeout catches a step that never returns (the target
# itself aborts on a step longer than 2 s).
mkdir -p "$build/corpus" "$build/findings"
"$build/tests/fuzz/spook_fuzz_scene" -max_total_time="$seconds" -timeout=25 -max_len=1024 -print_final_stats=1 \
  -artifact_prefix="$build/findings/" "$build/corpus" tests/fuzz/corpus
