// obscura bench: scene x technique x preset -> time per pass and error against the reference.
#include "commands.hpp"
#include "obscura/assets.hpp"
#include "obscura/error.hpp"
#include "obscura/headless.hpp"
#include "obscura/metrics.hpp"
#include "obscura/profiler.hpp"
#include "obscura/reference.hpp"
#include "scene_options.hpp"
#include "technique_registry.hpp"
#include "voxel_bench.hpp"

#include <fnmatch.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <thread>

namespace obscura::cli {
namespace {

struct BenchOptions {
    std::vector<std::string> scenes{"cornell"};
    //! Each lights every scene once more, for the techniques that need an environment.
    std::vector<std::string> environments;
    std::string techniques = "*";
    std::string presets; //!< comma-separated; empty = every preset of each technique
    std::string size = "128x128";
    int frames = 20;
    int spp = 1024;
    std::string cache;
    bool noCache = false; //!< a machine without an image writer (OBSCURA_WITH_OPENIMAGEIO=OFF)
    std::string out = "out/bench";
    bool referencePerformance = false;
    bool voxels = false;
    bool images = false; //!< also write each measured output and its reference (OUT/images)
    std::vector<std::string> overrides; //!< KEY=VALUE after each preset's own settings
    //! Each a comma-separated KEY=VALUE list: every preset runs once more with it, after the
    //! overrides, timed in turn with the preset itself (paired comparisons of one setting).
    std::vector<std::string> variants;
    VoxelBenchOptions voxel;
    std::string voxelResolutions = "128,512", voxelTargets = "1,4,8";
};

// The CSV columns of the design map, then extras.
const char* const kColumns[] = {"scene",    "technique", "preset",   "width",    "height",         "quantity",
                                "clock",    "gpu_ms",    "cpu_ms",   "rmse",     "relmse",         "ssim",
                                "max_abs",  "nan_count", "ref_noise_rmse", "mse", "psnr", "mean_abs",
                                "inf_count", "ref_spp",  "frames",   "renderer", "false_shadow", "false_light",
                                "umbra_leak", "memory_bytes", "shimmer", "variant"};

// A CSV field: quoted (quotes doubled) when it holds a comma, a quote or a line break, as
// RFC 4180 has it ("llvmpipe (LLVM 15.0.6, 256 bits)").
std::string csvField(const std::string& text) {
    if (text.find_first_of(",\"\n") == std::string::npos) return text;
    std::string quoted = "\"";
    for (const char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
    return quoted + "\"";
}

// A reference::Shadow's channel 0, with `mask` narrowed to the pixels its channel 1 marks
// (the light reaches the surface there: lit or shadowed).
Image shadowReference(const Image& shadow, Image& mask) {
    Image lit;
    lit.width = shadow.width;
    lit.height = shadow.height;
    lit.channels = 1;
    lit.pixels.resize(std::size_t(shadow.width) * std::size_t(shadow.height));
    for (std::size_t i = 0; i < lit.pixels.size(); ++i) {
        lit.pixels[i] = shadow.pixels[2 * i];
        if (shadow.pixels[2 * i + 1] == 0.0f) mask.pixels[i] = 0.0f;
    }
    return lit;
}

// The channels `channels` of `image`, in that order (Measurement::referenceChannels).
Image channelsOf(const Image& image, const std::vector<int>& channels) {
    Image out{image.width, image.height, int(channels.size()), {}};
    out.pixels.resize(std::size_t(image.width) * std::size_t(image.height) * channels.size());
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
            for (std::size_t c = 0; c < channels.size(); ++c) out.at(x, y, int(c)) = image.at(x, y, channels[c]);
    return out;
}

// MSE(A, B) / 4 of the reference's halves over `channels` of the pixels `mask` marks: the
// noise floor of a measurement that compares those (Reference::noiseMse takes every channel of
// every evaluated pixel).
double halvesNoise(const reference::Reference& ref, const std::vector<int>& channels, const Image& mask) {
    double sum = 0.0;
    std::size_t n = 0;
    for (int y = 0; y < ref.halfA.height; ++y)
        for (int x = 0; x < ref.halfA.width; ++x)
            for (int c : channels) {
                if (mask.at(x, y, 0) == 0.0f) continue;
                const double d = double(ref.halfA.at(x, y, c)) - ref.halfB.at(x, y, c);
                sum += d * d;
                ++n;
            }
    return n ? sum / double(n) / 4.0 : 0.0;
}

// Fractions of the masked pixels that a hard mask gets wrong.
struct Misclassified {
    double falseShadow = 0.0, falseLight = 0.0;
};
Misclassified misclassified(const Image& value, const Image& expected, const Image& mask) {
    std::size_t pixels = 0, falseShadow = 0, falseLight = 0;
    for (std::size_t i = 0; i < mask.pixels.size(); ++i) {
        if (!(mask.pixels[i] > 0.0f)) continue;
        ++pixels;
        const bool lit = value.pixels[i] >= 0.5f, truth = expected.pixels[i] >= 0.5f;
        falseShadow += truth && !lit ? 1 : 0;
        falseLight += !truth && lit ? 1 : 0;
    }
    if (pixels == 0) return {};
    return {double(falseShadow) / double(pixels), double(falseLight) / double(pixels)};
}

// The largest value a shadow mask keeps deep in the umbra: over the masked pixels whose
// reference is 0 with every masked pixel within kUmbraMargin pixels also 0, so that a
// filter's blur across the shadow's edge does not count. Negative: no such pixel.
constexpr int kUmbraMargin = 3;
double umbraLeak(const Image& value, const Image& expected, const Image& mask) {
    const int w = value.width, h = value.height;
    double leak = -1.0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            bool deep = mask.at(x, y, 0) > 0.0f && expected.at(x, y, 0) == 0.0f;
            for (int dy = -kUmbraMargin; dy <= kUmbraMargin && deep; ++dy)
                for (int dx = -kUmbraMargin; dx <= kUmbraMargin && deep; ++dx) {
                    const int u = std::clamp(x + dx, 0, w - 1), v = std::clamp(y + dy, 0, h - 1);
                    deep = !(mask.at(u, v, 0) > 0.0f) || expected.at(u, v, 0) == 0.0f;
                }
            if (deep) leak = std::max(leak, double(value.at(x, y, 0)));
        }
    return leak;
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return n == 0 ? 0.0 : (n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]));
}

