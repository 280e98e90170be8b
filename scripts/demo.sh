#!/usr/bin/env bash
# Installs what is missing (Debian 12), builds the obscura tool and renders the built-in
# Cornell box headless with every implemented technique into out/ (EXR + PNG), printing
# the per-pass times (median of the timed frames, and which clock measured them).
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
obscura_setup
obscura_build -DOBSCURA_BUILD_CLI=ON -- obscura_cli
out=${OBSCURA_DEMO_OUT:-$OBSCURA_ROOT/out}
"$OBSCURA_BUILD_DIR/src/cli/obscura" render --scene cornell --technique all --size 512x512 --frames 20 --out "$out"
echo "pictures:"
ls -1 "$out"
