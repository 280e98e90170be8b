#pragma once
// The G-buffer of the techniques that gather direct light (gbuffer, gi.*, compose): lit, with
// the scene's shadow-casting lights shadowed through ShadowMaps unless `shadows=0`.
#include "technique_registry.hpp"

#include "obscura/gbuffer.hpp"
#include "obscura/shadow_maps.hpp"

#include <string>
#include <vector>

namespace obscura::cli {

class LitGBuffer {
public:
    explicit LitGBuffer(Context& ctx) : gbuffer_(ctx), shadows_(ctx) {}

    //! The `--set` keys this adds to a technique's.
    static const std::vector<SettingInfo>& settings();
    //! Takes `key` if it is one of settings(); returns whether it did.
    bool set(const std::string& key, const std::string& value);
    //! As TechniqueRun::ignoredSetting: the shadow maps' keys with shadows=0, and all of
    //! settings() when the G-buffer computes no direct light (`directLighting` false).
    std::string ignoredSetting(const std::string& key, bool directLighting = true) const;
    //! As TechniqueRun::ignoredInScene: settings() in a scene without shadow-casting lights.
    static std::string ignoredInScene(const std::string& key, const Scene& scene);
    //! Renders shadow maps (pass "shadow.maps", only for scenes with shadow-casting lights)
    //! and the G-buffer; `settings` gives everything but the shadows.
    const GBufferView& render(const FrameSetup& frame, GBufferSettings settings);

    //! For a technique that lights the pixels itself (ssdo): the shadow maps as render() would,
    //! and a G-buffer without direct light. shadowMaps() returns either's maps, or null.
    const GBufferView& renderUnlit(const FrameSetup& frame, GBufferSettings settings);
    const ShadowMapSet* shadowMaps() const { return maps_used_; }
    //! Whether the maps include reflective shadow maps (ShadowMapSettings::reflective).
    void setReflective(bool reflective) { maps_.reflective = reflective; }
    const ShadowMaskSettings& shadowFilter() const { return filter_; }

    GBuffer& gbuffer() { return gbuffer_; }
    //! Whether the direct light, when the G-buffer computes it, is shadowed where the scene's
    //! lights cast shadows (the "shadows" setting).
    bool shadowed() const { return enabled_; }
    const GBufferView& view() const { return view_; }
    //! GPU memory of the G-buffer and of the shadow maps, bytes.
    std::vector<std::pair<std::string, std::size_t>> memory() const {
        return {{"gbuffer", gbuffer_.memoryBytes()}, {"shadow_maps", shadows_.memoryBytes()}};
    }

private:
    GBuffer gbuffer_;
    ShadowMaps shadows_;
    bool enabled_ = true;
    ShadowMapSettings maps_;
    ShadowMaskSettings filter_;
    const ShadowMapSet* maps_used_ = nullptr;
    GBufferView view_;
};

} // namespace obscura::cli
