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

// The technique's defaults: bent normals are part of the output (and of the bench's error
// report); the obscurance techniques start from the linear falloff.
AmbientOcclusionSettings cliDefaults(ObscuranceFalloff falloff) {
    AmbientOcclusionSettings s;
    s.bentNormals = true;
    s.falloff = falloff;
    return s;
}

std::vector<SettingInfo> moduleSettings(ObscuranceFalloff falloff) {
    return joinSettings(integratorSettings(tableSettings(cliDefaults(falloff), {"method"}), "reach of V_r"),
                        voxelGridSettings("ao.voxel"));
}

const std::vector<SettingInfo> kSettings = moduleSettings(ObscuranceFalloff::None);

// Each method's keys: the module's, less those it does not read, so that setting one is refused
// instead of silently ignored (the module cannot tell a set field from its default).
std::vector<SettingInfo> methodSettings(AoMethod method, ObscuranceFalloff falloff) {
    const std::vector<SettingInfo> all = moduleSettings(falloff);
    const auto& voxel = voxelGridKeys();
    const auto withVoxel = [&](std::vector<std::string> keys) {
        keys.insert(keys.end(), voxel.begin(), voxel.end());
        return keys;
    };
    switch (method) {
    case AoMethod::RayMarch: return withoutSettings(all, voxel);
    case AoMethod::Points: return withoutSettings(all, withVoxel({"steps", "march"})); // points, not marches
    case AoMethod::Horizon: // cosine-weighted AO only (the module refuses the others); no thickness test
        return withoutSettings(all, withVoxel({"cosine_weighted", "falloff", "thickness", "thickness_mode", "march"}));
    case AoMethod::Voxel: return withoutSettings(all, {"thickness", "thickness_mode", "march"});
    }
    return all;
}

class AoRun final : public TechniqueRun {
public:
    AoRun(Context& ctx, AoMethod method, ObscuranceFalloff falloff)
        : ctx_(ctx), gbuffer_(ctx), ao_(ctx), voxelizer_(ctx), settings_(cliDefaults(falloff)) {
        settings_.method = method;
    }

    void set(const std::string& key, const std::string& value) override {
        if (setFromTable(settings_, key, value)) {
            // The scene decides the default radius, the frame count the frame index.
            if (key == "radius") radius_ = settings_.radius;
            if (key == "frame_index") firstFrame_ = settings_.frameIndex;
        } else if (!setVoxelGridOption(key, value, voxelGrid_)) {
            unknownSetting("ao", key, kSettings);
        }
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
            if (name == "ao") {
                out.push_back(plainOutput(name, readTexture(ctx_, result_.ao), assets::PngEncoding::Linear));
            } else if (name == "bent_normal" && result_.bentNormal) {
                TechniqueOutput o = plainOutput(name, rgbOf(readTexture(ctx_, result_.bentNormal)), assets::PngEncoding::Linear);
                for (float& v : o.display.pixels) v = v * 0.5f + 0.5f;
                out.push_back(o);
            } else if (const std::string why = missingOutput(name); !why.empty()) {
                throw Error(ErrorCode::InvalidArgument, "ao output \"" + name + "\" " + why);
            } else {
                throw Error(ErrorCode::InvalidArgument, "ao has no output \"" + name +
                                                            "\" (outputs: ao, bent_normal with bent_normals=1)");
            }
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
    const std::vector<SettingInfo> settings = methodSettings(method, falloff);
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
