#!/usr/bin/env bash
# `ddafrac study source` at a strongly reduced size (every case at the block count and end time
# given below, its virtual joints weakened so that cracks form within that time), killed with its
# runs after its first case finished, then resumed. Asserts what must hold whatever the mesh:
#   - the resume keeps the finished first case (not run again: its files untouched);
#   - --status lists it as done, the others as to do, and all as done at the end; --report then
#     writes study.md with its row filled and the others "not run";
#   - cases 8 and 12 (case 4's scene) are not run again: study.csv points them at case 4's run;
#   - every case completed, study.md has a row for every case, study.csv lists them, and it
#     names the one engine (build commit, as `ddafrac --version` gives it) that ran them all;
#   - crack counts (total, tensile, shear) never decrease in any history.csv, nor the crack
#     lengths and fragment counts in fragments.csv;
#   - the largest |energy-balance error| of every run is within 1% (the run's own warning level);
#   - analysis.md gives every Brazilian disc's indirect tensile strength as k·2P/(πD) of its
#     peak force, and the flattened disc's mesh convergence table; the Brazilian pattern figures exist;
#   - the case that cracked most, run again on 2 threads, writes the same history.csv, cracks.csv
#     and fragments.csv byte for byte (results do not depend on the thread count);
#   - every figure is drawn, also by a --report for which a series' last case has not run;
#   - the cross-study figure (ddafrac_plots.py impact-series) puts cases 1-7 in the θ series,
#     4, 9, 10 in the γ series and 4, 11-15 in the v0 series, read from their scenes alone.
# Usage: study_source_reduced.sh DDAFRAC WORK_DIR
set -u
source "$(dirname "${BASH_SOURCE[0]}")/study_checks.sh"
exe=$1 work=$2
rm -rf "$work" && mkdir -p "$work"
study="$work/study"
blocks=700         # the scenes with a slot mesh into no fewer than ~590 blocks; 600 misses the flattened disc's target
end_time=6e-5      # s: 600 steps at dt_max = 1e-7 s
interval=2e-5      # s between outputs (the Brazilian scenes' own 5e-5 would exceed the end time)
strength=1e6       # Pa, tensile strength and cohesion of the virtual joints (the rock's: 7.86 and 8.29 MPa)
set_args=(--set "mesh.blocks=$blocks" --set "analysis.end_time=$end_time" --set "analysis.output_interval=$interval"
          --set "joints.virtual.tensile_strength=$strength" --set "joints.virtual.cohesion=$strength")
first=flattened-2045  # the first case of the study
# The run directory a case's numbers come from (study.csv): its own, or that of the case whose
# scene it repeats (at one block count for all, the three flattened discs are one scene).
run_of() { echo "$study/$(grep "^$1," "$study/study.csv" | cut -d, -f3)"; }

setsid "$exe" study source --out "$study" --parallel 1 "${set_args[@]}" > "$work/killed.log" 2>&1 &
group=$!
for _ in $(seq 1 1800); do grep -q "\[1/.*$first finished" "$work/killed.log" && break; sleep 0.1; done
grep -q "\[1/.*$first finished" "$work/killed.log" || { cat "$work/killed.log"; fail "the first case never finished"; }
kill -KILL -- "-$group"
wait "$group" 2>/dev/null
kept_summary=$(md5sum < "$study/$first/summary.json")

"$exe" study source --out "$study" --status > "$work/status_killed.log" 2>&1 || { cat "$work/status_killed.log"; fail "--status failed"; }
cat "$work/status_killed.log"
grep -q "^$first .* done$" "$work/status_killed.log" || fail "--status does not list $first as done"
grep -q "impact-case15 .* to do" "$work/status_killed.log" || fail "--status does not list impact-case15 as to do"

# --report writes the report of what finished: the first case's row has numbers, the others "not run".
"$exe" study source --out "$study" --report > "$work/report_killed.log" 2>&1 || { cat "$work/report_killed.log"; fail "--report failed"; }
grep -q "^| $first | flattened | [0-9]" "$study/study.md" || fail "--report: study.md has no numbers for $first"
grep -q "^| impact-case15 | impact-v0 | not run |" "$study/study.md" || fail "--report: study.md shows numbers for impact-case15, not run"

"$exe" study source --out "$study" --resume > "$work/resume.log" 2>&1
code=$?
cat "$work/resume.log"
[ $code = 0 ] || fail "the resumed study failed (exit status $code)"
grep -q "$first finished before (kept)" "$work/resume.log" || fail "$first was not kept"
grep -q "started  $first" "$work/resume.log" && fail "$first was run again"
[ "$(md5sum < "$study/$first/summary.json")" = "$kept_summary" ] || fail "$first's summary.json changed on resume"
grep -q "figures not drawn" "$work/resume.log" && fail "the study's figures were not drawn"

