# Scene/Fidelity: each level resolves to the settings of the table in
# doc/accuracy.md ("The fidelity levels"); an entry set in the file or by
# --set keeps its value; "as set" (the default) changes nothing and prints
# nothing; the banner of a run names the level; a bad level exits 2 with one
# line.
set -eu
cd "$WORK_DIR"
source "$SOURCE_DIR/tests/cli/lib/expect_error.bash"
# the table: rows "| `Sub/Entry` | draft | standard | reference |" after the
# heading "## The fidelity levels"
/usr/bin/python3 - "$SOURCE_DIR/doc/accuracy.md" > levels.txt <<'PY'
import re, sys
text = open(sys.argv[1]).read().split("## The fidelity levels", 1)[1]
table = text.split("\n## ", 1)[0]
header = None
for line in table.splitlines():
    cells = [c.strip() for c in line.strip().strip("|").split("|")]
    if header is None and cells[:4] == ["entry", "draft", "standard", "reference"]:
        header = cells
    elif header and len(cells) >= 4 and re.fullmatch(r"`[^`]+`", cells[0]):
        # "—": the level leaves the entry as set (the program's default)
        for level, value in zip(header[1:4], cells[1:4]):
            if value != "—":
                print(f"{level}\t{cells[0].strip('`')} = {value.strip('`')}")
assert header, "no table 'entry | draft | standard | reference' in doc/accuracy.md"
PY
[ "$(wc -l < levels.txt)" -ge 12 ]
scene() { # a scene that sets none of the levers; $1: the level or empty
  {
    [ -n "$1" ] && printf 'subsection Scene\n  set Fidelity = %s\nend\n' "$1"
    printf 'subsection Particles\n  set Centres = 0,0,1.25\nend\n'
  } > "scene_$1.prm"
  echo "scene_$1.prm"
}
estimate() { grep -o 'about [0-9,]* tetrahedra' | tr -d , ; }
for level in draft standard reference; do
  "$DENSIFY" --validate "$(scene $level)" > "validate_$level.txt"
  line=$(grep '^Fidelity: ' "validate_$level.txt")
  echo "$line"
  # "Fidelity: LEVEL (A = a, B = b, ...)": the same pairs as the table
  printf '%s\n' "$line" | sed "s/^Fidelity: $level (//; s/)\$//" | sed 's/, /\n/g' |
    sort > "got_$level.txt"
  grep "^$level	" levels.txt | cut -f2 | sort > "want_$level.txt"
  diff -u "want_$level.txt" "got_$level.txt"
  # an entry given by --set keeps its value and is named as set
  "$DENSIFY" --validate "$(scene $level)" --set "Mesh/Element size=0.7" > "set_$level.txt"
  grep -q "^Fidelity: $level (.*; as set: Mesh/Element size)$" "set_$level.txt"
  ! grep -q "Element size = " "set_$level.txt"
done
# the levels reach the scene: their element sizes give other meshes, and the
# size given by --set wins over every level
[ "$(estimate < validate_draft.txt)" != "$(estimate < validate_reference.txt)" ]
"$DENSIFY" --validate "$(scene "")" --set "Mesh/Element size=0.7" > set_none.txt
for level in draft standard reference; do
  [ "$(estimate < "set_$level.txt")" = "$(estimate < set_none.txt)" ]
done
# an entry set in the file keeps its value too
printf 'subsection Mesh\n  set Element size = 0.7\nend\n' | cat "$(scene draft)" - > file_set.prm
"$DENSIFY" --validate file_set.prm > file_set.txt
grep -q "as set: Mesh/Element size)$" file_set.txt
[ "$(estimate < file_set.txt)" = "$(estimate < set_none.txt)" ]
# "as set" and no Scene subsection: nothing printed, the same scene
"$DENSIFY" --validate "$(scene "as set")" > as_set.txt
"$DENSIFY" --validate "$(scene "")" > none.txt
! grep -q "Fidelity" as_set.txt none.txt
[ "$(estimate < as_set.txt)" = "$(estimate < none.txt)" ]
# every shipped scene keeps its settings: no level unless it names one
for prm in "$SOURCE_DIR"/prm/*.prm; do
  if grep -q "set Fidelity" "$prm"; then
    "$DENSIFY" --validate "$prm" | grep -q "^Fidelity: "
  else
    ! "$DENSIFY" --validate "$prm" | grep -q "Fidelity"
  fi
done
# the banner of a run names the level (two steps of a pressed sphere)
"$DENSIFY" "$(scene draft)" --set "Time stepping/Number of steps=2" \
  --set "Output/Directory=run" --set "Output/Interval=0" > run.txt
grep -q "^Fidelity: draft (Mesh/Element size = " run.txt
grep -q "^Fidelity: draft" run/log.txt
# bad levels (expect_error counts failures itself)
set +e
fails=0
expect_error bad-level 2 "Scene/Fidelity" "$DENSIFY" --validate "$(scene "")" --set "Scene/Fidelity=fine"
printf 'subsection Scene\n  set Fidelity = ultra\nend\n' > bad.prm
expect_error bad-level-file 2 "Fidelity" "$DENSIFY" --validate bad.prm
[ $fails -eq 0 ]
echo "fidelity ok"
