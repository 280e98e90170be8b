// "ao.raymarch", "ao.points", "ao.horizon", "ao.voxel" and "obscurance.raymarch", ".points"
// and ".voxel": the AmbientOcclusion module on the G-buffer of the scene (and, for the voxel
// methods, its voxel grid). Horizon integrates AO only (no falloff): no obscurance.horizon.
#include "obscura/ambient_occlusion.hpp"
#include "obscura/error.hpp"
#include "obscura/gbuffer.hpp"
#include "obscura/voxelizer.hpp"
#include "technique_registry.hpp"

#include <glm/gtc/matrix_inverse.hpp>

#include <cmath>
#include <cstdint>
#include <map>
#include <optional>

namespace obscura::cli {
namespace {

const std::vector<SettingInfo> kSettings = joinSettings({
    {"radius", "world units", "(0, inf)", "reach of V_r (default: a tenth of the scene's bounding-box diagonal)"},
    {"rays", "", "[1, 1024]", "directions (points) per pixel; horizon: 2 per slice"},
    {"steps", "", "[1, 256]", "depth samples per ray (per side for horizon; voxel march samples)"},
    {"cosine_weighted", "", "0|1", "cosine (AO_r) or uniform hemisphere weighting"},
    {"falloff", "", "none|linear|quadratic|smooth", "obscurance distance weighting (none: AO)"},
    {"thickness", "world units", "[0, inf)", "assumed thickness behind depth samples (0: the radius)"},
    {"thickness_mode", "", "constant|depth_peeling|peeling_or_constant",
     "raymarch, points: constant thickness, the second depth layer, or the deeper of both"},
    {"march", "", "view|texture|hiz", "raymarch: 3D samples, 2D samples, or 2D samples skipped through a Hi-Z pyramid"},
    {"resolution", "", "full|half|quarter", "AO resolution relative to the G-buffer"},
    {"blur_radius", "taps", "[0, 16]", "geometry-aware separable blur (0: off)"},
    {"blur_depth_sigma", "", "(0, 1]", "relative depth difference weighted e^-1/2"},
    {"blur_normal_power", "", "[0, 256]", "normal weight exponent"},
    {"refine_threshold", "", "[0, 1]", "upsampling: pixels with less similar-neighbour weight are computed at full resolution (0: none)"},
    {"ray_lanes", "", "1|2|4|8|16", "invocations that share each pixel's rays (the same result up to summation order)"},
    {"geometry_tiles", "", "0|1", "half, quarter: run only over the tiles with geometry (the same result; 0: every tile)"},
    {"frame_index", "", "[0, 4294967295]", "sampling shift of the first rendered frame (0: none); temporal=1 counts it up each frame"},
    {"temporal", "", "0|1", "accumulate the result over the rendered frames (--frames), reprojected; see TemporalSettings"},
    {"bent_normals", "", "0|1", "also compute the bent normal (default 1; horizon: of the directions above its slices' horizons)"},
}, voxelGridSettings("ao.voxel"));

// Each method's keys: the module's, less those it does not read, so that setting one is refused
// instead of silently ignored (the module cannot tell a set field from its default).
std::vector<SettingInfo> methodSettings(AoMethod method) {
    const auto& voxel = voxelGridKeys();
    const auto withVoxel = [&](std::vector<std::string> keys) {
        keys.insert(keys.end(), voxel.begin(), voxel.end());
        return keys;
    };
    switch (method) {
    case AoMethod::RayMarch: return withoutSettings(kSettings, voxel);
    case AoMethod::Points: return withoutSettings(kSettings, withVoxel({"steps", "march"})); // points, not marches
    case AoMethod::Horizon: // cosine-weighted AO only (the module refuses the others); no thickness test
        return withoutSettings(kSettings, withVoxel({"cosine_weighted", "falloff", "thickness", "thickness_mode", "march"}));
    case AoMethod::Voxel: return withoutSettings(kSettings, {"thickness", "thickness_mode", "march"});
    }
    return kSettings;
}

class AoRun final : public TechniqueRun {
public:
    AoRun(Context& ctx, AoMethod method, ObscuranceFalloff falloff) : ctx_(ctx), gbuffer_(ctx), ao_(ctx), voxelizer_(ctx) {
        settings_.method = method;
        settings_.falloff = falloff;
        // Bent normals are part of the output (and of the bench's error report) by default.
        settings_.bentNormals = true;
    }

