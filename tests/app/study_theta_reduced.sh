#!/usr/bin/env bash
# `ddafrac study sensitivity --family penalty-theta` at a strongly reduced size: the θ series with
# every contact and joint at kn = 10·E, at 700 blocks (--blocks 700 scales case 4's 5550), the two
# ends of the series (θ = 0° and 90°), to a short end time.
# Asserts what must hold whatever the mesh:
#   - every case completed; crack counts, crack lengths and fragments never fall; the energy
#     balance holds within 1% (study_checks.sh);
#   - every case got kn = 10·E and a dt_max shorter than the scene's that resolves its contact
#     period (its run did not warn), as the family promises;
#   - analysis.md has the θ section with one row per case, at its θ, and figures/penalty_theta.png;
#   - one case gives the same files on 2 threads.
# Usage: study_theta_reduced.sh DDAFRAC WORK_DIR
set -u
source "$(dirname "${BASH_SOURCE[0]}")/study_checks.sh"
exe=$1 work=$2
rm -rf "$work" && mkdir -p "$work"
study="$work/study"
# s: at kn = 10·E the disc shatters early: 248 (θ = 0°) and 205 (90°) cracks by 150 µs, balance
# errors 0.18% and 0.085% (dt_max 2e-8 s for both), about 4 minutes in all on the 2-core machine.
end_time=1.5e-4
cases=case01-700-kn10E,case07-700-kn10E
stiffness_multiple=10  # the family's kn / E
scene_dt=1e-7          # s: the impact scenes' dt_max
set_args=(--set "analysis.end_time=$end_time")

"$exe" study sensitivity --out "$study" --blocks 700 --family penalty-theta --cases "$cases" "${set_args[@]}" \
  > "$work/study.log" 2>&1
code=$?
cat "$work/study.log"
[ $code = 0 ] || fail "the study failed (exit status $code)"

for c in ${cases//,/ }; do
  grep -q "^| $c |" "$study/study.md" || fail "study.md has no row for $c"
  check_run "$c" "$study/$c"
  "${DDAFRAC_PYTHON:-/usr/bin/python3}" - "$study/$c/scene.resolved.toml" "$stiffness_multiple" <<'PY' ||
import sys, tomllib
scene = tomllib.load(open(sys.argv[1], "rb"))
young = scene["materials"][scene["bodies"]["disc"]["material"]]["young"]
print(f"kn = {scene['analysis']['penalty'] / young:g}·E")
sys.exit(0 if abs(scene["analysis"]["penalty"] / (float(sys.argv[2]) * young) - 1.0) < 1e-12 else 1)
PY
    fail "$c: kn is not ${stiffness_multiple}·E"
  check_contact_period_resolved "$c" "$study/$c" "$scene_dt"
done

grep -q "^## The θ series at kn = 10·E" "$study/analysis.md" || fail "analysis.md has no θ section"
angles=$(sed -n '/^## The θ series/,/^## [^T]/p' "$study/analysis.md" | awk -F'|' '/^\| case[0-9]/ { gsub(/ /, "", $3); printf "%s ", $3 }')
[ "$angles" = "0 90 " ] || fail "the θ section of analysis.md has rows at θ = '$angles', not 0 and 90"
echo "analysis.md: θ rows at $angles"
[ -s "$study/figures/penalty_theta.png" ] || fail "no figures/penalty_theta.png"

first=${cases%%,*}
check_same_on_two_threads "$first" "$study/$first" "$exe" "$work/two_threads" "$study/scenes/$first.toml" "${set_args[@]}"
echo "PASS"
