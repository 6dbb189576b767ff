#!/usr/bin/env bash
# Builds the libFuzzer targets (clang) and runs each for a fixed budget on its seed corpus
# (tests/fuzz_corpus/<target>/, copied to a scratch corpus so the repository is not modified).
#   bash scripts/fuzz.sh            # 30 s per target (what .ci/run does)
#   FUZZ_SECONDS=3600 bash scripts/fuzz.sh   # a long run
# A crash leaves crash-* files in build-fuzz/findings/<target>/ and exits non-zero; turn each
# into a regression test (tests/io or tests/core) before fixing it.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${FUZZ_SECONDS:-30}
CC=clang CXX=clang++ cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DABLMG_FUZZ=ON \
  -DBUILD_TESTING=OFF -DABLMG_BUILD_BENCH=OFF > /dev/null
targets=$(cd fuzz && ls fuzz_*.cpp | sed 's/\.cpp$//')
cmake --build build-fuzz -j"$(nproc)" --target $targets
for t in $targets; do
  name=${t#fuzz_}
  work=build-fuzz/corpus/$name findings=build-fuzz/findings/$name
  mkdir -p "$work" "$findings"
  [ -d "tests/fuzz_corpus/$name" ] && cp -r "tests/fuzz_corpus/$name/." "$work/"
  echo "== fuzzing $name for ${seconds}s"
  (cd "$findings" && "../../fuzz/$t" -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=10 "../../../$work" 2>&1 | tail -2)
  if ls "$findings"/crash-* "$findings"/timeout-* "$findings"/oom-* > /dev/null 2>&1; then
    echo "fuzz target $name found a failing input: $(ls "$findings")" >&2
    exit 1
  fi
done
