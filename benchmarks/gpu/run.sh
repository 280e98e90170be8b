#!/usr/bin/env bash
# Runs on the lent GPU machine (device tool), from the repository root, with .gl (glvnd's
# Debian packages) and .gpu (benchmarks/gpu/pack.sh) carried:
#   benchmarks/gpu/run.sh tests|main|resolution|resolution_1080|lanes
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
resolution) # the report's half-resolution study
  bench --spp 1024 --scene cornell --scene "$engine" --presets medium,medium_half,high,high_half --size 512x512 \
    --out "$OUT/resolution" ;;
resolution_1080) # the same at a size that fills the GPU (512x512 is one wave of threads on an H100,
  # so a pass's time is one thread's latency there, whatever the resolution); 256 spp, so that
  # the references fit in a call
  for family in ao obscurance gi; do
    bench --spp 256 --scene cornell --scene "$engine" --techniques "$family.*" \
      --presets medium,medium_half,high,high_half --size 1920x1080 --out "$OUT/resolution_1080_$family"
  done ;;
lanes) # ray lanes (rayLanes: invocations per pixel's rays) 1, 4 and 16 on the half-resolution
  # study's rows at 1920x1080, where a pass over few pixels lasts as long as its slowest
  # pixel's rays (2CylinderEngine); the references are cached across the three runs
  for lanes in 1 4 16; do
    "$dir/obscura" bench --frames 20 --spp 256 --cache /tmp/obscura-references --scene cornell --scene "$engine" \
      --techniques 'ao.*' --presets medium,medium_half,high,high_half --size 1920x1080 --set ray_lanes=$lanes \
      --out "$OUT/lanes_$lanes"
  done ;;
*) echo "unknown step $step" >&2; exit 2 ;;
esac
