#!/usr/bin/env bash
# `ddafrac study sensitivity --family node-model` at a strongly reduced size: case 4 at 700 blocks
# (--blocks 700; to its scene's 1800 µs: --set would reach the family's static runs too), under the three node models (node contacts judged on the joints'
# springs, node contacts judged on the blocks' stress, ties judged on the blocks' stress). The
# flattened-disc members are left out: they add nothing this test can bound in minutes.
# Asserts what must hold whatever the mesh:
#   - every case completed; crack counts never fall; the energy balance holds within 1%
#     (study_checks.sh), with the ties' release booked in it;
#   - each case ran the model its name says (summary.json's intact_nodes and fracture_load);
#   - ties carry load past the joints: the ties' joint_load_share (normal) is below the node
#     contacts' (design §4.6; the default scene: 0.16 against 0.37);
#   - analysis.md has its node-model section and figures/node_model.png exists;
#   - the ties case gives the same files on 2 threads.
# Usage: study_node_model_reduced.sh DDAFRAC WORK_DIR
set -u
source "$(dirname "${BASH_SOURCE[0]}")/study_checks.sh"
exe=$1 work=$2
rm -rf "$work" && mkdir -p "$work"
study="$work/study"
contacts=case04-700 stress=case04-700-stress ties=case04-700-ties

run_study "$work/study.log" "$exe" study sensitivity --out "$study" --family node-model --blocks 700 \
  --cases "$contacts,$stress,$ties"

for c in $contacts $stress $ties; do
  check_run "$c" "$study/$c"
done
model() { summary_value "$1" 's["scene"]["intact_nodes"] + "/" + s["scene"]["fracture_load"]'; }
[ "$(model "$study/$contacts")" = contact/joint_springs ] || fail "$contacts ran $(model "$study/$contacts")"
[ "$(model "$study/$stress")" = contact/block_stress ] || fail "$stress ran $(model "$study/$stress")"
[ "$(model "$study/$ties")" = tie/block_stress ] || fail "$ties ran $(model "$study/$ties")"
share() { summary_value "$1" 's["joint_load_share"]["normal"]'; }
python3 -c 'import sys; sys.exit(0 if float(sys.argv[1]) < float(sys.argv[2]) else 1)' \
  "$(share "$study/$ties")" "$(share "$study/$contacts")" ||
  fail "the ties' joint load share $(share "$study/$ties") is not below the node contacts' $(share "$study/$contacts")"
echo "joints' load share (normal): $(share "$study/$contacts") with node contacts, $(share "$study/$ties") with ties"

check_report "$study" "Node model" node_model.png

check_same_on_two_threads "$ties" "$study/$ties" "$exe" "$work/two_threads" "$study/scenes/$ties.toml"
echo "PASS"
