#!/usr/bin/env bash
# Every result says which engine wrote it: `ddafrac --version` and a run's summary.json name the
# source commit the build was made from (with "-dirty" when tracked files differed from it), the
# commit git gives for the source tree now; "unknown" outside a git work tree; and the
# instruction set it was built for (cmake's DDAFRAC_MARCH), on which the last digits depend.
# Usage: build_commit.sh DDAFRAC SOURCE_DIR WORK_DIR ARCH
set -u
exe=$1 source=$2 work=$3 arch=$4
rm -rf "$work" && mkdir -p "$work"
fail() { echo "FAIL: $*"; exit 1; }
expected=unknown
if head=$(git -C "$source" rev-parse --short=12 HEAD 2>/dev/null); then
  expected=$head
  [ -z "$(git -C "$source" status --porcelain --untracked-files=no)" ] || expected="$head-dirty"
fi
version=$("$exe" --version) || fail "ddafrac --version failed"
echo "ddafrac --version: $version; the source tree: $expected"
[ "$version" = "0.1.0 (commit $expected, $arch)" ] \
  || fail "--version names another commit than the source tree's ($expected) or another instruction set than $arch"
"$exe" run --out "$work/run" --max-steps 3 --no-figures --no-vtk > "$work/run.log" 2>&1 || { cat "$work/run.log"; fail "the run failed"; }
grep -q "\"ddafrac_commit\": \"$expected\"" "$work/run/summary.json" \
  || fail "summary.json does not name commit $expected: $(grep ddafrac_commit "$work/run/summary.json")"
grep -q "\"ddafrac_arch\": \"$arch\"" "$work/run/summary.json" \
  || fail "summary.json does not name the instruction set $arch: $(grep ddafrac_arch "$work/run/summary.json")"
echo PASS
