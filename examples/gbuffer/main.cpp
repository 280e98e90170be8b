// G-buffer example: renders a scene's G-buffer with Obscura on the example's own context
// (headless EGL or a GLFW window) and shows one buffer.
//
//   obscura_example_gbuffer --scene cornell --output normal --out normal.png
//   obscura_example_gbuffer --window --frames 0 --scene /usr/share/assimp/models/PLY/Wuson.ply
#include "app.hpp"
#include "obscura/error.hpp"
#include "obscura/profiler.hpp"
#include "technique_registry.hpp"

#include <cstdio>

using namespace obscura;

int main(int argc, char** argv) {
    CLI::App parser{"Obscura G-buffer example"};
    examples::AppOptions options;
    examples::addAppOptions(parser, options);
    std::string output = "direct";
    parser.add_option("--output", output, "direct, albedo, normal, depth, position or distance")->capture_default_str();
    CLI11_PARSE(parser, argc, argv);
    return examples::runGuarded([&] {
        examples::App app(options);
        const examples::ExampleScene example = examples::loadExampleScene(options, app.width(), app.height());
        const assets::LoadedScene& scene = example.loaded;
        const Camera& camera = example.camera;
        TextureImage shown;
        {
            Context ctx(app.contextDesc());
            auto run = cli::techniques().at("gbuffer").create(ctx);
            int presented = 0;
            do {
                run->run({scene, camera, app.width(), app.height()});
                const cli::TechniqueOutput out = run->outputs({output}).front();
                shown = app.present(assets::encodeDisplay(out.display, out.encoding));
                ++presented;
            } while (!app.done(presented));
            examples::printPassTimes(ctx);
        }
        examples::writeShown(options, app.windowed(), shown);
    });
}
