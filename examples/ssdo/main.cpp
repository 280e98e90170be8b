// SSDO example: screen-space directional occlusion of a scene lit by an HDR environment
// (blender-data's courtyard by default), its direct light, its one-bounce indirect light or
// their sum, on the example's own context (headless EGL, or a GLFW window with an ImGui panel).
//
//   obscura_example_ssdo --scene cornell --view sum --out ssdo.png
//   obscura_example_ssdo --scene /usr/share/assimp/models/PLY/Wuson.ply --environment forest.exr --rotation 90
//   obscura_example_ssdo --window --frames 0
#include "app.hpp"
#include "integrator_controls.hpp"
#include "obscura/obscura.hpp"

#include <imgui.h>

#include <cmath>
#include <cstdio>

using namespace obscura;

int main(int argc, char** argv) {
    CLI::App parser{"Obscura SSDO example"};
    examples::AppOptions options;
    examples::addAppOptions(parser, options);
    examples::IntegratorControls controls;
    controls.methods = {"ssdo"};
    controls.thicknessHelp = "World units behind each depth sample, >= 0 (0: the radius)";
    controls.addOptions(parser);
    std::string environment = "/usr/share/blender/datafiles/studiolights/world/courtyard.exr";
    float intensity = 1.0f, rotationDeg = 0.0f, exposure = 1.0f, strength = 1.0f;
    std::string viewName = "sum";
    parser.add_option("--environment", environment, "Equirectangular EXR/HDR that lights the scene")->capture_default_str();
    parser.add_option("--intensity", intensity, "Radiance scale of the environment, [0, 1e6]")
        ->check(CLI::Range(0.0f, 1e6f))
        ->capture_default_str();
    parser.add_option("--rotation", rotationDeg, "Rotation of the environment about +y, degrees")->capture_default_str();
    parser.add_option("--view", viewName, "direct, indirect (the bounce) or sum")
        ->check(CLI::IsMember({"direct", "indirect", "sum"}))
        ->capture_default_str();
    parser.add_option("--bounce-strength", strength, "Scale of the bounce, [0, 100]")
        ->check(CLI::Range(0.0f, 100.0f))
        ->capture_default_str();
    parser.add_option("--exposure", exposure, "Radiance multiplier of the picture, [0, 1e3]")
        ->check(CLI::Range(0.0f, 1e3f))
        ->capture_default_str();
    CLI11_PARSE(parser, argc, argv);
    return examples::runGuarded([&] {
        controls.check();
        examples::App app(options);
        const examples::ExampleScene example = examples::loadExampleScene(options, app.width(), app.height());
        if (controls.radius <= 0.0f) controls.radius = 0.1f * example.diagonal;
        static const char* const kViews[] = {"direct", "indirect", "sum"};
        int view = viewName == "direct" ? 0 : viewName == "indirect" ? 1 : 2;
        app.setPanel([&] {
            controls.drawPanel("ssdo");
            ImGui::Begin("ssdo");
            controls.changed |= ImGui::Combo("view", &view, kViews, 3);
            controls.changed |= ImGui::DragFloat("intensity", &intensity, 0.01f, 0.0f, 1e6f, "%.3f");
            controls.changed |= ImGui::DragFloat("rotation", &rotationDeg, 1.0f, -360.0f, 360.0f, "%.0f deg");
            controls.changed |= ImGui::DragFloat("bounce strength", &strength, 0.01f, 0.0f, 100.0f, "%.2f");
            controls.changed |= ImGui::DragFloat("exposure", &exposure, 0.01f, 0.0f, 1e3f, "%.3f");
            ImGui::End();
        });
        TextureImage shown;
        {
            Context ctx(app.contextDesc());
            GBuffer gbuffer(ctx);
            DirectionalOcclusion ssdo(ctx);
            EnvironmentMap env(ctx, assets::readImage(environment));
            for (const std::string& w : env.warnings()) std::fprintf(stderr, "warning: %s\n", w.c_str());
            // Two depth layers, so that the panel can switch to depth peeling.
            GBufferSettings layers{app.width(), app.height(), true, {}};
            layers.depthLayers = 2;
            const GBufferView gview = gbuffer.render(example.loaded.scene, example.camera, layers);
            shown = app.presentUntilDone(controls.changed, [&] {
                env.setLookup(intensity, rotationDeg * 3.14159265f / 180.0f);
                DirectionalOcclusionSettings s;
                s.rays = controls.rays;
                s.steps = controls.steps;
                s.radius = std::max(controls.radius, 1e-6f * example.diagonal);
                s.resolution = controls.aoResolution();
                s.blurRadius = controls.blur;
                s.thicknessMode = controls.screenThickness();
                s.thickness = controls.thickness;
                s.bounce = view != 0;
                s.bounceStrength = strength;
                const DirectionalOcclusionView result = ssdo.run(gview, {&env}, s);
                Image picture = readTexture(ctx, view == 1 ? result.indirect : result.direct);
                if (view == 2) {
                    const Image indirect = readTexture(ctx, result.indirect);
                    for (std::size_t i = 0; i < picture.pixels.size(); ++i) picture.pixels[i] += indirect.pixels[i];
                }
                for (float& v : picture.pixels) v *= exposure;
                return assets::encodeDisplay(picture, assets::PngEncoding::Srgb);
            });
            examples::printPassTimes(ctx);
        }
        examples::writeShown(options, app.windowed(), shown);
    });
}
