#include "lit_gbuffer.hpp"

#include <algorithm>

namespace obscura::cli {

const std::vector<SettingInfo>& LitGBuffer::settings() {
    static const std::vector<SettingInfo> s = {
        {"shadows", "", "0|1", "shadow the direct light of shadow-casting lights", "1"},
        renamedSetting(ShadowMapSettings{}, "resolution", "shadow_resolution", "side of every shadow map"),
        {"shadow_filter", "", "hard|pcf", "shadow lookups (the G-buffer's: hard or pcf)", "pcf"},
    };
    return s;
}

bool LitGBuffer::set(const std::string& key, const std::string& value) {
    if (key == "shadows") enabled_ = parseBool(key, value);
    else if (key == "shadow_resolution") setRenamed(maps_, "resolution", key, value);
    else if (key == "shadow_filter")
        filter_.filter = parseChoice<ShadowFilter>(key, value, {{"hard", ShadowFilter::Hard}, {"pcf", ShadowFilter::Pcf}});
    else return false;
    return true;
}

std::string LitGBuffer::ignoredSetting(const std::string& key, bool directLighting) const {
    if (!directLighting && hasSetting(settings(), key)) return "read only with direct_lighting=1 (shadows darken the direct light)";
    return !enabled_ && (key == "shadow_resolution" || key == "shadow_filter") ? "read only with shadows=1" : "";
}

std::string LitGBuffer::ignoredInScene(const std::string& key, const Scene& scene) {
    const bool shadowed = std::any_of(scene.lights.begin(), scene.lights.end(), hasShadowMaps);
    return hasSetting(settings(), key) && !shadowed ? "the scene has no shadow-casting light" : "";
}

const GBufferView& LitGBuffer::render(const FrameSetup& frame, GBufferSettings settings) {
    if (enabled_ && settings.directLighting) {
        settings.shadows = &shadows_.render(frame.scene.scene, frame.camera, maps_);
        settings.shadowFilter = filter_;
    }
    maps_used_ = settings.shadows;
    view_ = gbuffer_.render(frame.scene.scene, frame.camera, settings);
    return view_;
}

const GBufferView& LitGBuffer::renderUnlit(const FrameSetup& frame, GBufferSettings settings) {
    maps_used_ = enabled_ ? &shadows_.render(frame.scene.scene, frame.camera, maps_) : nullptr;
    settings.directLighting = false;
    view_ = gbuffer_.render(frame.scene.scene, frame.camera, settings);
    return view_;
}

} // namespace obscura::cli
