#!/usr/bin/env bash
# `ddafrac study sensitivity --family spread` at a strongly reduced size: case 4 at 700 blocks
# (--blocks 700) to its scene's 1800 µs, as specified and with its impact speed × (1 + n·10⁻⁶),
# n = 1, 2, 4, 8. Asserts what must hold whatever the mesh:
#   - every case completed; crack counts never fall; the energy balance holds within 1%
#     (study_checks.sh);
#   - each case ran the speed its name says, to 1e-12 (the change sits in the sixth digit, so a
#     scene written with fewer digits would lose it);
#   - the first crack comes within FIRST_CRACK_BAND of the specified run's in every run: before
#     any joint breaks the disc is elastic, and a load changed by 8·10⁻⁶ moves the time a joint's
#     force reaches its strength by about that fraction, well under one 0.1 µs step; the band
#     leaves room for a contact inside the open–close band settling in the other state first;
#   - analysis.md has its spread section and figures/spread.png exists.
# Usage: study_spread_reduced.sh DDAFRAC WORK_DIR
set -u
source "$(dirname "${BASH_SOURCE[0]}")/study_checks.sh"
exe=$1 work=$2
rm -rf "$work" && mkdir -p "$work"
study="$work/study"
readonly FIRST_CRACK_BAND=0.02
specified=case04-700
changes="1e-06 2e-06 4e-06 8e-06"
cases=$specified
for c in $changes; do cases="$cases,$specified-dv$c"; done

run_study "$work/study.log" "$exe" study sensitivity --out "$study" --family spread --blocks 700 --cases "$cases"

check_run "$specified" "$study/$specified"
speed() { python3 -c 'import math,sys,tomllib; v=tomllib.load(open(sys.argv[1],"rb"))["bodies"]["disc"]["velocity"]; print(repr(math.hypot(*v)))' "$1/scene.resolved.toml"; }
first() { summary_value "$1" 's["crack_metrics"]["first_crack_time"]'; }
v0=$(speed "$study/$specified")
t0=$(first "$study/$specified")
for c in $changes; do
  name=$specified-dv$c
  check_run "$name" "$study/$name"
  python3 -c 'import sys; v, v0, c = map(float, sys.argv[1:]); sys.exit(0 if abs(v / v0 - 1 - c) <= 1e-12 else 1)' \
    "$(speed "$study/$name")" "$v0" "$c" || fail "$name ran at $(speed "$study/$name") m/s against $v0 × (1 + $c)"
  t=$(first "$study/$name")
  python3 -c 'import sys; t, t0, band = map(float, sys.argv[1:]); sys.exit(0 if abs(t / t0 - 1) <= band else 1)' \
    "$t" "$t0" "$FIRST_CRACK_BAND" || fail "$name cracked first at $t s against $t0 s as specified"
  echo "$name: impact speed as named; first crack at $t s against $t0 s"
done

check_report "$study" "Spread" spread.png
echo "PASS"
