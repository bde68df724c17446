#!/usr/bin/env bash
# Runs every bad input of a corpus folder through ddafrac and checks the answer: the exit status
# and the words its message must contain. A case is a file in the folder (not in a sub-folder):
#   NAME.toml   a scene, run as `ddafrac run NAME.toml --out OUT --no-vtk --no-figures --max-steps 2`
#   NAME.args   an option list only
# whose leading comment lines say
#   # args: ...      the ddafrac arguments ({case}: the case file, {out}: a fresh folder, {dir}: the corpus)
#   # exit: N        the exit status expected
#   # expect: words  words the output (stdout and stderr) must contain; one line per fragment
# Every case must also end within its time limit and without a crash or an uncaught exception.
# Usage: run_bad_inputs.sh DDAFRAC CORPUS_DIR WORK_DIR
set -u
exe=$1 corpus=$2 work=$3
readonly kSecondsPerCase=120
rm -rf "$work" && mkdir -p "$work"
cases=0 failed=0
for file in "$corpus"/*.toml "$corpus"/*.args; do
  [ -f "$file" ] || continue
  name=$(basename "$file")
  out="$work/${name%.*}"
  args="run {case} --out {out} --no-vtk --no-figures --max-steps 2"
  grep -q '^# args:' "$file" && args=$(sed -n 's/^# args: \{0,1\}//p' "$file")
  args=${args//\{case\}/$file}
  args=${args//\{out\}/$out}
  args=${args//\{dir\}/$corpus}
  expected_exit=$(sed -n 's/^# exit: //p' "$file")
  eval "set -- $args"
  output=$(cd "$work" && timeout "$kSecondsPerCase" "$exe" "$@" 2>&1)
  status=$?
  cases=$((cases + 1))
  problems=""
  [ "$status" = "$expected_exit" ] || problems+=" exit status $status, expected $expected_exit;"
  while IFS= read -r words; do
    [[ "$output" == *"$words"* ]] || problems+=" no \"$words\";"
  done < <(sed -n 's/^# expect: //p' "$file")
  for crash in "terminate called" "Segmentation" "AddressSanitizer" "runtime error:"; do
    [[ "$output" != *"$crash"* ]] || problems+=" \"$crash\";"
  done
  if [ -n "$problems" ]; then
    failed=$((failed + 1))
    printf 'FAIL %s:%s\n--- output:\n%s\n---\n' "$name" "$problems" "$output"
  fi
done
echo "$cases bad inputs, $failed failed"
[ "$cases" -gt 0 ] && [ "$failed" -eq 0 ]
