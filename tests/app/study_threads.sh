#!/bin/bash
# A study shares the cores among the runs that go at once: on two cores, one case left to run
# (a single case, or a resume with one case to do) gets both, two cases at once get one each.
# Runs on cores 0 and 1 (taskset); skipped (77) on a machine with fewer.
# Usage: study_threads.sh DDAFRAC WORK_DIR
set -u
source "$(dirname "${BASH_SOURCE[0]}")/study_checks.sh"
ddafrac=$1 work=$2
[ "$(nproc --all)" -ge 2 ] || { echo "SKIP: fewer than 2 cores"; exit 77; }
rm -rf "$work" && mkdir -p "$work"
# case 4 at 700 blocks (the smallest its slot allows) for 20 steps: seconds per case.
study=(study sensitivity --blocks 700 --family timestep --set analysis.end_time=2e-6 --set analysis.output_interval=1e-6)

# expect_threads LOG THREADS: the study said each run gets THREADS threads and ended well.
expect_threads() {
  grep -q "at a time, $2 thread(s) each" "$1" || fail "expected $2 thread(s) per run: $(cat "$1")"
  grep -q "FAILED" "$1" && fail "a case failed: $(cat "$1")"
  return 0
}

taskset -c 0,1 "$ddafrac" "${study[@]}" --cases case04-700 --out "$work/one" > "$work/one.log" 2>&1
expect_threads "$work/one.log" 2
taskset -c 0,1 "$ddafrac" "${study[@]}" --cases case04-700,case04-700-dt5e-08 --out "$work/one" --resume \
  > "$work/resume.log" 2>&1
expect_threads "$work/resume.log" 2
taskset -c 0,1 "$ddafrac" "${study[@]}" --cases case04-700,case04-700-dt5e-08 --out "$work/two" > "$work/two.log" 2>&1
expect_threads "$work/two.log" 1
taskset -c 0,1 "$ddafrac" "${study[@]}" --cases case04-700,case04-700-dt5e-08 --parallel 1 --out "$work/serial" \
  > "$work/serial.log" 2>&1
expect_threads "$work/serial.log" 2
echo PASS