"$exe" study source --out "$study" --status > "$work/status_end.log" 2>&1 || fail "--status at the end failed"
cases=$(tail -n +2 "$study/study.csv" | cut -d, -f1)
cracked=0
[ "$(echo "$cases" | wc -l)" = 22 ] || fail "study.csv does not list 22 cases"
for c in impact-case08 impact-case12; do
  grep -q "^$c,.*,impact-case04," "$study/study.csv" || fail "study.csv does not point $c at impact-case04's run"
  [ -e "$study/$c" ] && fail "$c ran again in its own directory"
done
commit=$("$exe" --version | sed -n 's/.*(commit \([^,)]*\).*/\1/p')
grep -q "^Engine: the cases run so far were all run by the build of commit \`$commit\`" "$study/study.md" ||
  fail "study.md does not name the engine $commit"
for c in $cases; do
  grep -q "^| $c \(([a-z0-9-]*'s run) \)\?|" "$study/study.md" || fail "study.md has no row for $c"
  grep -q "^$c .* done\( (.*'s run)\)\?$" "$work/status_end.log" || fail "--status does not list $c as done at the end"
  run=$(run_of "$c")
  check_run "$c" "$run"
  [ "$(tail -n 1 "$run/history.csv" | cut -d, -f"$(head -n 1 "$run/history.csv" | tr , '\n' | grep -n '^cracks_total$' | cut -d: -f1)")" -gt 0 ] &&
    cracked=$((cracked + 1))
done
[ $cracked -gt 0 ] || fail "no case cracked: the checks of crack counts over time saw nothing"

# The Brazilian analysis: a peak-force row for every disc, its indirect tensile strength
# k·2P/(πD) recomputed here from summary.json (k = 0.9899 for 10° flats, D = 0.1 m), the
# flattened disc's convergence table, and the patterns at the peak and the end.
for c in $(echo "$cases" | grep -E '^(flattened|precracked)-'); do
  row=$(grep -m 1 "^| $c | " "$study/analysis.md") || fail "analysis.md has no peak-force row for $c"
  expected=$(python3 -c 'import json,math,sys
p = json.load(open(sys.argv[1]))["loading"]["peak"]["top_platen"]["peak_abs_force_y"]
print(f"{0.9899 * 2 * p / (math.pi * 0.1) * 1e-6:.2f}")' "$(run_of "$c")/summary.json")
  [ "$(echo "$row" | cut -d'|' -f7 | tr -d ' ')" = "$expected" ] ||
    fail "analysis.md: $c's indirect tensile strength is not k·2P/(πD) = $expected MPa: $row"
done
grep -q "^| crack length (mm) | " "$study/analysis.md" || fail "analysis.md has no mesh convergence table"
for s in flattened precracked; do
  [ -s "$study/figures/patterns_$s.png" ] || fail "no figures/patterns_$s.png"
done
echo "$cracked of 22 cases cracked"

most=$(for c in $(tail -n +2 "$study/study.csv" | cut -d, -f3 | sort -u); do echo "$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["cracks"]["total"])' "$study/$c/summary.json") $c"; done | sort -n | tail -n 1 | cut -d' ' -f2)
scene=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["scene"]["source"])' "$study/$most/summary.json")
check_same_on_two_threads "$most" "$study/$most" "$exe" "$work/two_threads" "$scene" "${set_args[@]}"

# A series whose last case has not run: --report draws the cases that have.
last=impact-case15
mv "$study/$last" "$work/$last.aside"
rm -f "$study/figures/cracks_impact-v0.png"
"$exe" study source --out "$study" --report > "$work/report_partial.log" 2>&1 || { cat "$work/report_partial.log"; fail "--report without $last failed"; }
grep -q "figures not drawn" "$work/report_partial.log" && { cat "$work/report_partial.log"; fail "--report without $last drew no figures"; }
[ -s "$study/figures/cracks_impact-v0.png" ] || fail "--report without $last: no figures/cracks_impact-v0.png"
mv "$work/$last.aside" "$study/$last"

# The cross-study figure: each impact series holds its cases, whatever they are called.
plots="$(dirname "${BASH_SOURCE[0]}")/../../plots"
"${DDAFRAC_PYTHON:-/usr/bin/python3}" - "$study" "$plots" "$work/series.png" <<'PY' || fail "impact-series"
import os, subprocess, sys
study, plots, figure = sys.argv[1:4]
sys.path.insert(0, plots)
import ddafrac_plots as h
import impact_series_plots as series
runs = series.study_runs(h, study)
def members(varied):
    return sorted(os.path.basename(r["dir"]) for r in runs if series.in_series(series.parameters(r), varied))
expected = {"θ": [f"impact-case0{k}" for k in range(1, 8)],
            "γ": ["impact-case04", "impact-case09", "impact-case10"],
            "v0": ["impact-case04"] + [f"impact-case{k}" for k in range(11, 16) if k != 12]}
for varied, cases in expected.items():
    if members(varied) != cases:
        sys.exit(f"the {varied} series holds {members(varied)}, expected {cases}")
subprocess.run([sys.executable, os.path.join(plots, "ddafrac_plots.py"), "impact-series", study, "--out", figure],
               check=True, stdout=subprocess.DEVNULL)
if os.path.getsize(figure) == 0:
    sys.exit("impact-series wrote an empty figure")
PY
echo "PASS"
