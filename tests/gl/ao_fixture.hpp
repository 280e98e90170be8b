// What the AO tests share: a G-buffer, a voxel grid and the AO module of one scene and
// camera (their open floor is scene_builders.hpp's floorScene).
#pragma once
#include "gl_fixture.hpp"
#include "scene_builders.hpp"

#include "obscura/obscura.hpp"

#include <glm/glm.hpp>

namespace obscura::test {

struct AoFixture {
    GlFixture gl;
    Context ctx{gl.desc()};
    GBuffer gbuffer{ctx};
    Voxelizer voxelizer{ctx};
    AmbientOcclusion ao{ctx};
    GBufferView view;
    Image positions; // view space, alpha = geometry

    //! depthLayers: 2 for ScreenThickness::DepthPeeling.
    void render(const Scene& scene, const Camera& camera, int width, int height, int depthLayers = 1) {
        GBufferSettings settings{width, height, false, {}};
        settings.depthLayers = depthLayers;
        view = gbuffer.render(scene, camera, settings);
        positions = readTexture(ctx, gbuffer.positions(view));
    }

    Image run(const Scene& scene, AmbientOcclusionSettings s, const VoxelizerSettings& voxels = {}) {
        if (s.method == AoMethod::Voxel) s.voxels = &voxelizer.voxelize(scene, voxels);
        return readTexture(ctx, ao.run(view, s).ao);
    }

    bool geometry(int x, int y) const { return positions.at(x, y, 3) > 0.0f; }
    glm::dvec3 world(int x, int y) const {
        const glm::dvec4 v(positions.at(x, y, 0), positions.at(x, y, 1), positions.at(x, y, 2), 1.0);
        return glm::dvec3(glm::inverse(glm::dmat4(view.camera.view)) * v);
    }
};

} // namespace obscura::test