std::vector<std::string> split(const std::string& s) {
    std::vector<std::string> out;
    std::stringstream in(s);
    std::string item;
    while (std::getline(in, item, ','))
        if (!item.empty()) out.push_back(item);
    return out;
}

// Primary-ray hits as the reference for positions and normals (exact: no noise).
Image geometryReference(const reference::ShadingPoints& pts, Measurement::Geometry g, Image& mask) {
    Image img;
    img.width = pts.width;
    img.height = pts.height;
    img.channels = 3;
    img.pixels.assign(pts.points.size() * 3, 0.0f);
    for (std::size_t i = 0; i < pts.points.size(); ++i) {
        const auto& p = pts.points[i];
        if (!p.surface()) {
            mask.pixels[i] = 0.0f;
            continue;
        }
        const glm::dvec3 v = g == Measurement::Geometry::Position ? p.position : p.normal;
        for (int c = 0; c < 3; ++c) img.pixels[i * 3 + static_cast<std::size_t>(c)] = static_cast<float>(v[c]);
    }
    return img;
}

Image gbufferMask(const GBufferSamples& s) {
    Image m;
    m.width = s.viewPositions.width;
    m.height = s.viewPositions.height;
    m.channels = 1;
    m.pixels.resize(static_cast<std::size_t>(m.width) * m.height);
    for (std::size_t i = 0; i < m.pixels.size(); ++i) m.pixels[i] = s.viewPositions.pixels[i * 4 + 3] > 0.0f ? 1.0f : 0.0f;
    return m;
}

struct Row {
    nlohmann::ordered_json fields;
    nlohmann::json passes;
    nlohmann::ordered_json memory;   //!< bytes per module (shadow techniques: per pass) after the timed frames
    nlohmann::ordered_json settings; //!< the preset's and --set's key: value, the last one set of each key
};

// One timed run of a preset: its settings, then --set's, then a --variant's (empty: none).
struct PresetRun {
    const Preset* preset;
    std::string variant;                //!< as given to --variant
    std::vector<std::string> keyValues; //!< --set's KEY=VALUE, then the variant's

