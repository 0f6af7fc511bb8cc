# compare_runs.py on three synthetic statistics.csv files with known answers
# (about 2 s, no solver run). Runs A, B, C have the same density law
# d = 0.4 + 0.4 s^2 sampled at different strokes s (A every 0.1 mm to 1.0,
# B every 0.15 mm to 0.6 plus a half-written last line, C every 0.05 mm to
# 1.2), so a density between rows shows which rows were interpolated; the
# upper punch forces are linear in s with F_B = 1.5 F_A and F_C = 2 F_A, so
# the ratios are exact at any stroke. Checked: interpolated densities,
# ratios 1.5 and 2 (0.5 with --reference C), "-" for strokes a run has not
# reached, the per-run summary, the default strokes, --out (comparison.csv
# and two PNGs; needs python3-matplotlib, installed by scripts/setup.sh),
# and a one-line error with exit status 2 for each bad argument.
set -eu
python=${PYTHON:-/usr/bin/python3}
script="$SOURCE_DIR/scripts/postprocess/compare_runs.py"
cd "${WORK_DIR:-$PWD}"
if ! "$python" -c "import matplotlib" 2>/dev/null; then
  echo "FAIL: $python cannot import matplotlib: install python3-matplotlib (bash scripts/setup.sh)" >&2
  exit 1
fi

rm -rf A B C nocsv nocolumn cmp out.txt err.txt
mkdir A B C nocsv nocolumn
# run A: 10 rows; F_lower = F_upper - die wall (residual 0), volume 100 -> 99
awk 'BEGIN {
  print "step,time,punch_displacement,upper_punch_force,lower_punch_force,die_wall_force," \
        "relative_density,newton_iterations,particle_volume,step_seconds"
  for (k = 1; k <= 10; k++) {
    s = 0.1 * k; f = 100 + 2000 * s
    printf "%d,%.2f,%.6f,%.6f,%.6f,10,%.10f,3,%s,0.5\n", k, k, s, f, f - 10, 0.4 + 0.4 * s * s,
           (k == 10 ? "99" : "100")
  }
}' > A/statistics.csv
# run B: 4 rows, columns in another order, F = 1.5 F_A; then a line still being written
awk 'BEGIN {
  print "particle_volume,step_seconds,newton_iterations,step,punch_displacement," \
        "relative_density,die_wall_force,lower_punch_force,upper_punch_force"
  for (k = 1; k <= 4; k++) {
    s = 0.15 * k; f = 1.5 * (100 + 2000 * s)
    printf "200,1,%d,%d,%.6f,%.10f,0,%.6f,%.6f\n", k, k, s, 0.4 + 0.4 * s * s, f, f
  }
  printf "200,1,5,5,0.75,0.6"
}' > B/statistics.csv
# run C: 24 rows, F = 2 F_A
awk 'BEGIN {
  print "step,punch_displacement,upper_punch_force,lower_punch_force,die_wall_force," \
        "relative_density,newton_iterations,particle_volume,step_seconds"
  for (k = 1; k <= 24; k++) {
    s = 0.05 * k; f = 2 * (100 + 2000 * s)
    printf "%d,%.6f,%.6f,%.6f,0,%.10f,2,50,0.25\n", k, s, f, f, 0.4 + 0.4 * s * s
  }
}' > C/statistics.csv
cut -d, -f1-8,10 A/statistics.csv > nocolumn/statistics.csv  # without particle_volume

fail_check() { echo "FAIL: $*" >&2; cat out.txt >&2; exit 1; }

