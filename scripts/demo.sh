#!/usr/bin/env bash
# Set up ddafrac on a fresh Debian 12 machine and run the main job on the built-in default
# scene (a reduced rockfall impact). Usage: bash scripts/demo.sh [extra ddafrac mesh args]
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
ddafrac_install_dependencies
ddafrac_build
cd "$DDAFRAC_ROOT"
"$DDAFRAC_BUILD/app/ddafrac" mesh "$@"