    // What the run was given: the preset's settings, then keyValues (a later value of a key
    // replaces an earlier one, as in the run itself).
    nlohmann::ordered_json settings() const {
        nlohmann::ordered_json settings = nlohmann::ordered_json::object();
        for (const auto& [key, value] : preset->settings) settings[key] = value;
        for (const std::string& kv : keyValues) {
            const auto [key, value] = splitSetting(kv);
            settings[key] = value;
        }
        return settings;
    }
};

class Bench {
public:
    explicit Bench(const BenchOptions& o) : o_(o) {
        if (o.frames < 20) throw Error(ErrorCode::Parse, "--frames must be >= 20 (the median of at least 20 warm frames)");
        for (std::size_t i = 0; i < o.variants.size(); ++i) {
            const std::string& v = o.variants[i];
            if (split(v).empty() || std::find(o.variants.begin(), o.variants.begin() + i, v) != o.variants.begin() + i)
                throw Error(ErrorCode::Parse, "--variant '" + v + "': each variant must be a new, non-empty KEY=VALUE list");
            for (const std::string& kv : split(v)) splitSetting(kv); // throws for an item without '='
        }
        // Every key of --set and --variant is one of each benched technique's: refused now, not
        // after the scenes before it have run.
        for (const auto& [name, info] : techniques()) {
            if (fnmatch(o.techniques.c_str(), name.c_str(), 0) != 0) continue;
            for (const std::string& kv : o.overrides) requireSetting(info, splitSetting(kv).first);
            for (const std::string& v : o.variants)
                for (const std::string& kv : split(v)) requireSetting(info, splitSetting(kv).first);
        }
        cache_ = o.cache.empty() ? std::filesystem::path(o.out) / "reference-cache" : std::filesystem::path(o.cache);
    }

    // The scene as it is for every technique that runs without an environment, then once per
    // --environment for those that need one (the others' references keep their cache keys).
    void runScene(const std::string& sceneName, Context& ctx) {
        runScene(sceneName, "", ctx);
        for (const std::string& environment : o_.environments) runScene(sceneName, environment, ctx);
    }

    void runScene(const std::string& sceneName, const std::string& environment, Context& ctx) {
        SceneOptions so;
        so.scene = sceneName;
        so.size = o_.size;
        so.environment = environment;
        ResolvedScene r = resolveScene(so);
        if (!environment.empty()) r.scene.name += "+" + std::filesystem::path(parseEnvironment(environment).path).stem().string();
        Scene withoutEnvironment = r.scene.scene;
        withoutEnvironment.environment.reset();
        std::vector<std::pair<std::string, const TechniqueInfo*>> chosen;
        for (const auto& [name, info] : techniques()) {
            if (fnmatch(o_.techniques.c_str(), name.c_str(), 0) != 0) continue;
            const auto run = info.create(ctx);
            // With an environment given, only the techniques that need one run again.
            if (!environment.empty() && run->unsupported(withoutEnvironment).empty()) continue;
            if (const std::string why = run->unsupported(r.scene.scene); !why.empty()) {
                if (o_.environments.empty()) std::printf("  %-10s skipped: %s\n", name.c_str(), why.c_str());
                continue;
            }
            chosen.push_back({name, &info});
        }
        if (chosen.empty() && !environment.empty()) return;
        const reference::RayScene rays(r.scene.scene);
        const reference::ShadingPoints cameraPoints = reference::fromCamera(rays, r.camera, r.width, r.height);
        std::printf("scene %s: %zu triangles, %dx%d\n", r.scene.name.c_str(), rays.triangleCount(), r.width, r.height);
        for (const auto& [name, info] : chosen)
            for (const std::vector<PresetRun>& group : presetGroups(*info)) runTechnique(ctx, r, rays, cameraPoints, *info, group);
    }

