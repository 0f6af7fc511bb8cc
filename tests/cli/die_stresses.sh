# The field's numbers of a die compaction in statistics.csv and the run's
# summary (doc/user_guide.md, "The compaction curve"):
#   1. upper_punch_stress and lower_punch_stress are the punch forces over
#      the die's bore area, die_wall_pressure the die wall's radial force
#      over pi x diameter x punch gap, radial_axial_ratio their ratio, on
#      every row (to 1e-8), by the implicit method (prm/default.prm, die
#      10 mm) and by explicit dynamics (the light layer, die 8.07 mm, gap
#      2.5 mm at the start, pressed until the outer spheres press on the
#      die wall);
#   2. the summary's Heckel constants equal a least-squares fit of
#      ln(1/(1 - D)) against the punch stress over the upper half of the
#      pressure range, computed here from the file (to the 4 printed
#      digits), and Kawakita's a and b are printed;
#   3. a run resumed over a statistics.csv written without these columns
#      (by an older Densify) gets today's header, its older rows padded with
#      nan, so every row has the header's fields.
set -u
cd "$WORK_DIR"
fails=0
"$DENSIFY" "$SOURCE_DIR/prm/default.prm" --set "Output/Directory=implicit" \
  --set "Output/Interval=0" > implicit.log 2>&1 || fails=$((fails + 1))
"$DENSIFY" "$SOURCE_DIR/prm/single_layer_sn_light.prm" \
  --set Solver/Method=explicit --set "Mesh/Element size=0.6" \
  --set "Explicit/Number of steps=3000" --set "Output/Directory=explicit" \
  --set "Output/Interval=0" > explicit.log 2>&1 || fails=$((fails + 1))

# check_columns DIR DIE_DIAMETER INITIAL_GAP
check_columns() {
  awk -F, -v d="$2" -v g0="$3" -v name="$1" '
    NR == 1 { for (i = 1; i <= NF; ++i) c[$i] = i; next }
    function bad(what, a, b) {
      e = a - b; if (e < 0) e = -e; s = b < 0 ? -b : b
      if (e > 1e-8 * s + 1e-12) { print "FAIL " name " row " NR - 1 ": " what " " a " against " b; n++ }
    }
    {
      pi = 3.14159265358979323846
      area = pi * d * d / 4
      bad("upper_punch_stress", $c["upper_punch_stress"], $c["upper_punch_force"] / area)
      bad("lower_punch_stress", $c["lower_punch_stress"], $c["lower_punch_force"] / area)
      p = $c["die_wall_radial_force"] / (pi * d * (g0 - $c["punch_displacement"]))
      bad("die_wall_pressure", $c["die_wall_pressure"], p)
      if ($c["upper_punch_stress"] > 0)
        bad("radial_axial_ratio", $c["radial_axial_ratio"], p / $c["upper_punch_stress"])
      last = $c["die_wall_pressure"]
    }
    END {
      print name ": " NR - 1 " rows checked, last die wall pressure " last " MPa"
      exit n > 0
    }' "$1/statistics.csv" || fails=$((fails + 1))
}
check_columns implicit 10 2.5
check_columns explicit 8.07 2.5
pressure=$(awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) c[$i] = i; next }
  END { print $c["die_wall_pressure"] }' explicit/statistics.csv)
if ! awk -v p="$pressure" 'BEGIN { exit !(p > 0) }'; then
  echo "FAIL the outer spheres do not press on the die wall ($pressure MPa)"
  fails=$((fails + 1))
fi

# the Heckel fit over the upper half of the pressure range, from the file
expected=$(awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) c[$i] = i; next }
  { P[NR] = $c["upper_punch_stress"]; D[NR] = $c["relative_density"]
    if (P[NR] > m) m = P[NR] }
  END {
    for (i in P) if (P[i] >= 0.5 * m) {
      x = P[i]; y = log(1 / (1 - D[i])); n++; sx += x; sy += y; sxx += x * x; sxy += x * y }
    K = (n * sxy - sx * sy) / (n * sxx - sx * sx)
    printf "%.4g %.4g\n", K, (sy - K * sx) / n
  }' explicit/statistics.csv)
heckel=$(grep "Heckel" explicit.log)
echo "summary: $heckel"
echo "from the file: K = ${expected% *} 1/MPa, A = ${expected#* }"
echo "$heckel" | grep -q "K = ${expected% *} 1/MPa" || fails=$((fails + 1))
echo "$heckel" | grep -q "A = ${expected#* }," || fails=$((fails + 1))
grep "Kawakita" explicit.log | grep -q "a = .*, b = .* 1/MPa" ||
  fails=$((fails + 1))
# 3. the columns before upper_punch_stress only, then --resume
"$DENSIFY" "$SOURCE_DIR/prm/default.prm" --set "Output/Directory=resumed" \
  --set "Output/Interval=0" --stop-after 2 > resumed.log 2>&1
old=$(head -n 1 resumed/statistics.csv | tr ',' '\n' | grep -n "^upper_punch_stress$" | cut -d: -f1)
cut -d, -f1-$((old - 1)) resumed/statistics.csv > older.csv
mv older.csv resumed/statistics.csv
"$DENSIFY" "$SOURCE_DIR/prm/default.prm" --set "Output/Directory=resumed" \
  --set "Output/Interval=0" --resume >> resumed.log 2>&1 || fails=$((fails + 1))
header=$(head -n 1 implicit/statistics.csv)
if [ "$(head -n 1 resumed/statistics.csv)" != "$header" ] ||
  [ "$(awk -F, '{print NF}' resumed/statistics.csv | sort -u | wc -l)" -ne 1 ] ||
  [ "$(sed -n 2p resumed/statistics.csv | cut -d, -f"$old")" != nan ] ||
  [ "$(wc -l < resumed/statistics.csv)" -ne 6 ]; then
  echo "FAIL the resumed statistics.csv:"; cat resumed/statistics.csv
  fails=$((fails + 1))
else
  echo "resumed over an older statistics.csv: today's header, rows padded"
fi
[ "$fails" -eq 0 ] || { echo "$fails check(s) failed"; exit 1; }
echo "all checks passed"
