# The mesh size is estimated before meshing (particles x tetrahedra per
# particle from its diameter and the element sizes): a scene above
# Mesh/Maximum elements is refused within seconds with exit code 2 and one
# line naming the entry; --validate prints the estimate, which is near the
# mesh a run makes.
set -u
cd "$WORK_DIR"
rm -rf out out_*
source "$SOURCE_DIR/tests/cli/lib/expect_error.bash"
prm="$SOURCE_DIR/prm/default.prm"
layer="$SOURCE_DIR/prm/single_layer_sn_light.prm"
within() {
  local limit=$1 start=$2 took
  took=$(($(date +%s) - start))
  [ "$took" -le "$limit" ] || { echo "FAIL: took ${took}s"; fails=$((fails + 1)); }
}
start=$(date +%s)
expect_error "element size 1e-6" 2 "Mesh/Maximum elements" \
  "$DENSIFY" "$prm" --set "Output/Directory=out" --set "Mesh/Element size=1e-6" \
  --set "Mesh/Refined element size=1e-6"
expect_error "element size 0.01" 2 "Mesh/Maximum elements" \
  "$DENSIFY" "$prm" --set "Output/Directory=out" --set "Mesh/Element size=0.01"
expect_error "element size 0.01, --validate" 2 "Mesh/Maximum elements" \
  "$DENSIFY" --validate "$prm" --set "Mesh/Element size=0.01"
within 20 $start
start=$(date +%s)
# (a stroke of 0.5 mm: the paper's 1.28 mm would press a layer that fills
# the die past 100 %, which is refused first)
expect_error "hexagonal layer in a 2000 mm die" 2 "Mesh/Maximum elements" \
  "$DENSIFY" "$layer" --set "Output/Directory=out" --set "Tools/Die wall/Diameter=2000" \
  --set "Tools/Upper punch/Displacement history=0:0, 0.8:0.5"
within 45 $start
[ ! -e out ] || { echo "FAIL: a refused run created its output directory"; fails=$((fails + 1)); }

# the limit can be raised
out=$("$DENSIFY" --validate "$prm" --set "Mesh/Element size=0.01" \
  --set "Mesh/Maximum elements=200000000" 2>&1)
echo "$out"
printf '%s' "$out" | grep -q "valid (3 particle(s), .*; about [0-9]* tetrahedra" ||
  { echo "FAIL: raised limit"; fails=$((fails + 1)); }

# the estimate against the mesh a run makes, uniform and refined
for case in "0.3 none" "0.3 0,0,1;0,0,-1" "0.6 none"; do
  set -- $case
  args=(--set "Mesh/Element size=$1" --set "Output/Interval=0"
    --set "Time stepping/Number of steps=1" --set "Output/Directory=out_$1")
  [ "$2" = none ] && args+=(--set "Mesh/Refinement directions=") ||
    args+=(--set "Mesh/Refinement directions=$2")
  estimate=$("$DENSIFY" --validate "$prm" "${args[@]}" |
    sed -n 's/.*about \([0-9]*\) tetrahedra.*/\1/p')
  actual=$("$DENSIFY" "$prm" "${args[@]}" | sed -n 's/^Densify: .*, \([0-9]*\) tetrahedra.*/\1/p')
  echo "h=$1 refinement $2: estimate $estimate, mesh $actual"
  if [ -z "$estimate" ] || [ -z "$actual" ] || [ $((2 * estimate)) -lt "$actual" ] ||
    [ "$estimate" -gt $((2 * actual)) ]; then
    echo "FAIL: estimate off by more than a factor 2"
    fails=$((fails + 1))
  fi
done
echo "$fails failure(s)"
[ "$fails" -eq 0 ]