    void referencePerformance(const std::string& sceneName) {
        SceneOptions so;
        so.scene = sceneName;
        so.size = "256x256";
        const ResolvedScene r = resolveScene(so);
        const reference::RayScene rays(r.scene.scene);
        const reference::ShadingPoints pts = reference::fromCamera(rays, r.camera, r.width, r.height);
        const Bounds b = rays.bounds();
        // A fifth of the scene's diagonal, rounded to two significant digits for the report.
        const double diagonal = 0.2 * glm::length(glm::dvec3(b.max - b.min));
        const double unit = std::pow(10.0, std::floor(std::log10(diagonal)) - 1);
        const double radius = std::round(diagonal / unit) * unit;
        reference::RenderSettings s;
        s.samplesPerPixel = 256;
        s.progress = true;
        const reference::Reference ref = reference::render(rays, pts, reference::AmbientOcclusion{radius, true}, s);
        const double rate = static_cast<double>(ref.rays) / ref.seconds;
        perf_.push_back({{"scene", sceneName}, {"width", 256}, {"height", 256}, {"spp", 256},
                         {"quantity", reference::describe(reference::AmbientOcclusion{radius, true})},
                         {"rays", ref.rays}, {"seconds", ref.seconds}, {"rays_per_second", rate},
                         {"threads", static_cast<int>(std::max(1u, std::thread::hardware_concurrency()))}});
        std::printf("reference performance, %s AO 256x256 x 256 spp: %.2f M rays/s\n", sceneName.c_str(), rate * 1e-6);
    }

    void write() const {
        const std::filesystem::path dir(o_.out);
        std::filesystem::create_directories(dir);
        std::ofstream csv(dir / "bench.csv");
        for (std::size_t i = 0; i < std::size(kColumns); ++i) csv << (i ? "," : "") << kColumns[i];
        csv << "\n";
        nlohmann::json rows = nlohmann::json::array();
        for (const Row& row : rows_) {
            for (std::size_t i = 0; i < std::size(kColumns); ++i) {
                const auto& v = row.fields.at(kColumns[i]);
                // JSON has no NaN or Inf (they are written as null): the CSV spells them out.
                const bool nonFinite = v.is_number_float() && !std::isfinite(v.get<double>());
                const std::string text = v.is_string() ? csvField(v.get<std::string>())
                                         : nonFinite   ? (std::isnan(v.get<double>()) ? "nan" : "inf")
                                                       : v.dump();
                csv << (i ? "," : "") << text;
            }
            csv << "\n";
            nlohmann::json j = row.fields;
            j["passes"] = row.passes;
            j["memory"] = row.memory;
            j["settings"] = row.settings;
            rows.push_back(j);
        }
        nlohmann::json doc = {{"rows", rows}, {"reference_performance", perf_}};
        if (!voxel_.is_null()) {
            doc["voxel"] = nlohmann::json::parse(voxel_.dump()); // (key order only matters to the CSVs)
            for (const char* table : {"voxelization", "traversal"}) writeTableCsv(dir / (std::string(table) + ".csv"), voxel_[table]);
        }
        std::ofstream(dir / "bench.json") << doc.dump(2) << "\n";
        std::printf("wrote %s and %s (%zu rows)\n", (dir / "bench.csv").string().c_str(), (dir / "bench.json").string().c_str(),
                    rows_.size());
    }

    void benchVoxels(Context& ctx) { voxel_ = benchVoxelizer(ctx, o_.voxel); }

private:
    // The scalar fields of JSON rows as CSV, in the first row's order.
    static void writeTableCsv(const std::filesystem::path& path, const nlohmann::ordered_json& rows) {
        std::ofstream csv(path);
        if (rows.empty()) return;
        std::vector<std::string> keys;
        for (const auto& [key, value] : rows.front().items())
            if (!value.is_structured()) keys.push_back(key);
        for (std::size_t i = 0; i < keys.size(); ++i) csv << (i ? "," : "") << keys[i];
        csv << "\n";
        for (const auto& row : rows) {
            for (std::size_t i = 0; i < keys.size(); ++i) {
                const auto& v = row.at(keys[i]);
                csv << (i ? "," : "") << (v.is_string() ? csvField(v.get<std::string>()) : v.dump());
            }
            csv << "\n";
        }
    }

