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

const std::vector<SettingInfo> kSettings = joinSettings({
    {"radius", "world units", "(0, inf)", "hits farther away are not gathered (default: a tenth of the scene's diagonal)"},
    {"rays", "", "[1, 1024]", "cosine-weighted directions per pixel"},
    {"steps", "", "[1, 256]", "depth samples per ray (gi.hybrid: march samples with voxel_traversal=march)"},
    {"thickness", "world units", "[0, inf)", "see IndirectLightSettings::thickness (0: the default)"},
    {"thickness_mode", "", "constant|depth_peeling|peeling_or_constant",
     "gi.screen: constant thickness, the second depth layer, or the deeper of both"},
    {"march", "", "view|texture|hiz", "gi.screen: 3D samples, 2D samples, or 2D samples skipped through a Hi-Z pyramid"},
    {"resolution", "", "full|half|quarter", "GI resolution relative to the G-buffer"},
    {"blur_radius", "taps", "[0, 16]", "geometry-aware separable blur (0: off)"},
    {"blur_depth_sigma", "", "(0, 1]", "relative depth difference weighted e^-1/2"},
    {"blur_normal_power", "", "[0, 256]", "normal weight exponent"},
    {"refine_threshold", "", "[0, 1]", "upsampling: pixels with less similar-neighbour weight are computed at full resolution (0: none)"},
    {"ray_lanes", "", "1|2|4|8|16", "invocations that share each pixel's rays (the same result up to summation order)"},
    {"geometry_tiles", "", "0|1", "half, quarter: run only over the tiles with geometry (the same result; 0: every tile)"},
    {"frame_index", "", "[0, 4294967295]", "sampling shift of the first rendered frame (0: none); temporal=1 counts it up each frame"},
    {"temporal", "", "0|1", "accumulate the result over the rendered frames (--frames), reprojected; see TemporalSettings"},
}, joinSettings(voxelGridSettings("gi.hybrid"), LitGBuffer::settings()));

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
        auto& s = settings_;
        if (key == "radius") radius_ = parseNumber(key, value, 1e-30, 1e30, "world units");
        else if (key == "rays") s.rays = parseInteger(key, value, 1, 1024, "");
        else if (key == "steps") s.steps = parseInteger(key, value, 1, 256, "");
        else if (key == "thickness") s.thickness = static_cast<float>(parseNumber(key, value, 0, 1e30, "world units"));
        else if (key == "thickness_mode") s.thicknessMode = parseScreenThickness(key, value);
        else if (key == "march") s.march = parseScreenMarch(key, value);
        else if (key == "resolution") s.resolution = parseChoice<AoResolution>(key, value, {{"full", AoResolution::Full},
                                                                                          {"half", AoResolution::Half},
                                                                                          {"quarter", AoResolution::Quarter}});
        else if (key == "blur_radius") s.blurRadius = parseInteger(key, value, 0, 16, "taps");
        else if (key == "blur_depth_sigma") s.blurDepthSigma = static_cast<float>(parseNumber(key, value, 1e-30, 1, ""));
        else if (key == "blur_normal_power") s.blurNormalPower = static_cast<float>(parseNumber(key, value, 0, 256, ""));
        else if (key == "refine_threshold") s.refineThreshold = static_cast<float>(parseNumber(key, value, 0, 1, ""));
        else if (key == "ray_lanes") s.rayLanes = parseInteger(key, value, 1, 16, "");
        else if (key == "geometry_tiles") s.geometryTiles = parseBool(key, value);
        else if (key == "frame_index") firstFrame_ = parseUnsigned32(key, value);
        else if (key == "temporal") s.temporal.enabled = parseBool(key, value);
        else if (!setVoxelGridOption(key, value, voxelGrid_, s.voxelTraversal) && !lit_.set(key, value)) throw Error(ErrorCode::Parse, "gi has no setting \"" + key + "\" (settings: " + settingKeys(kSettings) + ")");
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
            TechniqueOutput o;
            o.name = name;
            o.image = rgbOf(readTexture(ctx_, result_.radiance));
            o.display = o.image;
            out.push_back(o);
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
