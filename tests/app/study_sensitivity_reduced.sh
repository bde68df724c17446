#!/usr/bin/env bash
# `ddafrac study sensitivity` at a strongly reduced size: case 4's reference mesh at 1400 blocks
# (--blocks), to 400 µs (past its first cracks, at about 255 µs), and one member of each impact
# family besides the reference: the half-size mesh, every contact and joint at kn = E, the half time
# step, the slot's ends meshed at a quarter of a slot width.
# Asserts what must hold whatever the mesh:
#   - every case completed; crack counts, crack lengths and fragments never fall; the energy
#     balance holds within 1% (study_checks.sh), and within the looser bound below for the
#     stiff case;
#   - the total crack length of the two meshes agrees within the band below, and every crack of
#     either is a wing crack, near a slot tip;
#   - the stiff-joint case got a dt_max that resolves its contact period (shorter than the
#     scene's, and its run did not warn), as the family promises;
#   - the half time step gives the reference's crack length within the same band;
#   - the finer slot tip cracks first no later than the reference (a sharper notch concentrates
#     more stress: here 181.0 against 254.2 µs; 194 against 281 µs on case 4's 1375-block mesh).
#     Tips at half a slot width are too close to tell: 250.5 against 254.7 µs, and 257.7 against
#     254.2 µs once the node contact held the deeper copy (design §4.6): a 3% move, where a
#     contact-state decision alone moved the default scene's first crack by 8%
#     (docs/results/speed.md, the first guess);
#   - study.md has a row per case, analysis.md a section per family and the figures exist;
#   - the reference case (it cracks; the stiff one cracks more but costs 4× as much) gives the
#     same files on 2 threads.
# Then the flattened-disc factor of the analysis (Wang et al. 2004) against the FEM: the centre
# σxx of the FEM's flattened disc under a flat load P, over 2P/(πD), within the stated tolerance.
# Usage: study_sensitivity_reduced.sh DDAFRAC WORK_DIR
set -u
source "$(dirname "${BASH_SOURCE[0]}")/study_checks.sh"
exe=$1 work=$2
rm -rf "$work" && mkdir -p "$work"
study="$work/study"
end_time=4e-4   # s: 4000 steps at the scene's dt_max = 1e-7 s
# Total crack length, 700 against 1400 blocks, and the half time step against the reference.
# The cracks by 400 µs are the wing cracks at the slot's tips, where both meshes are refined
# alike; how far a wing runs is the mesh's (at full size the wings grow 7× from 5559 to 11137
# blocks, docs/results/sensitivity.md): on this engine 5.14 mm (8 cracks) at 700 blocks and
# 8.96 mm (10) at 1400 by 400 µs, the lower wing 2.9 against 5.2 mm from its tip; 6.05 mm at
# the half time step. Band: a factor of 2. What must hold whatever the mesh is that they are
# wing cracks: every crack within tip_reach of a slot tip, so that a change that cracks the
# disc elsewhere (far from the tips) is seen.
length_band=2.0
tip_reach=0.01  # m: 5.2 mm is the farthest today
# The FEM's centre σxx over 2P/(πD) is 0.978 for the study's 10° flats; the formula gives 0.990
# (it maps the flats onto arcs): 1.2% apart. Tolerance 2%.
factor_tolerance=0.02
# The stiff case (kn = E) shatters: ~230 cracks by 400 µs, against 8 at the study's kn. Its
# ledger closes within 0.09% through the burst of breaks (75-285 µs); then two contacts that
# detection finds 10-12 µm deep (at ~288 µs, the run's missed_contacts) add 1.46%: 1.54% at
# 400 µs, a gap in detection, open in docs/results/sensitivity.md. Bound 2%: the corner leak
# fixed before (3.6% by 400 µs) fails it, and so would one more missed contact of that depth.
stiff_balance_tolerance=0.02
set_args=(--set "analysis.end_time=$end_time")
cases=case04-700,case04-1400,case04-1400-kn1E,case04-1400-dt5e-08,case04-1400-tip0.25

run_study "$work/study.log" "$exe" study sensitivity --out "$study" --blocks 1400 --family mesh,penalty,timestep,slot-tips --cases "$cases" \
  "${set_args[@]}"

