#!/usr/bin/env bash
# A disk that fills up during a run: the run stops with exit status 4 and a message that says the
# disk is full and names the file; no half-written or temporary file is left, every CSV is whole
# (all rows complete), and after space is freed `--resume` finishes the run with the files of an
# uninterrupted one. Needs a small file system of its own: a 6 MB tmpfs mounted in a private
# mount namespace (unshare; as root, or as a user where user namespaces are allowed). Skipped
# (exit 77) where neither is possible.
# Usage: disk_full.sh DDAFRAC WORK_DIR
set -u
exe=$1 work=$2
if [ -z "${DDAFRAC_DISK_FULL_INSIDE:-}" ]; then
  rm -rf "$work" && mkdir -p "$work/disk"
  for flags in -m -rm; do
    if unshare $flags true 2>/dev/null; then
      exec unshare $flags env DDAFRAC_DISK_FULL_INSIDE=1 bash "$0" "$@"
    fi
  done
  echo "SKIP: cannot make a private mount namespace here (unshare -m / -rm refused)"
  exit 77
fi
fail() { echo "FAIL: $*"; exit 1; }
mount -t tmpfs -o size=6m tmpfs "$work/disk" 2>/dev/null || { echo "SKIP: cannot mount a tmpfs"; exit 77; }
run="$work/disk/run"
"$exe" run --out "$work/whole" --no-vtk --no-figures > "$work/whole.log" 2>&1 || fail "the uninterrupted run failed"
# The default scene, without snapshots, with a checkpoint (4.1 MB) every 0.5 s: the first fits in
# 6 MB, the next one (written beside it before it replaces it) does not.
"$exe" run --out "$run" --no-vtk --no-figures --checkpoint-every 0.5 > "$work/full.log" 2>&1
status=$?
grep -v "^t = " "$work/full.log"
[ "$status" = 4 ] || fail "exit status $status, expected 4"
grep -q "the disk is full" "$work/full.log" || fail "the message does not say the disk is full"
grep -q "checkpoint.bin" "$work/full.log" || fail "the message does not name the file"
grep -q "continue with: ddafrac run --resume" "$work/full.log" || fail "the message does not say how to go on"
leftovers=$(find "$run" -name '*.partial*')
[ -z "$leftovers" ] || fail "temporary files left: $leftovers"
for f in history.csv gauges.csv loading.csv cracks.csv; do
  awk -F, 'NR == 1 { n = NF } NF != n { bad = 1 } END { exit bad }' "$run/$f" || fail "$f has an incomplete row"
done
python3 -c "import json,sys; json.load(open(sys.argv[1]))" "$run/summary.json" || fail "summary.json is not valid JSON"
# Space freed: the run goes on from its checkpoint and ends with the uninterrupted run's files.
mount -o remount,size=64m "$work/disk" || fail "cannot grow the tmpfs"
"$exe" run --resume "$run" --no-figures --checkpoint-every 0 > "$work/resume.log" 2>&1 || { cat "$work/resume.log"; fail "resume failed"; }
for f in history.csv cracks.csv gauges.csv loading.csv crack_intervals.csv; do
  cmp -s "$work/whole/$f" "$run/$f" || fail "$f differs from the uninterrupted run's after the resume"
done
echo "PASS"
