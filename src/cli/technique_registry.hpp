#pragma once
// Techniques the CLI (render, and later bench) can run, registered by the technique's own
// source file, so a new technique appears in every tool without editing them.
#include "obscura/ambient_occlusion.hpp"
#include "obscura/assets.hpp"
#include "obscura/context.hpp"
#include "obscura/error.hpp"
#include "obscura/gbuffer.hpp"
#include "obscura/reference.hpp"
#include "obscura/screen_visibility.hpp"
#include "obscura/voxelizer.hpp"

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <cstdint>
#include <string>
#include <vector>

namespace obscura::cli {

//! One output buffer of a technique, read back.
struct TechniqueOutput {
    std::string name;            //!< e.g. "normal"
    Image image;                 //!< raw values (what EXR files contain)
    Image display;               //!< mapped for an 8-bit PNG
    assets::PngEncoding encoding = assets::PngEncoding::Srgb;
    //! The values are a display picture already (tone mapped, gamma encoded): written as PNG
    //! only, since an EXR holds linear values (and is tagged so).
    bool displayOnly = false;
};

//! A `--set key=value` setting: name, unit and range as documented in the settings table.
struct SettingInfo {
    std::string key, unit, range, description;
    std::string defaultValue{}; //!< as written after '='; empty: decided by the scene or the technique
};

//! The `--set` rows of S's settings table (settings_table.hpp), with the defaults of
//! `defaults` (a technique's own, which may differ from S{}), less the keys in `leaveOut`.
template <class S>
std::vector<SettingInfo> tableSettings(const S& defaults, const std::vector<std::string>& leaveOut = {}) {
    std::vector<SettingInfo> rows;
    for (const Setting<S>& row : S::table()) {
        bool left = false;
        for (const std::string& key : leaveOut) left = left || key == row.key;
        if (!left) rows.push_back({row.key, row.unit, row.range, row.doc, row.format(row.values(defaults))});
    }
    return rows;
}

//! Sets `key` of `s` from `value` through S's table: false when the table has no such key;
//! Error{Parse} "--set key=value: why" for a value the table refuses.
template <class S>
bool setFromTable(S& s, const std::string& key, const std::string& value) {
    try {
        return applySetting(S::table(), s, key, value);
    } catch (const Error& e) {
        throw Error(ErrorCode::Parse, "--set " + e.message());
    }
}

//! S's row `tableKey` under the technique's key `key` (e.g. "shadow_resolution" for
//! ShadowMapSettings' "resolution"), described as `description`.
template <class S>
SettingInfo renamedSetting(const S& defaults, const std::string& tableKey, const std::string& key,
                           const std::string& description) {
    const Setting<S>& row = *findSetting(S::table(), tableKey);
    return {key, row.unit, row.range, description, row.format(row.values(defaults))};
}

//! Sets S's `tableKey` from the technique's `key` (renamedSetting); errors name `key`.
template <class S>
void setRenamed(S& s, const std::string& tableKey, const std::string& key, const std::string& value) {
    try {
        applySetting(S::table(), s, tableKey, value);
    } catch (const Error& e) {
        throw Error(ErrorCode::Parse, "--set " + key + e.message().substr(tableKey.size()));
    }
}

//! `rows` with the description and default of `key` replaced (a technique's own meaning).
std::vector<SettingInfo> describedAs(std::vector<SettingInfo> rows, const std::string& key, const std::string& description,
                                     const std::string& defaultValue);

//! An integrator's (AO's, GI's) table rows as the tools read them: the radius's default is
//! the scene's (defaultRadius), and frame_index is the first rendered frame's.
std::vector<SettingInfo> integratorSettings(std::vector<SettingInfo> rows, const std::string& radiusMeaning);

//! Throws Error{Parse}: "<module> has no setting "<key>" (settings: ...)".
[[noreturn]] void unknownSetting(const std::string& module, const std::string& key, const std::vector<SettingInfo>& settings);

struct FrameSetup {
    const assets::LoadedScene& scene;
    Camera camera;
    int width = 0, height = 0;
};

//! What the bench compares with ground truth after the timed frames.
struct Measurement {
    std::string quantity; //!< e.g. "direct", "ao", "position"
    //! The technique's output in the reference's units, world space for vectors, row 0 at the
    //! top. Pixels without geometry are ignored (see GBufferSamples::viewPositions alpha).
    Image value;
    //! The ground truth to render at the G-buffer's samples; empty when `geometry` is set.
    std::optional<reference::Quantity> reference;
    //! Instead of a reference quantity: compare with primary-ray hits (exact, no noise).
    enum class Geometry { None, Position, Normal } geometry = Geometry::None;
    //! The reference is a reference::Shadow: compare `value` (1 channel) with its channel 0
    //! where its channel 1 says the light reaches the surface.
    bool shadowMask = false;
    //! With shadowMask: also count the pixels the technique classifies wrongly (value < 0.5
    //! against a lit reference: false shadow; >= 0.5 against a shadowed one: false light).
    bool classify = false;
    //! The reference's channels to compare `value` with, in order (empty: all of them), e.g.
    //! SingleScattering's radiance {0, 1, 2} or its transmittance {3}.
    std::vector<int> referenceChannels{};
    //! Cascaded shadows: the mean absolute change of the mask at fixed receivers when the
    //! camera moves by fractions of a texel (see shadow_technique.cpp); empty otherwise.
    std::optional<double> shimmer{};
};

//! The G-buffer samples a technique worked on (view-space positions with alpha = geometry,
//! view-space normals), read back: where the reference is evaluated (mode a).
struct GBufferSamples {
    Image viewPositions;
    Image viewNormals;
};

//! The samples of a G-buffer view that `gbuffer` rendered, read back.
GBufferSamples readSamples(Context& ctx, GBuffer& gbuffer, const GBufferView& view);

//! An integrator's refinement as TechniqueRun::counts: "refine_asked" and "refined_pixels".
std::vector<std::pair<std::string, std::size_t>> refinementCounts(const RefinementCount& count);

//! A technique instance bound to a Context. run() renders one frame; outputs() reads back.
class TechniqueRun {
public:
    virtual ~TechniqueRun() = default;
    virtual void set(const std::string& key, const std::string& value) = 0;
    virtual void run(const FrameSetup& frame) = 0;
    virtual std::vector<TechniqueOutput> outputs(const std::vector<std::string>& names) = 0;
    //! After run(): the technique's measurable outputs and the samples they were computed at.
    virtual std::vector<Measurement> measurements() = 0;
    virtual GBufferSamples samples() = 0;
    //! Why the technique cannot run on `scene` (the tools skip it and say so), or empty.
    virtual std::string unsupported(const Scene&) const { return {}; }
    //! Why its output `name` is missing with the settings given (render skips it when it writes
    //! every output into a directory, and says so; asked for by name, outputs() refuses it), or
    //! empty.
    virtual std::string missingOutput(const std::string& /*name*/) const { return {}; }
    //! After run(): the GPU memory each module (or, where a module says, each pass) holds,
    //! bytes (e.g. {"gbuffer", ...}, {"shadow.maps", ...}).
    virtual std::vector<std::pair<std::string, std::size_t>> memory() const = 0;
    //! After run(): counts the bench reports beside the time, e.g. {"refined_pixels", ...}.
    //! May wait for the GPU.
    virtual std::vector<std::pair<std::string, std::size_t>> counts() const { return {}; }
    //! After the settings are applied: why its setting `key` has no effect with the others
    //! (e.g. the upsampling's keys at full resolution), or empty. The tools print it as a note
    //! for the keys the user set, since a preset sets keys whether or not they matter.
    virtual std::string ignoredSetting(const std::string& /*key*/) const { return {}; }
    //! As ignoredSetting, for what only the scene decides (a directional light's cascade keys
    //! in a scene without one); the tools ask once the scene is loaded.
    virtual std::string ignoredInScene(const std::string& /*key*/, const Scene&) const { return {}; }
};

//! A named set of `--set` values ("low", "medium", "high", "ultra", or "default").
struct Preset {
    std::string name;
    std::vector<std::pair<std::string, std::string>> settings;
};

//! The quality presets of the ray-based integrators (AO, obscurance, indirect light): low,
//! medium, high and ultra by rays and steps (and, with `voxelGrid`, voxel grids of 128^3,
//! 256^3, 512^3 and 1024^3), and "<preset>_half" for medium and high: the same settings at
//! half resolution with a blur, for the resolution trade-off.
std::vector<Preset> integratorPresets(bool voxelGrid);
//! The presets with only the settings `settings` has (ao.points takes no steps): so that a
//! technique's presets set nothing it would ignore. A key that is none of `moduleSettings`
//! (the module's keys, of which `settings` is the method's) is a slip: std::logic_error.
std::vector<Preset> presetsFor(std::vector<Preset> presets, const std::vector<SettingInfo>& moduleSettings,
                               const std::vector<SettingInfo>& settings);

struct TechniqueInfo {
    std::string name;                  //!< "<module>.<method>", or "gbuffer"
    std::string description;
    std::vector<std::string> outputs;  //!< first = default
    std::vector<SettingInfo> settings;
    std::vector<Preset> presets;       //!< at least one
    std::function<std::unique_ptr<TechniqueRun>(Context&)> create;
};

const std::map<std::string, TechniqueInfo>& techniques();
void registerTechnique(TechniqueInfo info);

struct TechniqueRegistrar {
    explicit TechniqueRegistrar(TechniqueInfo info) { registerTechnique(std::move(info)); }
};

//! Splits a --set argument "key=value"; throws Error{Parse} without the '='.
std::pair<std::string, std::string> splitSetting(const std::string& keyValue);
//! Throws Error{Parse} unless `key` is one of the technique's settings; the message names the
//! techniques that have it, since most such keys are another method's (ao.points: steps).
void requireSetting(const TechniqueInfo& info, const std::string& key);
//! Applies --set arguments to a run of `info`, after its preset (requireSetting for each).
void applySettings(const TechniqueInfo& info, TechniqueRun& run, const std::vector<std::string>& keyValues);
//! After applySettings: "<technique> ignores --set key=value: <why>" for each of `keyValues`
//! the run ignores (TechniqueRun::ignoredSetting).
std::vector<std::string> ignoredSettingNotes(const TechniqueInfo& info, const TechniqueRun& run,
                                             const std::vector<std::string>& keyValues);
//! The same for what `scene` decides (TechniqueRun::ignoredInScene), for the keys
//! ignoredSettingNotes has no note for: one note a key.
std::vector<std::string> ignoredInSceneNotes(const TechniqueInfo& info, const TechniqueRun& run,
                                             const std::vector<std::string>& keyValues, const Scene& scene);
//! Why an integrator's (AO's, GI's) setting `key` has no effect with the others, or empty: the
//! refinement's and the tiles' keys at full resolution, the filters' weights with neither the
//! blur nor the upsampling, march samples with another voxel traversal (`voxelTraversal`:
//! empty for the screen-space methods).
std::string ignoredIntegratorSetting(const std::string& key, AoResolution resolution, int blurRadius,
                                     std::optional<VoxelTraversal> voxelTraversal);
//! Parses a boolean setting value ("1/0/true/false/on/off"); throws Error{Parse}.
bool parseBool(const std::string& key, const std::string& value);
//! Parses a number in [lo, hi]; throws Error{Parse} naming the key, the range and the unit.
double parseNumber(const std::string& key, const std::string& value, double lo, double hi, const std::string& unit);
//! parseNumber for counts: a value with a fraction is refused, not cut.
int parseInteger(const std::string& key, const std::string& value, int lo, int hi, const std::string& unit);
//! One of the named values; throws Error{Parse} listing them.
template <typename E>
E parseChoice(const std::string& key, const std::string& value, const std::map<std::string, E>& names) {
    const auto it = names.find(value);
    if (it != names.end()) return it->second;
    std::string known;
    for (const auto& n : names) known += (known.empty() ? "" : ", ") + n.first;
    throw Error(ErrorCode::Parse, "--set " + key + "=" + value + ": expected one of " + known);
}
//! The voxel-grid settings ao.voxel and gi.hybrid share ("voxel_resolution" and
//! "voxel_slices"; "voxel_traversal" is their settings' own), for their settings lists.
std::vector<SettingInfo> voxelGridSettings(const std::string& technique);
//! The grid as set. Without voxel_slices, in whatever order the settings come, the slices
//! follow voxel_resolution (a cubic grid, within the 128..1024 slices the voxelizer has), so
//! that overriding a preset's resolution does not leave it with another's slices.
struct VoxelGridOptions {
    int resolution = VoxelizerSettings{}.resolution;
    std::optional<int> slices;
    //! The voxelizer's settings for these options (grid placement: its defaults).
    VoxelizerSettings settings() const;
};
//! Applies one of them; false when `key` is none of them.
bool setVoxelGridOption(const std::string& key, const std::string& value, VoxelGridOptions& grid);
//! a followed by b.
std::vector<SettingInfo> joinSettings(std::vector<SettingInfo> a, const std::vector<SettingInfo>& b);
//! Whether `key` is one of `settings`' keys.
bool hasSetting(const std::vector<SettingInfo>& settings, const std::string& key);
//! `settings` without `keys` (each must be there): a method's list from its module's.
std::vector<SettingInfo> withoutSettings(std::vector<SettingInfo> settings, const std::vector<std::string>& keys);
//! The keys of voxelGridSettings and "voxel_traversal", which only the voxel methods read.
const std::vector<std::string>& voxelGridKeys();
//! "a, b, c": the keys of the settings, for error messages.
std::string settingKeys(const std::vector<SettingInfo>& settings);
//! The radius techniques use when none is set: a tenth of the scene's bounding-box
//! diagonal (world units), so presets fit scenes of any scale.
double defaultRadius(const Scene& scene);
//! Output `name` of `image`, displayed as it is (values in [0, 1] as they come), and written
//! to PNG with `encoding`.
TechniqueOutput plainOutput(const std::string& name, Image image, assets::PngEncoding encoding);
//! The first three channels of an image.
Image rgbOf(const Image& image);

} // namespace obscura::cli
