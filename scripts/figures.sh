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
