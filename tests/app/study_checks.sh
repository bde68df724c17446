# Checks the reduced study tests share (sourced by study_*_reduced.sh). Each prints "FAIL: ..."
# and exits on failure.

fail() { echo "FAIL: $*"; exit 1; }

# A number of a run's summary.json at a Python expression over `s`, e.g. summary_value RUN 's["steps"]'.
summary_value() {
  python3 -c 'import json,sys; s=json.load(open(sys.argv[1])); print(eval(sys.argv[2]))' "$1/summary.json" "$2"
}

# The run completed; crack counts (total, tensile, shear) never fall in its history.csv, nor the
# crack lengths and fragment counts in fragments.csv; its largest |energy-balance error| is
# within TOLERANCE (default 0.01: the run's own warning level).
check_run() {
  local name=$1 run=$2 tolerance=${3:-0.01}
  grep -q '"reason": "completed"' "$run/summary.json" || fail "$name did not complete"
  awk -F, -v c="$name" 'NR == 1 { for (i = 1; i <= NF; i++) col[$i] = i; next }
    { for (k in last) if ($col[k] + 0 < last[k]) { print "FAIL: " c ": " k " fell from " last[k] " to " $col[k]; exit 1 }
      last["cracks_total"] = $col["cracks_total"]; last["cracks_tensile"] = $col["cracks_tensile"];
      last["cracks_shear"] = $col["cracks_shear"] }' "$run/history.csv" || exit 1
  awk -F, -v c="$name" 'NR == 1 { for (i = 1; i <= NF; i++) col[$i] = i; next }
    { for (k in last) if ($col[k] + 0 < last[k]) { print "FAIL: " c ": fragments.csv " k " fell"; exit 1 }
      last["crack_length_tensile"] = $col["crack_length_tensile"]; last["crack_length_shear"] = $col["crack_length_shear"];
      last["fragments"] = $col["fragments"] }' "$run/fragments.csv" || exit 1
  local error
  error=$(summary_value "$run" 's["energy"]["largest_balance_error"]')
  python3 -c 'import sys; sys.exit(0 if abs(float(sys.argv[1])) <= float(sys.argv[2]) else 1)' "$error" "$tolerance" ||
    fail "$name: largest energy-balance error $error is above $tolerance"
  echo "$name: $(summary_value "$run" '" ".join(map(str, [s["cracks"]["tensile"], "tensile,", s["cracks"]["shear"], "shear,", round(1e3*(s["crack_metrics"]["crack_length_tensile"]+s["crack_metrics"]["crack_length_shear"]),2), "mm,", s["crack_metrics"]["fragments"], "fragments, energy error", s["energy"]["largest_balance_error"], ", wall", round(s["wall_time"]["total"],1), "s"]))')"
}

# A stiff-joint case (the penalty families) got a dt_max shorter than SCENE_DT (s, its base
# scene's) and its run was not warned that dt_max leaves its contact period unresolved.
check_contact_period_resolved() {
  local name=$1 run=$2 scene_dt=$3 dt
  dt=$(summary_value "$run" 's["scene"]["dt_max"]')
  python3 -c 'import sys; sys.exit(0 if float(sys.argv[1]) < float(sys.argv[2]) else 1)' "$dt" "$scene_dt" ||
    fail "$name kept dt_max = $dt s"
  grep -q "steps per period" "$run/run.log" && fail "$name was warned that its dt_max does not resolve its contacts"
  echo "$name: dt_max = $dt s, no contact-period warning"
}

# Runs the command after LOG (a study), its output in LOG and then on stdout; fails unless it succeeded.
run_study() {
  local log=$1
  shift
  "$@" > "$log" 2>&1
  local code=$?
  cat "$log"
  [ $code = 0 ] || fail "the study failed (exit status $code)"
}

# The study's analysis.md has a section whose heading starts with HEADING, and figures/FIGURE exists.
check_report() {
  local study=$1 heading=$2 figure=$3
  grep -q "^## $heading" "$study/analysis.md" || fail "analysis.md has no section '$heading'"
  [ -s "$study/figures/$figure" ] || fail "no figures/$figure"
}

# The run of scene file SCENE (with the extra `ddafrac run` arguments after it) on 2 threads
# writes the same history.csv, cracks.csv and fragments.csv as RUN did on 1.
check_same_on_two_threads() {
  local name=$1 run=$2 exe=$3 out=$4
  shift 4
  "$exe" run "$@" --out "$out" --threads 2 --keep-threads --no-figures > "$out.log" 2>&1 ||
    { cat "$out.log"; fail "$name on 2 threads failed"; }
  for f in history.csv cracks.csv fragments.csv; do
    cmp -s "$run/$f" "$out/$f" || fail "$name/$f differs between 1 and 2 threads"
  done
  echo "$name on 1 and 2 threads: history.csv, cracks.csv, fragments.csv identical"
}