# value of the table cell in the row of stroke $1, column headed $2 (in out.txt)
cell() {
  awk -F'|' -v stroke="$1" -v column="$2" '
    function trim(x) { gsub(/^ +| +$/, "", x); return x }
    /^\| stroke \(mm\)/ { for (i = 2; i < NF; i++) if (trim($i) == column) c = i; next }
    /^\|/ && c && trim($2) == stroke { print trim($c); found = 1; exit }
    END { if (!found) print "MISSING" }' out.txt
}
expect_cell() {  # stroke, column, expected text
  got=$(cell "$1" "$2")
  [ "$got" = "$3" ] || fail_check "stroke $1, column '$2': '$got', expected '$3'"
  echo "ok stroke $1 $2 = $got"
}
# value of column $2 in the CSV row of stroke $1 of cmp/comparison.csv
csv_value() {
  awk -F, -v stroke="$1" -v column="$2" '
    NR == 1 { for (i = 1; i <= NF; i++) if ($i == column) c = i; next }
    c && $1 + 0 == stroke + 0 { print $c; found = 1; exit }
    END { if (!found) print "MISSING" }' cmp/comparison.csv
}
expect_csv() {  # stroke, column, expected number, tolerance
  got=$(csv_value "$1" "$2")
  awk -v g="$got" -v e="$3" -v t="$4" 'BEGIN { exit !(g != "" && g != "MISSING" && (g - e) <= t && (e - g) <= t) }' \
    || { echo "FAIL: comparison.csv stroke $1, $2: '$got', expected $3 +- $4" >&2; cat cmp/comparison.csv >&2; exit 1; }
  echo "ok comparison.csv stroke $1 $2 = $got"
}

echo "== table at strokes 0.25 (between rows), 0.3 (a row of all), 0.7 (B not reached), 1.1 (C only)"
"$python" "$script" A B C --strokes 0.25,0.3,0.7,1.1 --out cmp > out.txt
cat out.txt
# density at 0.25: A between 0.2 and 0.3 -> (41.6 + 43.6) / 2; B between 0.15 and 0.3 ->
# 40.9 + 2/3 (43.6 - 40.9); C has a row at 0.25 -> 42.5 (the law itself)
expect_cell 0.25 "density A (%)" 42.600
expect_cell 0.25 "density B (%)" 42.700
expect_cell 0.25 "density C (%)" 42.500
expect_cell 0.3 "density B (%)" 43.600
expect_cell 0.25 "F_upper A (N)" 600.0
expect_cell 0.25 "F_upper B (N)" 900.0
expect_cell 0.25 "B/A" 1.5000
expect_cell 0.25 "C/A" 2.0000
expect_cell 0.3 "B/A" 1.5000
expect_cell 0.7 "density A (%)" 59.600
expect_cell 0.7 "density B (%)" -
expect_cell 0.7 "F_upper B (N)" -
expect_cell 0.7 "B/A" -
expect_cell 0.7 "C/A" 2.0000
expect_cell 1.1 "density A (%)" -
expect_cell 1.1 "density C (%)" 88.400
expect_cell 1.1 "C/A" -
grep -q "^-: the run has not reached this stroke" out.txt || fail_check "no legend for '-'"
# summary lines: A's last row, the residual, volume change, totals; B's half line is left out
summary_a="- A (A): last step 10, stroke 1 mm, density 80.000 %, F_upper 2100.0 N,"
summary_a="$summary_a F_lower 2090.0 N, die wall 10.0 N, F_upper - F_lower - die wall = 0 N,"
summary_a="$summary_a particle volume -1.0000 % from the first row, 30 Newton iterations,"
summary_a="$summary_a 5.0 s of step_seconds"
grep -qxF -- "$summary_a" out.txt || fail_check "summary line of A"
grep -qF -- "- B (B): last step 4, stroke 0.6 mm," out.txt || fail_check "summary line of B"
grep -qF -- "particle volume +0.0000 % from the first row, 48 Newton iterations, 6.0 s of step_seconds" out.txt \
  || fail_check "totals of C"

echo "== --out"
header="stroke_mm,density_percent_A,density_percent_B,density_percent_C"
header="$header,upper_force_N_A,upper_force_N_B,upper_force_N_C,ratio_B,ratio_C"
head -n 1 cmp/comparison.csv | grep -qxF "$header" \
  || { echo "FAIL: comparison.csv header: $(head -n 1 cmp/comparison.csv)" >&2; exit 1; }
