// The Cornell box from its own camera with the modules the integrator tests run on it: a lit
// G-buffer (indirect light gathers its radiance and albedo), its view-space positions (alpha
// marks geometry), a voxelizer, AO and indirect light.
#pragma once
#include "gl_fixture.hpp"

#include "obscura/assets.hpp"
#include "obscura/obscura.hpp"

namespace obscura::test {

struct CornellFrame {
    CornellFrame(int width, int height)
        : view(gbuffer.render(cornell.scene, assets::makeCamera(cornell.camera, width, height), {width, height, true, {}})),
          positions(readTexture(ctx, gbuffer.positions(view))) {}

    GlFixture gl;
    Context ctx{gl.desc()};
    GBuffer gbuffer{ctx};
    Voxelizer voxelizer{ctx};
    AmbientOcclusion ao{ctx};
    IndirectLight gi{ctx};
    assets::LoadedScene cornell = assets::builtinScene("cornell");
    GBufferView view;
    Image positions;
};

} // namespace obscura::test
