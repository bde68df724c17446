#!/usr/bin/env bash
# `ddafrac study sensitivity --family penalty-theta` at a strongly reduced size: the θ series with
# every contact and joint at kn = 10·E and, on the same meshes, at the scenes' own kn, at 700 blocks
# (--blocks 700 scales case 4's 5550), the two ends of the series (θ = 0° and 90°), to a short end
# time.
# Asserts what must hold whatever the mesh:
#   - every case completed; crack counts, crack lengths and fragments never fall; the energy
#     balance holds within 1% (study_checks.sh);
#   - every case got kn = 10·E and a dt_max shorter than the scene's that resolves its contact
#     period (its run did not warn), as the family promises;
#   - analysis.md has the θ section with a table per kn, each with one row per θ, and
#     figures/penalty_theta.png and a row of crack patterns per kn;
#   - --status and --report without --family and --blocks are about the same cases, and a
#     study.json whose record of them was edited is refused, naming the key;
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
stiff_cases="case01-700-kn10E case07-700-kn10E"
scene_kn_cases="case01-700 case07-700"
cases=$(echo $stiff_cases $scene_kn_cases | tr ' ' ,)
stiffness_multiple=10  # the family's kn / E
scene_dt=1e-7          # s: the impact scenes' dt_max
set_args=(--set "analysis.end_time=$end_time")

run_study "$work/study.log" "$exe" study sensitivity --out "$study" --blocks 700 --family penalty-theta --cases "$cases" "${set_args[@]}"

# --status and --report given without --family and --blocks take those the study began with: the
# same cases, not the full-size study of every family. The checks below read that report.
"$exe" study sensitivity --out "$study" --status > "$work/status.log" 2>&1 || { cat "$work/status.log"; fail "--status failed"; }
cat "$work/status.log"
grep -q -- "-5550" "$work/status.log" && fail "--status without --family and --blocks lists full-size cases"
"$exe" study sensitivity --out "$study" --report > "$work/report.log" 2>&1 || { cat "$work/report.log"; fail "--report failed"; }
for c in ${cases//,/ }; do
  grep -q "^$c .* done$" "$work/status.log" || fail "--status without --family and --blocks does not list $c as done"
  grep -q "^| $c |" "$study/study.md" || fail "study.md has no row for $c"
  check_run "$c" "$study/$c"
done
for c in $stiff_cases; do
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

grep -q "^## The θ series against the joints' stiffness" "$study/analysis.md" || fail "analysis.md has no θ section"
# The rows of the kn = 10·E table (stiff) or of the other one (scene) as "case:θ ".
theta_rows() {
  sed -n "/^## The θ series/,/^## [^T]/p" "$study/analysis.md" |
    awk -F'|' -v want="$1" '/^### / { stiff = index($0, "kn = 10·E") > 0; mine = (want == "stiff") == stiff }
      mine && /^\| case[0-9]/ { gsub(/ /, "", $2); gsub(/ /, "", $3); printf "%s:%s ", $2, $3 }'
}
stiff_rows=$(theta_rows stiff)
[ "$stiff_rows" = "case01-700-kn10E:0 case07-700-kn10E:90 " ] ||
  fail "the θ section's kn = 10·E table has rows '$stiff_rows', not case01-700-kn10E at 0 and case07-700-kn10E at 90"
scene_rows=$(theta_rows scene)
[ "$scene_rows" = "case01-700:0 case07-700:90 " ] ||
  fail "the θ section's table at the scenes' kn has rows '$scene_rows', not case01-700 at 0 and case07-700 at 90"
echo "analysis.md: θ rows at 10·E: $stiff_rows; at the scenes' kn: $scene_rows"
[ -s "$study/figures/penalty_theta.png" ] || fail "no figures/penalty_theta.png"
# A row of crack patterns per kn: the scenes' (0.35 GPa / 10.53 GPa) and 10·E.
for kn in 0.0332 10; do
  [ -s "$study/figures/penalty_theta_patterns_kn${kn}E.png" ] || fail "no figures/penalty_theta_patterns_kn${kn}E.png"
done

# A study.json whose recorded --blocks was edited into something else is refused, naming the key.
damaged="$work/damaged"
mkdir -p "$damaged" && sed 's/"blocks": "700"/"blocks": "7OO"/' "$study/study.json" > "$damaged/study.json"
grep -q '"7OO"' "$damaged/study.json" || fail "study.json does not record --blocks 700"
"$exe" study sensitivity --out "$damaged" --status > "$work/damaged.log" 2>&1 && fail "--status took a damaged study.json"
grep -q "options.blocks is '7OO', expected a whole number" "$work/damaged.log" ||
  { cat "$work/damaged.log"; fail "--status of a damaged study.json does not say what is wrong"; }

first=${stiff_cases%% *}
check_same_on_two_threads "$first" "$study/$first" "$exe" "$work/two_threads" "$study/scenes/$first.toml" "${set_args[@]}"
echo "PASS"
