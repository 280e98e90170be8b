// "gi.screen" and "gi.hybrid": the IndirectLight module on the scene's G-buffer (direct
// lighting on) and, for gi.hybrid, its voxel grid.
#include "obscura/error.hpp"
#include "obscura/gbuffer.hpp"
#include "obscura/indirect_light.hpp"
#include "obscura/voxelizer.hpp"
#include "lit_gbuffer.hpp"
#include "technique_registry.hpp"

#include <cstdint>
#include <optional>

namespace obscura::cli {
namespace {

const std::vector<SettingInfo> kSettings = joinSettings(
    integratorSettings(tableSettings(IndirectLightSettings{}, {"method"}), "hits farther away are not gathered"),
    joinSettings(voxelGridSettings("gi.hybrid"), LitGBuffer::settings()));

// Each method's keys, less those it does not read (as ao_technique.cpp): the hybrid method's
// rays test voxels, not depth samples.
std::vector<SettingInfo> methodSettings(GiMethod method) {
    if (method == GiMethod::Hybrid) return withoutSettings(kSettings, {"thickness_mode", "march"});
    return withoutSettings(kSettings, voxelGridKeys());
}

class GiRun final : public TechniqueRun {
public:
    GiRun(Context& ctx, GiMethod method) : ctx_(ctx), lit_(ctx), gi_(ctx), voxelizer_(ctx) { settings_.method = method; }

    void set(const std::string& key, const std::string& value) override {
        if (setFromTable(settings_, key, value)) {
            // The scene decides the default radius, the frame count the frame index.
            if (key == "radius") radius_ = settings_.radius;
            if (key == "frame_index") firstFrame_ = settings_.frameIndex;
        } else if (!setVoxelGridOption(key, value, voxelGrid_) && !lit_.set(key, value)) {
            unknownSetting("gi", key, kSettings);
        }
    }

    void run(const FrameSetup& frame) override {
        settings_.radius = static_cast<float>(radius_ ? *radius_ : defaultRadius(frame.scene.scene));
        GBufferSettings g{frame.width, frame.height, true, {}};
        g.depthLayers = depthLayersFor(settings_.thicknessMode);
        view_ = lit_.render(frame, g);
        if (settings_.method == GiMethod::Hybrid) settings_.voxels = &voxelizer_.voxelize(frame.scene.scene, voxelGrid_.settings());
        // Without temporal accumulation every frame is the same (the bench times and measures that).
        settings_.frameIndex = firstFrame_ + (settings_.temporal.enabled ? framesRun_++ : 0u);
        result_ = gi_.run(view_, settings_);
    }

    std::string ignoredSetting(const std::string& key) const override {
        const auto& s = settings_;
        const std::string why = ignoredIntegratorSetting(
            key, s.resolution, s.blurRadius, s.method == GiMethod::Hybrid ? std::optional(s.voxelTraversal) : std::nullopt);
        return why.empty() ? lit_.ignoredSetting(key) : why;
    }
    // shadows=0 adds the indirect_unshadowed measurement (measurements()) in any scene: the
    // reference shadows every light, whether or not it has shadow maps.
    std::string ignoredInScene(const std::string& key, const Scene& scene) const override {
        return key == "shadows" ? "" : LitGBuffer::ignoredInScene(key, scene);
    }

    std::vector<TechniqueOutput> outputs(const std::vector<std::string>& names) override {
        std::vector<TechniqueOutput> out;
        for (const std::string& name : names) {
            if (name != "indirect") throw Error(ErrorCode::InvalidArgument, "gi has no output \"" + name + "\" (outputs: indirect)");
            out.push_back(plainOutput(name, rgbOf(readTexture(ctx_, result_.radiance)), assets::PngEncoding::Srgb));
        }
        return out;
    }

    GBufferSamples samples() override {
        return readSamples(ctx_, gbuffer_, view_);
    }

    std::vector<std::pair<std::string, std::size_t>> memory() const override {
        auto m = lit_.memory();
        m.insert(m.end(), {{"gi", gi_.memoryBytes()}, {"voxelizer", voxelizer_.memoryBytes()}});
        return m;
    }

    std::vector<std::pair<std::string, std::size_t>> counts() const override {
        return refinementCounts(gi_.lastRefinement());
    }

    std::vector<Measurement> measurements() override {
        // "indirect": against the true one-bounce light (with shadows=0 that includes the
        // shadows the gathered light lacks). "indirect_unshadowed", only with shadows=0:
        // against the gathering of the same unshadowed direct light the technique is given,
        // its own error. With shadows the G-buffer's light is shadowed, and "indirect" is that
        // error plus the shadow maps' own.
        const Image radiance = rgbOf(readTexture(ctx_, result_.radiance));
        std::vector<Measurement> out = {{"indirect", radiance, reference::IndirectLight{settings_.radius}}};
        if (!lit_.shadowed()) {
            reference::IndirectLight unshadowed{settings_.radius};
            unshadowed.directVisibility = false;
            out.push_back({"indirect_unshadowed", radiance, unshadowed});
        }
        return out;
    }

private:
    Context& ctx_;
    LitGBuffer lit_;
    GBuffer& gbuffer_ = lit_.gbuffer();
    IndirectLight gi_;
    Voxelizer voxelizer_;
    IndirectLightSettings settings_;
    std::uint32_t firstFrame_ = 0, framesRun_ = 0;
    VoxelGridOptions voxelGrid_;
    std::optional<double> radius_;
    GBufferView view_;
    IndirectLightView result_;
};

TechniqueInfo giTechnique(const std::string& name, const std::string& description, GiMethod method) {
    const std::vector<SettingInfo> settings = methodSettings(method);
    return {name, description, {"indirect"}, settings, presetsFor(integratorPresets(method == GiMethod::Hybrid), kSettings, settings),
            [method](Context& ctx) { return std::make_unique<GiRun>(ctx, method); }};
}

const TechniqueRegistrar screen(giTechnique(
    "gi.screen", "One-bounce diffuse GI: rays through the depth buffer, radiance from the screen", GiMethod::Screen));
const TechniqueRegistrar hybrid(giTechnique(
    "gi.hybrid", "One-bounce diffuse GI: rays through the voxel grid, radiance from the screen", GiMethod::Hybrid));

} // namespace
} // namespace obscura::cli
