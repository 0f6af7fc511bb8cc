# The help texts of --print-parameters describe the current program, not
# its history or measurements: each entry has one; none names a work
# session, a past state ("was", "previously", "now") or a measured figure
# (a time such as "12 s" or "4 min", a percentage); and each entry whose
# value is a number names its unit (mm, MPa, N, s, t/mm^3, N/mm^3, mm/s) or
# says that it is dimensionless or an integer.
set -eu
cd "$WORK_DIR"
"$DENSIFY" --print-parameters > parameters.prm
/usr/bin/python3 - parameters.prm <<'PYTHON'
import re
import sys

path, block, entries = [], [], []
for line in open(sys.argv[1]):
    t = line.strip()
    if t.startswith('subsection '):
        path.append(t[len('subsection '):])
        block = []
    elif t == 'end':
        path.pop()
        block = []
    elif t.startswith('#'):
        block.append(t[1:].strip())
    elif t.startswith('set '):
        name, _, value = t[4:].partition('=')
        entries.append(('/'.join(path + [name.strip()]), value.strip(),
                        ' '.join(block)))
        block = []
    else:
        block = []

unit = re.compile(r'\b(mm|MPa|N/mm\^3|mm/s|t/mm\^3|s|N)\b|dimensionless|'
                  r'integer')
history = re.compile(r'\b(sessions?|measured|took|was|were|previously|now|'
                     r'faster than|slower than)\b', re.I)
measurement = re.compile(r'\d\s?(ms|min|h|s)\b|\d\s?%')
fail = False
for entry, value, text in entries:
    if not text:
        print(f'FAIL: {entry} has no help text')
        fail = True
        continue
    for what, pattern in (('history', history), ('a measurement', measurement)):
        m = pattern.search(text)
        if m:
            print(f'FAIL: {entry}: "{m.group(0)}" reads as {what}: {text}')
            fail = True
    if re.fullmatch(r'[-+0-9.eE]+', value) and not unit.search(text):
        print(f'FAIL: {entry} = {value}: no unit, "dimensionless" or '
              f'"integer" in: {text}')
        fail = True
print(f'{len(entries)} help texts checked')
if len(entries) < 25:
    print('FAIL: too few entries found')
    fail = True
sys.exit(1 if fail else 0)
PYTHON
echo "parameter_help: all checks passed"
