// "shadow.hard" .. "shadow.msm" (a spot or directional light), "shadow.cube",
// "shadow.paraboloid" and "shadow.pcss" (a point, sphere or rect light): the ShadowMaps
// module's mask of one light at the scene's G-buffer samples, against the reference's shadow
// (hard for point, spot and directional lights, the arriving fraction for area lights).
#include "obscura/error.hpp"
#include "obscura/gbuffer.hpp"
#include "obscura/shadow_maps.hpp"
#include "technique_registry.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>

namespace obscura::cli {
namespace {

// A technique's rows with its filter as the default (shadow.cube and shadow.paraboloid: hard).
std::vector<SettingInfo> shadowSettings(ShadowFilter filter) {
    ShadowMaskSettings mask;
    mask.filter = filter;
    const std::vector<SettingInfo> own = {
        {"light", "", "[0, lights)", "index in Scene::lights (default: the first shadow-casting light the technique maps)", ""},
        {"depth_bounds", "", "0|1", "cascades split the G-buffer's depth range (1) or the scene bounds' (0)", "1"}};
    return joinSettings(joinSettings(own, tableSettings(ShadowMapSettings{}, {"point_mapping"})), tableSettings(mask));
}

const std::vector<SettingInfo> kSettings = shadowSettings(ShadowFilter::Hard);

// The directional lights' cascades' keys. A point technique takes neither these nor
// `reflective` (spot and directional lights' reflective maps): its mask is of a light mapped
// from its centre; in a scene that also has spot or directional lights, their maps are
// rendered with the defaults.
const std::vector<std::string> kCascadeKeys = {"cascades", "split_lambda", "depth_bounds", "cascade_blend"};

std::string filterName(ShadowFilter filter) {
    return findSetting(ShadowMaskSettings::table(), "filter")->format({double(static_cast<int>(filter))});
}

bool isMomentFilter(ShadowFilter f) { return f != ShadowFilter::Hard && f != ShadowFilter::Pcf && f != ShadowFilter::Pcss; }

// Whether `filter` reads `key` (shadow_maps.hpp's ShadowMaskSettings: PCF's kernel, PCSS's
// search, the moment filters' prefilter and bounds); the keys every filter reads: true.
bool filterReads(ShadowFilter filter, const std::string& key) {
    const bool chebyshev = filter == ShadowFilter::Vsm || filter == ShadowFilter::Evsm2 || filter == ShadowFilter::Evsm4;
    if (key == "pcf_radius" || key == "pcf_kernel") return filter == ShadowFilter::Pcf;
    if (key == "receiver_plane") return filter == ShadowFilter::Pcf || filter == ShadowFilter::Pcss;
    if (key == "pcss_blocker_fraction") return filter == ShadowFilter::Pcss;
    if (key == "moment_blur" || key == "moment_precision") return isMomentFilter(filter);
    if (key == "min_variance" || key == "light_bleed_reduction") return chebyshev;
    if (key == "exponent") return filter == ShadowFilter::Esm || filter == ShadowFilter::Evsm2 || filter == ShadowFilter::Evsm4;
    if (key == "negative_exponent") return filter == ShadowFilter::Evsm4;
    return true;
}

// A technique's keys: a point technique's without the cascades'; one whose name fixes the
// filter (all but shadow.cube and shadow.paraboloid, which take `filter`) without `filter` and
// the keys of the other filters.
std::vector<SettingInfo> techniqueSettings(ShadowFilter filter, bool point, bool filterKey) {
    std::vector<std::string> unread = point ? kCascadeKeys : std::vector<std::string>{};
    if (point) unread.push_back("reflective");
    if (!filterKey) {
        unread.push_back("filter");
        for (const SettingInfo& s : kSettings)
            if (!filterReads(filter, s.key)) unread.push_back(s.key);
    }
    return withoutSettings(shadowSettings(filter), unread);
}

// The lights a technique maps: those mapped from a centre (point and sphere lights: cube or
// paraboloids; rect lights: one paraboloid, whatever the technique) or spot and directional ones.
bool mapped(const Light& l, bool point) {
    const bool centre = l.type == LightType::Point || l.type == LightType::Sphere || l.type == LightType::Rect;
    return hasShadowMaps(l) && centre == point;
}

std::optional<std::size_t> firstMappedLight(const Scene& scene, bool point) {
    for (std::size_t i = 0; i < scene.lights.size(); ++i)
        if (mapped(scene.lights[i], point)) return i;
    return std::nullopt;
}

class ShadowRun final : public TechniqueRun {
public:
    ShadowRun(Context& ctx, ShadowFilter filter, bool point, PointShadowMapping mapping)
        : ctx_(ctx), gbuffer_(ctx), shadows_(ctx), point_(point) {
        mask_.filter = filter;
        maps_.pointMapping = mapping;
    }