    void set(const std::string& key, const std::string& value) override {
        auto& s = settings_;
        if (key == "radius") radius_ = parseNumber(key, value, 1e-30, 1e30, "world units");
        else if (key == "rays") s.rays = parseInteger(key, value, 1, 1024, "");
        else if (key == "steps") s.steps = parseInteger(key, value, 1, 256, "");
        else if (key == "cosine_weighted") s.cosineWeighted = parseBool(key, value);
        else if (key == "falloff")
            s.falloff = parseChoice<ObscuranceFalloff>(key, value, {{"none", ObscuranceFalloff::None},
                                                                  {"linear", ObscuranceFalloff::Linear},
                                                                  {"quadratic", ObscuranceFalloff::Quadratic},
                                                                  {"smooth", ObscuranceFalloff::Smooth}});
        else if (key == "thickness") s.thickness = static_cast<float>(parseNumber(key, value, 0, 1e30, "world units"));
        else if (key == "thickness_mode") s.thicknessMode = parseScreenThickness(key, value);
        else if (key == "march") s.march = parseScreenMarch(key, value);
        else if (key == "resolution")
            s.resolution = parseChoice<AoResolution>(key, value, {{"full", AoResolution::Full},
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
        else if (key == "bent_normals") s.bentNormals = parseBool(key, value);
        else if (!setVoxelGridOption(key, value, voxelGrid_, s.voxelTraversal)) throw Error(ErrorCode::Parse, "ao has no setting \"" + key + "\" (settings: " + settingKeys(kSettings) + ")");
    }

    void run(const FrameSetup& frame) override {
        settings_.radius = static_cast<float>(radius_ ? *radius_ : defaultRadius(frame.scene.scene));
        GBufferSettings g{frame.width, frame.height, false, {}};
        g.depthLayers = depthLayersFor(settings_.thicknessMode);
        view_ = gbuffer_.render(frame.scene.scene, frame.camera, g);
        if (settings_.method == AoMethod::Voxel) settings_.voxels = &voxelizer_.voxelize(frame.scene.scene, voxelGrid_.settings());
        // Without temporal accumulation every frame is the same (the bench times and measures that).
        settings_.frameIndex = firstFrame_ + (settings_.temporal.enabled ? framesRun_++ : 0u);
        result_ = ao_.run(view_, settings_);
    }

    std::string missingOutput(const std::string& name) const override {
        return name == "bent_normal" && !settings_.bentNormals ? "needs --set bent_normals=1" : "";
    }

    std::string ignoredSetting(const std::string& key) const override {
        const auto& s = settings_;
        return ignoredIntegratorSetting(key, s.resolution, s.blurRadius,
                                        s.method == AoMethod::Voxel ? std::optional(s.voxelTraversal) : std::nullopt);
    }

    std::vector<TechniqueOutput> outputs(const std::vector<std::string>& names) override {
        std::vector<TechniqueOutput> out;
        for (const std::string& name : names) {
            TechniqueOutput o;
            o.name = name;
            if (name == "ao") {
                o.image = readTexture(ctx_, result_.ao);
                o.display = o.image;
            } else if (name == "bent_normal" && result_.bentNormal) {
                o.image = rgbOf(readTexture(ctx_, result_.bentNormal));
                o.display = o.image;
                for (float& v : o.display.pixels) v = v * 0.5f + 0.5f;
            } else if (const std::string why = missingOutput(name); !why.empty()) {
                throw Error(ErrorCode::InvalidArgument, "ao output \"" + name + "\" " + why);
            } else {
                throw Error(ErrorCode::InvalidArgument, "ao has no output \"" + name +
                                                            "\" (outputs: ao, bent_normal with bent_normals=1)");
            }
            o.encoding = assets::PngEncoding::Linear;
            out.push_back(o);
        }
        return out;
    }

    GBufferSamples samples() override {
        return readSamples(ctx_, gbuffer_, view_);
    }

    std::vector<std::pair<std::string, std::size_t>> memory() const override {
        return {{"gbuffer", gbuffer_.memoryBytes()}, {"ao", ao_.memoryBytes()}, {"voxelizer", voxelizer_.memoryBytes()}};
    }

    std::vector<std::pair<std::string, std::size_t>> counts() const override {
        return refinementCounts(ao_.lastRefinement());
    }

    std::vector<Measurement> measurements() override {
        std::vector<Measurement> m;
        const double radius = settings_.radius;
        if (settings_.falloff == ObscuranceFalloff::None)
            m.push_back({"ao", readTexture(ctx_, result_.ao), reference::AmbientOcclusion{radius, settings_.cosineWeighted}});
        else
            m.push_back({"obscurance", readTexture(ctx_, result_.ao), reference::Obscurance{radius, settings_.falloff, settings_.cosineWeighted}});
        if (result_.bentNormal) {
            // View space to world space, as the reference reports it.
            Image world = rgbOf(readTexture(ctx_, result_.bentNormal));
            const glm::mat3 toWorld(glm::inverse(glm::dmat4(view_.camera.view)));
            for (std::size_t i = 0; i + 2 < world.pixels.size(); i += 3) {
                const glm::vec3 w = toWorld * glm::vec3(world.pixels[i], world.pixels[i + 1], world.pixels[i + 2]);
                for (int c = 0; c < 3; ++c) world.pixels[i + static_cast<std::size_t>(c)] = w[c];
            }
            m.push_back({"bent_normal", world, reference::BentNormal{radius}});
        }
        return m;
    }

private:
    Context& ctx_;
    GBuffer gbuffer_;
    AmbientOcclusion ao_;
    Voxelizer voxelizer_;
    AmbientOcclusionSettings settings_;
    std::uint32_t firstFrame_ = 0, framesRun_ = 0;
    VoxelGridOptions voxelGrid_;
    std::optional<double> radius_;
    GBufferView view_;
    AmbientOcclusionView result_;
};

TechniqueInfo aoTechnique(const std::string& name, const std::string& description, AoMethod method,
                          ObscuranceFalloff falloff = ObscuranceFalloff::None) {
    const std::vector<std::string> outputs = {"ao", "bent_normal"};
    const std::vector<SettingInfo> settings = methodSettings(method);
    return {name, description, outputs, settings, presetsFor(integratorPresets(method == AoMethod::Voxel), kSettings, settings),
            [method, falloff](Context& ctx) { return std::make_unique<AoRun>(ctx, method, falloff); }};
}

const TechniqueRegistrar raymarch(aoTechnique(
    "ao.raymarch", "Ambient occlusion AO_r: rays x steps through the depth buffer (screen space)", AoMethod::RayMarch));
const TechniqueRegistrar points(aoTechnique(
    "ao.points", "Crytek-style point sampling in the normal's hemisphere ball (screen space)", AoMethod::Points));
const TechniqueRegistrar horizon(aoTechnique(
    "ao.horizon", "Horizon-based cosine-weighted AO per screen slice (GTAO-style, screen space)", AoMethod::Horizon));
const TechniqueRegistrar voxel(aoTechnique(
    "ao.voxel", "Ambient occlusion AO_r: rays through the voxelized scene (voxel space)", AoMethod::Voxel));
const TechniqueRegistrar obscurance(aoTechnique(
    "obscurance.raymarch", "Obscurance with the linear falloff (set falloff=...) by ray marching (screen space)",
    AoMethod::RayMarch, ObscuranceFalloff::Linear));
const TechniqueRegistrar obscurancePoints(aoTechnique(
    "obscurance.points", "Obscurance with the linear falloff (set falloff=...) by point sampling (screen space)",
    AoMethod::Points, ObscuranceFalloff::Linear));
const TechniqueRegistrar obscuranceVoxel(aoTechnique(
    "obscurance.voxel", "Obscurance with the linear falloff (set falloff=...) through the voxelized scene (voxel space)",
    AoMethod::Voxel, ObscuranceFalloff::Linear));

} // namespace
} // namespace obscura::cli
