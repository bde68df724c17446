#!/usr/bin/env bash
# A run killed with SIGTERM stops at the next step with valid files, summary.json saying
# "interrupted" and exit status 143; and a new run in a directory holding a previous run's files
# removes those (stale snapshots and joint tables) but nothing it did not write.
# Usage: sigterm_and_stale_files.sh DDAFRAC SCENE WORK_DIR
set -u
exe=$1 scene=$2 work=$3
rm -rf "$work" && mkdir -p "$work/run/vtk" "$work/run/joints" "$work/run/figures"
touch "$work/run/vtk/snapshot_000099.vtu" "$work/run/joints/joints_000099.csv" \
      "$work/run/figures/crack_pattern_000100us.png" "$work/run/vtk/mine.vtu" "$work/run/joints/mine.csv" \
      "$work/run/notes.txt"
fail() { echo "FAIL: $*"; exit 1; }
# A long enough run to be killed mid-way (the end time made 100 times longer, a summary after every step).
"$exe" run "$scene" --out "$work/run" --no-figures --set analysis.end_time=2e-4 --set analysis.output_interval=1e-7 \
  > "$work/run.log" 2>&1 &
pid=$!
for _ in $(seq 1 600); do
  grep -q '"steps": [1-9]' "$work/run/summary.json" 2>/dev/null && break
  sleep 0.1
done
kill -TERM "$pid"
wait "$pid"
status=$?
cat "$work/run.log"
[ "$status" = 143 ] || fail "exit status $status, expected 143"
grep -q "interrupted by signal 15" "$work/run.log" || fail "no message naming the signal"
grep -q '"reason": "interrupted"' "$work/run/summary.json" || fail "summary.json does not say interrupted"
grep -q '"status": 143' "$work/run/summary.json" || fail "summary.json does not give exit status 143"
[ ! -e "$work/run/vtk/snapshot_000099.vtu" ] || fail "the previous run's snapshot is still there"
[ ! -e "$work/run/joints/joints_000099.csv" ] || fail "the previous run's joint table is still there"
[ ! -e "$work/run/figures/crack_pattern_000100us.png" ] || fail "the previous run's figure is still there"
[ -e "$work/run/vtk/mine.vtu" ] && [ -e "$work/run/joints/mine.csv" ] && [ -e "$work/run/notes.txt" ] ||
  fail "a file ddafrac did not write was removed"
grep -q "removed 3 file(s) of a previous run" "$work/run.log" || fail "the removal was not reported"
echo "PASS"
