#!/usr/bin/env bash
# Renders the figures of the docs pages (docs/figures/*.png) with the obscura CLI. Run after a
# build (scripts/test.sh or scripts/demo.sh); the pictures are committed, as the pages show them.
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
obscura="$OBSCURA_BUILD_DIR/src/cli/obscura"
[ -x "$obscura" ] || { echo "build first: $obscura is missing" >&2; exit 1; }
out="$OBSCURA_ROOT/docs/figures"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$out"

# docs/compose.md: the three combine formulas on a block under a low sun (its shadow, its
# faces turned away), with the same ambient light and screen-space indirect light.
for formula in standard physical thesis; do
  "$obscura" render --scene "$OBSCURA_ROOT/scenes/sun_courtyard.json" --size 320x240 --technique compose \
    --set formula=$formula --set ambient=0.15 --output image --out "$work/$formula.png" > /dev/null
done
oiiotool "$work/standard.png" "$work/physical.png" "$work/thesis.png" --mosaic 3x1 -o "$out/compose_formulas.png"
echo "wrote $out/compose_formulas.png"

# docs/ssdo.md: the Cornell box lit by blender-data's courtyard.exr through its open front:
# SSDO's direct light, its bounce (times 2 to show), and their sum.
worlds=/usr/share/blender/datafiles/studiolights/world
for output in direct indirect; do
  "$obscura" render --scene cornell --environment "$worlds/courtyard.exr" --size 240x240 --technique ssdo \
    --set bounce=1 --set rays=32 --output $output --out "$work/ssdo_$output.exr" > /dev/null 2>&1
done
oiiotool "$work/ssdo_indirect.exr" --mulc 2 -o "$work/ssdo_indirect2.exr"
oiiotool "$work/ssdo_direct.exr" "$work/ssdo_indirect.exr" --add -o "$work/ssdo_sum.exr"
oiiotool "$work/ssdo_direct.exr" "$work/ssdo_indirect2.exr" "$work/ssdo_sum.exr" --mosaic 3x1 \
  --colorconvert linear sRGB -d uint8 -o "$out/ssdo_cornell.png"
echo "wrote $out/ssdo_cornell.png"
# docs/media.md: the god-ray scene through its fog by ray marching (shadow maps at every step),
# Sun et al.'s closed form (no shadows) and froxels, then the smoke-filled Cornell box by ray
# marching, the lit frame through the media (Media::apply).
for method in raymarch analytic froxel; do
  "$obscura" render --scene god_rays --size 240x180 --technique "media.$method" --set steps=100 --output frame \
    --out "$work/media_$method.exr" > /dev/null 2>&1
done
oiiotool "$work/media_raymarch.exr" "$work/media_analytic.exr" "$work/media_froxel.exr" --mosaic 3x1 \
  --colorconvert linear sRGB -d uint8 -o "$out/media_god_rays.png"
echo "wrote $out/media_god_rays.png"
