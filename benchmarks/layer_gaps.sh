#!/usr/bin/env bash
# How far each scene's second depth layer lies behind its first (gbuffer output layer_gap),
# against the AO presets' radius: the numbers behind benchmarks/README.md's "Depth peeling and
# thin parts". Needs a built obscura tool (scripts/report.sh builds it).
#   benchmarks/layer_gaps.sh [WxH]
source "$(dirname "${BASH_SOURCE[0]}")/../scripts/common.sh"
size=${1:-128x128}
models=/usr/share/assimp/models
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for scene in cornell "$models/PLY/Wuson.ply" "$models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb"; do
  radius=$(obscura_default_radius "$scene" "$size")
  "$OBSCURA_BUILD_DIR/src/cli/obscura" render --scene "$scene" --size "$size" --technique gbuffer \
    --set depth_layers=2 --output layer_gap --out "$work/gap.exr" > /dev/null
  # Pixels with both layers (gap > 0) and those with geometry but no second layer are told
  # apart by the distance output: geometry is where it is > 0.
  "$OBSCURA_BUILD_DIR/src/cli/obscura" render --scene "$scene" --size "$size" --technique gbuffer \
    --output distance --out "$work/distance.exr" > /dev/null
  paste <(oiiotool --dumpdata:empty=1 "$work/gap.exr" | sed -n 's/.*: *//p') \
        <(oiiotool --dumpdata:empty=1 "$work/distance.exr" | sed -n 's/.*: *//p') |
    awk -v r="$radius" '$2 > 0 { print ($1 > 0 ? $1 / r : "none") }' > "$work/ratios"
  geometry=$(wc -l < "$work/ratios")
  grep -v none "$work/ratios" | sort -g > "$work/sorted"
  n=$(wc -l < "$work/sorted")
  quantile() { sed -n "$(( $1 * n / 100 + 1 ))p" "$work/sorted"; }
  echo "$(basename "$scene"): $geometry pixels with geometry, $(( geometry - n )) without a second layer;" \
    "gap / radius quantiles 10 % $(quantile 10), 50 % $(quantile 50), 90 % $(quantile 90) (radius $radius)"
done
