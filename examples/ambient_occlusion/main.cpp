// Ambient occlusion example: AO of a scene with every method of obscura::AmbientOcclusion,
// on the example's own context (headless EGL, or a GLFW window with an ImGui panel).
//
//   obscura_example_ambient_occlusion --scene cornell --method horizon --rays 16 --out ao.png
//   obscura_example_ambient_occlusion --window --frames 0 --scene /usr/share/assimp/models/PLY/Wuson.ply
//   --view lit: the AO shading the direct light and an ambient term (the thesis's combine)
#include "app.hpp"
#include "integrator_controls.hpp"
#include "obscura/obscura.hpp"

#include <imgui.h>

#include <cstdio>

using namespace obscura;

int main(int argc, char** argv) {
    CLI::App parser{"Obscura ambient occlusion example"};
    examples::AppOptions options;
    examples::addAppOptions(parser, options);
    examples::IntegratorControls controls;
    controls.methods = {"raymarch", "points", "horizon", "voxel"};
    controls.addOptions(parser);
    std::string viewName = "ao";
    parser.add_option("--view", viewName, "ao (the AO term) or lit (AO in the combined image)")->capture_default_str();
    CLI11_PARSE(parser, argc, argv);
    return examples::runGuarded([&] {
        controls.check();
        if (viewName != "ao" && viewName != "lit") throw Error(ErrorCode::Parse, "--view: expected ao or lit");
        examples::App app(options);
        const examples::ExampleScene example = examples::loadExampleScene(options, app.width(), app.height());
        const assets::LoadedScene& scene = example.loaded;
        const Camera& camera = example.camera;
        const float diagonal = example.diagonal;
        if (controls.radius <= 0.0f) controls.radius = 0.1f * diagonal;
        bool lit = viewName == "lit";
        app.setPanel([&] {
            controls.drawPanel("ambient occlusion");
            ImGui::Begin("ambient occlusion");
            controls.changed |= ImGui::Checkbox("lit", &lit);
            ImGui::End();
        });
        TextureImage shown;
        {
            Context ctx(app.contextDesc());
            GBuffer gbuffer(ctx);
            Voxelizer voxelizer(ctx);
            AmbientOcclusion ao(ctx);
            Composer composer(ctx);
            const GBufferView view = gbuffer.render(scene.scene, camera, {app.width(), app.height(), true, {}});
            shown = app.presentUntilDone(controls.changed, [&] {
                TextureImage picture;
                AmbientOcclusionSettings s;
                s.method = static_cast<AoMethod>(controls.method);
                s.rays = s.method == AoMethod::Horizon ? std::max(2, controls.rays & ~1) : controls.rays;
                s.steps = controls.steps;
                s.radius = std::max(controls.radius, 1e-6f * diagonal);
                s.resolution = controls.aoResolution();
                s.blurRadius = controls.blur;
                if (s.method == AoMethod::Voxel) s.voxels = &voxelizer.voxelize(scene.scene, {});
                const AmbientOcclusionView result = ao.run(view, s);
                if (lit) {
                    ComposeSettings c;
                    c.formula = CombineFormula::Thesis;
                    c.ambient = glm::vec3(0.5f);
                    // The display values are already encoded: passed on as they are.
                    picture = assets::encodeDisplay(readTexture(ctx, composer.compose({view, result.ao, {}}, c)),
                                                    assets::PngEncoding::Linear);
                } else {
                    picture = assets::encodeDisplay(readTexture(ctx, result.ao), assets::PngEncoding::Linear);
                }
                return picture;
            });
            examples::printPassTimes(ctx);
        }
        examples::writeShown(options, app.windowed(), shown);
    });
}
