#!/usr/bin/env bash
# Installs what spook needs to build, test and benchmark on Debian 12.
# Does nothing (and needs no network or root) when everything is present.
set -euo pipefail

# clang and libclang-rt-14-dev (libFuzzer and the sanitizer runtimes, only
# recommended by clang): the single-header clang test and tools/run-fuzz.sh.
packages=(cmake g++ make python3 libeigen3-dev libccd-dev doctest-dev libbenchmark-dev libfcl-dev
  clang libclang-rt-14-dev)

missing=()
for package in "${packages[@]}"; do
  if ! dpkg -s "$package" 2>/dev/null | grep -q '^Status: install ok installed$'; then
    missing+=("$package")
  fi
done

if [ "${#missing[@]}" -eq 0 ]; then
  echo "install-deps: all present (${packages[*]})"
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
as_root=()
if [ "$(id -u)" -ne 0 ]; then
  if command -v sudo >/dev/null 2>&1; then
    as_root=(sudo)
  else
    echo "install-deps: not root and no sudo; install these yourself: ${missing[*]}" >&2
    exit 1
  fi
fi

export DEBIAN_FRONTEND=noninteractive
"${as_root[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update -q
"${as_root[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends "${missing[@]}"
