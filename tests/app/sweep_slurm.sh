#!/usr/bin/env bash
# `ddafrac sweep --emit-slurm` and `ddafrac sweep --collect`, without Slurm: the job array's
# script has one task per case (longest expected first), the sweep's threads per task and each
# task's `ddafrac run` command; its tasks, run as Slurm would run them (SLURM_ARRAY_TASK_ID set),
# write the same files as the plain sweep; --collect on a folder with done, failed, interrupted
# and not started cases lists each as such, and once the rest have run, as done.
# Usage: sweep_slurm.sh DDAFRAC WORK_DIR
set -u
exe=$(readlink -f "$1") work=$2
rm -rf "$work" && mkdir -p "$work"
source "$(dirname "$0")/small_sweep.sh"
write_small_sweep "$work/cases" 2
out=$work/array
script=$out/sweep.slurm
task() { SLURM_ARRAY_TASK_ID=$1 bash "$script"; }

"$exe" sweep "$work/cases/small.sweep.toml" --out "$out" --emit-slurm > "$work/emit.log" 2>&1 || { cat "$work/emit.log"; fail "--emit-slurm failed"; }
cat "$script"
bash -n "$script" || fail "the script is not valid bash"
grep -qx '#SBATCH --array=0-4' "$script" || fail "the array is not of 5 tasks"
grep -qx '#SBATCH --cpus-per-task=2' "$script" || fail "the tasks do not ask for the sweep's 2 threads"
grep -qx 'export OMP_NUM_THREADS=2' "$script" || fail "the tasks do not set the sweep's 2 threads"
grep -qF "  0) dir='$out/case4' fresh=('$exe' 'run' '--threads' '2' '$work/cases/case4.toml' '--out' '$out/case4')" "$script" ||
  fail "task 0 does not run case4 (the longest expected) with its command"
[ "$(grep -c '^  [0-9]) dir=' "$script")" = 5 ] || fail "the script does not list 5 tasks"
task 7 2> "$work/task7.log" && fail "a task number beyond the array ran"
grep -q "no case for array task 7" "$work/task7.log" || fail "a task beyond the array is not explained"

# Tasks 0 (case4) and 4 (too-coarse, fails) run; case3's run (task 1) is stopped by a SIGTERM, as
# Slurm stops a task at its time limit; tasks 2 and 3 have not started.
task 0 || fail "task 0 failed"
task 4 && fail "task 4 (too-coarse) did not fail"
SLURM_ARRAY_TASK_ID=1 setsid bash "$script" & group=$!
for _ in $(seq 1 600); do [ -e "$out/case3/summary.json" ] && break; sleep 0.1; done
kill -TERM -- "-$group"  # Slurm signals every process of the task
wait "$group" && fail "the stopped task 1 ended with status 0"
"$exe" sweep --collect "$out" > "$work/collect.log" 2>&1 || { cat "$work/collect.log"; fail "--collect failed"; }
cat "$work/collect.log" "$out/sweep.csv"
grep -q "5 cases: 1 done, 1 failed, 2 not started, 1 unfinished" "$work/collect.log" || fail "--collect's counts are wrong"
grep -q '^case4,.*,0,case4,done,[0-9.e+]*$' "$out/sweep.csv" || fail "case4 is not listed as done"
grep -q '^too-coarse,.*,1,too-coarse,failed,[0-9.e+]*$' "$out/sweep.csv" || fail "too-coarse is not listed as failed"
grep -q '^case3,.*,,,,.*,,case3,unfinished,[0-9.e+]*$' "$out/sweep.csv" || fail "case3 is not listed as unfinished (without counts)"
grep -q '^case1,.*,case1,not started,[0-9.e+]*$' "$out/sweep.csv" || fail "case1 is not listed as not started"

# The rest run (case3 again: from its checkpoint if it wrote one, else from t = 0); all is done.
for k in 1 2 3; do task $k || fail "task $k failed"; done
"$exe" sweep --collect "$out" > "$work/collect2.log" 2>&1 || fail "the second --collect failed"
grep -q "5 cases: 4 done, 1 failed" "$work/collect2.log" || { cat "$work/collect2.log"; fail "the second --collect's counts are wrong"; }
[ -e "$out/figures/sweep_cracks.png" ] || fail "--collect drew no figure"

# The tasks' files are the plain sweep's.
"$exe" sweep "$work/cases/small.sweep.toml" --out "$work/plain" --parallel 1 > "$work/plain.log" 2>&1
for n in 1 2 3 4; do same_run_files "$work/plain/case$n" "$out/case$n"; done
echo "PASS"