    // The wanted presets of a technique, each alone, except that a preset X and X_half (the
    // same rays at half resolution) are timed together: their ratio is the half-resolution
    // study's verdict, so they take their frames in turn and share the machine's drift. Each
    // --variant of a group's presets joins the group for the same reason: on llvmpipe two
    // processes timing the same passes differ by up to half (scripts/report.sh's geometry-tiles
    // study: gi.screen at 1.44x apart, 1.02x when timed in turn).
    std::vector<std::vector<PresetRun>> presetGroups(const TechniqueInfo& info) const {
        const auto wanted = split(o_.presets);
        const auto isWanted = [&](const std::string& name) {
            return wanted.empty() || std::find(wanted.begin(), wanted.end(), name) != wanted.end();
        };
        const auto find = [&](const std::string& name) -> const Preset* {
            for (const Preset& p : info.presets)
                if (p.name == name && isWanted(name)) return &p;
            return nullptr;
        };
        std::vector<std::vector<PresetRun>> groups;
        for (const Preset& preset : info.presets) {
            if (!isWanted(preset.name)) continue;
            const std::string suffix = "_half";
            const bool half = preset.name.size() > suffix.size() && preset.name.ends_with(suffix);
            if (half && find(preset.name.substr(0, preset.name.size() - suffix.size()))) continue; // timed with X
            std::vector<const Preset*> members{&preset};
            if (const Preset* partner = half ? nullptr : find(preset.name + suffix)) members.push_back(partner);
            std::vector<PresetRun> group;
            for (const Preset* member : members) {
                group.push_back({member, "", o_.overrides});
                for (const std::string& variant : o_.variants) {
                    std::vector<std::string> keyValues = o_.overrides;
                    for (const std::string& kv : split(variant)) keyValues.push_back(kv);
                    group.push_back({member, variant, keyValues});
                }
            }
            groups.push_back(group);
        }
        return groups;
    }

    struct Timing {
        double gpuMs = 0.0;      //!< the sum of the passes' medians
        double cpuMs = 0.0;      //!< median wall time of a frame's calls
        nlohmann::json passes;   //!< per pass: median, min, max over the frames
    };

