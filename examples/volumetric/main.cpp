// Volumetric example: single scattering in the scene's media (the god-ray scene by default:
// a spot light through a lattice into fog) by ray marching, Sun et al.'s closed form, a
// froxel grid or marching within the spot's shadow volume, shown as the lit frame seen through the media, the in-scattered light alone or
// the transmittance, on the example's own context (headless EGL, or a GLFW window with an
// ImGui panel).
//
//   obscura_example_volumetric --out god_rays.png
//   obscura_example_volumetric --scene cornell_fog --method analytic --view scattering
//   obscura_example_volumetric --scene cornell_smoke --method froxel --window --frames 0
#include "app.hpp"
#include "obscura/obscura.hpp"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>

using namespace obscura;

int main(int argc, char** argv) {
    CLI::App parser{"Obscura volumetric example"};
    examples::AppOptions options;
    options.scene = "god_rays";
    examples::addAppOptions(parser, options);
    std::string methodName = "raymarch", viewName = "frame";
    int steps = 64;
    float exposure = 1.0f;
    parser.add_option("--method", methodName, "raymarch, analytic (no shadows), froxel or bounded (within shadow volumes)")
        ->check(CLI::IsMember({"raymarch", "analytic", "froxel", "bounded"}))
        ->capture_default_str();
    parser.add_option("--steps", steps, "March samples, quadrature intervals or froxel slices, [1, 1024]")
        ->check(CLI::Range(1, 1024))
        ->capture_default_str();
    parser.add_option("--view", viewName, "frame (the lit frame through the media), scattering or transmittance")
        ->check(CLI::IsMember({"frame", "scattering", "transmittance"}))
        ->capture_default_str();
    parser.add_option("--exposure", exposure, "Radiance multiplier of the picture, [0, 1e3]")
        ->check(CLI::Range(0.0f, 1e3f))
        ->capture_default_str();
    CLI11_PARSE(parser, argc, argv);
    return examples::runGuarded([&] {
        examples::App app(options);
        const examples::ExampleScene example = examples::loadExampleScene(options, app.width(), app.height());
        const Scene& scene = example.loaded.scene;
        if (scene.media.empty()) throw Error(ErrorCode::InvalidArgument, "the scene has no media (try god_rays or cornell_fog)");
        static const char* const kMethods[] = {"raymarch", "analytic", "froxel", "bounded"};
        static const MediaMethod kMethodValues[] = {MediaMethod::RayMarch, MediaMethod::Analytic, MediaMethod::Froxel,
                                                    MediaMethod::Bounded};
        static const char* const kViews[] = {"frame", "scattering", "transmittance"};
        int method = int(std::find(std::begin(kMethods), std::end(kMethods), methodName) - std::begin(kMethods));
        int view = viewName == "frame" ? 0 : viewName == "scattering" ? 1 : 2;
        bool changed = true;
        app.setPanel([&] {
            ImGui::Begin("volumetric");
            changed |= ImGui::Combo("method", &method, kMethods, 4);
            changed |= ImGui::SliderInt("steps", &steps, 1, 256);
            changed |= ImGui::Combo("view", &view, kViews, 3);
            changed |= ImGui::DragFloat("exposure", &exposure, 0.01f, 0.0f, 1e3f, "%.3f");
            ImGui::End();
        });
        TextureImage shown;
        {
            Context ctx(app.contextDesc());
            ShadowMaps shadows(ctx);
            GBuffer gbuffer(ctx);
            Media media(ctx);
            const ShadowMapSet& maps = shadows.render(scene, example.camera, ShadowMapSettings{});
            GBufferSettings g{app.width(), app.height(), true, {}};
            g.shadows = &maps;
            const GBufferView gview = gbuffer.render(scene, example.camera, g);
            shown = app.presentUntilDone(changed, [&] {
                MediaSettings s;
                s.method = kMethodValues[method];
                s.steps = steps;
                const MediaView result = media.run(gview, {scene.media, scene.lights, &maps}, s);
                Image picture = readTexture(ctx, view == 0 ? media.apply(result, gview.directRadiance)
                                                 : view == 1 ? result.scattering
                                                             : result.opticalDepth);
                for (float& v : picture.pixels) v = view == 2 ? std::exp(-v) : v * exposure;
                return assets::encodeDisplay(picture, assets::PngEncoding::Srgb);
            });
            examples::printPassTimes(ctx);
        }
        examples::writeShown(options, app.windowed(), shown);
    });
}
