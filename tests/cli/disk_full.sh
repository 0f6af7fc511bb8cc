# A full disk: the run stops with one line naming the file and the cause
# (exit 1), on one and on two ranks, and what was written before stays
# valid: complete rows in statistics.csv and particles.csv, a complete
# solution.pvd naming existing files, and a checkpoint that --resume
# continues from. On a 1 MB tmpfs where mounting is permitted (as root);
# else only the simulated part: statistics.csv as a link to /dev/full. The
# 1-rank and the 2-rank cases are parts of their own, each on its own tmpfs
# (tests/cli/lib/parts.bash).
# ctest parts: one_rank two_ranks:2
set -u
cd "$WORK_DIR"
source "$SOURCE_DIR/tests/cli/lib/parts.bash"
source "$SOURCE_DIR/tests/cli/lib/expect_error.bash"
prm="$SOURCE_DIR/prm/default.prm"
scene=(--set "Mesh/Element size=0.6" --set "Mesh/Refinement directions="
  --set "Time stepping/Number of steps=40" --set "Output/Interval=1"
  --set "Tools/Upper punch/Displacement history=0:0, 1:0.2")

# valid CSV rows, a valid .pvd naming existing files
check_outputs() {
  /usr/bin/python3 - "$1" <<'PY'
import csv, os, re, sys
import xml.etree.ElementTree as ET
d = sys.argv[1]
for name in ("statistics.csv", "particles.csv"):
    text = open(os.path.join(d, name)).read()
    assert text.endswith("\n"), (name, "ends inside a row")
    rows = list(csv.reader(text.splitlines()))
    assert all(len(r) == len(rows[0]) for r in rows), (name, "an incomplete row")
    steps = [int(r[0]) for r in rows[1:]]
    assert steps == sorted(steps), (name, steps)
    print(name, len(rows) - 1, "complete row(s)")
if os.path.exists(os.path.join(d, "solution.pvd")):
    root = ET.parse(os.path.join(d, "solution.pvd")).getroot()
    files = [e.get("file") for e in root.iter("DataSet")]
    for f in files:
        assert os.path.exists(os.path.join(d, f)), f
    print("solution.pvd:", len(files), "record(s), all present")
PY
}

# the cases on 1 (one_rank) or 2 ranks (two_ranks)
disk_full() {
  local np=$1 launch=("$DENSIFY")
  [ "$np" -eq 2 ] && launch=("$MPIEXEC" --oversubscribe -np 2 "$DENSIFY")

  # simulated: every write to statistics.csv fails with ENOSPC
  rm -rf sim_$np
  mkdir sim_$np
  ln -s /dev/full sim_$np/statistics.csv
  expect_error "statistics.csv on /dev/full, $np rank(s)" 1 "cannot write 'sim_$np/statistics.csv' (No space left on device)" \
    "${launch[@]}" "$prm" "${scene[@]}" --set "Output/Directory=sim_$np"

  full="$WORK_DIR/full_$np"
  mkdir -p "$full"
  umount "$full" 2>/dev/null
  trap "umount '$full' 2> /dev/null" EXIT
  if ! mount -t tmpfs -o size=1m tmpfs "$full" 2>/dev/null; then
    echo "mounting a tmpfs is not permitted here: only the simulated disk-full case ran"
    return
  fi
  # with checkpoints (the disk fills while one is written), and with graphics
  # only (it fills while a .vtu is written)
  for interval in 2 0; do
    every=(--set "Output/Checkpoint interval=$interval")
    rm -rf "$full"/* resumed_$np
    expect_error "1 MB tmpfs, $np rank(s), checkpoint interval $interval" 1 "No space left on device" \
      "${launch[@]}" "$prm" "${scene[@]}" "${every[@]}" --set "Output/Directory=$full/run"
    grep -h "^densify: error" "$full"/run/log.txt 2>/dev/null | grep -q "$full/run/" ||
      echo "  (the log could not take the error line: the disk is full)"
    check_outputs "$full/run" || fails=$((fails + 1))
    [ "$interval" -eq 0 ] && continue
    # the last checkpoint continues elsewhere
    cp -r "$full/run" resumed_$np
    if "${launch[@]}" "$prm" "${scene[@]}" --set "Output/Directory=resumed_$np" \
      --set "Output/Interval=0" --resume > resumed_$np.log 2>&1; then
      grep "Resumed" resumed_$np.log
      check_outputs resumed_$np || fails=$((fails + 1))
      [ "$(($(wc -l < resumed_$np/statistics.csv) - 1))" -eq 40 ] ||
        { echo "FAIL: resumed rows"; fails=$((fails + 1)); }
    else
      echo "FAIL: --resume from the checkpoint left on the full disk:"
      cat resumed_$np.log
      fails=$((fails + 1))
    fi
  done
  umount "$full"
}

part one_rank && disk_full 1
part two_ranks && disk_full 2
[ "$test_part" = check ] && echo "the parts one_rank and two_ranks checked everything"
echo "$fails failure(s)"
[ "$fails" -eq 0 ]