    // Warms each run up, then times `frames` frames of each, the runs taking turns frame by
    // frame. The profiler is read and reset after every frame, so each pass's samples are
    // its own run's.
    std::vector<Timing> timeInTurn(Context& ctx, const std::vector<std::unique_ptr<TechniqueRun>>& runs, const FrameSetup& frame) {
        // Warm-up, not timed: compilation and allocation, and on a GPU half a second of
        // frames, so that its clocks have left the idle state the CPU reference put it in
        // (an H100 timed from idle gave the same G-buffer pass 0.26 ms in one row, 1.48 in another).
        const double warmupMs = ctx.profiler().clock() == ClockSource::GpuTimestamp ? 500.0 : 0.0;
        for (const auto& run : runs) {
            const auto warmupStart = std::chrono::steady_clock::now();
            do {
                run->run(frame);
                ctx.profiler().statistics(/*wait=*/true);
            } while (std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - warmupStart).count() < warmupMs);
        }
        ctx.profiler().reset();
        std::vector<std::vector<double>> cpu(runs.size());
        std::vector<std::vector<std::pair<std::string, std::vector<double>>>> passes(runs.size()); // first-seen order
        for (int i = 0; i < o_.frames; ++i)
            for (std::size_t k = 0; k < runs.size(); ++k) {
                const auto t0 = std::chrono::steady_clock::now();
                runs[k]->run(frame);
                cpu[k].push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
                for (const PassStatistics& s : ctx.profiler().statistics(/*wait=*/true)) {
                    auto it = std::find_if(passes[k].begin(), passes[k].end(), [&](const auto& p) { return p.first == s.name; });
                    if (it == passes[k].end()) it = passes[k].insert(passes[k].end(), {s.name, {}});
                    it->second.push_back(s.medianMs); // this frame's only sample
                }
                ctx.profiler().reset();
            }
        std::vector<Timing> out(runs.size());
        for (std::size_t k = 0; k < runs.size(); ++k) {
            out[k].cpuMs = median(cpu[k]);
            out[k].passes = nlohmann::json::array();
            for (const auto& [name, ms] : passes[k]) {
                out[k].gpuMs += median(ms);
                out[k].passes.push_back({{"pass", name}, {"median_ms", median(ms)},
                                         {"min_ms", *std::min_element(ms.begin(), ms.end())},
                                         {"max_ms", *std::max_element(ms.begin(), ms.end())}, {"samples", ms.size()}});
            }
        }
        return out;
    }

    void runTechnique(Context& ctx, const ResolvedScene& r, const reference::RayScene& rays,
                      const reference::ShadingPoints& cameraPoints, const TechniqueInfo& info,
                      const std::vector<PresetRun>& presets) {
        std::vector<std::unique_ptr<TechniqueRun>> runs;
        for (const PresetRun& preset : presets) {
            runs.push_back(info.create(ctx));
            for (const auto& [key, value] : preset.preset->settings) runs.back()->set(key, value);
            applySettings(info, *runs.back(), preset.keyValues);
            // Once per run, not per scene: e.g. refine_threshold at a full-resolution preset.
            for (const std::string& note : ignoredSettingNotes(info, *runs.back(), preset.keyValues))
                if (notes_.insert(preset.preset->name + ": " + note).second)
                    std::printf("  note: preset %s: %s\n", preset.preset->name.c_str(), note.c_str());
            for (const std::string& note : ignoredInSceneNotes(info, *runs.back(), preset.keyValues, r.scene.scene))
                if (notes_.insert(preset.preset->name + " " + r.scene.name + ": " + note).second)
                    std::printf("  note: preset %s on %s: %s\n", preset.preset->name.c_str(), r.scene.name.c_str(), note.c_str());
        }
        const std::vector<Timing> timings = timeInTurn(ctx, runs, FrameSetup{r.scene, r.camera, r.width, r.height});
        groupReferences_.clear();
        for (std::size_t k = 0; k < runs.size(); ++k) measure(ctx, r, rays, cameraPoints, info, presets[k], *runs[k], timings[k]);
        groupReferences_.clear();
    }

    // A reference, rendered once per preset group: its variants (and X and X_half) measure the
    // same G-buffer points, and without a cache on disk (--no-cache) each would render it
    // again (at 1920x1080 and 256 spp, minutes on a GPU machine's CPU).
    const reference::Reference& groupReference(const reference::RayScene& rays, const reference::ShadingPoints& points,
                                               const reference::Quantity& quantity, const reference::RenderSettings& rs) {
        const std::uint64_t key = reference::referenceKey(rays, points, quantity, rs);
        auto it = groupReferences_.find(key);
        if (it == groupReferences_.end())
            it = groupReferences_
                     .emplace(key, o_.noCache ? reference::render(rays, points, quantity, rs)
                                              : reference::renderCached(cache_, rays, points, quantity, rs))
                     .first;
        return it->second;
    }

    void measure(Context& ctx, const ResolvedScene& r, const reference::RayScene& rays,
                 const reference::ShadingPoints& cameraPoints, const TechniqueInfo& info, const PresetRun& presetRun,
                 TechniqueRun& run, const Timing& timing) {
        const Preset& preset = *presetRun.preset;
        const double gpu = timing.gpuMs;
        const GBufferSamples samples = run.samples();
        const Image samplesMask = gbufferMask(samples);
        const auto geometryPixels = std::count(samplesMask.pixels.begin(), samplesMask.pixels.end(), 1.0f);
        const auto counts = run.counts();
        const reference::ShadingPoints gbufferPoints =
            reference::fromGBuffer(rays, r.camera, samples.viewPositions, samples.viewNormals);
        for (const Measurement& m : run.measurements()) {
            Image mask = samplesMask, expected;
            double noise = 0.0;
            int spp = 0;
            if (m.geometry != Measurement::Geometry::None) {
                expected = geometryReference(cameraPoints, m.geometry, mask);
            } else {
                reference::RenderSettings rs;
                rs.samplesPerPixel = o_.spp;
                rs.progress = true;
                const reference::Reference& ref = groupReference(rays, gbufferPoints, *m.reference, rs);
                expected = ref.value;
                noise = ref.noiseMse;
                spp = ref.samplesPerPixel;
                if (m.shadowMask) expected = shadowReference(ref.value, mask);
                if (!m.referenceChannels.empty()) {
                    expected = channelsOf(expected, m.referenceChannels);
                    noise = halvesNoise(ref, m.referenceChannels, mask); // the compared pixels' and channels' own noise
                }
            }
            metrics::Options mo;
            mo.mask = &mask;
            const metrics::Report e = metrics::compare(m.value, expected, mo);
            if (o_.images) writeMeasurementImages(r.scene.name + "_" + info.name + "_" + preset.name + "_" + m.quantity +
                                                 (presetRun.variant.empty() ? "" : "_" + presetRun.variant),
                                             m.value, expected);
            Row row;
            row.fields = {{"scene", r.scene.name},   {"technique", info.name},  {"preset", preset.name},
                          {"width", r.width},        {"height", r.height},      {"quantity", m.quantity},
                          {"clock", toString(ctx.profiler().clock())},       {"gpu_ms", gpu},
                          {"cpu_ms", timing.cpuMs},   {"rmse", e.rmse},          {"relmse", e.relMse},
                          {"ssim", e.ssim},          {"max_abs", e.maxAbs},     {"nan_count", e.nanCount},
                          {"ref_noise_rmse", std::sqrt(noise)}, {"mse", e.mse}, {"psnr", e.psnr},
                          {"mean_abs", e.meanAbs},   {"inf_count", e.infCount}, {"ref_spp", spp},
                          {"frames", o_.frames},     {"renderer", ctx.info().renderer},
                          {"false_shadow", ""},      {"false_light", ""},      {"umbra_leak", ""},     {"shimmer", ""},
                          {"variant", presetRun.variant}};
            if (m.shimmer) row.fields["shimmer"] = *m.shimmer;
            // JSON only (the CSV's columns are fixed): what explains a row's time.
            row.fields["geometry_pixels"] = geometryPixels;
            for (const auto& [name, n] : counts) row.fields[name] = n;
            std::size_t memoryBytes = 0;
            nlohmann::ordered_json memory = nlohmann::ordered_json::object();
            for (const auto& [module, bytes] : run.memory()) {
                memory[module] = bytes;
                memoryBytes += bytes;
            }
            row.fields["memory_bytes"] = memoryBytes;
            row.memory = memory;
            if (m.shadowMask) {
                const double leak = umbraLeak(m.value, expected, mask);
                if (leak >= 0.0) row.fields["umbra_leak"] = leak;
            }
            if (m.classify) {
                const Misclassified wrong = misclassified(m.value, expected, mask);
                row.fields["false_shadow"] = wrong.falseShadow;
                row.fields["false_light"] = wrong.falseLight;
            }
            row.passes = timing.passes;
            row.settings = presetRun.settings();
            std::printf("  %-10s %-8s %-10s %8.3f ms (%s)  rmse %.4g  relmse %.4g  ssim %.4f  ref noise rmse %.3g%s%s\n",
                        info.name.c_str(), preset.name.c_str(), m.quantity.c_str(), gpu, toString(ctx.profiler().clock()),
                        e.rmse, e.relMse, e.ssim, std::sqrt(noise), presetRun.variant.empty() ? "" : "  variant ",
                        presetRun.variant.c_str());
            rows_.push_back(std::move(row));
        }
    }

    // OUT/images/NAME.exr and NAME_reference.exr: where the error is, for a look. Scene
    // names come from files and may hold separators or spaces: those become '_'.
    void writeMeasurementImages(std::string name, const Image& value, const Image& expected) const {
        for (char& c : name)
            if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '-' && c != '_') c = '_';
        const std::filesystem::path dir = std::filesystem::path(o_.out) / "images";
        std::filesystem::create_directories(dir);
        assets::writeImage(dir / (name + ".exr"), value);
        assets::writeImage(dir / (name + "_reference.exr"), expected);
    }

    BenchOptions o_;
    std::filesystem::path cache_;
    std::map<std::uint64_t, reference::Reference> groupReferences_; //!< groupReference's, for one group
    std::vector<Row> rows_;
    std::set<std::string> notes_; //!< the ignored-setting notes printed so far
    nlohmann::json perf_ = nlohmann::json::array();
    nlohmann::ordered_json voxel_;
};

