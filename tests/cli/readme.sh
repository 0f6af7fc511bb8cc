# The README's promises hold: every repository path it names exists, every
# command it shows starts with something that runs (densify --help, the
# scripts it names), and the user-facing texts (README, doc/, prm/ comments,
# the parameter help of --print-parameters) name no work session and no
# commit hash: they describe the current state, the git log keeps history.
# (mpirun is only looked up, never run: one processor)
# ctest processors: 1
set -eu
cd "$WORK_DIR"
readme="$SOURCE_DIR/README.md"
fail=0

echo "== length"
lines=$(wc -l < "$readme")
echo "$lines lines"
[ "$lines" -le 110 ] || { echo "FAIL: README.md has $lines lines (at most about 100)" >&2; fail=1; }

echo "== paths"
# `...` spans and image links that start with a top-level directory
paths=$( { grep -o '`[^`]*`' "$readme" | tr -d '`' | tr ' ' '\n'; grep -o '](doc/[^)]*)' "$readme" | sed 's/^](//; s/)$//'; } \
  | grep -E '^(prm|doc|scripts|tests|benchmarks|source|include|\.ci)/' | sed 's/[,.;:]*$//' | sort -u)
n=0
for p in $paths; do
  n=$((n + 1))
  case "$p" in
    *DIR*|*FILE*|*NAME*) continue ;;   # placeholders
  esac
  [ -e "$SOURCE_DIR/$p" ] || { echo "FAIL: README names $p, which does not exist" >&2; fail=1; }
done
echo "$n paths checked"
[ "$n" -ge 10 ] || { echo "FAIL: found only $n paths in README.md" >&2; fail=1; }

echo "== commands"
"$DENSIFY" --help > help.txt || { echo "FAIL: densify --help" >&2; fail=1; }
# every line of a sh block: its program exists and answers --help
awk '/^```sh/ {on = 1; next} /^```/ {on = 0} on' "$readme" | sed 's/#.*//' | grep -v '^ *$' > commands.txt
cat commands.txt
while read -r first second rest; do
  case "$first" in
    build/densify) "$DENSIFY" --help > /dev/null ;;
    mpirun) [ -x "$MPIEXEC" ] ;;
    bash) [ -f "$SOURCE_DIR/$second" ] || { echo "FAIL: no $second" >&2; fail=1; } ;;
    cd) ;;
    *) echo "FAIL: unknown command '$first' in README.md" >&2; fail=1 ;;
  esac
done < commands.txt
# the options the README shows are ones densify knows
for option in --set --validate --print-parameters --stop-after --resume; do
  if grep -q -- "$option" "$readme"; then
    grep -q -- "$option" help.txt || { echo "FAIL: densify --help does not know $option" >&2; fail=1; }
  fi
done
# the scripts the README names run (--help), and --validate accepts its scenes
for script in $(echo "$paths" | grep '^scripts/postprocess/.*\.py$'); do
  /usr/bin/python3 "$SOURCE_DIR/$script" --help > /dev/null || { echo "FAIL: $script --help" >&2; fail=1; }
done
for scene in $(echo "$paths" | grep '^prm/.*\.prm$'); do
  "$DENSIFY" --validate "$SOURCE_DIR/$scene" > /dev/null || { echo "FAIL: --validate $scene" >&2; fail=1; }
done

echo "== no sessions, no commit hashes"
"$DENSIFY" --print-parameters > parameters.prm
texts=("$readme" "$SOURCE_DIR"/doc/*.md "$SOURCE_DIR"/doc/parameters.prm "$SOURCE_DIR"/prm/*.prm parameters.prm)
if grep -n -i -w -E 'sessions?' "${texts[@]}"; then
  echo "FAIL: the lines above name a session" >&2; fail=1
fi
# 7 to 40 hexadecimal digits with at least one digit and one letter a-f
if grep -n -o -i -w -E '[0-9a-f]{7,40}' "${texts[@]}" | grep -i -E ':[^:]*[a-f][^:]*$' | grep -E ':[^:]*[0-9][^:]*$'; then
  echo "FAIL: the lines above name a commit hash" >&2; fail=1
fi
[ ! -e "$SOURCE_DIR/doc/experiments" ] || { echo "FAIL: doc/experiments/ is history" >&2; fail=1; }
[ "$fail" -eq 0 ] && echo "readme: all checks passed"
exit "$fail"
