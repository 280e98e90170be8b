# Shared by scripts/demo.sh and scripts/test.sh: install what is missing, configure, build.
# OBSCURA_BUILD_DIR overrides the build directory (default: build/ in the checkout).
set -euo pipefail
OBSCURA_ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
OBSCURA_BUILD_DIR=${OBSCURA_BUILD_DIR:-$OBSCURA_ROOT/build}
OBSCURA_JOBS=$(nproc 2>/dev/null || echo 2)

# obscura_default_radius SCENE SIZE: the AO presets' radius for a scene (a tenth of its
# bounding box's diagonal, world units), as the obscura tool prints it.
obscura_default_radius() {
  local probe log radius
  probe=$(mktemp --suffix=.exr)
  # Not a pipe into sed: a failing render must stop the caller, not give an empty radius.
  log=$("$OBSCURA_BUILD_DIR/src/cli/obscura" render --scene "$1" --size "$2" --technique gbuffer --output depth \
    --out "$probe" --frames 1) || { rm -f "$probe"; echo "obscura render --scene $1 failed" >&2; return 1; }
  rm -f "$probe"
  radius=$(sed -n 's/.*default radius \([^,]*\),.*/\1/p' <<< "$log")
  [ -n "$radius" ] || { echo "obscura render --scene $1 printed no default radius" >&2; return 1; }
  echo "$radius"
}

obscura_setup() {
  "$OBSCURA_ROOT/scripts/setup-debian.sh"
}

# obscura_build [cmake configure args...] -- [targets...]
obscura_build() {
  local configure=() targets=()
  while [ $# -gt 0 ] && [ "$1" != "--" ]; do configure+=("$1"); shift; done
  [ $# -gt 0 ] && shift
  targets=("$@")
  cmake -S "$OBSCURA_ROOT" -B "$OBSCURA_BUILD_DIR" -DCMAKE_BUILD_TYPE=Release "${configure[@]}"
  if [ ${#targets[@]} -gt 0 ]; then
    cmake --build "$OBSCURA_BUILD_DIR" --parallel "$OBSCURA_JOBS" --target "${targets[@]}"
  else
    cmake --build "$OBSCURA_BUILD_DIR" --parallel "$OBSCURA_JOBS"
  fi
}