    void set(const std::string& key, const std::string& value) override {
        if (setFromTable(maps_, key, value) || setFromTable(mask_, key, value)) return;
        if (key == "light") light_ = static_cast<std::size_t>(parseInteger(key, value, 0, 1000000, ""));
        else if (key == "depth_bounds") depthBounds_ = parseBool(key, value);
        else unknownSetting("shadow", key, kSettings);
    }

    std::string ignoredSetting(const std::string& key) const override {
        if (!filterReads(mask_.filter, key)) return "not read with filter=" + filterName(mask_.filter);
        if ((key == "contact_steps" || key == "contact_thickness") && mask_.contactLength == 0.0f)
            return "read only with contact_length > 0";
        // One cascade spans the whole view distance: nothing to split or blend into.
        if ((key == "split_lambda" || key == "cascade_blend") && maps_.cascades == 1) return "read only with cascades > 1";
        return {};
    }

    // Only directional lights have cascades (a spot light has one map).
    std::string ignoredInScene(const std::string& key, const Scene& scene) const override {
        const bool cascadeKey = std::find(kCascadeKeys.begin(), kCascadeKeys.end(), key) != kCascadeKeys.end();
        const bool directional = std::any_of(scene.lights.begin(), scene.lights.end(), [](const Light& l) {
            return l.type == LightType::Directional && hasShadowMaps(l);
        });
        return cascadeKey && !directional ? "the scene has no shadow-casting directional light, the only kind with cascades"
                                          : "";
    }

    std::string unsupported(const Scene& scene) const override {
        if (light_ ? *light_ < scene.lights.size() && mapped(scene.lights[*light_], point_)
                   : firstMappedLight(scene, point_).has_value())
            return {};
        const std::string kind = point_ ? "point, sphere or rect" : "spot or directional";
        return light_ ? "light " + std::to_string(*light_) + " is not a shadow-casting " + kind + " light"
                      : "no shadow-casting " + kind + " light";
    }

    void run(const FrameSetup& frame) override {
        const Scene& scene = frame.scene.scene;
        const std::string why = unsupported(scene);
        if (!why.empty()) throw Error(ErrorCode::InvalidArgument, "shadow: " + why);
        usedLight_ = light_ ? *light_ : *firstMappedLight(scene, point_);
        scene_ = &scene;
        camera_ = frame.camera;
        view_ = gbuffer_.render(scene, frame.camera, {frame.width, frame.height, false, {}});
        renderMask();
    }

    std::vector<TechniqueOutput> outputs(const std::vector<std::string>& names) override {
        std::vector<TechniqueOutput> out;
        for (const std::string& name : names) {
            if (name != "shadow") throw Error(ErrorCode::InvalidArgument, "shadow has no output \"" + name + "\" (outputs: shadow)");
            out.push_back(plainOutput(name, readTexture(ctx_, result_), assets::PngEncoding::Linear));
        }
        return out;
    }

    GBufferSamples samples() override {
        return readSamples(ctx_, gbuffer_, view_);
    }

