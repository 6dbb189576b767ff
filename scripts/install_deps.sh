#!/usr/bin/env bash
# Installs ablmg's build and test dependencies from Debian 12 packages. Idempotent:
# packages already present are not downloaded again; `apt-get update` runs only when a
# package is missing. Run as root (or with sudo).
set -euo pipefail
packages=(
  cmake g++ make pkg-config
  libeigen3-dev        # dense 2x2/3x3 algebra, sparse matrices (core, fem, adapt)
  libsuitesparse-dev   # CHOLMOD supernodal Cholesky for the P1 systems (fem)
  liblapack-dev        # dpotrf/dtrsv for the separator's dense Schur complement (fem/split_cholesky.cpp)
  libmetis-dev         # METIS_NodeND, the graph ordering compared with ours (fem/ordering.cpp)
  libopenblas0-pthread # optimised BLAS for CHOLMOD's supernodal kernels (4x faster than reference BLAS at 10^6)
  nlohmann-json3-dev   # JSON configuration and reports (cli)
  libvtk9-dev          # .vtu output through VTK's XML writer (io)
  libgtest-dev         # unit tests
  libbenchmark-dev     # bench/
  libmuparser-dev      # metric and surface expressions in x,y / u,v (core)
  libcairo2-dev        # PNG pictures of bubbles, meshes, convergence plots (io)
  libpng-dev           # the pictures written at zlib level 1 (io/picture.cpp; cairo's writer is 10x slower)
  clang libclang-rt-14-dev libomp-dev  # libFuzzer targets in fuzz/ (scripts/fuzz.sh; clang's OpenMP)
  python3-dev python3-numpy pybind11-dev python3-pybind11  # the Python module `ablmg` (python/)
  python3-pytest python3-meshio  # its tests (python/tests: pytest; medit/VTU interchange with meshio)
  python3-dolfinx mpi-default-bin  # examples/python/dolfinx_adaptive.py: DOLFINx solving on ablmg meshes, serial and MPI
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -q
  $SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
fi
