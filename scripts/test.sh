#!/usr/bin/env bash
# The whole test suite, set-up included (what CI runs through .ci/run):
#   1. install the Debian packages (idempotent),
#   2. Release build + all CTest tests (unit tests, CLI tests, examples at small size),
#   3. an AddressSanitizer + UndefinedBehaviorSanitizer build running the unit tests (the C
#      interface's included)
#      (set ABLMG_SKIP_SANITIZE=1 to skip it locally),
#   4. every libFuzzer target for FUZZ_SECONDS (default 30) each, as many at a time as there are
#      cores (scripts/fuzz.sh; ABLMG_SKIP_FUZZ=1 skips).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_deps.sh
jobs=$(nproc)
# ctest runs tests in parallel and each uses OpenMP: sleeping (not spinning) idle threads keep
# an oversubscribed machine from slowing to a crawl.
export OMP_WAIT_POLICY=passive
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DABLMG_BUILD_BENCH=ON
cmake --build build -j"$jobs"
ctest --test-dir build --output-on-failure -j"$jobs" --timeout 900
if [ "${ABLMG_SKIP_SANITIZE:-0}" != "1" ]; then
  cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DABLMG_SANITIZE=ON -DABLMG_BUILD_BENCH=OFF
  cmake --build build-asan -j"$jobs" --target test_core test_io test_mesher test_fem test_adapt test_capi 2>/dev/null ||
    cmake --build build-asan -j"$jobs"
  export LSAN_OPTIONS="suppressions=$PWD/tests/sanitizer/lsan.supp:print_suppressions=0"
  ctest --test-dir build-asan --output-on-failure -j"$jobs" --timeout 900 -L "core|io|mesher|fem|adapt|capi"
fi
if [ "${ABLMG_SKIP_FUZZ:-0}" != "1" ]; then
  bash scripts/fuzz.sh
fi
