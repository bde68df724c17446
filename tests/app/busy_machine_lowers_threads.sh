#!/bin/bash
# With every core but one kept busy by other processes, `ddafrac run` (threads = all cores) runs on
# one thread: it says so, and summary.json records 1 as the fewest threads used.
# usage: busy_machine_lowers_threads.sh DDAFRAC OUT_DIR
set -u
exe=$1
out=$2
cores=$(nproc)
if [ "$cores" -lt 2 ]; then echo "one core: nothing to govern"; exit 0; fi
pids=()
trap 'kill "${pids[@]}" 2>/dev/null' EXIT
for _ in $(seq 1 $((cores - 1))); do
  ( while :; do :; done ) &
  pids+=($!)
done
sleep 1  # let the busy loops show in the CPU counters
log=$("$exe" run --threads "$cores" --max-steps 20 --no-vtk --no-figures --out "$out" 2>&1)
status=$?
echo "$log"
[ $status -eq 0 ] || { echo "FAIL: exit status $status"; exit 1; }
grep -q "running on 1 thread(s) of $cores" <<<"$log" || { echo "FAIL: no 'running on 1 thread(s) of $cores'"; exit 1; }
grep -q '"threads_fewest": 1' "$out/summary.json" || { echo "FAIL: summary.json threads_fewest is not 1"; exit 1; }
echo "PASS"
