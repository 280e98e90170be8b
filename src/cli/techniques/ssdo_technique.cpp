// "ssdo": the DirectionalOcclusion module on the scene's lit G-buffer, lit by the scene's
// environment (Scene::environment: a JSON scene's, or --environment).
#include "obscura/assets.hpp"
#include "obscura/directional_occlusion.hpp"
#include "obscura/environment.hpp"
#include "obscura/error.hpp"
#include "obscura/gbuffer.hpp"
#include "lit_gbuffer.hpp"
#include "technique_registry.hpp"

#include <cstdint>
#include <cstdio>
#include <memory>
#include <optional>

namespace obscura::cli {
namespace {

const std::vector<SettingInfo> kSettings = joinSettings(
    integratorSettings(tableSettings(DirectionalOcclusionSettings{}), "r_max: how far occluders are looked for"),
    LitGBuffer::settings());

// The integrators' presets, and the medium one with the bounce (the bench measures both).
std::vector<Preset> ssdoPresets() {
    std::vector<Preset> presets = integratorPresets(false);
    Preset bounce{"medium_bounce", {{"rays", "16"}, {"steps", "8"}, {"bounce", "1"}}};
    presets.push_back(bounce);
    return presetsFor(presets, kSettings, kSettings);
}

class SsdoRun final : public TechniqueRun {
public:
    explicit SsdoRun(Context& ctx) : ctx_(ctx), lit_(ctx), ssdo_(ctx) {}

    void set(const std::string& key, const std::string& value) override {
        if (setFromTable(settings_, key, value)) {
            if (key == "radius") radius_ = settings_.radius;
            if (key == "frame_index") firstFrame_ = settings_.frameIndex;
        } else if (!lit_.set(key, value)) {
            unknownSetting("ssdo", key, kSettings);
        }
    }

    std::string unsupported(const Scene& scene) const override {
        return scene.environment ? "" : "the scene has no environment (give one with --environment FILE)";
    }

    void run(const FrameSetup& frame) override {
        const Scene& scene = frame.scene.scene;
        if (!scene.environment) throw Error(ErrorCode::InvalidArgument, "ssdo: " + unsupported(scene));
        loadEnvironment(*scene.environment);
        settings_.radius = static_cast<float>(radius_ ? *radius_ : defaultRadius(scene));
        GBufferSettings g{frame.width, frame.height, true, {}};
        g.depthLayers = depthLayersFor(settings_.thicknessMode);
        // SSDO lights the pixels with the scene's lights itself (their shadow maps corrected in
        // screen space): the G-buffer keeps only emission.
        lit_.setReflective(settings_.vplGrid > 0);
        view_ = lit_.renderUnlit(frame, g);
        settings_.frameIndex = firstFrame_ + (settings_.temporal.enabled ? framesRun_++ : 0u);
        DirectionalOcclusionInputs inputs{environment_.get(), scene.lights, lit_.shadowMaps(), lit_.shadowFilter(), &scene};
        result_ = ssdo_.run(view_, inputs, settings_);
    }

    std::string ignoredSetting(const std::string& key) const override {
        if (key == "bounce_strength" && !settings_.bounce) return "only with bounce=1";
        if ((key == "shadow_correction" || key == "vpl_grid") && !lit_.shadowed()) return "only with shadows=1";
        if ((key == "extra_view_scale" || key == "extra_view_offset") && settings_.extraViews == 0)
            return "only with extra_views > 0";
        if (key == "march" && settings_.extraViews > 0) return "extra views march in view space";
        const std::string why = ignoredIntegratorSetting(key, settings_.resolution, settings_.blurRadius, std::nullopt);
        return why.empty() ? lit_.ignoredSetting(key) : why;
    }
    std::string ignoredInScene(const std::string& key, const Scene& scene) const override {
        return LitGBuffer::ignoredInScene(key, scene);
    }

    std::vector<TechniqueOutput> outputs(const std::vector<std::string>& names) override {
        std::vector<TechniqueOutput> out;
        for (const std::string& name : names) {
            if (name != "direct" && name != "indirect")
                throw Error(ErrorCode::InvalidArgument, "ssdo has no output \"" + name + "\" (outputs: direct, indirect)");
            if (name == "indirect" && !result_.indirect)
                throw Error(ErrorCode::InvalidArgument, "ssdo: output \"indirect\" needs --set bounce=1 or vpl_grid > 0");
            const TextureView& t = name == "direct" ? result_.direct : result_.indirect;
            out.push_back(plainOutput(name, rgbOf(readTexture(ctx_, t)), assets::PngEncoding::Srgb));
        }
        return out;
    }
    std::string missingOutput(const std::string& name) const override {
        return name == "indirect" && !settings_.bounce && settings_.vplGrid == 0 ? "needs bounce=1 or vpl_grid > 0" : "";
    }

    GBufferSamples samples() override { return readSamples(ctx_, gbuffer_, view_); }

    std::vector<std::pair<std::string, std::size_t>> memory() const override {
        auto m = lit_.memory();
        m.insert(m.end(), {{"ssdo", ssdo_.memoryBytes()}, {"environment", environment_ ? environment_->memoryBytes() : 0}});
        return m;
    }

    std::vector<Measurement> measurements() override {
        // "direct": against image-based light with every occluder (SSDO sees those within
        // r_max only, and on screen) plus the lights' shadowed direct light; "direct_r": the
        // environment's occluders within r_max, the method's own error. "indirect": the bounce
        // of the environment's and the lights' light.
        const Image direct = rgbOf(readTexture(ctx_, result_.direct));
        reference::ImageBasedLight all;
        all.lights = true;
        reference::ImageBasedLight within = all;
        within.radius = settings_.radius;
        std::vector<Measurement> out = {{"direct", direct, all}, {"direct_r", direct, within}};
        if (result_.indirect) {
            // The bounce gathers within r_max; the VPLs' light comes from any distance.
            reference::IndirectLight bounce{settings_.vplGrid > 0 ? reference::kInfinity : double(settings_.radius)};
            bounce.environment = settings_.bounce;
            out.push_back({"indirect", rgbOf(readTexture(ctx_, result_.indirect)), bounce});
        }
        return out;
    }

private:
    // Precomputed once per file; intensity and rotation are applied at lookup.
    void loadEnvironment(const Environment& e) {
        if (!environment_ || environmentPath_ != e.path) {
            environment_ = std::make_unique<EnvironmentMap>(ctx_, assets::readImage(e.path));
            environmentPath_ = e.path;
            for (const std::string& w : environment_->warnings()) std::fprintf(stderr, "warning: %s\n", w.c_str());
        }
        environment_->setLookup(e.intensity, e.rotation);
    }

    Context& ctx_;
    LitGBuffer lit_;
    GBuffer& gbuffer_ = lit_.gbuffer();
    DirectionalOcclusion ssdo_;
    std::unique_ptr<EnvironmentMap> environment_;
    std::string environmentPath_;
    DirectionalOcclusionSettings settings_;
    std::uint32_t firstFrame_ = 0, framesRun_ = 0;
    std::optional<double> radius_;
    GBufferView view_;
    DirectionalOcclusionView result_;
};

const TechniqueRegistrar ssdo({"ssdo",
                               "Screen-space directional occlusion: environment light through the open directions, "
                               "and (bounce=1) the occluders' light",
                               {"direct", "indirect"},
                               kSettings,
                               ssdoPresets(),
                               [](Context& ctx) { return std::make_unique<SsdoRun>(ctx); }});

} // namespace
} // namespace obscura::cli
