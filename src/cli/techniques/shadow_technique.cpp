// "shadow.hard" and "shadow.pcf" (a spot or directional light) and "shadow.cube" (a point
// light): the ShadowMaps module's mask of one light at the scene's G-buffer samples,
// against the reference's hard shadow.
#include "obscura/error.hpp"
#include "obscura/gbuffer.hpp"
#include "obscura/shadow_maps.hpp"
#include "technique_registry.hpp"

#include <optional>

namespace obscura::cli {
namespace {

const std::vector<SettingInfo> kSettings = {
    {"light", "", "[0, lights)", "index in Scene::lights (default: the first shadow-casting light the technique maps)"},
    {"filter", "", "hard|pcf", "shadow.cube: one comparison (default) or PCF"},
    {"resolution", "texels", "[16, 8192]", "side of every map"},
    {"cascades", "", "[1, 4]", "maps per directional light"},
    {"split_lambda", "", "[0, 1]", "PSSM weight of the logarithmic split"},
    {"pcf_radius", "texels", "[0, 8]", "shadow.pcf: comparisons each side of the centre"},
    {"constant_bias", "world units", "[0, inf)", "receiver moved toward the light"},
    {"slope_bias", "texels", "[0, 16]", "times tan(theta), toward the light"},
    {"normal_offset", "texels", "[0, 16]", "receiver moved along its normal"},
    {"cascade_blend", "", "[0, 0.5]", "fraction of each cascade blended into the next"},
    {"receiver_plane", "", "0|1", "PCF: receiver-plane depth bias (default 1)"},
};

// The lights a technique maps: point lights (cube) or spot and directional ones.
bool mapped(const Light& l, bool point) {
    return l.castsShadows && (point ? l.type == LightType::Point : l.type == LightType::Spot || l.type == LightType::Directional);
}

std::optional<std::size_t> firstMappedLight(const Scene& scene, bool point) {
    for (std::size_t i = 0; i < scene.lights.size(); ++i)
        if (mapped(scene.lights[i], point)) return i;
    return std::nullopt;
}

class ShadowRun final : public TechniqueRun {
public:
    ShadowRun(Context& ctx, ShadowFilter filter, bool point) : ctx_(ctx), gbuffer_(ctx), shadows_(ctx), point_(point) {
        mask_.filter = filter;
    }

    void set(const std::string& key, const std::string& value) override {
        if (key == "light") light_ = static_cast<std::size_t>(parseNumber(key, value, 0, 1e6, ""));
        else if (key == "resolution") maps_.resolution = static_cast<int>(parseNumber(key, value, 16, 8192, "texels"));
        else if (key == "cascades") maps_.cascades = static_cast<int>(parseNumber(key, value, 1, kMaxShadowCascades, ""));
        else if (key == "split_lambda") maps_.splitLambda = static_cast<float>(parseNumber(key, value, 0, 1, ""));
        else if (key == "filter")
            mask_.filter = parseChoice<ShadowFilter>(key, value, {{"hard", ShadowFilter::Hard}, {"pcf", ShadowFilter::Pcf}});
        else if (key == "pcf_radius") mask_.pcfRadius = static_cast<int>(parseNumber(key, value, 0, 8, "texels"));
        else if (key == "constant_bias") mask_.constantBias = static_cast<float>(parseNumber(key, value, 0, 1e30, "world units"));
        else if (key == "slope_bias") mask_.slopeBias = static_cast<float>(parseNumber(key, value, 0, 16, "texels"));
        else if (key == "normal_offset") mask_.normalOffset = static_cast<float>(parseNumber(key, value, 0, 16, "texels"));
        else if (key == "receiver_plane") mask_.receiverPlane = parseBool(key, value);
        else if (key == "cascade_blend") mask_.cascadeBlend = static_cast<float>(parseNumber(key, value, 0, 0.5, ""));
        else throw Error(ErrorCode::Parse, "shadow has no setting \"" + key + "\" (settings: " + settingKeys(kSettings) + ")");
    }

