# Checkpoints of the previous file format (9, which interleaved the
# system's, the load stepper's and the explicit driver's state) resume with
# this densify: each in tests/data/checkpoint_format9/ (README.md there
# says how it was written) continued with --resume ends with the rows of the
# run made without a stop by this densify, to 1e-9 (the wall times and the
# linear iterations aside, as in cli.checkpoint):
#  1. two J2 tin spheres with particle and die contact (implicit, plastic
#     history, contact multipliers and friction history), stopped after
#     step 4 of 6;
#  2. the shrunk light layer by explicit dynamics (velocities, mass-scaling
#     factors, the energy account), stopped after step 3 of 6.
set -eu
cd "$WORK_DIR"
data="$SOURCE_DIR/tests/data/checkpoint_format9"
all=1-8,11-15,17-
same_rows() {
  cut -d, -f"$all" "$1" > a.csv
  cut -d, -f"$all" "$2" > b.csv
  "$NUMDIFF" -q -r 1e-9 -a 1e-9 -s ', \n' a.csv b.csv
}
# a copy of a stored checkpoint's output directory, its rank file unpacked
unpack() {
  rm -rf "$2"
  cp -r "$data/$1" "$2"
  gunzip "$2/checkpoint/rank_0.bin.gz"
}

# cli.checkpoint's spheres, without graphics
source "$SOURCE_DIR/tests/cli/lib/two_tin_spheres.bash"
pair+=(--set "Output/Interval=0")
"$DENSIFY" "$prm" "${pair[@]}" --set "Output/Directory=pair" > pair.log
unpack pair pair_resumed
"$DENSIFY" "$prm" "${pair[@]}" --set "Output/Directory=pair_resumed" \
  --resume > pair_resumed.log
grep -q "Resumed from the checkpoint after step 4" pair_resumed.log
same_rows pair/statistics.csv pair_resumed/statistics.csv
"$NUMDIFF" -q -r 1e-9 -a 1e-12 -s ', \n' pair/particles.csv pair_resumed/particles.csv
echo "format 9, implicit pair resumed after step 4 = uninterrupted run: yes"

source "$SOURCE_DIR/tests/cli/lib/shrunk_light_scene.bash"
explicit=(--set "Solver/Method=explicit" --set "Explicit/Number of steps=2000"
  --set "Time stepping/Number of steps=6")
"$DENSIFY" "$scene" "${common[@]}" "${explicit[@]}" \
  --set "Output/Directory=explicit" > explicit.log
unpack explicit explicit_resumed
"$DENSIFY" "$scene" "${common[@]}" "${explicit[@]}" \
  --set "Output/Directory=explicit_resumed" --resume > explicit_resumed.log
grep -q "Resumed from the checkpoint after step 3" explicit_resumed.log
same_rows explicit/statistics.csv explicit_resumed/statistics.csv
"$NUMDIFF" -q -r 1e-9 -a 1e-12 -s ', \n' explicit/particles.csv explicit_resumed/particles.csv
echo "format 9, explicit layer resumed after step 3 = uninterrupted run: yes"
