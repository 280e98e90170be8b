// "media.raymarch", "media.analytic", "media.bounded", "media.froxel": the Media module on the scene's media
// (Scene::media; a JSON scene's, or a built-in fog scene), lit by the scene's lights with the
// lit G-buffer's shadow maps. Outputs: "scattering" (the in-scattered radiance alone, as the
// reference's SingleScattering), "transmittance" (exp(-tau) per channel) and "frame" (the
// G-buffer's direct radiance seen through the media: Media::apply).
#include "obscura/error.hpp"
#include "obscura/media.hpp"
#include "lit_gbuffer.hpp"
#include "technique_registry.hpp"

#include <algorithm>
#include <cmath>
#include <memory>

namespace obscura::cli {
namespace {

const std::vector<SettingInfo> kSettings = joinSettings(tableSettings(MediaSettings{}, {"method"}), LitGBuffer::settings());

// Each method's keys: the module's less those it does not read.
std::vector<SettingInfo> methodSettings(MediaMethod method) {
    std::vector<SettingInfo> rows;
    for (const SettingInfo& s : kSettings) {
        const bool analyticOnly = s.key == "integral" || s.key == "table_size";
        const bool froxelOnly = s.key == "froxel_tile" || s.key == "froxel_range";
        const bool marchOnly = s.key == "jitter" || s.key == "frame_index" || s.key == "resolution" || s.key == "blur_radius" ||
                               s.key == "blur_depth_sigma";
        const bool boundedOnly = s.key == "volume_cell";
        if (analyticOnly && method != MediaMethod::Analytic) continue;
        if (froxelOnly && method != MediaMethod::Froxel) continue;
        if (marchOnly && method != MediaMethod::RayMarch && method != MediaMethod::Bounded) continue;
        if (boundedOnly && method != MediaMethod::Bounded) continue;
        rows.push_back(s);
    }
    return rows;
}

// The thesis's step counts (20 to 200) as presets; the analytic form's "low" is its table.
std::vector<Preset> mediaPresets(MediaMethod method) {
    if (method == MediaMethod::Analytic)
        return {{"low", {{"integral", "table"}}},
                {"medium", {{"steps", "16"}}},
                {"high", {{"steps", "64"}}},
                {"ultra", {{"steps", "256"}}}};
    return {{"low", {{"steps", "20"}}}, {"medium", {{"steps", "50"}}}, {"high", {{"steps", "100"}}}, {"ultra", {{"steps", "200"}}}};
}

Image transmittanceOf(const Image& opticalDepth) {
    Image t = rgbOf(opticalDepth);
    for (float& v : t.pixels) v = std::exp(-v);
    return t;
}

class MediaRun final : public TechniqueRun {
public:
    MediaRun(Context& ctx, MediaMethod method) : ctx_(ctx), lit_(ctx), media_(ctx) { settings_.method = method; }

    void set(const std::string& key, const std::string& value) override {
        if (key == "method" || !setFromTable(settings_, key, value))
            if (!lit_.set(key, value)) unknownSetting(name(), key, methodSettings(settings_.method));
    }

    std::string unsupported(const Scene& scene) const override {
        if (scene.media.empty()) return "the scene has no media (Scene::media; a JSON scene's \"media\")";
        const bool heterogeneous = std::any_of(scene.media.begin(), scene.media.end(),
                                               [](const Medium& m) { return m.density != MediumDensity::Constant; });
        if (settings_.method == MediaMethod::Analytic && heterogeneous) return "its media are not homogeneous (the closed form's)";
        // The reference (SingleScattering) integrates one medium: the errors would compare others.
        if (scene.media.size() > 1) return "it has " + std::to_string(scene.media.size()) + " media; the tools measure one";
        return "";
    }

    void run(const FrameSetup& frame) override {
        const Scene& scene = frame.scene.scene;
        if (const std::string why = unsupported(scene); !why.empty()) throw Error(ErrorCode::InvalidArgument, name() + ": " + why);
        view_ = lit_.render(frame, GBufferSettings{frame.width, frame.height, true, {}});
        result_ = media_.run(view_, {scene.media, scene.lights, lit_.shadowMaps()}, settings_);
    }

    std::string ignoredSetting(const std::string& key) const override {
        if (key == "table_size" && settings_.integral != AnalyticIntegral::Table) return "only with integral=table";
        return lit_.ignoredSetting(key);
    }
    std::string ignoredInScene(const std::string& key, const Scene& scene) const override {
        return LitGBuffer::ignoredInScene(key, scene);
    }

