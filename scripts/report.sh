#!/usr/bin/env bash
# Regenerates docs/results.md: builds the obscura tool, benchmarks every technique on the
# Cornell box and four real models (Debian's assimp-testmodels) against the Embree
# reference (SSDO lit by two of blender-data's HDR environments), and the voxelizer (eight copies of 2CylinderEngine, about 1M triangles) and
# its traversals, the half- and quarter-resolution trade-off at 512x512, half resolution
# with and without its refinement, the reduced-resolution presets with and without geometry
# tiles, ray lanes, the screen-space marches (view, texture, Hi-Z), thickness (constant,
# depth peeling, the deeper of both) and obscurance's falloffs, each study's variants timed in
# turn in one process, the participating-media methods, then draws the plots.
# References are cached in the build directory.
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
obscura_setup
obscura_build -DOBSCURA_BUILD_CLI=ON -- obscura_cli
models=/usr/share/assimp/models
worlds=/usr/share/blender/datafiles/studiolights/world
out=${OBSCURA_BENCH_OUT:-$OBSCURA_BUILD_DIR/bench}
"$OBSCURA_BUILD_DIR/src/cli/obscura" bench \
  --scene cornell \
  --scene "$models/PLY/Wuson.ply" \
  --scene "$models/OBJ/spider.obj" \
  --scene "$models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb" \
  --scene "$models/Collada/duck.dae" \
  --environment "$worlds/forest.exr" --environment "$worlds/courtyard.exr" \
  --size 128x128 --frames 20 --spp 1024 --reference-performance \
  --voxels --voxel-scene "$models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb" \
  --cache "$OBSCURA_BUILD_DIR/reference-cache" --out "$out"
# Soft shadows: the Cornell box's emitter as a sphere light and as a rect light, whose
# reference is the fraction of the area light that arrives (shadow.pcss, and the hard and
# filtered masks from the same light's centre beside it).
"$OBSCURA_BUILD_DIR/src/cli/obscura" bench \
  --scene cornell_sphere --scene cornell_rect --techniques 'shadow.*' --size 128x128 --frames 20 --spp 1024 \
  --cache "$OBSCURA_BUILD_DIR/reference-cache" --out "$out/soft_shadows"
# The half-resolution trade-off at a size where the per-pixel work, not the fixed cost of a
# pass, dominates: presets medium and high, each at full and half resolution, and both at
# quarter resolution (--variant: timed in turn with them), on the Cornell box and the finest
# model; the integrators ([!sm]*.*: not shadow.*, whose `resolution` is its map's size, nor media.*,
# whose own study follows), then
# the shadow techniques at the same size, which the GPU section compares with llvmpipe.
"$OBSCURA_BUILD_DIR/src/cli/obscura" bench \
  --scene cornell \
  --scene "$models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb" \
  --techniques '[!sm]*.*' --presets medium,medium_half,high,high_half --size 512x512 --frames 20 --spp 1024 \
  --variant resolution=quarter --cache "$OBSCURA_BUILD_DIR/reference-cache" --out "$out/resolution"
"$OBSCURA_BUILD_DIR/src/cli/obscura" bench \
  --scene cornell \
  --scene "$models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb" \
  --techniques 'shadow.*' --presets medium,high --size 512x512 --frames 20 --spp 1024 \
  --cache "$OBSCURA_BUILD_DIR/reference-cache" --out "$out/resolution/shadows"
# The refinement at half resolution: X_half with and without it (refine_threshold=0), timed in
# turn with X, at the scene tables' size, where the half-resolution misses are, on the two
# scenes with the most edge pixels (thin legs, stacked thin parts).
"$OBSCURA_BUILD_DIR/src/cli/obscura" bench \
  --scene "$models/OBJ/spider.obj" \
  --scene "$models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb" \
  --techniques '[!sm]*.*' --presets medium,medium_half,high,high_half --size 128x128 --frames 20 --spp 1024 \
  --variant refine_threshold=0 --cache "$OBSCURA_BUILD_DIR/reference-cache" --out "$out/refine"