for c in ${cases//,/ }; do
  grep -q "^| $c |" "$study/study.md" || fail "study.md has no row for $c"
  if [ "$c" = case04-1400-kn1E ]; then check_run "$c" "$study/$c" "$stiff_balance_tolerance"; else check_run "$c" "$study/$c"; fi
done
reference=case04-1400
[ "$(summary_value "$study/$reference" 's["cracks"]["total"]')" -gt 0 ] ||
  fail "$reference did not crack: the checks of crack counts over time and threads see nothing"

length() { summary_value "$1" 's["crack_metrics"]["crack_length_tensile"] + s["crack_metrics"]["crack_length_shear"]'; }
within_band() {
  python3 -c 'import sys; a, b, band = map(float, sys.argv[1:]); sys.exit(0 if a > 0 and b > 0 and max(a, b) / min(a, b) <= band else 1)' "$@"
}
coarse=$(length "$study/case04-700") fine=$(length "$study/case04-1400") short=$(length "$study/case04-1400-dt5e-08")
within_band "$coarse" "$fine" "$length_band" || fail "crack length $coarse m (700 blocks) against $fine m (1400 blocks): outside a factor of $length_band"
within_band "$short" "$fine" "$length_band" || fail "crack length $short m (dt_max 5e-8 s) against $fine m (1e-7 s): outside a factor of $length_band"
echo "crack length: $coarse m at 700 blocks, $fine m at 1400 blocks, $short m at half the time step (band: a factor of $length_band)"
for c in case04-700 case04-1400 case04-1400-dt5e-08; do
  python3 - "$study/$c" "$tip_reach" <<'PY' || fail "$c cracked farther than $tip_reach m from the slot's tips"
import csv, math, os, sys, tomllib
run, reach = sys.argv[1], float(sys.argv[2])
with open(os.path.join(run, "scene.resolved.toml"), "rb") as f:
    g = tomllib.load(f)["geometry"]
half = 0.5 * g["connectivity"] * g["diameter"]
a = math.radians(g["joint_angle"])
tips = [(half * math.cos(a), half * math.sin(a)), (-half * math.cos(a), -half * math.sin(a))]
far = [r for r in csv.DictReader(open(os.path.join(run, "cracks.csv")))
       if min(math.hypot(float(r["x"]) - x, float(r["y"]) - y) for x, y in tips) > reach]
for r in far:
    print(f"crack at ({r['x']}, {r['y']}) m, t = {r['t']} s")
sys.exit(1 if far else 0)
PY
done

check_contact_period_resolved case04-1400-kn1E "$study/case04-1400-kn1E" 1e-7

first_crack() { summary_value "$1" 's["crack_metrics"]["first_crack_time"]'; }
tip_first=$(first_crack "$study/case04-1400-tip0.25") reference_first=$(first_crack "$study/$reference")
python3 -c 'import sys; sys.exit(0 if float(sys.argv[1]) <= float(sys.argv[2]) else 1)' "$tip_first" "$reference_first" ||
  fail "the finer slot tip cracked first at $tip_first s, after the reference's $reference_first s"
echo "first crack: $tip_first s at the quarter-width slot tip, $reference_first s at the reference's"

for section in "## Mesh" "## Joint stiffness" "## Time step" "## Slot tips"; do
  grep -q "^$section" "$study/analysis.md" || fail "analysis.md has no section '$section'"
done
for figure in mesh penalty timestep slot_tips; do
  [ -s "$study/figures/$figure.png" ] || fail "no figures/$figure.png"
done

check_same_on_two_threads "$reference" "$study/$reference" "$exe" "$work/two_threads" "$study/scenes/$reference.toml" "${set_args[@]}"

# The flattened-disc factor against the FEM reference of the same disc (its geometry as a run
# of the scene resolves it: one step).
flattened="$(dirname "${BASH_SOURCE[0]}")/../../scenes/verify/flattened_static.toml"
"$exe" verify "$flattened" --out "$work/verify" --no-figures > "$work/verify.log" 2>&1 ||
  { cat "$work/verify.log"; fail "verify flattened_static failed"; }
"$exe" run "$flattened" --out "$work/geometry" --max-steps 1 --no-vtk --no-figures > "$work/geometry.log" 2>&1 ||
  { cat "$work/geometry.log"; fail "one step of flattened_static failed"; }
"${DDAFRAC_PYTHON:-/usr/bin/python3}" - "$work" "$(dirname "${BASH_SOURCE[0]}")/../../plots" "$factor_tolerance" <<'PY' || fail "flattened-disc factor"
import json, math, sys, tomllib
work, plots, tolerance = sys.argv[1], sys.argv[2], float(sys.argv[3])
sys.path.insert(0, plots)
from study_sensitivity_plots import flattened_disc_factor
c = json.load(open(f"{work}/verify/comparison.json"))
geometry = tomllib.load(open(f"{work}/geometry/scene.resolved.toml", "rb"))["geometry"]
fem = c["centre"]["fem"][0] / (2.0 * c["load"] / (math.pi * geometry["diameter"]))
formula = flattened_disc_factor(geometry["flat_angle"])
print(f"flattened-disc factor: FEM {fem:.4f}, formula {formula:.4f} ({(formula / fem - 1) * 100:+.2f}%)")
sys.exit(0 if abs(formula / fem - 1.0) <= tolerance else 1)
PY
echo "PASS"
