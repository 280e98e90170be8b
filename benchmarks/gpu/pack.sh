#!/usr/bin/env bash
# Packs the obscura tool for a GPU machine that has no Debian packages (the session's lent
# NVIDIA box): a build without OpenImageIO (whose dependencies run to 400 MB), the libraries
# it needs beyond glibc and libstdc++, the GL tests, and the models the bench uses, into .gpu/bundle.tar.xz
# (ignored by git). benchmarks/gpu/run.sh unpacks and runs it there.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
build=${OBSCURA_GPU_BUILD_DIR:-/tmp/obscura-gpu-build}
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DOBSCURA_BUILD_TESTS=ON -DOBSCURA_BUILD_EXAMPLES=OFF \
  -DOBSCURA_BUILD_CLI=ON -DOBSCURA_WITH_OPENIMAGEIO=OFF -DOBSCURA_INSTALL=OFF >/dev/null
cmake --build "$build" --target obscura_cli obscura_gl_tests -j "${OBSCURA_JOBS:-2}"
stage=$(mktemp -d)
mkdir -p "$stage/lib" "$stage/models"
cp "$build/src/cli/obscura" "$build/tests/obscura_gl_tests" "$stage/"
# Everything ldd resolves except the C runtime, which the machine has (newer).
ldd "$build/src/cli/obscura" | awk '$3 ~ /^\// {print $3}' |
  grep -v -E '/(libc|libm|libdl|librt|libpthread|libgcc_s|libstdc\+\+)\.so' |
  grep -v -E '/lib(EGL|GL|GLX|GLdispatch|OpenGL)\.so' | xargs -r cp -L -t "$stage/lib"
models=/usr/share/assimp/models
cp "$models/PLY/Wuson.ply" "$models/OBJ/spider.obj" "$models/OBJ/spider.mtl" \
  "$models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb" "$stage/models/"
mkdir -p "$root/.gpu"
tar -C "$stage" -cJf "$root/.gpu/bundle.tar.xz" .
rm -rf "$stage"
ls -l "$root/.gpu/bundle.tar.xz"
