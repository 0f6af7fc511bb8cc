#!/usr/bin/env bash
# Installs the Debian packages Densify needs (if missing), configures and builds it into build/.
# Usage: bash scripts/setup.sh [TARGET...]   (environment: BUILD_TYPE=Release|Debug, JOBS=n)
#   Without TARGET everything is built (the executable, the test programs,
#   the benchmarks); scripts/run.sh builds only the target densify.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
packages=(libdeal.ii-dev libmumps-dev g++ make cmake numdiff openmpi-bin
          python3-numpy python3-matplotlib python3-vtk9 xvfb xauth  # scripts/postprocess
          time  # /usr/bin/time in benchmarks/scene_speed.sh
          bc  # arithmetic of benchmarks/explicit_vs_implicit.sh
          liggghts  # the DEM die fill of scripts/packing/liggghts_fill.sh (test cli.liggghts_fill)
          libopenblas0-serial)  # optimised BLAS/LAPACK for MUMPS (2-4x faster factorizations)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  sudo_cmd=""
  [ "$(id -u)" -ne 0 ] && sudo_cmd="sudo"
  $sudo_cmd apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
# Open MPI refuses to run as root unless told it may.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
jobs=${JOBS:-$(nproc)}
cmake -S "$root" -B "$root/build" -DCMAKE_BUILD_TYPE="${BUILD_TYPE:-Release}" ${CMAKE_ARGS:-} >/dev/null
targets=()
for t in "$@"; do targets+=(--target "$t"); done
cmake --build "$root/build" -j "$jobs" "${targets[@]}"
