#!/usr/bin/env bash
# Builds the libFuzzer targets (clang; fuzz/fuzz_<name>.cpp) and runs each for a fixed budget on
# its seed corpus (tests/fuzz_corpus/<name>/ plus the real input files of tests/data and
# examples/configs it parses, copied to a scratch corpus so the repository is not
# modified), as many at a time as there are cores.
#   bash scripts/fuzz.sh                              # 30 s per target (what .ci/run does)
#   FUZZ_SECONDS=3600 bash scripts/fuzz.sh            # a long run: one hour per target
#   FUZZ_SECONDS=600 bash scripts/fuzz.sh medit_sol poly   # only these targets
# A failing input leaves crash-*/timeout-*/oom-* files in build-fuzz/findings/<name>/ and the
# script exits non-zero; reproduce with `build-fuzz/fuzz/fuzz_<name> FILE`, minimise with
# `-minimize_crash=1 -runs=10000 FILE`, and turn it into a regression test (tests/io, tests/core)
# before fixing it.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${FUZZ_SECONDS:-30}
jobs=${FUZZ_JOBS:-$(nproc)}
# The same configuration as scripts/test.sh's sanitizer stage, so the libraries built there are reused.
CC=clang CXX=clang++ cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DABLMG_FUZZ=ON \
  -DABLMG_BUILD_BENCH=OFF -DABLMG_PYTHON=OFF -DABLMG_INSTALL=OFF > /dev/null
if [ $# -gt 0 ]; then
  names="$*"
else
  names=$(cd fuzz && ls fuzz_*.cpp | sed 's/^fuzz_//; s/\.cpp$//')
fi
targets=$(for n in $names; do echo "fuzz_$n"; done)
cmake --build build-fuzz -j"$(nproc)" --target $targets

# One target: fuzz for $seconds in build-fuzz/findings/<name>/, the log in run.log there.
fuzz_one() {
  local name=$1 work=build-fuzz/corpus/$1 findings=build-fuzz/findings/$1
  mkdir -p "$work" "$findings"
  rm -f "$findings"/crash-* "$findings"/timeout-* "$findings"/oom-* "$findings"/leak-*
  [ -d "tests/fuzz_corpus/$name" ] && cp -r "tests/fuzz_corpus/$name/." "$work/"
  # The repository's real input files are seeds too (kept in one place, not copied into the corpus).
  local seeds=()
  case $name in
    medit_mesh) seeds=(tests/data/*.mesh) ;;
    medit_sol) seeds=(tests/data/*.sol) ;;
    poly) seeds=(tests/data/*.poly) ;;
    config) seeds=(examples/configs/paper_*.json examples/configs/speed_*.json) ;;
    problem) seeds=(examples/configs/adapt_*.json) ;;
  esac
  [ ${#seeds[@]} -eq 0 ] || cp "${seeds[@]}" "$work/"
  (cd "$findings" && "../../fuzz/fuzz_$name" -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=10 \
     "../../../$work" > run.log 2>&1) || true
}

running=0
for n in $names; do
  echo "== fuzzing $n for ${seconds}s"
  fuzz_one "$n" &
  running=$((running + 1))
  if [ "$running" -ge "$jobs" ]; then
    wait -n || true
    running=$((running - 1))
  fi
done
wait

failed=0
for n in $names; do
  findings=build-fuzz/findings/$n
  echo "== $n: $(grep -E '^Done [0-9]+ runs' "$findings/run.log" || echo 'no summary')"
  if ls "$findings"/crash-* "$findings"/timeout-* "$findings"/oom-* "$findings"/leak-* > /dev/null 2>&1; then
    echo "fuzz target $n found a failing input: $(cd "$findings" && ls crash-* timeout-* oom-* leak-* 2> /dev/null)" >&2
    grep -E -m 5 'ERROR|runtime error|SUMMARY|deadly signal' "$findings/run.log" >&2 || true
    failed=1
  elif ! grep -qE '^Done [0-9]+ runs' "$findings/run.log"; then
    echo "fuzz target $n did not finish its run:" >&2
    tail -n 5 "$findings/run.log" >&2
    failed=1
  fi
done
exit $failed
