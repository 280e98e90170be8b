// Ambient occlusion example: AO of a scene with every method of obscura::AmbientOcclusion,
// on the example's own context (headless EGL, or a GLFW window with an ImGui panel).
//
//   obscura_example_ambient_occlusion --scene cornell --method horizon --rays 16 --out ao.png
//   obscura_example_ambient_occlusion --window --frames 0 --scene /usr/share/assimp/models/PLY/Wuson.ply
//   --view lit: the AO shading the direct light and an ambient term (the thesis's combine)
//   --view bent: the bent normals (view space, n * 0.5 + 0.5); --falloff linear: obscurance
//   --thickness-mode depth_peeling: what lies behind a depth sample (raymarch and points)
#include "app.hpp"
#include "integrator_controls.hpp"
#include "obscura/obscura.hpp"

#include <imgui.h>

#include <algorithm>
#include <cstdio>

using namespace obscura;

int main(int argc, char** argv) {
    CLI::App parser{"Obscura ambient occlusion example"};
    examples::AppOptions options;
    examples::addAppOptions(parser, options);
    examples::IntegratorControls controls;
    controls.methods = {"raymarch", "points", "horizon", "voxel"};
    controls.addOptions(parser);
    const char* const views[] = {"ao", "bent", "lit"};
    const char* const falloffs[] = {"none", "linear", "quadratic", "smooth"}; // ObscuranceFalloff's order
    std::string viewName = "ao", falloffName = "none";
    parser.add_option("--view", viewName, "ao (the AO or obscurance term), bent (bent normals) or lit (AO in the combined image)")
        ->check(CLI::IsMember({"ao", "bent", "lit"}))
        ->capture_default_str();
    parser.add_option("--falloff", falloffName, "Obscurance's distance weighting, none (AO), linear, quadratic or smooth "
                                               "(all but the horizon method)")
        ->check(CLI::IsMember({"none", "linear", "quadratic", "smooth"}))
        ->capture_default_str();
    CLI11_PARSE(parser, argc, argv);
    return examples::runGuarded([&] {
        controls.check();
        int output = int(std::find(std::begin(views), std::end(views), viewName) - std::begin(views));
        int falloff = int(std::find(std::begin(falloffs), std::end(falloffs), falloffName) - std::begin(falloffs));
        if (falloff != 0 && controls.methods[std::size_t(controls.method)] == "horizon")
            throw Error(ErrorCode::Parse, "--falloff: the horizon method computes AO only (falloff none)");
        examples::App app(options);
        const examples::ExampleScene example = examples::loadExampleScene(options, app.width(), app.height());
        const assets::LoadedScene& scene = example.loaded;
        const Camera& camera = example.camera;
        const float diagonal = example.diagonal;
        if (controls.radius <= 0.0f) controls.radius = 0.1f * diagonal;
        app.setPanel([&] {
            controls.drawPanel("ambient occlusion");
            ImGui::Begin("ambient occlusion");
            controls.changed |= ImGui::Combo("view", &output, views, 3);
            controls.changed |= ImGui::Combo("falloff", &falloff, falloffs, 4);
            ImGui::End();
        });
        TextureImage shown;
        {
            Context ctx(app.contextDesc());
            GBuffer gbuffer(ctx);
            Voxelizer voxelizer(ctx);
            AmbientOcclusion ao(ctx);
            Composer composer(ctx);
            // Two depth layers, so that the panel can switch to depth peeling.
            GBufferSettings layers{app.width(), app.height(), true, {}};
            layers.depthLayers = 2;
            const GBufferView view = gbuffer.render(scene.scene, camera, layers);
            shown = app.presentUntilDone(controls.changed, [&] {
                TextureImage picture;
                AmbientOcclusionSettings s;
                s.method = static_cast<AoMethod>(controls.method);
                s.rays = s.method == AoMethod::Horizon ? std::max(2, controls.rays & ~1) : controls.rays;
                s.steps = controls.steps;
                s.radius = std::max(controls.radius, 1e-6f * diagonal);
                s.resolution = controls.aoResolution();
                s.blurRadius = controls.blur;
                // The panel may pick a falloff with the horizon method, which has none.
                s.falloff = s.method == AoMethod::Horizon ? ObscuranceFalloff::None : static_cast<ObscuranceFalloff>(falloff);
                s.bentNormals = output == 1;
                s.thicknessMode = controls.screenThickness();
                s.thickness = controls.thickness;
                if (s.method == AoMethod::Voxel) s.voxels = &voxelizer.voxelize(scene.scene, {});
                const AmbientOcclusionView result = ao.run(view, s);
                if (output == 1) {
                    Image bent = readTexture(ctx, result.bentNormal);
                    // Opaque, the sky too (its bent normal is 0: shown grey).
                    for (std::size_t i = 0; i < bent.pixels.size(); ++i)
                        bent.pixels[i] = i % 4 == 3 ? 1.0f : bent.pixels[i] * 0.5f + 0.5f;
                    picture = assets::encodeDisplay(bent, assets::PngEncoding::Linear);
                } else if (output == 2) {
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
