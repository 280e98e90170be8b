// Shadows example: the shadow mask of a scene's first shadow-casting light with every filter
// of obscura::ShadowMaps, or the direct light the G-buffer shadows with the maps, on the
// example's own context (headless EGL, or a GLFW window with an ImGui panel).
//
//   obscura_example_shadows --scene cornell --filter pcf --out mask.png
//   obscura_example_shadows --scene /usr/share/assimp/models/PLY/Wuson.ply --filter evsm4 --window --frames 0
//   --view lit: the composed direct light, shadowed per fragment (hard and pcf)
//   --point-maps paraboloid: point lights as two paraboloid maps instead of a cube
//   --pcf-kernel optimized|poisson: PCF's grid from fewer taps, or a rotated Poisson disc
#include "app.hpp"
#include "obscura/obscura.hpp"

#include <imgui.h>

#include <algorithm>
#include <cstdio>
#include <optional>

using namespace obscura;

namespace {

const char* const kFilters[] = {"hard", "pcf", "vsm", "esm", "evsm2", "evsm4", "msm", "pcss"}; // ShadowFilter order
constexpr int kFilterCount = 8;
const char* const kKernels[] = {"grid", "poisson", "optimized"}; // PcfKernel order
constexpr int kKernelCount = 3;

struct ShadowControls {
    int filter = 1;
    int kernel = 0;
    int resolution = 1024;
    int cascades = 3;
    bool paraboloid = false;
    ShadowMaskSettings mask;
    bool lit = false;
    bool changed = true;

    void drawPanel() {
        ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_FirstUseEver);
        ImGui::Begin("shadows", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
        changed |= ImGui::Combo("filter", &filter, kFilters, kFilterCount);
        changed |= ImGui::SliderInt("resolution", &resolution, 64, 4096);
        changed |= ImGui::SliderInt("cascades", &cascades, 1, kMaxShadowCascades);
        changed |= ImGui::Checkbox("point: dual paraboloid", &paraboloid);
        changed |= ImGui::SliderInt("pcf radius", &mask.pcfRadius, 0, 8);
        changed |= ImGui::Combo("pcf kernel", &kernel, kKernels, kKernelCount);
        changed |= ImGui::SliderFloat("normal offset", &mask.normalOffset, 0.0f, 16.0f);
        changed |= ImGui::SliderFloat("slope bias", &mask.slopeBias, 0.0f, 16.0f);
        changed |= ImGui::SliderInt("moment blur", &mask.momentBlur, 0, 8);
        changed |= ImGui::Checkbox("lit (hard, pcf)", &lit);
        ImGui::End();
    }
};

std::optional<std::size_t> firstShadowedLight(const Scene& scene) {
    for (std::size_t i = 0; i < scene.lights.size(); ++i)
        if (hasShadowMaps(scene.lights[i])) return i;
    return std::nullopt;
}

} // namespace

int main(int argc, char** argv) {
    CLI::App parser{"Obscura shadows example"};
    examples::AppOptions options;
    examples::addAppOptions(parser, options);
    ShadowControls controls;
    std::string filterName = "pcf", viewName = "mask", pointMaps = "cube", kernelName = "grid";
    parser.add_option("--filter", filterName, "hard|pcf|vsm|esm|evsm2|evsm4|msm|pcss")->capture_default_str();
    parser.add_option("--resolution", controls.resolution, "Shadow map side, texels [16, 8192]")->capture_default_str();
    parser.add_option("--cascades", controls.cascades, "Directional lights: maps [1, 4]")->capture_default_str();
    parser.add_option("--pcf-radius", controls.mask.pcfRadius, "PCF taps each side [0, 8]")->capture_default_str();
    parser.add_option("--pcf-kernel", kernelName, "grid|optimized|poisson")->capture_default_str();
    parser.add_option("--normal-offset", controls.mask.normalOffset, "Texels [0, 16]")->capture_default_str();
    parser.add_option("--contact", controls.mask.contactLength, "Contact-shadow ray, world units (0: off)")->capture_default_str();
    parser.add_option("--point-maps", pointMaps, "Point lights: cube or paraboloid")->capture_default_str();
    parser.add_option("--view", viewName, "mask (the light's shadow) or lit (the shadowed direct light)")->capture_default_str();
    CLI11_PARSE(parser, argc, argv);
    return examples::runGuarded([&] {
        const auto* known = std::find(std::begin(kFilters), std::end(kFilters), filterName);
        if (known == std::end(kFilters)) throw Error(ErrorCode::Parse, "--filter: expected hard, pcf, vsm, esm, evsm2, evsm4, msm or pcss");
        controls.filter = static_cast<int>(known - std::begin(kFilters));
        const auto* kernel = std::find(std::begin(kKernels), std::end(kKernels), kernelName);
        if (kernel == std::end(kKernels)) throw Error(ErrorCode::Parse, "--pcf-kernel: expected grid, optimized or poisson");
        controls.kernel = static_cast<int>(kernel - std::begin(kKernels));
        if (viewName != "mask" && viewName != "lit") throw Error(ErrorCode::Parse, "--view: expected mask or lit");
        controls.lit = viewName == "lit";
        if (pointMaps != "cube" && pointMaps != "paraboloid") throw Error(ErrorCode::Parse, "--point-maps: expected cube or paraboloid");
        controls.paraboloid = pointMaps == "paraboloid";
        examples::App app(options);
        const examples::ExampleScene example = examples::loadExampleScene(options, app.width(), app.height());
        const Scene& scene = example.loaded.scene;
        const std::optional<std::size_t> light = firstShadowedLight(scene);
        if (!light) throw Error(ErrorCode::InvalidArgument, "the scene has no shadow-casting light");
        app.setPanel([&] { controls.drawPanel(); });
        TextureImage shown;
        {
            Context ctx(app.contextDesc());
            GBuffer gbuffer(ctx);
            ShadowMaps shadows(ctx);
            Composer composer(ctx);
            shown = app.presentUntilDone(controls.changed, [&] {
                ShadowMaskSettings mask = controls.mask;
                mask.filter = static_cast<ShadowFilter>(controls.filter);
                mask.pcfKernel = static_cast<PcfKernel>(controls.kernel);
                const PointShadowMapping point = controls.paraboloid ? PointShadowMapping::DualParaboloid : PointShadowMapping::Cube;
                const ShadowMapSet& maps = shadows.render(scene, example.camera, {controls.resolution, controls.cascades, 0.75f, point});
                GBufferSettings g{app.width(), app.height(), true, {}};
                // The G-buffer looks shadows up with hard or PCF comparisons only.
                const bool lit = controls.lit && (mask.filter == ShadowFilter::Hard || mask.filter == ShadowFilter::Pcf);
                if (lit) {
                    g.shadows = &maps;
                    g.shadowFilter = mask;
                }
                const GBufferView view = gbuffer.render(scene, example.camera, g);
                if (lit)
                    return assets::encodeDisplay(readTexture(ctx, composer.compose({view, {}, {}}, {})),
                                                 assets::PngEncoding::Linear);
                return assets::encodeDisplay(readTexture(ctx, shadows.mask(view, maps, *light, mask)),
                                             assets::PngEncoding::Linear);
            });
            examples::printPassTimes(ctx);
        }
        examples::writeShown(options, app.windowed(), shown);
    });
}
