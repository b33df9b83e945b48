#!/bin/bash
# Generate blindgen cases, run `rtb diagnose` on each (sequentially, one
# thread) and score the reports.
#
#   run_blind.sh [--cases "E[,E2]:SEED ..."] [--set singles|hard|all] [--seeds "1 2"]
#                [--duration 4] [--timeout 300] [--out DIR] [--build DIR]
#
# --cases overrides --set.  A case directory is named E1+E2_sSEED and holds
# the records, truth.json, report.json, diagnose.log, wall.txt, status.txt.
set -u
here=$(cd "$(dirname "$0")" && pwd)
py=/usr/bin/python3
cases=""
set_name="singles"
seeds="1"
duration=4
tmo=300
out=/tmp/blindgen_run
build="$here/../../build"

while [ $# -gt 0 ]; do
  case "$1" in
    --cases) cases="$2"; shift 2 ;;
    --set) set_name="$2"; shift 2 ;;
    --seeds) seeds="$2"; shift 2 ;;
    --duration) duration="$2"; shift 2 ;;
    --timeout) tmo="$2"; shift 2 ;;
    --out) out="$2"; shift 2 ;;
    --build) build="$2"; shift 2 ;;
    -h|--help) sed -n '2,10p' "$0"; exit 0 ;;
    *) echo "run_blind.sh: unknown option $1" >&2; exit 2 ;;
  esac
done

rtb="$build/rtb"
[ -x "$rtb" ] || { echo "run_blind.sh: no executable $rtb" >&2; exit 2; }

if [ -z "$cases" ]; then
  list=$("$py" -B -c "
import sys; sys.path.insert(0, '$here')
import blindgen as b
s = '$set_name'
print(' '.join((b.SINGLES if s in ('singles', 'all') else []) + (b.HARD if s in ('hard', 'all') else [])))
") || exit 2
  for s in $seeds; do
    for e in $list; do cases="$cases $e:$s"; done
  done
fi

mkdir -p "$out"
echo "run_blind: $(echo $cases | wc -w) cases -> $out (timeout ${tmo}s, duration ${duration}s)"
for c in $cases; do
  eff=${c%%:*}
  seed=${c##*:}
  dir="$out/$(echo "$eff" | tr ',' '+')_s$seed"
  rm -rf "$dir"
  if ! "$py" "$here/blindgen.py" make --effects "$eff" --seed "$seed" --out "$dir" --duration "$duration"; then
    mkdir -p "$dir"; echo "generation failed" > "$dir/status.txt"; continue
  fi
  # file and scale options from the truth
  mapfile -t args < <("$py" -c "
import json, os
t = json.load(open('$dir/truth.json'))
for f in t['fit']: print('--data'); print(os.path.join('$dir', f))
for f in t['holdout']: print('--holdout'); print(os.path.join('$dir', f))
sc = t['scale']
for k in ('time', 'displacement', 'force'):
    if sc[k] != 1.0: print('--scale-' + k); print(repr(sc[k]))
")
  t0=$(date +%s.%N)
  timeout "$tmo" "$rtb" diagnose "${args[@]}" --threads 1 --quiet --out "$dir/report.json" \
      > "$dir/diagnose.log" 2>&1
  rc=$?
  t1=$(date +%s.%N)
  wall=$(awk -v a="$t0" -v b="$t1" 'BEGIN { print b - a }')
  printf '%.1f\n' "$wall" > "$dir/wall.txt"
  if [ $rc -eq 124 ]; then st="timeout"; elif [ $rc -ne 0 ]; then st="exit $rc"; else st="ok"; fi
  echo "$st" > "$dir/status.txt"
  cause=$("$py" -c "import json; print(json.load(open('$dir/report.json')).get('cause','?'))" 2>/dev/null || echo "-")
  printf '  %-32s %-8s cause %-20s %6.1f s\n' "$(basename "$dir")" "$st" "$cause" "$wall"
done
echo
"$py" "$here/score_blind.py" "$out"
