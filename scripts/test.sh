#!/usr/bin/env bash
# Set up ddafrac on a fresh Debian 12 machine, build it and run the test suite that CI runs
# (labels unit and verification; the full-size `slow` cases are left out).
# Usage: bash scripts/test.sh [extra ctest args]
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
ddafrac_install_dependencies
ddafrac_build
# mpirun refuses to start as root unless told that this is intended (CI runs as root).
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
# Tests run side by side, each with OpenMP threads: idle threads must sleep, not spin, or an
# oversubscribed run is 10-25x slower. This changes timing only, never results.
export OMP_WAIT_POLICY=passive
ctest --test-dir "$DDAFRAC_BUILD" -L 'unit|verification' --output-on-failure -j "$(nproc)" "$@"
