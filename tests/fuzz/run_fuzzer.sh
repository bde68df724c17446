#!/usr/bin/env bash
# Runs a libFuzzer target on a copy of its seed corpus (the fuzzer adds the inputs it finds
# interesting to its corpus folder; the repository's seeds stay as they are). A finding (crash,
# sanitizer report, leak, timeout) fails the test and is saved in WORK_DIR as crash-*, leak-*
# or timeout-*, to be replayed with `FUZZER FILE`.
# Usage: run_fuzzer.sh FUZZER SEED_DIR WORK_DIR [libFuzzer options...]
set -euo pipefail
fuzzer=$1 seeds=$2 work=$3
shift 3
rm -rf "$work" && mkdir -p "$work/corpus"
cp "$seeds"/* "$work/corpus/"
exec "$fuzzer" "$work/corpus" -artifact_prefix="$work/" "$@"
