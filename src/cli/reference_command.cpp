// obscura reference: CPU ground truth for one quantity, written as EXR plus JSON metadata.
#include "commands.hpp"
#include "obscura/error.hpp"
#include "obscura/gbuffer.hpp"
#include "obscura/headless.hpp"
#include "obscura/reference.hpp"
#include "quantity_options.hpp"
#include "scene_options.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <thread>

namespace obscura::cli {
namespace {

struct ReferenceOptions {
    SceneOptions scene;
    std::string integrator = "ao";
    std::vector<std::string> sets;
    int spp = 256;
    std::uint64_t seed = 1;
    int threads = 0;
    std::string at = "camera";
    std::string out;
    bool quiet = false;
    bool halves = false;
    std::string cache; //!< directory; empty: always render
};

reference::ShadingPoints samplesFromGBuffer(const ResolvedScene& r, const reference::RayScene& scene) {
    headless::HeadlessContext gl;
    Context ctx(gl.contextDesc());
    GBuffer gbuffer(ctx);
    GBufferSettings settings;
    settings.width = r.width;
    settings.height = r.height;
    const GBufferView view = gbuffer.render(r.scene.scene, r.camera, settings);
    return reference::fromGBuffer(scene, r.camera, readTexture(ctx, gbuffer.positions(view)), readTexture(ctx, view.normal));
}

void runReference(const ReferenceOptions& o) {
    if (o.out.empty()) throw Error(ErrorCode::Parse, "--out FILE.exr is required");
    const ResolvedScene r = resolveScene(o.scene);
    const reference::Quantity quantity = parseQuantity(o.integrator, o.sets);
    const reference::RayScene scene(r.scene.scene);
    reference::ShadingPoints points;
    if (o.at == "camera") points = reference::fromCamera(scene, r.camera, r.width, r.height);
    else if (o.at == "gbuffer") points = samplesFromGBuffer(r, scene);
    else throw Error(ErrorCode::Parse, "--at " + o.at + ": expected camera or gbuffer");
    reference::RenderSettings settings;
    settings.samplesPerPixel = o.spp;
    settings.seed = o.seed;
    settings.threads = o.threads;
    settings.progress = !o.quiet;
    const reference::Reference ref = o.cache.empty() ? reference::render(scene, points, quantity, settings)
                                                     : reference::renderCached(o.cache, scene, points, quantity, settings);

    const std::filesystem::path out(o.out);
    assets::writeImage(out, ref.value);
    if (o.halves) {
        assets::writeImage(std::filesystem::path(out).replace_extension(".a.exr"), ref.halfA);
        assets::writeImage(std::filesystem::path(out).replace_extension(".b.exr"), ref.halfB);
    }
    const double raysPerSecond = ref.seconds > 0 ? static_cast<double>(ref.rays) / ref.seconds : 0.0;
    const int threads = o.threads > 0 ? o.threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    const nlohmann::json meta = {
        {"scene", o.scene.scene},         {"camera", o.scene.camera.empty() ? "scene default" : o.scene.camera},
        {"width", r.width},               {"height", r.height},
        {"integrator", o.integrator},     {"quantity", reference::describe(quantity)},
        {"samples_at", o.at},             {"spp", ref.samplesPerPixel},
        {"seed", o.seed},                 {"noise_mse", ref.noiseMse},
        {"noise_rmse", std::sqrt(ref.noiseMse)}, {"seconds", ref.seconds},
        {"rays", ref.rays},               {"rays_per_second", raysPerSecond},
        {"threads", threads},             {"triangles", scene.triangleCount()},
        {"renderer", "Embree 3 (CPU)"}};
    std::ofstream(std::filesystem::path(out).replace_extension(".json")) << meta.dump(2) << "\n";
    std::printf("%s: %dx%d at %s samples, %d spp, noise RMSE %.3g (MSE(A,B)/4), %llu rays in %.2f s = %.2f M rays/s on "
                "%d threads\nwrote %s\n",
                reference::describe(quantity).c_str(), r.width, r.height, o.at.c_str(), ref.samplesPerPixel,
                std::sqrt(ref.noiseMse), static_cast<unsigned long long>(ref.rays), ref.seconds, raysPerSecond * 1e-6,
                threads, out.string().c_str());
}

} // namespace

void addReferenceCommand(CLI::App& app) {
    auto o = std::make_shared<ReferenceOptions>();
    CLI::App* cmd = app.add_subcommand("reference", "Render CPU ground truth (Embree) for one quantity");
    addSceneOptions(*cmd, o->scene);
    std::string names;
    for (const auto& n : integratorNames()) names += (names.empty() ? "" : ", ") + n;
    cmd->add_option("--integrator", o->integrator, "Quantity: " + names)->capture_default_str();
    cmd->add_option("--set", o->sets, "Integrator setting key=value (repeatable), e.g. radius=1");
    cmd->add_option("--spp", o->spp, "Samples per pixel, split into two independent halves")->capture_default_str();
    cmd->add_option("--seed", o->seed, "Random seed")->capture_default_str();
    cmd->add_option("--threads", o->threads, "Threads (0 = all cores)")->capture_default_str();
    cmd->add_option("--at", o->at, "Where: camera (primary-ray hits) or gbuffer (the G-buffer's samples)")->capture_default_str();
    cmd->add_option("--out", o->out, "Output FILE.exr (metadata in FILE.json)")->required();
    cmd->add_flag("--quiet", o->quiet, "No progress bar");
    cmd->add_flag("--halves", o->halves, "Also write the two halves as FILE.a.exr and FILE.b.exr");
    cmd->add_option("--cache", o->cache, "Reuse a cached reference from (and store it in) this directory");
    cmd->callback([o] { runReference(*o); });
}

} // namespace obscura::cli
