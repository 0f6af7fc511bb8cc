#!/usr/bin/env bash
# A die fill by LIGGGHTS written as Densify's particle file: runs
# scripts/packing/liggghts_fill.py (its --help lists the options) with the
# system Python, which has numpy (scripts/setup.sh installs it and liggghts).
# Usage: bash scripts/packing/liggghts_fill.sh --die-diameter 20 --particles 200 \
#          --diameters 2,3 --materials Sn:0.7,Fe:0.3 --seed 1 --out output/fill
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
exec "${PYTHON:-/usr/bin/python3}" "$here/liggghts_fill.py" "$@"
