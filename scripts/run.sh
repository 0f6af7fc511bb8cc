#!/usr/bin/env bash
# The first run: install what is missing, build, compact the paper's light
# layer (prm/single_layer_sn_light.prm, seven tin spheres, about 2 minutes on
# one core), then write its curves, pictures and per-particle table and print
# a summary (scripts/postprocess/report.sh).
# Usage: bash scripts/run.sh [FILE.prm] [--set "Subsection/Name=value" ...]
#   Without FILE.prm the light layer runs; --set overrides apply either way.
#   DENSIFY=path/to/densify skips the set-up and runs that executable.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
if [ -z "${DENSIFY:-}" ]; then
  # only the executable: the test programs are built by scripts/test.sh
  bash "$root/scripts/setup.sh" densify
  DENSIFY=$root/build/densify
fi
if [ $# -eq 0 ] || [[ $1 == -* ]]; then
  set -- "$root/prm/single_layer_sn_light.prm" "$@"
fi
log=$(mktemp)
trap 'rm -f "$log"' EXIT
"$DENSIFY" "$@" | tee "$log"
# the run's last line names its output directory: "Finished ...; results in DIR/"
dir=$(sed -n 's/^Finished .*; results in \(.*\)\/$/\1/p' "$log" | tail -n 1)
if [ -z "$dir" ]; then
  echo "run.sh: the run did not finish; nothing to post-process" >&2
  exit 1
fi
echo
bash "$root/scripts/postprocess/report.sh" "$dir"
