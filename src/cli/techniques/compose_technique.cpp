// "compose": the whole frame, G-buffer + ray-marched AO + screen-space GI combined and tone
// mapped (Composer). Outputs the display picture and the combined radiance.
#include "obscura/ambient_occlusion.hpp"
#include "obscura/compose.hpp"
#include "obscura/error.hpp"
#include "obscura/gbuffer.hpp"
#include "obscura/indirect_light.hpp"
#include "lit_gbuffer.hpp"
#include "technique_registry.hpp"

#include <optional>

namespace obscura::cli {
namespace {

std::vector<SettingInfo> composeSettings() {
    SettingInfo radius = renamedSetting(AmbientOcclusionSettings{}, "radius", "radius",
                                        "AO and GI radius (default: a tenth of the scene's diagonal)");
    radius.defaultValue.clear();
    const std::vector<SettingInfo> passes = {
        {"ao", "", "0|1",
         "ray-marched AO (medium quality; shades the ambient term, so read only with ambient > 0, or with "
         "formula=thesis; the physical formula only with gi=0)",
         "1"},
        {"gi", "", "0|1", "screen-space one-bounce GI (medium quality)", "1"},
        radius};
    return joinSettings(joinSettings(tableSettings(ComposeSettings{}), passes), LitGBuffer::settings());
}

const std::vector<SettingInfo> kSettings = composeSettings();

class ComposeRun final : public TechniqueRun {
public:
    explicit ComposeRun(Context& ctx) : ctx_(ctx), lit_(ctx), ao_(ctx), gi_(ctx), composer_(ctx) {}

    void set(const std::string& key, const std::string& value) override {
        if (setFromTable(settings_, key, value)) return;
        if (key == "ao") withAo_ = parseBool(key, value);
        else if (key == "gi") withGi_ = parseBool(key, value);
        else if (key == "radius") {
            AmbientOcclusionSettings ao;
            setRenamed(ao, "radius", key, value);
            radius_ = ao.radius;
        } else if (!lit_.set(key, value)) unknownSetting("compose", key, kSettings);
    }

    void run(const FrameSetup& frame) override {
        const float radius = static_cast<float>(radius_ ? *radius_ : defaultRadius(frame.scene.scene));
        view_ = lit_.render(frame, {frame.width, frame.height, true, {}});
        ComposeInputs inputs{view_, {}, {}};
        if (aoUsed()) {
            AmbientOcclusionSettings a;
            a.radius = radius;
            inputs.ao = ao_.run(view_, a).ao;
        }
        if (withGi_) {
            IndirectLightSettings g;
            g.radius = radius;
            inputs.indirect = gi_.run(view_, g).radiance;
        }
        display_ = composer_.compose(inputs, settings_);
    }

    std::string ignoredSetting(const std::string& key) const override {
        const auto& s = settings_;
        const bool physicalGi = s.formula == CombineFormula::Physical && withGi_;
        if (key.starts_with("drago_") && s.toneMapper != ToneMapper::Drago) return "read only with tone_mapper=drago";
        if (key == "gamma" && s.srgb) return "read only with srgb=0";
        if ((key == "ambient" || key == "ao") && physicalGi)
            return "the physical formula replaces the ambient term by the indirect light: read only with gi=0 or formula=thesis";
        if (key == "ao" && !combineReadsAo())
            return "the standard and physical formulas darken only the ambient term with AO, and ambient is 0: read only "
                   "with ambient > 0 or formula=thesis";
        if (key == "indirect_scale" && !withGi_) return "read only with gi=1";
        if (key == "radius" && !withGi_ && !aoUsed())
            return "read only with gi=1, or with ao=1 where the combine reads AO (formula=thesis, or ambient > 0)";
        return lit_.ignoredSetting(key);
    }
    std::string ignoredInScene(const std::string& key, const Scene& scene) const override {
        return LitGBuffer::ignoredInScene(key, scene);
    }

    std::vector<TechniqueOutput> outputs(const std::vector<std::string>& names) override {
        std::vector<TechniqueOutput> out;
        for (const std::string& name : names) {
            TechniqueOutput o;
            o.name = name;
            if (name == "image") {
                o.image = rgbOf(readTexture(ctx_, display_));
                o.display = o.image;
                o.encoding = assets::PngEncoding::Linear; // already display-encoded
                o.displayOnly = true;
            } else if (name == "radiance") {
                // W/(sr m^2) as combined; the picture after the exposure, as the tone mapper sees it.
                o.image = rgbOf(readTexture(ctx_, composer_.radiance()));
                o.display = o.image;
                for (float& v : o.display.pixels) v *= settings_.exposure;
            } else {
                throw Error(ErrorCode::InvalidArgument, "compose has no output \"" + name + "\" (outputs: image, radiance)");
            }
            out.push_back(o);
        }
        return out;
    }

    GBufferSamples samples() override {
        return readSamples(ctx_, gbuffer_, view_);
    }

    std::vector<std::pair<std::string, std::size_t>> memory() const override {
        auto m = lit_.memory();
        m.insert(m.end(), {{"ao", ao_.memoryBytes()}, {"gi", gi_.memoryBytes()}, {"compose", composer_.memoryBytes()}});
        return m;
    }

    // No ground truth for the composite yet: its parts are measured by their own techniques.
    std::vector<Measurement> measurements() override { return {}; }

private:
    // Whether the combine reads AO (obscura::combineReadsAo): otherwise no AO pass runs.
    bool combineReadsAo() const { return obscura::combineReadsAo(settings_, withGi_); }
    bool aoUsed() const { return withAo_ && combineReadsAo(); }

    Context& ctx_;
    LitGBuffer lit_;
    GBuffer& gbuffer_ = lit_.gbuffer();
    AmbientOcclusion ao_;
    IndirectLight gi_;
    Composer composer_;
    ComposeSettings settings_;
    bool withAo_ = true, withGi_ = true;
    std::optional<double> radius_;
    GBufferView view_;
    TextureView display_;
};

const TechniqueRegistrar registrar({
    "compose",
    "The frame: G-buffer direct light + ray-marched AO + screen-space GI, combined and tone mapped",
    {"image", "radiance"},
    kSettings,
    {{"default", {}}},
    [](Context& ctx) { return std::make_unique<ComposeRun>(ctx); },
});

} // namespace
} // namespace obscura::cli