    std::string unsupported(const Scene& scene) const override {
        if (light_ ? *light_ < scene.lights.size() && mapped(scene.lights[*light_], point_)
                   : firstMappedLight(scene, point_).has_value())
            return {};
        const std::string kind = point_ ? "point" : "spot or directional";
        return light_ ? "light " + std::to_string(*light_) + " is not a shadow-casting " + kind + " light"
                      : "no shadow-casting " + kind + " light";
    }

    void run(const FrameSetup& frame) override {
        const Scene& scene = frame.scene.scene;
        const std::string why = unsupported(scene);
        if (!why.empty()) throw Error(ErrorCode::InvalidArgument, "shadow: " + why);
        usedLight_ = light_ ? *light_ : *firstMappedLight(scene, point_);
        view_ = gbuffer_.render(scene, frame.camera, {frame.width, frame.height, false, {}});
        const ShadowMapSet& maps = shadows_.render(scene, frame.camera, maps_);
        result_ = shadows_.mask(view_, maps, usedLight_, mask_);
    }

    std::vector<TechniqueOutput> outputs(const std::vector<std::string>& names) override {
        std::vector<TechniqueOutput> out;
        for (const std::string& name : names) {
            if (name != "shadow") throw Error(ErrorCode::InvalidArgument, "shadow has no output \"" + name + "\" (outputs: shadow)");
            TechniqueOutput o;
            o.name = name;
            o.image = readTexture(ctx_, result_);
            o.display = o.image;
            o.encoding = assets::PngEncoding::Linear;
            out.push_back(o);
        }
        return out;
    }

    GBufferSamples samples() override {
        return readSamples(ctx_, gbuffer_, view_);
    }

    std::vector<Measurement> measurements() override {
        Measurement m{"shadow", readTexture(ctx_, result_), reference::Shadow{usedLight_}};
        m.shadowMask = true;
        m.classify = mask_.filter == ShadowFilter::Hard;
        return {m};
    }

private:
    Context& ctx_;
    GBuffer gbuffer_;
    ShadowMaps shadows_;
    ShadowMapSettings maps_;
    ShadowMaskSettings mask_;
    bool point_;
    std::optional<std::size_t> light_;
    std::size_t usedLight_ = 0;
    GBufferView view_;
    TextureView result_;
};

// Map sizes and cascades grow with the preset; PCF's kernel too.
std::vector<Preset> presets(bool pcf) {
    const auto kernel = [pcf](const char* r) {
        return pcf ? std::vector<std::pair<std::string, std::string>>{{"pcf_radius", r}}
                   : std::vector<std::pair<std::string, std::string>>{};
    };
    std::vector<Preset> p = {{"low", {{"resolution", "512"}, {"cascades", "1"}}},
                             {"medium", {{"resolution", "1024"}, {"cascades", "2"}}},
                             {"high", {{"resolution", "2048"}, {"cascades", "3"}}},
                             {"ultra", {{"resolution", "4096"}, {"cascades", "4"}}}};
    const char* radii[] = {"1", "1", "2", "3"};
    for (std::size_t i = 0; i < p.size(); ++i)
        for (auto& kv : kernel(radii[i])) p[i].settings.push_back(kv);
    return p;
}

TechniqueInfo shadowTechnique(const std::string& name, const std::string& description, ShadowFilter filter,
                              bool point = false) {
    return {name, description, {"shadow"}, kSettings, presets(filter == ShadowFilter::Pcf),
            [filter, point](Context& ctx) { return std::make_unique<ShadowRun>(ctx, filter, point); }};
}

const TechniqueRegistrar hard(shadowTechnique("shadow.hard", "Hard shadow mask: one shadow-map comparison (spot, cascaded directional)",
                                              ShadowFilter::Hard));
const TechniqueRegistrar pcf(shadowTechnique("shadow.pcf", "Percentage-closer filtering: a grid of bilinear comparisons",
                                             ShadowFilter::Pcf));
const TechniqueRegistrar cube(shadowTechnique("shadow.cube", "Point light: six perspective maps (hard unless filter=pcf)",
                                              ShadowFilter::Hard, true));

} // namespace
} // namespace obscura::cli
