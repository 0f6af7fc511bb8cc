# Load steps end exactly at their time: 250 steps of 0.0032 s (the paper's
# schedule) accumulate round-off, and a remainder of about 1e-14 s used to
# make one more, tiny increment at the end of a step, from which the next
# step crawled back to full length by doubling (39 increments for step 248
# here; 42 increments and 349 Newton iterations in step 248 of the
# 43-sphere layer). Every step without a cut-back is one increment.
set -u
cd "$WORK_DIR"
"$DENSIFY" "$SOURCE_DIR/prm/default.prm" --set "Output/Directory=out" \
  --set "Particles/Centres=0,0,1.25" --set "Mesh/Element size=1" \
  --set "Mesh/Refinement directions=" \
  --set "Time stepping/End time=0.8" \
  --set "Time stepping/Number of steps=250" \
  --set "Tools/Upper punch/Displacement history=0:0, 0.8:0.01" \
  --set "Output/Interval=0" > log.txt 2>&1 || { cat log.txt; exit 1; }
# columns: step (1), increments (17), cutbacks (18)
head -n 1 out/statistics.csv | cut -d, -f1,17,18 | grep -q '^step,increments,cutbacks$' || exit 1
[ "$(tail -n +2 out/statistics.csv | wc -l)" -eq 250 ] || exit 1
bad=$(awk -F, 'NR > 1 && $18 == 0 && $17 != 1 {print $1 ": " $17 " increments"}' out/statistics.csv)
echo "steps without a cut-back but with more than one increment: ${bad:-none}"
[ -z "$bad" ]
