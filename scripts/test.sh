#!/usr/bin/env bash
# Quick start 2: install what is missing, build, and run the whole ctest suite.
# Usage: bash scripts/test.sh [extra ctest arguments]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
bash "$root/scripts/setup.sh"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
cd "$root/build"
exec ctest --output-on-failure -j "${JOBS:-$(nproc)}" "$@"
