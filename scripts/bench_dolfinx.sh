#!/usr/bin/env bash
# DOLFINx in ablmg's adaptive loop (examples/python/dolfinx_adaptive.py) at ~10^5 vertices:
# serial against `ablmg adapt` (same schedule) and on its meshes, the same loop on 2 MPI ranks,
# and the remesh/solve time split at ~10^6 triangles on 2 ranks. Writes out/dolfinx/ and the
# section "DOLFINx in the loop" of docs/benchmarks.md (replaced if present).
#
#   bash scripts/bench_dolfinx.sh            (about 15 min on a 2-core machine)
#   ABLMG_BUILD=DIR  build directory (default build); SKIP_1M=1 skips the 10^6 run
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
build=${ABLMG_BUILD:-$repo/build}
out=$repo/out/dolfinx
targets=1000,2000,4000,8000,16000,32000,64000,100000
export PYTHONPATH=$build/python ABLMG_BIN=$build/bin/ablmg OMP_WAIT_POLICY=passive
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
# Idle ranks yield the core (Open MPI busy-polls otherwise; the machine is shared).
export OMPI_MCA_mpi_yield_when_idle=1
py=/usr/bin/python3
ex=$repo/examples/python/dolfinx_adaptive.py
mkdir -p "$out"
echo "== serial, with ablmg adapt"
$py "$ex" --target-vertices $targets --compare --out-dir "$out/serial" 2>&1 | grep -v '^INFO' | tee "$out/serial.log"
# 1 against 2 ranks: both with the metric snapped to a grid (--metric-quantum), so that the
# distributed solve's round-off (~1e-11) does not send the chaotic placement to other meshes.
q=0.00390625
echo "== serial, metric snapped"
$py "$ex" --target-vertices $targets --metric-quantum $q --out-dir "$out/serial_snapped" 2>&1 | grep -v '^INFO' \
  | tee "$out/serial_snapped.log"
echo "== 2 MPI ranks, metric snapped"
mpirun -n 2 --oversubscribe $py "$ex" --target-vertices $targets --metric-quantum $q --out-dir "$out/mpi2" \
  --reference "$out/serial_snapped" --reference-error-tol 1 2>&1 | grep -v '^INFO' | tee "$out/mpi2.log"
if [[ "${SKIP_1M:-0}" != 1 ]]; then
  echo "== 2 MPI ranks, wave front to ~10^6 triangles"
  mpirun -n 2 --oversubscribe $py "$ex" --problem wavefront --target-vertices 100000,500000 \
    --no-errors --out-dir "$out/mpi2_1m" 2>&1 | grep -v '^INFO' | tee "$out/mpi2_1m.log"
fi
$py "$repo/scripts/dolfinx_tables.py" "$out" "$repo/docs/benchmarks.md"
mkdir -p "$repo/docs/figures"
for p in wavefront lshape; do cp "$out/serial/$p.png" "$repo/docs/figures/dolfinx_$p.png"; done
