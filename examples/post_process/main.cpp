// Post-process example, the headline use case: an engine with its own GL loader renders its
// own G-buffer (reversed-Z depth, smooth shading normals, sRGB albedo, lit HDR colour) into its
// own framebuffers, with GL state of its own set; Obscura adopts those buffers, adds ambient
// occlusion and one bounce of indirect light, composes, and draws the frame back into the
// engine's display framebuffer. The engine then checks that its GL state is as it left it and
// writes the picture. Headless by default; --window opens a GLFW window with a panel.
//
//   obscura_example_post_process --scene cornell --out frame.png
//   obscura_example_post_process --scene /usr/share/assimp/models/PLY/Wuson.ply --gi 0 --out ao_only.png
//   obscura_example_post_process --window --frames 0
#include "app.hpp"
#include "host_engine.hpp"
#include "obscura/obscura.hpp"

#include <imgui.h>

#include <cstdio>

using namespace obscura;

namespace {

struct Options {
    bool ao = true, gi = true;
    float ambient = 0.05f; //!< W/(sr m^2), the AO-shaded ambient term
    bool half = true;      //!< AO and GI at half resolution
    bool temporal = false; //!< a new sampling pattern every frame, accumulated over frames
};

// The integration: the engine's buffers in, its display framebuffer out. This is what
// README.md shows.
struct PostProcess {
    explicit PostProcess(Context& ctx) : gbuffer(ctx), ao(ctx), gi(ctx), composer(ctx) {}
    GBuffer gbuffer;
    AmbientOcclusion ao;
    IndirectLight gi;
    Composer composer;
    AmbientOcclusionSettings aoSettings;
    IndirectLightSettings giSettings;
    ComposeSettings composeSettings;

    HostGBuffer hostBuffers(const examples::HostEngine& engine, int w, int h) const {
        HostGBuffer host;
        host.depth = {engine.depth(), GL_DEPTH_COMPONENT32F, w, h};
        host.normal = {engine.normal(), GL_RGBA16F, w, h};
        host.normalDeviation = engine.normalDeviation(); // smooth shading normals
        host.albedo = {engine.albedo(), GL_SRGB8_ALPHA8, w, h};
        host.directRadiance = {engine.lit(), GL_RGBA16F, w, h};
        return host;
    }

    void configure(const Options& o, float radius) {
        aoSettings.temporal.enabled = giSettings.temporal.enabled = o.temporal;
        aoSettings.radius = giSettings.radius = radius;
        aoSettings.method = AoMethod::Horizon;
        aoSettings.resolution = giSettings.resolution = o.half ? AoResolution::Half : AoResolution::Full;
        aoSettings.blurRadius = giSettings.blurRadius = 2;
        composeSettings.ambient = glm::vec3(o.ambient);
    }

    // Compiles every program the frame takes, so that the first frame does not stall.
    void prepare(const examples::HostEngine& engine, int w, int h) {
        gbuffer.prepareAdopt(hostBuffers(engine, w, h));
        ao.prepare(aoSettings);
        gi.prepare(giSettings);
        composer.prepare(composeSettings);
    }

    void frame(const examples::HostEngine& engine, const Camera& camera, const Options& o, int w, int h) {
        if (o.temporal) aoSettings.frameIndex = giSettings.frameIndex = giSettings.frameIndex + 1;
        const GBufferView view = gbuffer.adopt(hostBuffers(engine, w, h), camera);
        ComposeInputs inputs{view, {}, {}};
        if (o.gi) inputs.indirect = gi.run(view, giSettings).radiance;
        if (o.ao && combineReadsAo(composeSettings, o.gi)) inputs.ao = ao.run(view, aoSettings).ao;
        composer.drawToHost(composer.compose(inputs, composeSettings), {engine.displayFramebuffer(), 0, 0, w, h});
    }
};

} // namespace

int main(int argc, char** argv) {
    CLI::App parser{"Obscura post-process example: an engine's own G-buffer through AO, indirect light and compose"};
    examples::AppOptions options;
    examples::addAppOptions(parser, options);
    Options o;
    parser.add_option("--ao", o.ao, "Ambient occlusion (horizon-based) shading the ambient term (1) or not (0)")
        ->capture_default_str();
    parser.add_option("--gi", o.gi, "One bounce of screen-space indirect light (1) or not (0)")->capture_default_str();
    parser.add_option("--ambient", o.ambient, "Ambient radiance L_amb, W/(sr m^2), [0, 65504]")
        ->check(CLI::Range(0.0f, 65504.0f))
        ->capture_default_str();
    parser.add_option("--half", o.half, "AO and indirect light at half resolution (1) or full (0)")->capture_default_str();
    parser.add_option("--temporal", o.temporal,
                      "A new sampling pattern every frame (frameIndex), accumulated over up to 16 frames (1), or "
                      "the same pattern each frame (0)")
        ->capture_default_str();
    CLI11_PARSE(parser, argc, argv);
    return examples::runGuarded([&] {
        examples::App app(options);
        const int w = app.width(), h = app.height();
        const examples::ExampleScene example = examples::loadExampleScene(options, w, h, DepthMode::Reversed);
        bool changed = true; // an engine renders every frame: set again after each
        app.setPanel([&] {
            ImGui::Begin("post process");
            changed |= ImGui::Checkbox("ambient occlusion", &o.ao);
            changed |= ImGui::Checkbox("indirect light", &o.gi);
            changed |= ImGui::DragFloat("ambient", &o.ambient, 0.001f, 0.0f, 65504.0f, "%.4f");
            changed |= ImGui::Checkbox("half resolution", &o.half);
            changed |= ImGui::Checkbox("temporal accumulation", &o.temporal);
            ImGui::End();
        });
        TextureImage shown;
        std::size_t items = 0;
        int frames = 0;
        {
            examples::HostEngine engine(example.loaded, w, h);
            std::printf("HostGBuffer::normalDeviation: %.1f degrees (the engine's smooth normals)\n",
                        double(engine.normalDeviation()) * 57.29577951308232);
            Context ctx(app.contextDesc());
            PostProcess post(ctx);
            post.configure(o, 0.1f * example.diagonal);
            post.prepare(engine, w, h);
            shown = app.presentUntilDone(changed, [&] {
                post.configure(o, 0.1f * example.diagonal);
                engine.renderGBuffer(example.camera);
                engine.setOwnState();
                const std::vector<std::string> before = engine.ownState();
                post.frame(engine, {example.camera.view, example.camera.projection, ClipDepth::ZeroToOne}, o, w, h);
                const std::vector<std::string> after = engine.ownState();
                for (std::size_t i = 0; i < before.size(); ++i)
                    if (after[i] != before[i])
                        throw Error(ErrorCode::InvalidState, "the engine's GL state changed: " + before[i] + " became " + after[i]);
                engine.resetOwnState();
                items = before.size();
                ++frames;
                changed = true;
                return TextureImage{w, h, engine.readDisplay()};
            });
            examples::printPassTimes(ctx);
        }
        std::printf("host GL state: %zu items as the engine left them, in each of %d frames\n", items, frames);
        examples::writeShown(options, app.windowed(), shown);
    });
}