# The half-resolution presets with geometry tiles and over every tile (geometryTiles off),
# their frames timed in turn (--variant): what skipping the background's tiles saves, and that
# the RMSEs agree exactly.
tiles=()
for techniques in 'ao.*' 'gi.*'; do
  dir="$out/tiles/${techniques%%.*}"
  "$OBSCURA_BUILD_DIR/src/cli/obscura" bench \
    --scene cornell --scene "$models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb" \
    --techniques "$techniques" --presets medium_half --size 512x512 --frames 20 --spp 1024 --variant geometry_tiles=0 \
    --cache "$OBSCURA_BUILD_DIR/reference-cache" --out "$dir"
  tiles+=(--tiles-study "$dir/bench.json")
done
# Ray lanes (rayLanes: invocations that share each pixel's rays) on ao.points medium, the
# half-resolution study's closest call, 1, 4 and 16 lanes timed in turn: llvmpipe runs a
# workgroup's lanes on the same cores, so what they cost there shows; what they save on a GPU,
# benchmarks/gpu/run.sh lanes measures.
"$OBSCURA_BUILD_DIR/src/cli/obscura" bench \
  --scene cornell --scene "$models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb" \
  --techniques ao.points --presets medium,medium_half --size 512x512 --frames 20 --spp 1024 \
  --set ray_lanes=1 --variant ray_lanes=4 --variant ray_lanes=16 \
  --cache "$OBSCURA_BUILD_DIR/reference-cache" --out "$out/lanes"
lanes=(--lanes-study "$out/lanes/bench.json")
# The screen-space marches on the same samples, timed in turn: view and texture space, and
# Hi-Z (the texture-space march's first hit with runs of samples skipped), at the presets' 16
# and 32 steps and at 128, where the pyramid has runs to skip.
marches=()
for steps in preset 128; do
  dir="$out/marches/$steps"
  presets=high,ultra steps_set=()
  [ "$steps" = 128 ] && presets=high steps_set=(--set steps=128)
  "$OBSCURA_BUILD_DIR/src/cli/obscura" bench \
    --scene cornell --scene "$models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb" \
    --techniques ao.raymarch --presets "$presets" --size 128x128 --frames 20 --spp 1024 \
    --set march=view "${steps_set[@]}" --variant march=texture --variant march=hiz \
    --cache "$OBSCURA_BUILD_DIR/reference-cache" --out "$dir"
  marches+=(--march-study "$dir/bench.json")
done
# Screen-space thickness: constant (the presets', the radius) against depth peeling and the
# deeper of both, and both with a tenth of the radius, timed in turn, on the Cornell box and
# the two models whose layers differ most (thick blocks, thin stacked parts). The thickness is
# in world units, so each scene runs on its own.
thickness=()
for scene in cornell "$models/PLY/Wuson.ply" "$models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb"; do
  radius=$(obscura_default_radius "$scene" 128x128)
  thin=$(awk -v r="$radius" 'BEGIN { printf "%.6g", r / 10 }')
  dir="$out/thickness/$(basename "${scene%.*}")"
  "$OBSCURA_BUILD_DIR/src/cli/obscura" bench --scene "$scene" \
    --techniques 'ao.[rp]*' --presets low,medium,high,ultra --size 128x128 --frames 20 --spp 1024 \
    --variant thickness_mode=depth_peeling --variant thickness_mode=peeling_or_constant \
    --variant "thickness=$thin" --variant "thickness_mode=peeling_or_constant,thickness=$thin" \
    --cache "$OBSCURA_BUILD_DIR/reference-cache" --out "$dir"
  thickness+=(--thickness-study "$dir/bench.json")
done
# Obscurance's falloffs: the techniques' default (linear) against none, quadratic and smooth,
# each against the reference with the same falloff, timed in turn.
"$OBSCURA_BUILD_DIR/src/cli/obscura" bench \
  --scene cornell --scene "$models/PLY/Wuson.ply" \
  --scene "$models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb" \
  --techniques 'obscurance.*' --presets medium,high --size 128x128 --frames 20 --spp 1024 \
  --variant falloff=none --variant falloff=quadratic --variant falloff=smooth \
  --cache "$OBSCURA_BUILD_DIR/reference-cache" --out "$out/falloffs"
