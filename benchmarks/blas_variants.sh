#!/bin/bash
# The whole ctest suite under each OpenBLAS kernel family and thread count
# that machines of the project's kind pick: OPENBLAS_CORETYPE = Haswell,
# SkylakeX and Zen, each with 1 and 2 threads (OPENBLAS_NUM_THREADS and
# OMP_NUM_THREADS; the serial OpenBLAS that scripts/setup.sh installs ignores
# them, a threaded one set by update-alternatives does not). Nothing in the
# tests pins a kernel: this script only varies the environment they run in.
# Prints one line per variant (passed/failed, the failing tests, seconds)
# and exits 1 if any variant failed. doc/verification.md, "Round-off".
# Usage (after bash scripts/test.sh has built build/):
#   bash benchmarks/blas_variants.sh [KERNELS] [THREADS] [extra ctest args]
#   e.g. bash benchmarks/blas_variants.sh "Haswell SkylakeX Zen" "1 2"
set -u
root=$(cd "$(dirname "$0")/.." && pwd)
kernels=${1:-"Haswell SkylakeX Zen"}
threads=${2:-"1 2"}
shift $(( $# > 2 ? 2 : $# ))
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
cd "$root/build" || { echo "blas_variants.sh: no build/ (run bash scripts/test.sh)"; exit 2; }
echo "BLAS: $(readlink -f /usr/lib/x86_64-linux-gnu/libblas.so.3)"
status=0
for k in $kernels; do
  for t in $threads; do
    log=$(mktemp)
    start=$(date +%s)
    OPENBLAS_CORETYPE=$k OPENBLAS_NUM_THREADS=$t OMP_NUM_THREADS=$t \
      ctest -j "$(nproc)" "$@" > "$log" 2>&1
    rc=$?
    seconds=$(( $(date +%s) - start ))
    summary=$(grep -E "tests passed|tests failed" "$log" | tail -n 1)
    failed=$(sed -n 's/^[[:space:]]*[0-9]* - \([^ ]*\) .*/\1/p' "$log" | tr '\n' ' ')
    echo "OPENBLAS_CORETYPE=$k threads=$t: ${summary:-no summary} ${failed:+(failed: $failed)} ${seconds} s"
    [ $rc -eq 0 ] || status=1
    rm -f "$log"
  done
done
exit $status