std::vector<int> parseIntList(const std::string& option, const std::string& text) {
    std::vector<int> out;
    for (const std::string& item : split(text)) {
        try {
            out.push_back(std::stoi(item));
        } catch (const std::exception&) {
            throw Error(ErrorCode::Parse, option + " " + text + ": expected comma-separated integers");
        }
    }
    return out;
}

void runBench(BenchOptions o) {
    o.voxel.frames = o.frames;
    o.voxel.resolutions = parseIntList("--voxel-resolutions", o.voxelResolutions);
    o.voxel.targets = parseIntList("--voxel-targets", o.voxelTargets);
    o.voxel.traversalScenes = o.scenes;
    if (o.voxel.scene.empty()) o.voxel.scene = o.scenes.back();
    Bench bench(o);
    headless::HeadlessContext gl;
    Context ctx(gl.contextDesc());
    std::printf("%s on %s, clock %s\n", ctx.info().version.c_str(), ctx.info().renderer.c_str(),
                toString(ctx.profiler().clock()));
    for (const auto& scene : o.scenes) bench.runScene(scene, ctx);
    if (o.referencePerformance)
        for (const auto& scene : o.scenes) bench.referencePerformance(scene);
    if (o.voxels) bench.benchVoxels(ctx);
    bench.write();
}

} // namespace

