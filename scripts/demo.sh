#!/usr/bin/env bash
# Installs what is missing (Debian 12), builds the obscura tool and renders the built-in
# Cornell box headless with every implemented technique into out/ (EXR + PNG), printing
# the per-pass times (median of the timed frames, and which clock measured them), then
# voxelizes it (out/voxels: grid.json, grid.u8, grid.ply) and draws the voxels and two of
# their mip levels (out/voxels.png), and runs the AO and GI examples on it and on a real model.
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
obscura_setup
obscura_build -DOBSCURA_BUILD_CLI=ON -DOBSCURA_BUILD_EXAMPLES=ON -- obscura_cli obscura_example_voxelization \
  obscura_example_ambient_occlusion obscura_example_global_illumination
out=${OBSCURA_DEMO_OUT:-$OBSCURA_ROOT/out}
"$OBSCURA_BUILD_DIR/src/cli/obscura" render --scene cornell --technique all --size 512x512 --frames 20 --out "$out"
"$OBSCURA_BUILD_DIR/src/cli/obscura" voxelize --scene cornell --res 128 --slices 128 --mode surface --frames 20 \
  --out "$out/voxels" --ply
"$OBSCURA_BUILD_DIR/examples/obscura_example_voxelization" --scene cornell --res 64 --levels 0,1,2 --size 1536x512 \
  --out "$out/voxels.png"
# AO and one-bounce GI of the Cornell box and of a real model (assimp-testmodels).
wuson=/usr/share/assimp/models/PLY/Wuson.ply
for scene in cornell "$wuson"; do
  name=$(basename "$scene" .ply)
  "$OBSCURA_BUILD_DIR/examples/obscura_example_ambient_occlusion" --scene "$scene" --size 512x512 --rays 32 --steps 16 \
    --out "$out/example_ao_${name}.png"
  "$OBSCURA_BUILD_DIR/examples/obscura_example_global_illumination" --scene "$scene" --size 512x512 --rays 32 --steps 16 \
    --method hybrid --out "$out/example_gi_${name}.png"
done
echo "pictures:"
ls -1 "$out"
