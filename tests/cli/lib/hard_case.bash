# Sourced by the cli tests of hard cases. check_run DIR STEPS FORCE TOLERANCE:
# the run in DIR wrote STEPS rows to statistics.csv (every step converged), no
# entry is NaN or infinite (the columns that are nan without a die wall or a
# pair of punches, relative_density and the die's stresses, are skipped), and
# the last upper punch force (column 4) is within
# the relative TOLERANCE of FORCE. Prints the Newton iterations and cut-backs
# (columns 8 and 18). Counts failures in $fails.
fails=${fails:-0}
check_run() {
  local dir=$1 steps=$2 force=$3 tolerance=$4
  local csv="$dir/statistics.csv"
  local rows newton cutbacks last bad
  rows=$(tail -n +2 "$csv" 2>/dev/null | wc -l)
  newton=$(awk -F, 'NR > 1 {s += $8} END {print s + 0}' "$csv" 2>/dev/null)
  cutbacks=$(awk -F, 'NR > 1 {s += $18} END {print s + 0}' "$csv" 2>/dev/null)
  last=$(tail -n 1 "$csv" 2>/dev/null | cut -d, -f4)
  bad=$(awk -F, 'NR == 1 {
      for (i = 1; i <= NF; ++i)
        skip[i] = ($i ~ /^(relative_density|upper_punch_stress|lower_punch_stress|die_wall_pressure|radial_axial_ratio)$/)
      next }
    { for (i = 1; i <= NF; ++i) if (!skip[i] && tolower($i) ~ /nan|inf/) { n++; next } }
    END { print n + 0 }' "$csv" 2>/dev/null)
  if [ "$rows" -ne "$steps" ] || [ "$bad" -ne 0 ] ||
    ! awk -v f="$last" -v r="$force" -v t="$tolerance" \
      'BEGIN {d = f - r; if (d < 0) d = -d; exit !(d <= t * r)}'; then
    echo "FAIL $dir: $rows of $steps steps, $bad rows with NaN or inf," \
      "force ${last:-none} N against $force N (tolerance $tolerance)"
    fails=$((fails + 1))
  else
    echo "ok   $dir: $steps steps, force $last N ($force N +- $tolerance)," \
      "$newton Newton iterations, $cutbacks cut-backs"
  fi
}