[ "$(wc -l < cmp/comparison.csv)" -eq 5 ] || { echo "FAIL: comparison.csv should have 4 strokes" >&2; exit 1; }
expect_csv 0.25 ratio_B 1.5 1e-6
expect_csv 0.3 ratio_B 1.5 1e-6
expect_csv 0.25 ratio_C 2 1e-6
expect_csv 0.7 ratio_C 2 1e-6
expect_csv 0.25 density_percent_A 42.6 1e-9
expect_csv 0.25 density_percent_B 42.7 1e-9
[ "$(csv_value 0.7 density_percent_B)" = "" ] || { echo "FAIL: not reached should be an empty cell" >&2; exit 1; }
for png in cmp/compare_density.png cmp/compare_forces.png; do
  [ -s "$png" ] || { echo "FAIL: $png missing or empty" >&2; exit 1; }
  [ "$(head -c 4 "$png" | tail -c 3)" = "PNG" ] || { echo "FAIL: $png is not a PNG" >&2; exit 1; }
  echo "$png: $(stat -c %s "$png") bytes"
done

echo "== --reference C and --labels"
"$python" "$script" A B C --labels a,b,c --strokes 0.25 --reference c > out.txt
cat out.txt
expect_cell 0.25 "a/c" 0.5000
expect_cell 0.25 "b/c" 0.7500
grep -q "c/c" out.txt && fail_check "the reference has a ratio column"

echo "== default strokes: the rows of the shortest run B (4 rows, fewer than 7)"
"$python" "$script" A B C > out.txt
cat out.txt
strokes=$(awk -F'|' '/^\| [0-9]/ { gsub(/ /, "", $2); printf "%s ", $2 }' out.txt)
[ "$strokes" = "0.15 0.3 0.45 0.6 " ] || fail_check "default strokes '$strokes'"
grep -q "^| .* - " out.txt && fail_check "a default stroke not reached by a run"
echo "== default strokes of A and C: rows round(9 k / 7), k = 1..7, of A (10 rows)"
"$python" "$script" A C > out.txt
strokes=$(awk -F'|' '/^\| [0-9]/ { gsub(/ /, "", $2); printf "%s ", $2 }' out.txt)
[ "$strokes" = "0.2 0.4 0.5 0.6 0.7 0.9 1 " ] || fail_check "default strokes '$strokes'"
echo "ok $strokes"

echo "== errors: one line naming the argument, exit status 2"
expect_error() {  # text the message must contain, then the arguments
  text=$1; shift
  status=0
  "$python" "$script" "$@" > out.txt 2> err.txt || status=$?
  [ "$status" -eq 2 ] || { echo "FAIL: '$*' exited with $status, expected 2" >&2; cat err.txt >&2; exit 1; }
  [ "$(wc -l < err.txt)" -eq 1 ] || { echo "FAIL: '$*' gave not one line:" >&2; cat err.txt >&2; exit 1; }
  grep -qF -- "$text" err.txt || { echo "FAIL: '$*': message lacks '$text':" >&2; cat err.txt >&2; exit 1; }
  echo "ok $*: $(cat err.txt)"
}
expect_error "at least two" A
expect_error "'does_not_exist' does not exist" A does_not_exist
expect_error "statistics.csv' does not exist" A nocsv
expect_error "lacks the column(s) particle_volume" A nocolumn
expect_error "--labels gives 2 label(s) for 3 run" A B C --labels x,y
expect_error "--labels" A B --labels x,
expect_error "not unique" A A
expect_error "--strokes: -0.1 is negative" A B --strokes -0.1,0.2
expect_error "--strokes: -0.5 is negative" A B --strokes=-0.5
expect_error "--strokes: 'abc' is not a number" A B --strokes 0.2,abc
expect_error "--strokes: 'nan' is not a number" A B --strokes nan
expect_error "--strokes: 1.5 mm is beyond every run" A B C --strokes 0.2,1.5
expect_error "--reference 'D' is none of the labels" A B --reference D
echo "postprocess_compare: all checks passed"
