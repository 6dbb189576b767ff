#!/usr/bin/env bash
# The whole test suite, set-up included (what CI runs through .ci/run):
#   1. install the Debian packages (idempotent),
#   2. Release build + all CTest tests (unit tests, CLI tests, examples at small size),
#   3. one clang build with AddressSanitizer + UndefinedBehaviorSanitizer and libFuzzer's
#      coverage hooks (build-fuzz/), running the unit tests (the C interface's included;
#      ABLMG_SKIP_SANITIZE=1 skips them),
#   4. and every libFuzzer target of that build for FUZZ_SECONDS (default here 10) each, as many
#      at a time as there are cores (scripts/fuzz.sh; ABLMG_SKIP_FUZZ=1 skips).
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
# One clang build serves both the sanitizer tests and the fuzzers: every target is compiled with
# AddressSanitizer + UndefinedBehaviorSanitizer (UB aborts) and libFuzzer's coverage hooks
# (ABLMG_FUZZ), so the libraries are built once for both.
if [ "${ABLMG_SKIP_SANITIZE:-0}" != "1" ] || [ "${ABLMG_SKIP_FUZZ:-0}" != "1" ]; then
  CC=clang CXX=clang++ cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DABLMG_FUZZ=ON \
    -DABLMG_BUILD_BENCH=OFF -DABLMG_PYTHON=OFF -DABLMG_INSTALL=OFF > /dev/null
fi
if [ "${ABLMG_SKIP_SANITIZE:-0}" != "1" ]; then
  cmake --build build-fuzz -j"$jobs" --target test_core test_io test_mesher test_fem test_adapt test_capi
  export LSAN_OPTIONS="suppressions=$PWD/tests/sanitizer/lsan.supp:print_suppressions=0"
  ctest --test-dir build-fuzz --output-on-failure -j"$jobs" --timeout 900 -L "core|io|mesher|fem|adapt|capi"
fi
if [ "${ABLMG_SKIP_FUZZ:-0}" != "1" ]; then
  FUZZ_SECONDS=${FUZZ_SECONDS:-10} bash scripts/fuzz.sh
fi
