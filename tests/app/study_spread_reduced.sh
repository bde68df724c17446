#!/usr/bin/env bash
# `ddafrac study sensitivity --family spread` at a strongly reduced size (--blocks 700): case 4 at
# 700 blocks to its scene's 1800 µs with its impact speed, and the flattened disc at 258 blocks
# with its platen speed, each as specified and × (1 + n·10⁻⁶), n = 1, 2, 4, 8. Asserts what must
# hold whatever the mesh:
#   - every case completed; crack counts never fall; the energy balance holds within 1%
#     (study_checks.sh);
#   - each case ran the speed its name says, to 1e-12 (the change sits in the sixth digit, so a
#     scene written with fewer digits would lose it);
#   - the first crack (and the flattened disc's peak force) comes within FIRST_CRACK_BAND
#     (PEAK_FORCE_BAND) of the specified run's in every run: before any joint breaks the disc is
#     elastic, and a load changed by 8·10⁻⁶ moves the time a joint's force reaches its strength,
#     and the force at a given travel, by about that fraction, well under one 0.1 µs step; the
#     bands leave room for a contact inside the open–close band settling in the other state first;
#   - analysis.md has both spread sections and figures/spread.png, spread_flattened.png exist.
# Usage: study_spread_reduced.sh DDAFRAC WORK_DIR
set -u
source "$(dirname "${BASH_SOURCE[0]}")/study_checks.sh"
exe=$1 work=$2
rm -rf "$work" && mkdir -p "$work"
study="$work/study"
readonly FIRST_CRACK_BAND=0.02 PEAK_FORCE_BAND=0.01
impact=case04-700 flattened=flattened-258  # 2045 * 700 / 5550 = 258 blocks
changes="1e-06 2e-06 4e-06 8e-06"
cases=$impact,$flattened
for c in $changes; do cases="$cases,$impact-dv$c,$flattened-dv$c"; done

run_study "$work/study.log" "$exe" study sensitivity --out "$study" --family spread --blocks 700 --cases "$cases"

# A run's speed (m/s): the disc's impact speed, or the top platen's.
impact_speed() { python3 -c 'import math,sys,tomllib; v=tomllib.load(open(sys.argv[1],"rb"))["bodies"]["disc"]["velocity"]; print(repr(math.hypot(*v)))' "$1/scene.resolved.toml"; }
platen_speed() { python3 -c 'import sys,tomllib; v=tomllib.load(open(sys.argv[1],"rb"))["bodies"]["top_platen"]["prescribed_velocity"]; print(repr(abs(v[1])))' "$1/scene.resolved.toml"; }
first() { summary_value "$1" 's["crack_metrics"]["first_crack_time"]'; }
peak() { summary_value "$1" 's["loading"]["peak"]["top_platen"]["peak_abs_force_y"]'; }
within() {  # within VALUE REFERENCE BAND
  python3 -c 'import sys; v, v0, band = map(float, sys.argv[1:]); sys.exit(0 if abs(v / v0 - 1) <= band else 1)' "$@"
}
# check_spread SPECIFIED SPEED_FUNCTION: each changed run's speed, first crack against the specified run's.
check_spread() {
  local specified=$1 speed=$2 v0 t0 name v t
  check_run "$specified" "$study/$specified"
  v0=$($speed "$study/$specified")
  t0=$(first "$study/$specified")
  for c in $changes; do
    name=$specified-dv$c
    check_run "$name" "$study/$name"
    v=$($speed "$study/$name")
    python3 -c 'import sys; v, v0, c = map(float, sys.argv[1:]); sys.exit(0 if abs(v / v0 - 1 - c) <= 1e-12 else 1)' \
      "$v" "$v0" "$c" || fail "$name ran at $v m/s against $v0 × (1 + $c)"
    t=$(first "$study/$name")
    within "$t" "$t0" "$FIRST_CRACK_BAND" || fail "$name cracked first at $t s against $t0 s as specified"
    echo "$name: speed as named; first crack at $t s against $t0 s"
  done
}
check_spread "$impact" impact_speed
check_spread "$flattened" platen_speed
p0=$(peak "$study/$flattened")
for c in $changes; do
  p=$(peak "$study/$flattened-dv$c")
  within "$p" "$p0" "$PEAK_FORCE_BAND" || fail "$flattened-dv$c: peak force $p N/m against $p0 N/m as specified"
  echo "$flattened-dv$c: peak force $p N/m against $p0 N/m"
done

check_report "$study" "Spread: case 4" spread.png
check_report "$study" "Spread: the flattened disc" spread_flattened.png
echo "PASS"
