#!/bin/bash
# A study case whose scene repeats another's under a new name runs once: the source study's cases
# 8 and 12 are case 4's scene. Chosen together, only case 4 runs (one run directory, the run said
# why); --status lists 8 and 12 as done with case 4's run; study.md gives them case 4's numbers,
# marked as its run; study.csv points them at its run directory; the γ and v0 series' figures
# are drawn with them.
# Usage: study_repeats.sh DDAFRAC WORK_DIR
set -u
source "$(dirname "${BASH_SOURCE[0]}")/study_checks.sh"
ddafrac=$1 work=$2
rm -rf "$work" && mkdir -p "$work"
study="$work/study"
# 700 blocks (the smallest the slot allows) for 20 steps: seconds per run.
set_args=(--set mesh.blocks=700 --set analysis.end_time=2e-6 --set analysis.output_interval=1e-6)

"$ddafrac" study source --out "$study" --cases impact-case08,impact-case04,impact-case12 "${set_args[@]}" \
  > "$work/run.log" 2>&1 || { cat "$work/run.log"; fail "the study failed"; }
cat "$work/run.log"
grep -q "1 case (1 to run)" "$work/run.log" || fail "expected one case to run"
grep -q "impact-case08 repeats impact-case04's scene" "$work/run.log" || fail "the run does not say case 8 repeats case 4"
grep -q "impact-case12 repeats impact-case04's scene" "$work/run.log" || fail "the run does not say case 12 repeats case 4"
[ -s "$study/impact-case04/summary.json" ] || fail "impact-case04 did not run"
for c in impact-case08 impact-case12; do
  [ -e "$study/$c" ] && fail "$c ran in its own directory"
  grep -q "^$c,.*,impact-case04," "$study/study.csv" || fail "study.csv does not point $c at impact-case04's run"
done

"$ddafrac" study source --out "$study" --status > "$work/status.log" 2>&1 || { cat "$work/status.log"; fail "--status failed"; }
grep -q "^impact-case08 .* done (impact-case04's run)$" "$work/status.log" || { cat "$work/status.log"; fail "--status: case 8"; }
grep -q "^impact-case04 .* done$" "$work/status.log" || fail "--status does not list impact-case04 as done"

# The rows of 8 and 12 are case 4's, cell for cell after the case and series.
row04=$(grep "^| impact-case04 | " "$study/study.md" | cut -d'|' -f4-)
[ -n "$row04" ] || fail "study.md has no row for impact-case04"
echo "$row04" | grep -q "^ [0-9]" || fail "impact-case04's row has no numbers: $row04"
for c in impact-case08 impact-case12; do
  row=$(grep "^| $c (impact-case04's run) | " "$study/study.md" | cut -d'|' -f4-)
  [ "$row" = "$row04" ] || fail "study.md: $c's row is not case 4's: '$row' against '$row04'"
done
for s in impact-gamma impact-v0; do
  [ -s "$study/figures/cracks_$s.png" ] || fail "no figures/cracks_$s.png"
done
echo PASS