void addBenchCommand(CLI::App& app) {
    auto o = std::make_shared<BenchOptions>();
    CLI::App* cmd = app.add_subcommand("bench", "Time every technique and measure its error against the reference");
    cmd->add_option("--scene", o->scenes, "Scene(s): built-in name, JSON scene or mesh file (repeatable)")
        ->capture_default_str();
    cmd->add_option("--environment", o->environments,
                    "FILE[,intensity[,rotation_deg]] (repeatable): each scene again, lit by it, for the techniques that need "
                    "an environment");
    cmd->add_option("--techniques", o->techniques, "Glob of technique names")->capture_default_str();
    cmd->add_option("--presets", o->presets, "Comma-separated presets (default: all of each technique); X and X_half, when both run, take their timed frames in turn");
    cmd->add_option("--size", o->size, "Image size WxH")->capture_default_str();
    cmd->add_option("--frames", o->frames, "Timed frames after the warm-up (one frame; half a second of frames on a GPU) (>= 20)")->capture_default_str();
    cmd->add_option("--spp", o->spp, "Reference samples per pixel")->capture_default_str();
    cmd->add_option("--cache", o->cache, "Reference cache directory (default OUT/reference-cache)");
    cmd->add_flag("--no-cache", o->noCache, "Render every reference afresh and store none");
    cmd->add_option("--set", o->overrides, "KEY=VALUE after each preset's settings (every technique benched must take it)");
    cmd->add_option("--variant", o->variants,
                    "Comma-separated KEY=VALUE list after --set: every preset runs once more with it, its frames timed in turn "
                    "with the preset's own (repeatable; rows carry it in the `variant` column; every technique benched must take its keys)");
    cmd->add_option("--out", o->out, "Output directory for bench.csv and bench.json")->capture_default_str();
    cmd->add_flag("--images", o->images, "Also write each measured output and its reference as OUT/images/*.exr");
    cmd->add_flag("--reference-performance", o->referencePerformance,
                  "Also time the AO reference (256x256, 256 spp) of each scene, in rays/s");
    cmd->add_flag("--voxels", o->voxels,
                  "Also time the voxelizer (voxelization.csv) and the voxel traversals on each scene (traversal.csv)");
    cmd->add_option("--voxel-scene", o->voxel.scene, "Scene to voxelize, copied to about --voxel-triangles (default: the last --scene)");
    cmd->add_option("--voxel-triangles", o->voxel.triangles, "Triangles to voxelize (whole copies of the scene, nearest count)")->capture_default_str();
    cmd->add_option("--voxel-resolutions", o->voxelResolutions, "Grid resolutions R (R x R columns)")->capture_default_str();
    cmd->add_option("--voxel-targets", o->voxelTargets, "Render-target counts k (128 k slices)")->capture_default_str();
    cmd->add_option("--voxel-segments", o->voxel.segments, "Segments per traversal measurement")->capture_default_str();
    cmd->add_option("--voxel-traversal-resolution", o->voxel.traversalResolution, "Grid resolution for the traversals")
        ->capture_default_str();
    cmd->callback([o] { runBench(*o); });
}

} // namespace obscura::cli
