# --help and --print-parameters work; every entry is documented; doc/parameters.prm is up to date.
set -eu
cd "$WORK_DIR"
"$DENSIFY" --help | grep -q "Usage"
"$DENSIFY" --print-parameters > parameters.prm
# every "set" line is directly preceded by its documentation comment
awk '/^ *set / { if (prev !~ /^ *#/) { print "undocumented: " $0; bad = 1 } }
     { if ($0 !~ /^ *$/) prev = $0 }
     END { exit bad }' parameters.prm
# units or a range are named in each documentation block
n_entries=$(grep -c '^ *set ' parameters.prm)
echo "$n_entries documented entries"
[ "$n_entries" -ge 25 ]
# the reference in doc/ is the generated one
if ! diff -u "$SOURCE_DIR/doc/parameters.prm" parameters.prm; then
  echo "doc/parameters.prm is out of date: regenerate it with"
  echo "  build/densify --print-parameters > doc/parameters.prm"
  exit 1
fi
# --validate accepts every scene in prm/
for scene in "$SOURCE_DIR"/prm/*.prm; do
  "$DENSIFY" --validate "$scene"
done
