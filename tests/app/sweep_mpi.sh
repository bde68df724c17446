#!/usr/bin/env bash
# `mpirun -np 2 ddafrac sweep` (oversubscribed if need be) against the plain sweep of the same
# five cases: every case's files and sweep.csv (but the run times) byte-identical; both ranks ran
# cases, handed out longest expected first; the case whose run fails is reported as failed, the
# others finish, and the sweep's exit status says so; a plain sweep never starts MPI.
# Usage: sweep_mpi.sh DDAFRAC MPIEXEC WORK_DIR
set -u
exe=$1 mpiexec=$2 work=$3
# CI runs as root, which Open MPI refuses without these two.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
rm -rf "$work" && mkdir -p "$work"
source "$(dirname "$0")/small_sweep.sh"
write_small_sweep "$work/cases" 1
sweep=$work/cases/small.sweep.toml

"$exe" sweep "$sweep" --out "$work/serial" --parallel 2 > "$work/serial.log" 2>&1
status=$?
cat "$work/serial.log"
[ $status = 1 ] || fail "the plain sweep ended with status $status, not 1 (one case fails)"
grep -q "1 of 5 cases failed" "$work/serial.log" || fail "the plain sweep does not report its failed case"
grep -q "rank" "$work/serial.log" && fail "the plain sweep speaks of ranks"
[ "$(grep -m 1 '^started' "$work/serial.log" | cut -d' ' -f3)" = case4 ] || fail "the longest case did not start first"

"$mpiexec" --oversubscribe -np 2 "$exe" sweep "$sweep" --out "$work/mpi" --parallel 1 > "$work/mpi.log" 2>&1
status=$?
cat "$work/mpi.log"
[ $status != 0 ] || fail "mpirun ended with status 0 though a case failed"
grep -q "1 of 5 cases failed" "$work/mpi.log" || fail "the MPI sweep does not report its failed case"
grep -q "too-coarse FAILED" "$work/mpi.log" || fail "the failed case is not named"
grep -q "^started .* on rank 0 of 2" "$work/mpi.log" || fail "rank 0 ran no case"
grep -q "^started .* on rank 1 of 2" "$work/mpi.log" || fail "rank 1 ran no case"
[ "$(grep -c '^\[[0-9]/5\]' "$work/mpi.log")" = 5 ] || fail "rank 0 did not report 5 ended cases"

for n in 1 2 3 4; do same_run_files "$work/serial/case$n" "$work/mpi/case$n"; done
cut -d, -f1-8,10- "$work/serial/sweep.csv" > "$work/serial.table"
cut -d, -f1-8,10- "$work/mpi/sweep.csv" > "$work/mpi.table"
cmp -s "$work/serial.table" "$work/mpi.table" || fail "sweep.csv differs (run times aside)"
grep -q "^too-coarse,.*,1,too-coarse,failed,[0-9.e+]*$" "$work/mpi/sweep.csv" || fail "sweep.csv does not list too-coarse as failed"
[ "$(grep -c ',0,case[1-4],done,[0-9.e+]*$' "$work/mpi/sweep.csv")" = 4 ] || fail "sweep.csv does not list the 4 others as done"
echo "PASS"
