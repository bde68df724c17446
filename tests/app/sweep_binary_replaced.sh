#!/bin/bash
# A sweep whose executable is deleted (as a rebuild replaces it) after its first case started
# still runs every case, with the engine it began with: its runs start from the running
# executable, not from the file at its path.
# Usage: sweep_binary_replaced.sh DDAFRAC WORK_DIR
set -u
ddafrac=$1 work=$2
source "$(dirname "$0")/small_sweep.sh"
rm -rf "$work" && mkdir -p "$work/bin"
cp "$ddafrac" "$work/bin/ddafrac"
write_small_sweep "$work/sweep" 1
printf 'name = "two"\ncases = ["case1.toml", "case2.toml"]\ncrack_time = 4e-5\nthreads = 1\n' > "$work/sweep/two.sweep.toml"

"$work/bin/ddafrac" sweep "$work/sweep/two.sweep.toml" --out "$work/out" --parallel 1 > "$work/sweep.log" 2>&1 &
sweep=$!
for _ in $(seq 1 600); do
  grep -q "^started " "$work/sweep.log" && break
  sleep 0.1
done
grep -q "^started " "$work/sweep.log" || fail "the sweep started no case: $(cat "$work/sweep.log")"
rm "$work/bin/ddafrac"
wait "$sweep"
status=$?
[ "$status" -eq 0 ] || fail "the sweep ended with exit status $status: $(cat "$work/sweep.log")"
for c in case1 case2; do
  grep -q '"reason": "completed"' "$work/out/$c/summary.json" 2>/dev/null ||
    fail "$c did not complete after the executable was deleted: $(cat "$work/sweep.log")"
done
echo PASS
