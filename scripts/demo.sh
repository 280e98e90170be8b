#!/usr/bin/env bash
# Installs what is missing (Debian 12), builds the obscura tool and renders the built-in
# Cornell box headless with every implemented technique into out/ (EXR + PNG), printing
# the per-pass times (median of the timed frames, and which clock measured them), then
# voxelizes it (out/voxels: grid.json, grid.u8, grid.ply) and draws the voxels and two of
# their mip levels (out/voxels.png).
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
obscura_setup
obscura_build -DOBSCURA_BUILD_CLI=ON -DOBSCURA_BUILD_EXAMPLES=ON -- obscura_cli obscura_example_voxelization
out=${OBSCURA_DEMO_OUT:-$OBSCURA_ROOT/out}
"$OBSCURA_BUILD_DIR/src/cli/obscura" render --scene cornell --technique all --size 512x512 --frames 20 --out "$out"
"$OBSCURA_BUILD_DIR/src/cli/obscura" voxelize --scene cornell --res 128 --slices 128 --mode surface --frames 20 \
  --out "$out/voxels" --ply
"$OBSCURA_BUILD_DIR/examples/obscura_example_voxelization" --scene cornell --res 64 --levels 0,1,2 --size 1536x512 \
  --out "$out/voxels.png"
echo "pictures:"
ls -1 "$out"