falloffs=(--falloff-study "$out/falloffs/bench.json")
# SSDO's overhead over AO (the paper's Table 1): ao.raymarch, ssdo and ssdo with its bounce
# at N = 8 and 16 rays, 8 steps, three sizes; the two ssdo runs timed in turn. Only the times
# are reported, so the references take 64 samples.
ssdo=()
for size in 128x128 256x256 512x512; do
  for rays in 8 16; do
    dir="$out/ssdo_overhead/$size-$rays"
    "$OBSCURA_BUILD_DIR/src/cli/obscura" bench --scene cornell --environment "$worlds/forest.exr" \
      --techniques ao.raymarch --presets medium --size "$size" --frames 20 --spp 64 --set "rays=$rays" --set steps=8 \
      --cache "$OBSCURA_BUILD_DIR/reference-cache" --out "$dir/ao"
    "$OBSCURA_BUILD_DIR/src/cli/obscura" bench --scene cornell --environment "$worlds/forest.exr" \
      --techniques ssdo --presets medium --size "$size" --frames 20 --spp 64 --set "rays=$rays" --set steps=8 \
      --variant bounce=1 --cache "$OBSCURA_BUILD_DIR/reference-cache" --out "$dir/ssdo"
    ssdo+=(--ssdo-overhead-study "$dir/ao/bench.json" --ssdo-overhead-study "$dir/ssdo/bench.json")
  done
done
# SSDO's options on and off, timed in turn: two extra views, depth peeling (the study's
# sources lit by the same two environments as the main run).
"$OBSCURA_BUILD_DIR/src/cli/obscura" bench \
  --scene cornell --scene "$models/PLY/Wuson.ply" \
  --scene "$models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb" \
  --environment "$worlds/forest.exr" --environment "$worlds/courtyard.exr" \
  --techniques ssdo --presets medium --size 128x128 --frames 20 --spp 1024 \
  --variant extra_views=2 --variant thickness_mode=depth_peeling \
  --cache "$OBSCURA_BUILD_DIR/reference-cache" --out "$out/ssdo_options"
ssdo+=(--ssdo-options-study "$out/ssdo_options/bench.json")
# Participating media: every method's presets against the reference on the god-ray scene (a
# spot light through a lattice, shadowed), the Cornell box filled with fog and the one filled
# with smoke (a noise density grid); then the thesis's table, time against steps at two
# sizes on the fogged box and the god-ray scene (times only: references of 16 samples).
"$OBSCURA_BUILD_DIR/src/cli/obscura" bench \
  --scene god_rays --scene cornell_fog --scene cornell_smoke --techniques 'media.*' --size 128x128 --frames 20 \
  --spp 1024 --cache "$OBSCURA_BUILD_DIR/reference-cache" --out "$out/media"
# Marching blurred, at half resolution, and both, against each preset as run (timed in turn).
"$OBSCURA_BUILD_DIR/src/cli/obscura" bench \
  --scene god_rays --scene cornell_fog --techniques 'media.[rb]*' --size 128x128 --frames 20 --spp 1024 \
  --variant blur_radius=2 --variant resolution=half --variant resolution=half,blur_radius=1 \
  --cache "$OBSCURA_BUILD_DIR/reference-cache" --out "$out/media_filters"
media=(--media-filters-study "$out/media_filters/bench.json")
for size in 256x256 512x512; do
  "$OBSCURA_BUILD_DIR/src/cli/obscura" bench --scene cornell_fog --scene god_rays --techniques 'media.*' --size "$size" --frames 20 \
    --spp 16 --cache "$OBSCURA_BUILD_DIR/reference-cache" --out "$out/media_steps/$size"
  media+=(--media-study "$out/media_steps/$size/bench.json")
done
# Runs on a lent GPU machine (benchmarks/gpu/run.sh), kept in the repository: their own section;
# the lanes and tiles studies' files (lanes*.json, tiles*.json) in its tables of those studies.
gpu=()
for f in "$OBSCURA_ROOT"/benchmarks/gpu/*/*.json; do
  [ -f "$f" ] || continue
  case $(basename "$f") in
  lanes* | tiles*) gpu+=(--gpu-study "$f") ;;
  *) gpu+=(--gpu "$f") ;;
  esac
done
/usr/bin/python3 "$OBSCURA_ROOT/benchmarks/plot_report.py" "$out/bench.json" "$out/soft_shadows/bench.json" "$out/media/bench.json" \
  --resolution-study "$out/resolution/bench.json" \
  --resolution-study "$out/resolution/shadows/bench.json" "${tiles[@]}" "${lanes[@]}" "${marches[@]}" \
  "${thickness[@]}" "${falloffs[@]}" "${ssdo[@]}" "${media[@]}" --refine-study "$out/refine/bench.json" "${gpu[@]}" --out "$OBSCURA_ROOT/docs"
