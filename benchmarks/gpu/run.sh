#!/usr/bin/env bash
# Runs on the lent GPU machine (device tool), from the repository root, with .gl (glvnd's
# Debian packages) and .gpu (benchmarks/gpu/pack.sh) carried:
#   benchmarks/gpu/run.sh tests|main|resolution|resolution_1080|lanes|tiles
# and writes the bench's output under $OUT/<step>. Timings there are GPU timer queries.
set -euo pipefail
step=$1
for f in .gl/*.deb; do dpkg -x "$f" /; done
ldconfig
dir=/tmp/obscura-gpu
mkdir -p "$dir" && tar -C "$dir" -xJf .gpu/bundle.tar.xz
export LD_LIBRARY_PATH=$dir/lib
vendor=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json
[ -f "$vendor" ] && export __EGL_VENDOR_LIBRARY_FILENAMES=$vendor
nvidia-smi -L || true
bench() { "$dir/obscura" bench --frames 20 --no-cache "$@"; }
engine=$dir/models/2CylinderEngine.glb
case $step in
tests) # the GL test suite (no image files are read there), with the models where it looks for them
  m=/usr/share/assimp/models && mkdir -p $m/PLY $m/OBJ && cp "$dir/models/Wuson.ply" $m/PLY/ &&
    cp "$dir/models/spider.obj" "$dir/models/spider.mtl" $m/OBJ/
  mkdir -p "$OUT/tests" && (cd /tmp && "$dir/obscura_gl_tests" -r compact) 2>&1 | tee "$OUT/tests/gl_tests.log" | tail -40 ;;
main) # the report's main run, less the models with textures (no image reader here)
  bench --spp 1024 --scene cornell --scene "$dir/models/Wuson.ply" --scene "$engine" --size 128x128 --out "$OUT/main" ;;
resolution) # the report's half- and quarter-resolution study, then its shadow techniques
  bench --spp 1024 --scene cornell --scene "$engine" --techniques '[!s]*.*' \
    --presets medium,medium_half,high,high_half --size 512x512 --variant resolution=quarter --out "$OUT/resolution"
  bench --spp 1024 --scene cornell --scene "$engine" --techniques 'shadow.*' --presets medium,high --size 512x512 \
    --out "$OUT/resolution_shadows" ;;
resolution_1080) # the same at a size that fills the GPU (512x512 is one wave of threads on an H100,
  # so a pass's time is one thread's latency there, whatever the resolution); 256 spp, so that
  # the references fit in a call
  for family in ao obscurance gi; do
    bench --spp 256 --scene cornell --scene "$engine" --techniques "$family.*" \
      --presets medium,medium_half,high,high_half --size 1920x1080 --variant resolution=quarter \
      --out "$OUT/resolution_1080_$family"
  done ;;
lanes) # ray lanes (rayLanes: invocations per pixel's rays) 1, 4 and 16, timed in turn, on the
  # half-resolution study's rows at 1920x1080, where a pass over few pixels lasts as long as its
  # slowest pixel's rays (2CylinderEngine)
  bench --spp 256 --scene cornell --scene "$engine" --techniques 'ao.*' --presets medium,medium_half,high,high_half \
    --size 1920x1080 --set ray_lanes=1 --variant ray_lanes=4 --variant ray_lanes=16 --out "$OUT/lanes" ;;
tiles) # the half-resolution presets with geometry tiles and over every tile, timed in turn, at 1920x1080
  for family in ao gi; do
    bench --spp 256 --scene cornell --scene "$engine" --techniques "$family.*" --presets medium_half,high_half \
      --size 1920x1080 --variant geometry_tiles=0 --out "$OUT/tiles_$family"
  done ;;
*) echo "unknown step $step" >&2; exit 2 ;;
esac
