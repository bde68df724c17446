#!/usr/bin/env bash
# Set up ddafrac on a fresh Debian 12 machine and run the main job on the built-in default
# scene: a reduced rockfall impact (about 1200 blocks, 300 µs) that cracks, with its figures
# in runs/default-impact/run/figures/. Usage: bash scripts/demo.sh [extra `ddafrac run` args]
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
ddafrac_install_dependencies
ddafrac_build ddafrac  # the executable only: the test command builds the rest
cd "$DDAFRAC_ROOT"
"$DDAFRAC_BUILD/app/ddafrac" run "$@"