    // By pass: the G-buffer's, then the shadow passes' (ShadowMaps::memoryByPass).
    std::vector<std::pair<std::string, std::size_t>> memory() const override {
        std::vector<std::pair<std::string, std::size_t>> m = {{"gbuffer.render", gbuffer_.memoryBytes()}};
        for (const auto& pass : shadows_.memoryByPass()) m.push_back(pass);
        return m;
    }

    std::vector<Measurement> measurements() override {
        Measurement m{"shadow", readTexture(ctx_, result_), reference::Shadow{usedLight_}};
        m.shadowMask = true;
        m.classify = mask_.filter == ShadowFilter::Hard;
        if (scene_->lights[usedLight_].type == LightType::Directional) {
            m.shimmer = shimmer();
            renderMask(); // back to the frame's own maps and mask
        }
        return {m};
    }

private:
    void renderMask() {
        const ShadowMapSet& maps =
            depthBounds_ ? shadows_.render(*scene_, camera_, maps_, view_) : shadows_.render(*scene_, camera_, maps_);
        result_ = shadows_.mask(view_, maps, usedLight_, mask_);
    }

    // Shimmer: the G-buffer stays (the receivers do not move) while the cascades are fitted
    // to the camera moved by k/8 of the first cascade's texel along its right-up diagonal,
    // k = 1..8; the mean absolute change of the mask over the geometry pixels against the
    // unmoved fit, averaged over k. The moved maps are looked up from the unmoved G-buffer
    // (their camera field set to it, which mask() checks). Scene-bounds fitting throughout:
    // a depth range would need a view from the moved camera.
    double shimmer() {
        const Image geometry = readSamples(ctx_, gbuffer_, view_).viewPositions;
        const ShadowMapSet& base = shadows_.render(*scene_, camera_, maps_);
        const float texel = base.find(usedLight_)->texelSize[0];
        const Image still = readTexture(ctx_, shadows_.mask(view_, base, usedLight_, mask_));
        const glm::mat4 toWorld = glm::inverse(camera_.view);
        const glm::vec3 diagonal = glm::normalize(glm::vec3(toWorld[0]) + glm::vec3(toWorld[1]));
        double change = 0.0;
        std::size_t samples = 0;
        for (int k = 1; k <= 8; ++k) {
            Camera moved = camera_;
            moved.view = camera_.view * glm::translate(glm::mat4(1.0f), -diagonal * (texel * float(k) / 8.0f));
            ShadowMapSet maps = shadows_.render(*scene_, moved, maps_);
            maps.camera = camera_;
            const Image mask = readTexture(ctx_, shadows_.mask(view_, maps, usedLight_, mask_));
            for (std::size_t i = 0; i < mask.pixels.size(); ++i)
                if (geometry.pixels[4 * i + 3] != 0.0f) {
                    change += std::abs(double(mask.pixels[i]) - double(still.pixels[i]));
                    ++samples;
                }
        }
        return samples ? change / double(samples) : 0.0;
    }

