// Renders a G-buffer headless with an installed (or add_subdirectory'd) Obscura.
#include <obscura/headless.hpp>
#include <obscura/obscura.hpp>

#include <cstdio>

int main() {
    try {
        obscura::headless::HeadlessContext gl;
        obscura::Context ctx(gl.contextDesc());
        obscura::GBuffer gbuffer(ctx);
        obscura::Scene scene;
        scene.materials.push_back({});
        auto quad = std::make_shared<obscura::MeshData>();
        quad->positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
        quad->indices = {0, 1, 2, 0, 2, 3};
        scene.meshes.push_back({quad, glm::mat4(1.0f), 0, "quad"});
        const auto camera = obscura::Camera::perspective({{0, 0, 2}, {0, 0, 0}, {0, 1, 0}}, 0.8f, 1.0f, 0.1f, 10.0f);
        const auto view = gbuffer.render(scene, camera, {8, 8, true, {}});
        const obscura::Image n = obscura::readTexture(ctx, view.normal);
        if (n.pixels.at(2) < 0.999f) {
            std::fprintf(stderr, "consumer: unexpected normal\n");
            return 1;
        }
        std::printf("consumer: obscura %s OK on %s\n", OBSCURA_VERSION_STRING, ctx.info().renderer.c_str());
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "consumer: %s\n", e.what());
        return 1;
    }
}
