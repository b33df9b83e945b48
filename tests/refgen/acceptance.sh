#!/usr/bin/env bash
# acceptance.sh -- `rtb diagnose` on records from the independent reference
# generator (tests/refgen/, issue #10 item 8): for each case EFFECTS:SEED it
# generates the records with `refgen`, runs `rtb diagnose` with a time limit,
# scores the report against the truth (score.py) and prints a table and the
# summary "single: a/b, combined/new/out-of-vocabulary: c/d, wrong physical
# names: e".
#
#   tests/refgen/acceptance.sh [--set quick|singles|hard|definitions|conventions|all] [--cases "E:S ..."]
#                              [--duration S] [--timeout S] [--out DIR]
#                              [--build DIR] [--keep] [-- DIAGNOSE_OPTIONS...]
#
# Sets (default quick): quick = plain + 10 single words + 2 pairs, 2 new words
# and mains hum on seed 1 (about 15 x 10-60 s); singles = every word of
# the vocabulary, both clearance forms and plain on seeds 1-2; hard = pairs,
# new words, the low-pass definition of the delay and out-of-vocabulary
# (hum, drift, clipping, force spikes, a creeping force zero) on seeds 1-2; definitions = other
# definitions of four words (quadratic asymmetry, tanh softening, an
# erf-shaped Mullins loss, a fifth-order stiffening) on seeds 1-2;
# conventions = rig conventions that are not effects (records about a held
# preload; a compression-positive load cell; band-limited noise), alone and under words, on
# seeds 1-2; all = singles + hard + definitions + conventions.
# Meant to run in the background: nohup tests/refgen/acceptance.sh > acc.log 2>&1 &
# Output: DIR/table.txt, DIR/results.jsonl, DIR/CASE/{truth,report}.json and
# diagnose.log (records deleted unless --keep). Exit status 0 when every case ran.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/../.." && pwd)"
build="$root/build"
set_name=quick
cases=""
duration=8
timeout_s=300
out=""
keep=0
extra=()

usage() { sed -n '2,25p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'; exit "${1:-2}"; }

while [ $# -gt 0 ]; do
  case "$1" in
    --set) set_name="$2"; shift 2 ;;
    --cases) cases="$2"; shift 2 ;;
    --duration) duration="$2"; shift 2 ;;
    --timeout) timeout_s="$2"; shift 2 ;;
    --out) out="$2"; shift 2 ;;
    --build) build="$(cd "$2" && pwd)"; shift 2 ;;
    --keep) keep=1; shift ;;
    -h|--help) usage 0 ;;
    --) shift; extra=("$@"); break ;;
    *) echo "acceptance.sh: unknown option $1" >&2; usage ;;
  esac
done

singles="cubic_stiffness asymmetry maxwell viscous backlash backlash_held mullins delay inertia offset softening"
hard="delay,asymmetry maxwell,offset backlash,cubic_stiffness viscous,cubic_stiffness inertia,backlash delay_lowpass
      slack relaxation_spectrum friction_asymmetry hum drift clipping spikes zero_drift"
definitions="asymmetry_quadratic softening_tanh mullins_erf stiffening_quintic"
conventions="preload preload,backlash_held preload,maxwell preload,cubic_stiffness preload,inertia
             compression_positive compression_positive,backlash compression_positive,delay
             colored_noise colored_noise,maxwell colored_noise,backlash colored_noise,inertia"
on_seeds() {  # on_seeds "WORDS" "SEEDS"
  local w s
  for s in $2; do for w in $1; do printf '%s:%s ' "$w" "$s"; done; done
}
if [ -z "$cases" ]; then
  case "$set_name" in
    quick) cases="none:1 $(on_seeds "cubic_stiffness asymmetry maxwell viscous backlash backlash_held mullins delay inertia softening" 1)
                  $(on_seeds "delay,asymmetry backlash,cubic_stiffness slack friction_asymmetry hum" 1)" ;;
    singles) cases="$(on_seeds "none $singles" "1 2")" ;;
    hard) cases="$(on_seeds "$hard" "1 2")" ;;
    definitions) cases="$(on_seeds "$definitions" "1 2")" ;;
    conventions) cases="$(on_seeds "$conventions" "1 2")" ;;
    all) cases="$(on_seeds "none $singles" "1 2") $(on_seeds "$hard" "1 2") $(on_seeds "$definitions" "1 2")
                $(on_seeds "$conventions" "1 2")" ;;
    *) echo "acceptance.sh: unknown set $set_name" >&2; usage ;;
  esac
fi

rtb="$build/rtb"
refgen="$build/refgen"
for exe in "$rtb" "$refgen"; do
  [ -x "$exe" ] || { echo "acceptance.sh: $exe not built (make build, or --build DIR)" >&2; exit 2; }
done
command -v python3 > /dev/null || { echo "acceptance.sh: python3 is needed to read the reports" >&2; exit 2; }
[ -n "$out" ] || out="$build/acceptance"
mkdir -p "$out"
results="$out/results.jsonl"
: > "$results"

echo "acceptance: $(echo $cases | wc -w) cases, ${duration} s records, ${timeout_s} s limit per diagnosis; $(uptime)"
failed=0
for c in $cases; do
  effects="${c%:*}"
  seed="${c##*:}"
  name="${effects//,/+}_s$seed"
  dir="$out/$name"
  rm -rf "$dir"
  mkdir -p "$dir"
  if ! "$refgen" --effect "$effects" --seed "$seed" --duration "$duration" --out-dir "$dir" \
       > "$dir/refgen.log" 2>&1; then
    echo "acceptance: refgen failed for $c (see $dir/refgen.log)" >&2
    failed=1
    continue
  fi
  args=()
  for f in "$dir"/fit_*.csv; do args+=(--data "$f"); done
  for f in "$dir"/holdout_*.csv; do args+=(--holdout "$f"); done
  status=ok
  # Wall and CPU (user + system) seconds: on a shared machine CPU is the steadier figure.
  TIMEFORMAT='%R %U %S'
  { time timeout --kill-after=10 "$timeout_s" "$rtb" diagnose "${args[@]}" --out "$dir/report.json" \
      ${extra[@]+"${extra[@]}"} > "$dir/diagnose.log" 2>&1 ; } 2> "$dir/time.txt" || {
      rc=$?
      if [ $rc -eq 124 ] || [ $rc -eq 137 ]; then status=timeout; else status="exit$rc"; fi
      failed=1
    }
  # The last line: a crashed diagnosis puts the shell's report before the times.
  wall=$(tail -n 1 "$dir/time.txt" | awk '{ printf "%.1f", $1 }')
  cpu=$(tail -n 1 "$dir/time.txt" | awk '{ printf "%.1f", $2 + $3 }')
  python3 "$here/score.py" row "$name" "$dir/truth.json" "$dir/report.json" "$wall" "$cpu" "$status" >> "$results"
  [ $keep -eq 1 ] || rm -f "$dir"/*.csv
  tail -n 1 "$results" | python3 -c 'import json,sys; r=json.loads(sys.stdin.read()); print("  %-30s -> %-20s %s (%.0f s, cpu %.0f s)" % (r["case"], r["cause"], "ok" if r["ok"] else "MISS", r["wall_s"], r["cpu_s"]))'
done
python3 "$here/score.py" table "$results" | tee "$out/table.txt"
echo "load after the run: $(uptime)"
exit $failed
