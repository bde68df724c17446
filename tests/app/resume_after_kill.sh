#!/usr/bin/env bash
# A run killed outright (SIGKILL: no chance to write anything) and resumed from its last
# checkpoint, on another thread count, finishes with the files of an uninterrupted run, byte for
# byte (history.csv, cracks.csv, gauges.csv, loading.csv, crack_intervals.csv, run.pvd, every
# VTU snapshot and joint table); so does a run stopped at --max-steps and resumed, also with
# softening joints part-way damaged. A resume refuses a changed scene, options that would change
# the run, and a directory without a checkpoint.
# Usage: resume_after_kill.sh DDAFRAC WORK_DIR   (runs the built-in default scene)
set -u
exe=$1 work=$2
rm -rf "$work" && mkdir -p "$work"
fail() { echo "FAIL: $*"; exit 1; }
same_files() {  # every file of the uninterrupted run ($2, default whole) but summary.json (wall times) is identical
  local n=0 whole="$work/${2:-whole}"
  for f in $(cd "$whole" && find . -type f ! -name summary.json | sort); do
    cmp -s "$whole/$f" "$1/$f" || fail "$1/$f differs from the uninterrupted run's"
    n=$((n + 1))
  done
  [ -e "$1/checkpoint.bin" ] && fail "$1: a finished run kept its checkpoint"
  echo "$1: $n files identical to the uninterrupted run's"
}

"$exe" run --out "$work/whole" --no-figures --threads 2 > "$work/whole.log" 2>&1 || fail "the uninterrupted run failed"
steps=$(grep -o '"steps": [0-9]*' "$work/whole/summary.json" | head -1 | grep -o '[0-9]*$')

# Killed: a checkpoint every 0.5 s of wall time, SIGKILL well after the first one.
"$exe" run --out "$work/killed" --no-figures --threads 2 --checkpoint-every 0.5 > "$work/killed.log" 2>&1 &
pid=$!
for _ in $(seq 1 600); do [ -e "$work/killed/checkpoint.bin" ] && break; sleep 0.1; done
sleep 1.3
kill -KILL "$pid"
wait "$pid" 2>/dev/null
grep -q '"reason": "running"' "$work/killed/summary.json" || fail "the killed run had finished before the kill"
"$exe" run --resume "$work/killed" --no-figures --threads 1 > "$work/resume.log" 2>&1 || { cat "$work/resume.log"; fail "resume failed"; }
cat "$work/resume.log" | grep -v "^t = "
grep -q "was killed" "$work/resume.log" || fail "the resume does not say the run was killed"
from=$(grep -o 'checkpoint at step [0-9]*' "$work/resume.log" | grep -o '[0-9]*$')
[ "$from" -gt 0 ] && [ "$from" -lt "$steps" ] || fail "resumed from step '$from', expected one in (0, $steps)"
grep -q '"resumed_from"' "$work/killed/summary.json" || fail "summary.json does not record the resume"
same_files "$work/killed"

# Stopped at --max-steps, resumed to the end.
"$exe" run --out "$work/stopped" --no-figures --max-steps 700 --checkpoint-every 0 > "$work/stopped.log" 2>&1 \
  || fail "the run to 700 steps failed"
"$exe" run --resume "$work/stopped" --no-figures > "$work/resume2.log" 2>&1 || { cat "$work/resume2.log"; fail "resume failed"; }
grep -q "stopped: max_steps" "$work/resume2.log" || fail "the resume does not say how the run stopped"
same_files "$work/stopped"

# Softening joints (a fracture energy): stopped while a joint is damaged, resumed to the end on
# another thread count; the joints' damage travels in the checkpoint.
softening="--set joints.virtual.fracture_energy=50"
"$exe" run --out "$work/whole-softening" --no-figures --threads 2 $softening > "$work/whole-softening.log" 2>&1 \
  || fail "the uninterrupted softening run failed"
"$exe" run --out "$work/softening" --no-figures --threads 2 --max-steps 2300 --checkpoint-every 0 $softening \
  > "$work/softening.log" 2>&1 || fail "the softening run to 2300 steps failed"
grep -A1 '"joints_softening"' "$work/softening/summary.json" | grep -q '"count": [1-9]' \
  || fail "no joint was softening at the stop (the case this checks)"
"$exe" run --resume "$work/softening" --no-figures --threads 1 > "$work/resume3.log" 2>&1 \
  || { cat "$work/resume3.log"; fail "resume failed"; }
same_files "$work/softening" whole-softening

# Refusals.
"$exe" run --resume "$work/whole" > "$work/none.log" 2>&1 && fail "resumed a finished run"
grep -q "no checkpoint to resume from" "$work/none.log" || fail "no clear message for a missing checkpoint"
"$exe" run --resume "$work/whole" --set analysis.dt_max=1e-8 > "$work/set.log" 2>&1 && fail "--set accepted with --resume"
grep -q -- "--resume excludes --set\|--set excludes --resume" "$work/set.log" || { cat "$work/set.log"; fail "no clear message for --set with --resume"; }
scene="$work/scene.toml"
default_scene="$(cd "$(dirname "$0")/../.." && pwd)/scenes/default.toml"
printf 'base = "%s"\n[analysis]\nend_time = 3e-5\n' "$default_scene" > "$scene"
"$exe" run "$scene" --out "$work/changed" --no-figures --max-steps 50 > /dev/null 2>&1 || fail "the short run failed"
printf 'base = "%s"\n[analysis]\nend_time = 4e-5\n' "$default_scene" > "$scene"
"$exe" run --resume "$work/changed" > "$work/changed.log" 2>&1 && fail "resumed with a changed scene"
grep -q "changed since the run started" "$work/changed.log" || { cat "$work/changed.log"; fail "no clear message for a changed scene"; }
printf 'broken' > "$work/stopped/checkpoint.bin"
"$exe" run --resume "$work/stopped" > "$work/damaged.log" 2>&1 && fail "resumed from a damaged checkpoint"
grep -q "damaged or not a ddafrac checkpoint" "$work/damaged.log" || { cat "$work/damaged.log"; fail "no clear message for a damaged checkpoint"; }
echo "PASS"
