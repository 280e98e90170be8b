// Global illumination example: one-bounce indirect light of a scene, screen-space or hybrid
// (voxel visibility, screen radiance), alone or combined with the direct light (and AO-shaded
// ambient light, with --ambient), on the example's own context (headless EGL, or a GLFW window
// with an ImGui panel).
//
//   obscura_example_global_illumination --scene cornell --method hybrid --view composed --out gi.png
//   obscura_example_global_illumination --formula thesis --ambient 0.05 --out gi_ambient.png
//   obscura_example_global_illumination --window --frames 0
//   --thickness-mode depth_peeling: what lies behind a depth sample (the screen-space method)
#include "app.hpp"
#include "integrator_controls.hpp"
#include "obscura/obscura.hpp"

#include <imgui.h>

#include <cstdio>

using namespace obscura;

int main(int argc, char** argv) {
    CLI::App parser{"Obscura global illumination example"};
    examples::AppOptions options;
    examples::addAppOptions(parser, options);
    examples::IntegratorControls controls;
    controls.methods = {"screen", "hybrid"};
    controls.thicknessHelp = "World units, >= 0: screen, how far behind each depth sample a point counts as inside "
                             "(0: the radius); hybrid, how far a voxel hit may lie from the pixel's tangent plane "
                             "(0: two voxel diagonals)";
    controls.addOptions(parser);
    std::string viewName = "composed";
    float exposure = 0.0f;
    float ambient = 0.0f;
    std::string formulaName = "standard";
    parser.add_option("--view", viewName, "indirect (L1 alone) or composed (the combine of ComposeSettings, tone mapped)")
        ->capture_default_str();
    parser.add_option("--formula", formulaName,
                      "Combine of the composed view: standard (direct + AO-shaded ambient + L1), physical (direct + "
                      "L1: the indirect light replaces the ambient term) or thesis (AO-shaded ambient + L1 + AO "
                      "times direct)")
        ->check(CLI::IsMember({"standard", "physical", "thesis"}))
        ->capture_default_str();
    parser.add_option("--ambient", ambient,
                      "Ambient radiance L_amb, W/(sr m^2), [0, 65504], that AO shades in the composed view with "
                      "--formula standard or thesis (0: none)")
        ->check(CLI::Range(0.0f, 65504.0f))
        ->capture_default_str();
    bool withAo = true;
    parser.add_option("--ao", withAo, "Shade the ambient term with AO (1) or not (0)")->capture_default_str();
    parser.add_option("--exposure", exposure, "Radiance multiplier before tone mapping, [0, 1e3] (0: 1, no scaling)")
        ->check(CLI::Range(0.0f, 1e3f))
        ->capture_default_str();
    CLI11_PARSE(parser, argc, argv);
    return examples::runGuarded([&] {
        controls.check();
        if (viewName != "indirect" && viewName != "composed") throw Error(ErrorCode::Parse, "--view: expected indirect or composed");
        examples::App app(options);
        const examples::ExampleScene example = examples::loadExampleScene(options, app.width(), app.height());
        const assets::LoadedScene& scene = example.loaded;
        const Camera& camera = example.camera;
        const float diagonal = example.diagonal;
        if (controls.radius <= 0.0f) controls.radius = 0.1f * diagonal;
        bool composed = viewName == "composed";
        static const char* const kFormulas[] = {"standard", "physical", "thesis"};
        static const CombineFormula kFormulaValues[] = {CombineFormula::Standard, CombineFormula::Physical,
                                                        CombineFormula::Thesis};
        int formula = formulaName == "physical" ? 1 : formulaName == "thesis" ? 2 : 0;
        app.setPanel([&] {
            controls.drawPanel("global illumination");
            ImGui::Begin("global illumination");
            controls.changed |= ImGui::Checkbox("composed", &composed);
            controls.changed |= ImGui::Combo("formula", &formula, kFormulas, 3);
            controls.changed |= ImGui::DragFloat("ambient", &ambient, 0.001f, 0.0f, 65504.0f, "%.4f");
            controls.changed |= ImGui::Checkbox("ambient occlusion", &withAo);
            controls.changed |= ImGui::DragFloat("exposure", &exposure, 0.001f, 0.0f, 1e3f, "%.4f");
            ImGui::End();
        });
        TextureImage shown;
        {
            Context ctx(app.contextDesc());
            GBuffer gbuffer(ctx);
            Voxelizer voxelizer(ctx);
            IndirectLight gi(ctx);
            AmbientOcclusion ao(ctx);
            Composer composer(ctx);
            // Two depth layers, so that the panel can switch to depth peeling.
            GBufferSettings layers{app.width(), app.height(), true, {}};
            layers.depthLayers = 2;
            const GBufferView view = gbuffer.render(scene.scene, camera, layers);
            shown = app.presentUntilDone(controls.changed, [&] {
                TextureImage picture;
                IndirectLightSettings s;
                s.method = static_cast<GiMethod>(controls.method);
                s.rays = controls.rays;
                s.steps = controls.steps;
                s.radius = std::max(controls.radius, 1e-6f * diagonal);
                s.resolution = controls.aoResolution();
                s.blurRadius = controls.blur;
                s.thicknessMode = controls.screenThickness();
                s.thickness = controls.thickness;
                if (s.method == GiMethod::Hybrid) s.voxels = &voxelizer.voxelize(scene.scene, {});
                const IndirectLightView result = gi.run(view, s);
                ComposeSettings c;
                c.exposure = exposure > 0.0f ? exposure : 1.0f;
                c.formula = kFormulaValues[formula];
                c.ambient = glm::vec3(ambient);
                if (composed) {
                    ComposeInputs inputs{view, {}, result.radiance};
                    // AO shades the ambient term (and, in the thesis's formula, the direct
                    // light); the physical combine uses neither next to L1: no AO pass then.
                    if (combineReadsAo(c, true) && withAo) {
                        AmbientOcclusionSettings a;
                        a.radius = s.radius;
                        a.resolution = s.resolution;
                        a.blurRadius = s.blurRadius;
                        // The hybrid's thickness bounds voxel hits, not depth samples.
                        if (s.method == GiMethod::Screen) {
                            a.thicknessMode = s.thicknessMode;
                            a.thickness = s.thickness;
                        }
                        inputs.ao = ao.run(view, a).ao;
                    }
                    picture = assets::encodeDisplay(readTexture(ctx, composer.compose(inputs, c)), assets::PngEncoding::Linear);
                } else {
                    Image l1 = readTexture(ctx, result.radiance);
                    for (float& v : l1.pixels) v *= c.exposure;
                    picture = assets::encodeDisplay(l1, assets::PngEncoding::Srgb);
                }
                return picture;
            });
            examples::printPassTimes(ctx);
        }
        examples::writeShown(options, app.windowed(), shown);
    });
}