    std::vector<TechniqueOutput> outputs(const std::vector<std::string>& names) override {
        std::vector<TechniqueOutput> out;
        for (const std::string& n : names) {
            if (n == "scattering") out.push_back(plainOutput(n, rgbOf(readTexture(ctx_, result_.scattering)), assets::PngEncoding::Srgb));
            else if (n == "transmittance")
                out.push_back(plainOutput(n, transmittanceOf(readTexture(ctx_, result_.opticalDepth)), assets::PngEncoding::Srgb));
            else if (n == "frame")
                out.push_back(plainOutput(n, rgbOf(readTexture(ctx_, media_.apply(result_, view_.directRadiance))),
                                          assets::PngEncoding::Srgb));
            else
                throw Error(ErrorCode::InvalidArgument, name() + " has no output \"" + n + "\" (outputs: scattering, transmittance, frame)");
        }
        return out;
    }

    GBufferSamples samples() override { return readSamples(ctx_, lit_.gbuffer(), view_); }

    std::vector<std::pair<std::string, std::size_t>> memory() const override {
        auto m = lit_.memory();
        m.push_back({"media", media_.memoryBytes()});
        return m;
    }

    // "scattering" against SingleScattering's radiance, shadowed as the scene's lights are
    // (with shadows=1: the picture's truth); for the analytic form, which has no shadows, also
    // "scattering_unshadowed", its own error where it applies. "transmittance" against the
    // mean transmittance. Scene::media[0]: the reference takes one medium.
    std::vector<Measurement> measurements() override {
        const Image scattering = rgbOf(readTexture(ctx_, result_.scattering));
        const bool shadowed = lit_.shadowMaps() != nullptr;
        std::vector<Measurement> out = {{"scattering", scattering, reference::SingleScattering{0, shadowed}}};
        out.back().referenceChannels = {0, 1, 2};
        if (settings_.method == MediaMethod::Analytic && shadowed) {
            out.push_back({"scattering_unshadowed", scattering, reference::SingleScattering{0, false}});
            out.back().referenceChannels = {0, 1, 2};
        }
        const Image t = transmittanceOf(readTexture(ctx_, result_.opticalDepth));
        Image mean{t.width, t.height, 1, std::vector<float>(std::size_t(t.width) * std::size_t(t.height))};
        for (std::size_t i = 0; i < mean.pixels.size(); ++i)
            mean.pixels[i] = (t.pixels[3 * i] + t.pixels[3 * i + 1] + t.pixels[3 * i + 2]) / 3.0f;
        out.push_back({"transmittance", mean, reference::SingleScattering{0, shadowed}});
        out.back().referenceChannels = {3};
        return out;
    }

private:
    std::string name() const {
        switch (settings_.method) {
        case MediaMethod::RayMarch: return "media.raymarch";
        case MediaMethod::Analytic: return "media.analytic";
        case MediaMethod::Bounded: return "media.bounded";
        case MediaMethod::Froxel: return "media.froxel";
        }
        return "media";
    }

    Context& ctx_;
    LitGBuffer lit_;
    Media media_;
    MediaSettings settings_;
    GBufferView view_;
    MediaView result_;
};

TechniqueInfo mediaTechnique(const std::string& name, const std::string& description, MediaMethod method) {
    const std::vector<SettingInfo> settings = methodSettings(method);
    return {name, description, {"scattering", "transmittance", "frame"}, settings,
            presetsFor(mediaPresets(method), kSettings, settings),
            [method](Context& ctx) { return std::make_unique<MediaRun>(ctx, method); }};
}

const TechniqueRegistrar raymarch(mediaTechnique(
    "media.raymarch", "Single scattering by ray marching the view ray, shadow maps at every step", MediaMethod::RayMarch));
const TechniqueRegistrar analytic(mediaTechnique(
    "media.analytic", "Single scattering from Sun et al.'s closed form (no shadows), by quadrature or table",
    MediaMethod::Analytic));
const TechniqueRegistrar bounded(mediaTechnique(
    "media.bounded", "Ray marching within the lit part of each view ray, from shadow volumes of the spot lights' maps",
    MediaMethod::Bounded));
const TechniqueRegistrar froxel(mediaTechnique(
    "media.froxel", "Volumetric fog in a froxel grid: lights once per froxel, integrated front to back", MediaMethod::Froxel));

} // namespace
} // namespace obscura::cli
