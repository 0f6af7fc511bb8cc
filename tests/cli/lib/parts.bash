# Sourced by cli tests that ctest runs in parts (tests/CMakeLists.txt: a
# script with a line "# ctest parts: NAME[:PROCESSORS] ..." becomes one test
# cli.SCRIPT.NAME per part, each holding its processors (default 1), and the
# test cli.SCRIPT that runs the checks once every part has passed). So ctest
# runs a 1-rank part beside another test while only 2-rank parts hold both
# cores. "bash SCRIPT.sh PART" runs one part, "bash SCRIPT.sh check" the
# checks on the parts' outputs, "bash SCRIPT.sh" everything in order.
test_part=${1:-all}
# part NAME: true when this invocation runs the part NAME
part() { [ "$test_part" = all ] || [ "$test_part" = "$1" ]; }
