// obscura render: one technique (or all of them) on a scene, headless, written as EXR + PNG,
// with the per-pass times of the frames it rendered.
#include "commands.hpp"
#include "obscura/assets.hpp"
#include "obscura/error.hpp"
#include "obscura/headless.hpp"
#include "obscura/profiler.hpp"
#include "scene_options.hpp"
#include "technique_registry.hpp"

#include <cstdio>
#include <filesystem>

namespace obscura::cli {
namespace {

struct RenderOptions {
    SceneOptions scene;
    std::string technique = "gbuffer";
    std::vector<std::string> sets;
    std::string output;
    std::string out;
    int frames = 5;
};

// EXR (the raw values, but for a display picture: none) and PNG, each where a path is given.
void writeOutput(const TechniqueOutput& o, const std::filesystem::path& exr, const std::filesystem::path& png) {
    if (!exr.empty() && !o.displayOnly) assets::writeImage(exr, o.image);
    if (!png.empty()) assets::writeImage(png, o.display, o.encoding);
}

void printTimings(const std::string& technique, Profiler& profiler) {
    for (const PassStatistics& s : profiler.statistics(/*wait=*/true))
        std::printf("%-12s %-22s %10.3f %10.3f %10.3f %7zu  %s\n", technique.c_str(), s.name.c_str(), s.medianMs, s.minMs,
                    s.maxMs, s.samples, toString(s.clock));
}

// The technique's outputs that its settings produce; says which it leaves out and why.
std::vector<std::string> presentOutputs(const TechniqueInfo& t, const TechniqueRun& run) {
    std::vector<std::string> names;
    for (const std::string& name : t.outputs) {
        if (const std::string why = run.missingOutput(name); why.empty())
            names.push_back(name);
        else
            std::printf("%-12s output %s skipped: %s\n", t.name.c_str(), name.c_str(), why.c_str());
    }
    return names;
}

// Empty for a directory (one that exists, or a new one without an extension), else ".exr"
// or ".png" (in any case) for an image file. Anything else is refused, rather than becoming a
// directory named like an image.
std::string imageExtension(const std::filesystem::path& out) {
    if (std::filesystem::is_directory(out)) return {};
    const std::string ext = assets::lowerExtension(out);
    if (ext == ".exr" || ext == ".png" || ext.empty()) return ext;
    throw Error(ErrorCode::InvalidArgument, "--out " + out.string() +
                                                ": not FILE.exr, FILE.png or a directory (a new directory's name takes no extension)");
}

void runRender(const RenderOptions& o) {
    if (o.frames < 1) throw Error(ErrorCode::Parse, "--frames must be >= 1");
    const ResolvedScene resolved = resolveScene(o.scene);
    const assets::LoadedScene& scene = resolved.scene;
    const Camera& camera = resolved.camera;
    const int width = resolved.width, height = resolved.height;

    std::vector<const TechniqueInfo*> selected;
    if (o.technique == "all") {
        for (const auto& entry : techniques()) selected.push_back(&entry.second);
    } else {
        const auto it = techniques().find(o.technique);
        if (it == techniques().end()) {
            std::string known;
            for (const auto& e : techniques()) known += " " + e.first;
            throw Error(ErrorCode::InvalidArgument, "unknown technique \"" + o.technique + "\" (known:" + known + ", all)");
        }
        selected.push_back(&it->second);
    }
    // Every key before any GL work: with --technique all, each technique must take it.
    for (const TechniqueInfo* t : selected)
        for (const std::string& kv : o.sets) requireSetting(*t, splitSetting(kv).first);
    const std::filesystem::path out(o.out.empty() ? "out" : o.out);
    const std::string ext = imageExtension(out);
    const bool toDirectory = ext.empty();
    if (!toDirectory && selected.size() > 1)
        throw Error(ErrorCode::InvalidArgument, "--technique all writes several images: --out must be a directory");

    headless::HeadlessContext gl;
    Context ctx(gl.contextDesc());
    // The default radius, so that distances in the outputs can be read against it.
    std::printf("scene %s, %dx%d, default radius %g, %s on %s (%s)\n", scene.name.c_str(), width, height,
                defaultRadius(scene.scene), ctx.info().version.c_str(), ctx.info().renderer.c_str(),
                toString(ctx.profiler().clock()));
    std::printf("%-12s %-22s %10s %10s %10s %7s  %s\n", "technique", "pass", "median ms", "min ms", "max ms", "frames",
                "clock");
    for (const TechniqueInfo* t : selected) {
        auto run = t->create(ctx);
        // "all" leaves out what the scene cannot have; a technique asked for by name says why.
        if (const std::string why = run->unsupported(scene.scene); !why.empty() && selected.size() > 1) {
            std::printf("%-12s skipped: %s\n", t->name.c_str(), why.c_str());
            continue;
        }
        applySettings(*t, *run, o.sets);
        for (const std::string& note : ignoredSettingNotes(*t, *run, o.sets)) std::fprintf(stderr, "note: %s\n", note.c_str());
        for (const std::string& note : ignoredInSceneNotes(*t, *run, o.sets, scene.scene))
            std::fprintf(stderr, "note: %s\n", note.c_str());
        const FrameSetup frame{scene, camera, width, height};
        run->run(frame); // warm-up: shader compilation and allocation are not timed
        ctx.profiler().reset();
        for (int i = 0; i < o.frames; ++i) run->run(frame);
        printTimings(t->name, ctx.profiler());
        const std::vector<std::string> names =
            toDirectory ? (o.output.empty() ? presentOutputs(*t, *run) : std::vector<std::string>{o.output})
                        : std::vector<std::string>{o.output.empty() ? t->outputs.front() : o.output};
        for (const TechniqueOutput& output : run->outputs(names)) {
            if (toDirectory) {
                const std::string stem = t->name + "_" + output.name;
                writeOutput(output, out / (stem + ".exr"), out / (stem + ".png"));
            } else {
                if (ext == ".exr" && output.displayOnly)
                    throw Error(ErrorCode::InvalidArgument, t->name + " output " + output.name +
                                                                " is a display picture (tone mapped, encoded): write it as .png");
                writeOutput(output, ext == ".exr" ? out : std::filesystem::path{}, ext == ".png" ? out : std::filesystem::path{});
            }
        }
    }
    std::printf("wrote %s\n", out.string().c_str());
}

} // namespace

void addRenderCommand(CLI::App& app) {
    auto options = std::make_shared<RenderOptions>();
    CLI::App* cmd = app.add_subcommand("render", "Render a technique's output buffers headless (EXR and/or PNG)");
    addSceneOptions(*cmd, options->scene);
    cmd->add_option("--technique", options->technique, "Technique name, or 'all'")->capture_default_str();
    cmd->add_option("--set", options->sets, "Technique setting key=value (repeatable; `obscura info` lists each technique's keys)");
    cmd->add_option("--output", options->output, "Output buffer (default: the technique's first; a directory gets all)");
    cmd->add_option("--out", options->out, "FILE.exr, FILE.png, or a directory")->required();
    cmd->add_option("--frames", options->frames, "Timed frames after one warm-up frame")->capture_default_str();
    cmd->callback([options] { runRender(*options); });
}

void addInfoCommand(CLI::App& app) {
    CLI::App* cmd = app.add_subcommand("info", "Show the GL context, techniques and built-in scenes");
    cmd->callback([] {
        headless::HeadlessContext gl;
        Context ctx(gl.contextDesc());
        const ContextInfo& i = ctx.info();
        std::printf("GL %s (%s profile), GLSL %s\nrenderer %s, vendor %s, EGL platform %s\nprofiler clock %s\n",
                    i.version.c_str(), i.coreProfile ? "core" : "compatibility", i.glslVersion.c_str(), i.renderer.c_str(),
                    i.vendor.c_str(), gl.platform().c_str(), toString(ctx.profiler().clock()));
        std::printf("\ntechniques:\n");
        for (const auto& [name, t] : techniques()) {
            std::printf("  %-16s %s\n", name.c_str(), t.description.c_str());
            std::string outs;
            for (const auto& o : t.outputs) outs += " " + o;
            std::printf("  %-16s outputs:%s\n", "", outs.c_str());
            for (const auto& s : t.settings)
                std::printf("  %-16s --set %s (%s%s%s%s%s): %s\n", "", s.key.c_str(), s.range.c_str(), s.unit.empty() ? "" : " ",
                            s.unit.c_str(), s.defaultValue.empty() ? "" : "; default ", s.defaultValue.c_str(),
                            s.description.c_str());
        }
        std::printf("\nbuilt-in scenes:");
        for (const auto& n : assets::builtinSceneNames()) std::printf(" %s", n.c_str());
        std::printf("\n");
    });
}

} // namespace obscura::cli
