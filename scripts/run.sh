#!/usr/bin/env bash
# Quick start 1: install what is missing, build, and run a scene (default: prm/default.prm) into output/.
# Usage: bash scripts/run.sh [FILE.prm] [--set "Subsection/Name=value" ...]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
bash "$root/scripts/setup.sh"
if [ $# -eq 0 ]; then set -- "$root/prm/default.prm"; fi
exec "$root/build/densify" "$@"
