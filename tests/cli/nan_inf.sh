# NaN and infinity in numbers the patterns do not check (tables, points)
# are refused with exit code 2 and one line naming the entry, before any
# meshing.
set -u
cd "$WORK_DIR"
source "$SOURCE_DIR/tests/cli/lib/expect_error.bash"
prm="$SOURCE_DIR/prm/default.prm"
run=("$DENSIFY" "$prm" --set "Output/Directory=out")
for bad in nan inf -inf NaN; do
  expect_error "displacement history $bad" 2 "Tools/Upper punch/Displacement history" \
    "${run[@]}" --set "Tools/Upper punch/Displacement history=0:0, 1:$bad"
  expect_error "displacement history time $bad" 2 "Tools/Upper punch/Displacement history" \
    "${run[@]}" --set "Tools/Upper punch/Displacement history=0:0, $bad:0.1"
  expect_error "body force $bad" 2 "Particles/Body force" \
    "${run[@]}" --set "Particles/Body force=0,0,$bad"
  expect_error "body force history $bad" 2 "Particles/Body force history" \
    "${run[@]}" --set "Particles/Body force history=0:1, 1:$bad"
  expect_error "lateral history $bad" 2 "Tools/Upper punch/Lateral displacement history" \
    "${run[@]}" --set "Tools/Upper punch/Lateral displacement history=0:$bad"
  expect_error "centre $bad" 2 "Particles/Centres" \
    "${run[@]}" --set "Particles/Centres=0,$bad,1.25"
  expect_error "diameter $bad" 2 "Particles/Diameters" \
    "${run[@]}" --set "Particles/Diameters=$bad"
done
# --validate refuses them too
expect_error "--validate with nan" 2 "Tools/Upper punch/Displacement history" \
  "$DENSIFY" --validate "$prm" --set "Tools/Upper punch/Displacement history=0:0, 1:nan"
[ ! -e out ] || { echo "FAIL: a refused run created its output directory"; fails=$((fails + 1)); }
echo "$fails failure(s)"
[ "$fails" -eq 0 ]
