#!/usr/bin/env bash
# Writes tests/costs.txt, each test's wall time in seconds from the last
# ctest runs in build/ (ctest keeps them in
# build/Testing/Temporary/CTestCostData.txt), longest first. ctest -j
# starts the tests with the largest COST first (tests/CMakeLists.txt reads
# the file), so that no long test runs alone at the end of the suite.
# Usage (after `cd build && ctest -j2`): bash tests/update_costs.sh
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
data="$root/build/Testing/Temporary/CTestCostData.txt"
[ -f "$data" ] || { echo "update_costs.sh: no $data; run ctest in build/ first"; exit 2; }
{
  echo "# test seconds (bash tests/update_costs.sh; read by tests/CMakeLists.txt)"
  # lines "name runs average_seconds" up to the line "---" (failed tests)
  awk '/^---/ { exit } NF == 3 { printf "%s %.1f\n", $1, $3 }' "$data" | sort -k2,2 -rn
} > "$root/tests/costs.txt"
echo "update_costs.sh: $(grep -vc '^#' "$root/tests/costs.txt") tests in tests/costs.txt"
