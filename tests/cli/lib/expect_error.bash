# Sourced by cli tests of bad input and faults. expect_error NAME CODE PATTERN
# COMMAND...: the command ends within 60 s with exit code CODE and prints
# exactly one line of its own (mpirun's banners and densify's warnings are
# not counted) that contains PATTERN. Counts failures in $fails.
fails=${fails:-0}
expect_error() {
  local name=$1 code=$2 pattern=$3
  shift 3
  local out rc ours
  out=$(timeout -k 5 60 "$@" 2>&1 >/dev/null)
  rc=$?
  # warnings about entries without effect are not errors
  ours=$(printf '%s\n' "$out" | grep '^densify: ' | grep -v '^densify: warning: ')
  if [ $rc -ne "$code" ] || [ "$(printf '%s\n' "$ours" | grep -c .)" -ne 1 ] ||
    ! printf '%s' "$ours" | grep -qF -- "$pattern"; then
    echo "FAIL $name: exit $rc (expected $code), output:"
    printf '%s\n' "$out"
    fails=$((fails + 1))
  else
    echo "ok   $name: $ours"
  fi
}
