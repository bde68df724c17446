#!/usr/bin/env bash
# A sweep killed outright (the sweep and its runs: SIGKILL to the process group) while its second
# case runs, then `ddafrac sweep --resume`: the finished first case is kept, the second continues
# from its checkpoint, the third starts; every case's files and the table (but its run times) are
# byte-identical to an uninterrupted sweep's. The same when only the sweep is killed: its running
# case stops by itself and is resumed. A case whose scene changed runs again.
# Usage: sweep_resume.sh DDAFRAC WORK_DIR   (cases extend the built-in default scene)
set -u
exe=$1 work=$2
rm -rf "$work" && mkdir -p "$work/cases"
fail() { echo "FAIL: $*"; exit 1; }
default_scene="$(cd "$(dirname "$0")/../.." && pwd)/scenes/default.toml"
for n in 1 2 3; do  # three short impacts at 10, 12 and 14 m/s
  printf 'base = "%s"\nname = "case%s"\n[analysis]\nend_time = 1.2e-4\n[bodies.disc]\nvelocity = [0.0, -%s.0]\n' \
    "$default_scene" "$n" "$((8 + 2 * n))" > "$work/cases/case$n.toml"
done
printf 'name = "resume-test"\ncases = ["case1.toml", "case2.toml", "case3.toml"]\ncrack_time = 1.2e-4\nthreads = 1\nparallel = 1\n' \
  > "$work/cases/test.sweep.toml"

"$exe" sweep "$work/cases/test.sweep.toml" --out "$work/whole" > "$work/whole.log" 2>&1 || { cat "$work/whole.log"; fail "the uninterrupted sweep failed"; }

setsid "$exe" sweep "$work/cases/test.sweep.toml" --out "$work/killed" --checkpoint-every 0.3 > "$work/killed.log" 2>&1 &
group=$!
for _ in $(seq 1 1200); do [ -e "$work/killed/case2/checkpoint.bin" ] && break; sleep 0.1; done
[ -e "$work/killed/case2/checkpoint.bin" ] || fail "case 2 never wrote a checkpoint"
sleep 0.5
kill -KILL -- "-$group"
wait "$group" 2>/dev/null
grep -q '"reason": "running"' "$work/killed/case2/summary.json" || fail "case 2 had finished before the kill"
"$exe" sweep "$work/cases/test.sweep.toml" --out "$work/killed" --resume > "$work/resume.log" 2>&1 || { cat "$work/resume.log"; fail "the resumed sweep failed"; }
cat "$work/resume.log"
grep -q "case1 finished before (kept)" "$work/resume.log" || fail "case 1 was not kept"
grep -q "resumed  case2" "$work/resume.log" || fail "case 2 was not resumed from its checkpoint"
grep -q "started  case3" "$work/resume.log" || fail "case 3 was not started"
for n in 1 2 3; do
  for f in $(cd "$work/whole/case$n" && find . -type f ! -name summary.json ! -name run.log | sort); do
    cmp -s "$work/whole/case$n/$f" "$work/killed/case$n/$f" || fail "case$n/$f differs from the uninterrupted sweep's"
  done
done
cut -d, -f1-8,10- "$work/whole/sweep.csv" > "$work/whole.table"
cut -d, -f1-8,10- "$work/killed/sweep.csv" > "$work/killed.table"
cmp -s "$work/whole.table" "$work/killed.table" || fail "sweep.csv differs (run times aside)"

# The sweep alone killed (SIGKILL to it, not to its runs): its running case stops by itself
# (valid files, a checkpoint, summary.json says interrupted) instead of running on unattended,
# and --resume finishes it to the same files.
"$exe" sweep "$work/cases/test.sweep.toml" --out "$work/orphaned" --checkpoint-every 0.3 > "$work/orphaned.log" 2>&1 &
sweep=$!
for _ in $(seq 1 1200); do [ -e "$work/orphaned/case2/checkpoint.bin" ] && break; sleep 0.1; done
[ -e "$work/orphaned/case2/checkpoint.bin" ] || fail "case 2 of the sweep killed alone never wrote a checkpoint"
kill -KILL "$sweep"
wait "$sweep" 2>/dev/null
for _ in $(seq 1 300); do pgrep -f -- "--resume $work/orphaned/case2|--out $work/orphaned/case2" > /dev/null || break; sleep 0.1; done
pgrep -f -- "--out $work/orphaned/case2" > /dev/null && fail "case 2's run went on after its sweep was killed"
grep -q '"reason": "interrupted"' "$work/orphaned/case2/summary.json" || fail "case 2 did not stop as interrupted"
"$exe" sweep "$work/cases/test.sweep.toml" --out "$work/orphaned" --resume > "$work/orphaned_resume.log" 2>&1 ||
  { cat "$work/orphaned_resume.log"; fail "resuming the sweep killed alone failed"; }
grep -q "resumed  case2" "$work/orphaned_resume.log" || fail "case 2 of the sweep killed alone was not resumed"
for f in $(cd "$work/whole/case2" && find . -type f ! -name summary.json ! -name run.log | sort); do
  cmp -s "$work/whole/case2/$f" "$work/orphaned/case2/$f" || fail "case2/$f differs after the sweep killed alone"
done

# A changed case runs again from t = 0; the unchanged ones are kept.
sed -i 's/end_time = 1.2e-4/end_time = 1.1e-4/' "$work/cases/case3.toml"
"$exe" sweep "$work/cases/test.sweep.toml" --out "$work/killed" --resume > "$work/changed.log" 2>&1 || fail "the sweep after a change failed"
grep -q "started  case3" "$work/changed.log" || fail "the changed case 3 was not run again"
[ "$(grep -c 'finished before (kept)' "$work/changed.log")" = 2 ] || fail "the unchanged cases were not kept"
echo "PASS"