    Context& ctx_;
    GBuffer gbuffer_;
    ShadowMaps shadows_;
    const Scene* scene_ = nullptr;
    Camera camera_;
    ShadowMapSettings maps_;
    ShadowMaskSettings mask_;
    bool point_;
    bool depthBounds_ = true;
    std::optional<std::size_t> light_;
    std::size_t usedLight_ = 0;
    GBufferView view_;
    TextureView result_;
};

// The moment filters prefilter every texel of every map each frame: smaller maps, wider blurs.
std::vector<Preset> momentPresets() {
    return {{"low", {{"resolution", "256"}, {"cascades", "1"}, {"moment_blur", "1"}}},
            {"medium", {{"resolution", "512"}, {"cascades", "2"}, {"moment_blur", "2"}}},
            {"medium_16bit", {{"resolution", "512"}, {"cascades", "2"}, {"moment_blur", "2"}, {"moment_precision", "16"}}},
            {"high", {{"resolution", "1024"}, {"cascades", "2"}, {"moment_blur", "2"}}},
            {"ultra", {{"resolution", "1024"}, {"cascades", "4"}, {"moment_blur", "3"}}}};
}

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
    // "high" with the 5 x 5 grid's weights from 9 taps, and with 16 Poisson-disc taps over
    // the same reach.
    if (pcf)
        for (const char* k : {"optimized", "poisson"})
            p.push_back({std::string("high_") + k,
                         {{"resolution", "2048"}, {"cascades", "3"}, {"pcf_radius", "2"}, {"pcf_kernel", k}}});
    return p;
}

// shadow.cube also runs the filters on its maps ("medium_<filter>"), so that on a sphere
// light (cornell_sphere) every filtered mask meets the area-light reference.
std::vector<Preset> cubePresets() {
    std::vector<Preset> p = presets(false);
    p.push_back({"medium_pcf", {{"resolution", "1024"}, {"filter", "pcf"}, {"pcf_radius", "2"}}});
    for (const char* filter : {"vsm", "esm", "evsm4", "msm"})
        p.push_back({std::string("medium_") + filter, {{"resolution", "512"}, {"filter", filter}, {"moment_blur", "2"}}});
    return p;
}

TechniqueInfo shadowTechnique(const std::string& name, const std::string& description, ShadowFilter filter,
                              bool point = false, PointShadowMapping mapping = PointShadowMapping::Cube) {
    const bool cube = point && filter == ShadowFilter::Hard && mapping == PointShadowMapping::Cube;
    const bool filterKey = point && filter == ShadowFilter::Hard; // shadow.cube, shadow.paraboloid
    const std::vector<SettingInfo> settings = techniqueSettings(filter, point, filterKey);
    return {name, description, {"shadow"}, settings,
            presetsFor(cube ? cubePresets() : isMomentFilter(filter) ? momentPresets() : presets(filter == ShadowFilter::Pcf),
                       kSettings, settings),
            [filter, point, mapping](Context& ctx) { return std::make_unique<ShadowRun>(ctx, filter, point, mapping); }};
}

const TechniqueRegistrar hard(shadowTechnique("shadow.hard", "Hard shadow mask: one shadow-map comparison (spot, cascaded directional)",
                                              ShadowFilter::Hard));
const TechniqueRegistrar pcf(shadowTechnique("shadow.pcf", "Percentage-closer filtering: a grid of bilinear comparisons",
                                             ShadowFilter::Pcf));
const TechniqueRegistrar vsm(shadowTechnique("shadow.vsm", "Variance shadow map: Chebyshev's bound on prefiltered moments",
                                             ShadowFilter::Vsm));
const TechniqueRegistrar esm(shadowTechnique("shadow.esm", "Exponential shadow map, prefiltered in log space", ShadowFilter::Esm));
const TechniqueRegistrar evsm2(shadowTechnique("shadow.evsm2", "Exponentially warped VSM (positive warp)", ShadowFilter::Evsm2));
const TechniqueRegistrar evsm4(shadowTechnique("shadow.evsm4", "Exponentially warped VSM (positive and negative warps)",
                                               ShadowFilter::Evsm4));
const TechniqueRegistrar msm(shadowTechnique("shadow.msm", "Moment shadow map: four moments, Hamburger reconstruction (32F)",
                                             ShadowFilter::Msm));
const TechniqueRegistrar cube(shadowTechnique("shadow.cube", "Point light: six perspective maps (hard unless filter=pcf)",
                                              ShadowFilter::Hard, true));
const TechniqueRegistrar pcss(shadowTechnique("shadow.pcss",
                                              "Percentage-closer soft shadows of a point, sphere (Light::radius) or rect light",
                                              ShadowFilter::Pcss, true));
const TechniqueRegistrar paraboloid(shadowTechnique("shadow.paraboloid",
                                                    "Point light: two paraboloid maps with per-pixel depth (hard unless filter=pcf)",
                                                    ShadowFilter::Hard, true, PointShadowMapping::DualParaboloid));

} // namespace
} // namespace obscura::cli
