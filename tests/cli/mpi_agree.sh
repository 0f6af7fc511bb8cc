# The default scene on 1 and 2 MPI ranks gives the same forces to solver tolerance.
set -eu
cd "$WORK_DIR"
common=(--set "Output/Interval=0" --set "Time stepping/Number of steps=2"
  --set "Solver/Newton tolerance=1e-10" --set "Solver/Linear tolerance=1e-10")
"$DENSIFY" "$SOURCE_DIR/prm/default.prm" --set "Output/Directory=np1" "${common[@]}" > np1.log
"$MPIEXEC" --oversubscribe -np 2 "$DENSIFY" "$SOURCE_DIR/prm/default.prm" \
  --set "Output/Directory=np2" "${common[@]}" > np2.log
grep -q "2 MPI rank" np2.log
# columns 1-9 (step .. relative density): forces to 1e-7 relative
cut -d, -f1-7 np1/statistics.csv > f1.csv
cut -d, -f1-7 np2/statistics.csv > f2.csv
cat f1.csv
"$NUMDIFF" -r 1e-7 -a 1e-9 -s ', \n' f1.csv f2.csv
