#include "technique_registry.hpp"

#include "obscura/error.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <stdexcept>

namespace obscura::cli {
namespace {
std::map<std::string, TechniqueInfo>& registry() {
    static std::map<std::string, TechniqueInfo> r;
    return r;
}
} // namespace

const std::map<std::string, TechniqueInfo>& techniques() { return registry(); }

bool hasSetting(const std::vector<SettingInfo>& settings, const std::string& key) {
    return std::any_of(settings.begin(), settings.end(), [&](const SettingInfo& s) { return s.key == key; });
}

void registerTechnique(TechniqueInfo info) {
    // A preset's key the technique does not take is a slip in its source file: fail at start-up,
    // in every tool and test, rather than when the preset is run.
    for (const Preset& p : info.presets)
        for (const auto& [key, value] : p.settings)
            if (!hasSetting(info.settings, key))
                throw std::logic_error(info.name + " preset " + p.name + " sets " + key + ", which is not one of its settings");
    const std::string name = info.name;
    registry().emplace(name, std::move(info));
}

std::pair<std::string, std::string> splitSetting(const std::string& keyValue) {
    const auto eq = keyValue.find('=');
    if (eq == std::string::npos) throw Error(ErrorCode::Parse, "--set " + keyValue + ": expected key=value");
    return {keyValue.substr(0, eq), keyValue.substr(eq + 1)};
}

void requireSetting(const TechniqueInfo& info, const std::string& key) {
    if (hasSetting(info.settings, key)) return;
    std::string others;
    int count = 0;
    for (const auto& [name, other] : techniques())
        if (hasSetting(other.settings, key)) others += (count++ ? ", " : "") + name;
    throw Error(ErrorCode::Parse, info.name + " has no setting \"" + key + "\"" +
                                      (count ? " (" + others + (count == 1 ? " has it)" : " have it)") : "") +
                                      "; its settings: " + settingKeys(info.settings));
}

void applySettings(const TechniqueInfo& info, TechniqueRun& run, const std::vector<std::string>& keyValues) {
    for (const std::string& kv : keyValues) {
        const auto [key, value] = splitSetting(kv);
        requireSetting(info, key);
        run.set(key, value);
    }
}

namespace {
std::vector<std::string> notesFor(const TechniqueInfo& info, const std::vector<std::string>& keyValues,
                                  const std::function<std::string(const std::string&)>& reason) {
    std::vector<std::string> notes;
    for (const std::string& kv : keyValues)
        if (const std::string why = reason(splitSetting(kv).first); !why.empty())
            notes.push_back(info.name + " ignores --set " + kv + ": " + why);
    return notes;
}
} // namespace

std::vector<std::string> ignoredSettingNotes(const TechniqueInfo& info, const TechniqueRun& run,
                                             const std::vector<std::string>& keyValues) {
    return notesFor(info, keyValues, [&](const std::string& key) { return run.ignoredSetting(key); });
}

std::vector<std::string> ignoredInSceneNotes(const TechniqueInfo& info, const TechniqueRun& run,
                                             const std::vector<std::string>& keyValues, const Scene& scene) {
    return notesFor(info, keyValues, [&](const std::string& key) {
        return run.ignoredSetting(key).empty() ? run.ignoredInScene(key, scene) : std::string{};
    });
}

std::string ignoredIntegratorSetting(const std::string& key, AoResolution resolution, int blurRadius,
                                     std::optional<VoxelTraversal> voxelTraversal) {
    const bool full = resolution == AoResolution::Full;
    if (full && (key == "refine_threshold" || key == "geometry_tiles")) return "read only at resolution half or quarter";
    if (full && blurRadius == 0 && (key == "blur_depth_sigma" || key == "blur_normal_power"))
        return "read only by the blur (blur_radius > 0) and the upsampling (resolution half or quarter)";
    if (voxelTraversal && *voxelTraversal != VoxelTraversal::March && key == "steps")
        return "read only with voxel_traversal=march (the other traversals visit every voxel on the way)";
    return {};
}

bool parseBool(const std::string& key, const std::string& value) {
    if (value == "1" || value == "true" || value == "on") return true;
    if (value == "0" || value == "false" || value == "off") return false;
    throw Error(ErrorCode::Parse, "--set " + key + "=" + value + ": expected 1/0, true/false or on/off");
}

namespace {
std::string boundText(double v) {
    if (v >= 1e30) return "inf";
    if (v <= -1e30) return "-inf";
    char text[32];
    std::snprintf(text, sizeof text, "%g", v);
    return text;
}

// [lo, hi] as a reader takes it: a lower bound above 0 but at most 1e-30 means "more than 0",
// an upper bound of 1e30 or more "no limit".
std::string rangeText(double lo, double hi) {
    std::string text = lo > 0.0 && lo <= 1e-30 ? std::string("(0") : std::string("[").append(boundText(lo));
    text.append(", ").append(boundText(hi)).append(hi >= 1e30 ? ")" : "]");
    return text;
}

// `value` as a number in [lo, hi]; an Error{Parse} saying "<said>: <why not>" otherwise.
double numberIn(const std::string& value, double lo, double hi, const std::string& unit, const std::string& said) {
    double v = 0;
    try {
        std::size_t used = 0;
        v = std::stod(value, &used);
        if (used != value.size()) throw std::invalid_argument(value);
    } catch (const std::exception&) {
        throw Error(ErrorCode::Parse, said + ": not a number");
    }
    if (!(v >= lo && v <= hi))
        throw Error(ErrorCode::Parse,
                    said + ": must be in " + rangeText(lo, hi) + (unit.empty() ? "" : " " + unit));
    return v;
}
} // namespace

double parseNumber(const std::string& key, const std::string& value, double lo, double hi, const std::string& unit) {
    return numberIn(value, lo, hi, unit, "--set " + key + "=" + value);
}


namespace {
double parseWhole(const std::string& key, const std::string& value, double lo, double hi, const std::string& unit) {
    const double v = parseNumber(key, value, lo, hi, unit);
    if (v != std::floor(v)) throw Error(ErrorCode::Parse, "--set " + key + "=" + value + ": must be a whole number");
    return v;
}
} // namespace

int parseInteger(const std::string& key, const std::string& value, int lo, int hi, const std::string& unit) {
    return static_cast<int>(parseWhole(key, value, lo, hi, unit));
}


namespace {
constexpr int kSlicesPerTarget = 128; // one RGBA32UI render target
constexpr int kMaxTargets = 8;
} // namespace

// The grid's resolution row as a technique's key; the slices are the CLI's own (the
// voxelizer counts render targets).
std::vector<SettingInfo> voxelGridSettings(const std::string& technique) {
    const SettingInfo resolution = renamedSetting(VoxelizerSettings{}, "resolution", "voxel_resolution",
                                                  technique + ": grid columns along x and y; also the slices along z "
                                                              "unless voxel_slices is set (cubic cells, 128..1024 slices)");
    return {resolution,
            {"voxel_slices", "voxels", "[128, 1024], a multiple of 128", technique + ": grid slices along z (128 per render target)",
             ""}};
}

VoxelizerSettings VoxelGridOptions::settings() const {
    VoxelizerSettings grid;
    grid.resolution = resolution;
    grid.targets = slices ? *slices / kSlicesPerTarget : std::clamp(resolution / kSlicesPerTarget, 1, kMaxTargets);
    return grid;
}

bool setVoxelGridOption(const std::string& key, const std::string& value, VoxelGridOptions& grid) {
    if (key == "voxel_resolution") {
        VoxelizerSettings settings;
        setRenamed(settings, "resolution", key, value);
        grid.resolution = settings.resolution;
    } else if (key == "voxel_slices") {
        const double slices = parseNumber(key, value, kSlicesPerTarget, kMaxTargets * kSlicesPerTarget, "voxels");
        if (std::fmod(slices, kSlicesPerTarget) != 0.0)
            throw Error(ErrorCode::Parse, "--set " + key + "=" + value + ": must be a multiple of 128 (slices per render target)");
        grid.slices = static_cast<int>(slices);
    } else {
        return false;
    }
    return true;
}

std::vector<SettingInfo> describedAs(std::vector<SettingInfo> rows, const std::string& key, const std::string& description,
                                     const std::string& defaultValue) {
    for (SettingInfo& row : rows)
        if (row.key == key) {
            row.description = description;
            row.defaultValue = defaultValue;
            return rows;
        }
    throw std::logic_error("describedAs: no setting " + key);
}

std::vector<SettingInfo> integratorSettings(std::vector<SettingInfo> rows, const std::string& radiusMeaning) {
    rows = describedAs(rows, "radius", radiusMeaning + " (default: a tenth of the scene's bounding-box diagonal)", "");
    return describedAs(rows, "frame_index",
                       "sampling shift of the first rendered frame (0: none); temporal=1 counts it up each frame", "0");
}

void unknownSetting(const std::string& module, const std::string& key, const std::vector<SettingInfo>& settings) {
    throw Error(ErrorCode::Parse, module + " has no setting \"" + key + "\" (settings: " + settingKeys(settings) + ")");
}

std::vector<SettingInfo> joinSettings(std::vector<SettingInfo> a, const std::vector<SettingInfo>& b) {
    a.insert(a.end(), b.begin(), b.end());
    return a;
}

std::vector<SettingInfo> withoutSettings(std::vector<SettingInfo> settings, const std::vector<std::string>& keys) {
    for (const std::string& key : keys) {
        const auto it = std::find_if(settings.begin(), settings.end(), [&](const SettingInfo& s) { return s.key == key; });
        if (it == settings.end()) throw std::logic_error("withoutSettings: no setting " + key);
        settings.erase(it);
    }
    return settings;
}

const std::vector<std::string>& voxelGridKeys() {
    static const std::vector<std::string> keys = [] {
        std::vector<std::string> k;
        for (const SettingInfo& s : voxelGridSettings("")) k.push_back(s.key);
        k.push_back("voxel_traversal");
        return k;
    }();
    return keys;
}

std::string settingKeys(const std::vector<SettingInfo>& settings) {
    std::string keys;
    for (const auto& k : settings) keys += (keys.empty() ? "" : ", ") + k.key;
    return keys;
}


GBufferSamples readSamples(Context& ctx, GBuffer& gbuffer, const GBufferView& view) {
    return {readTexture(ctx, gbuffer.positions(view)), readTexture(ctx, view.normal)};
}

std::vector<std::pair<std::string, std::size_t>> refinementCounts(const RefinementCount& count) {
    return {{"refine_asked", count.asked}, {"refined_pixels", count.refined}};
}

// X_half: X's rays and steps at half resolution, blurred and upsampled. The blur trades noise
// for bias: 3 taps each side at 16 rays, and at 64 rays (half the noise) half as wide,
// rounded down to 1 (2CylinderEngine 512x512, ao.horizon high_half RMSE 0.083 with 3 taps,
// 0.061 with 2, 0.051 with 1, against 0.029 at full resolution).
//
// Voxel grids double with each preset, from 128^3 (256 KiB) to 1024^3 (128 MiB, and its
// mipmaps): on 2CylinderEngine (128x128) they, more than the rays, set voxel AO's error: RMSE
// 0.151-0.156 at 128^3 from 8 to 256 rays, 0.072 at 512^3 and 0.038 at 1024^3 with 256 rays.
std::vector<Preset> integratorPresets(bool voxelGrid) {
    const std::map<std::string, std::string> blurTaps = {{"medium", "3"}, {"high", "1"}};
    std::vector<Preset> presets = {
        {"low", {{"rays", "8"}, {"steps", "4"}, {"resolution", "half"}, {"blur_radius", "3"}}},
        {"medium", {{"rays", "16"}, {"steps", "8"}}},
        {"high", {{"rays", "64"}, {"steps", "16"}}},
        {"ultra", {{"rays", "256"}, {"steps", "32"}}},
    };
    if (voxelGrid) {
        const std::map<std::string, std::string> grids = {{"low", "128"}, {"medium", "256"}, {"high", "512"}, {"ultra", "1024"}};
        for (Preset& p : presets)
            p.settings.push_back({"voxel_resolution", grids.at(p.name)}); // cubic: the slices follow
    }
    for (const char* name : {"high", "medium"}) {
        const auto full = std::find_if(presets.begin(), presets.end(), [&](const Preset& p) { return p.name == name; });
        Preset halved{full->name + "_half", full->settings};
        halved.settings.push_back({"resolution", "half"});
        halved.settings.push_back({"blur_radius", blurTaps.at(name)});
        presets.insert(full + 1, halved);
    }
    return presets;
}

std::vector<Preset> presetsFor(std::vector<Preset> presets, const std::vector<SettingInfo>& moduleSettings,
                               const std::vector<SettingInfo>& settings) {
    for (Preset& p : presets) {
        for (const auto& [key, value] : p.settings)
            if (!hasSetting(moduleSettings, key)) throw std::logic_error("preset " + p.name + " sets " + key + ", no setting of its module");
        std::erase_if(p.settings, [&](const auto& kv) { return !hasSetting(settings, kv.first); });
    }
    return presets;
}

double defaultRadius(const Scene& scene) {
    const Bounds b = sceneBounds(scene);
    return 0.1 * glm::length(glm::dvec3(b.max - b.min));
}

TechniqueOutput plainOutput(const std::string& name, Image image, assets::PngEncoding encoding) {
    TechniqueOutput o;
    o.name = name;
    o.display = image;
    o.image = std::move(image);
    o.encoding = encoding;
    return o;
}

Image rgbOf(const Image& src) {
    Image out{src.width, src.height, 3, {}};
    out.pixels.reserve(static_cast<std::size_t>(src.width) * static_cast<std::size_t>(src.height) * 3);
    for (std::size_t i = 0; i + static_cast<std::size_t>(src.channels) <= src.pixels.size(); i += static_cast<std::size_t>(src.channels))
        for (std::size_t c = 0; c < 3; ++c) out.pixels.push_back(c < static_cast<std::size_t>(src.channels) ? src.pixels[i + c] : 0.0f);
    return out;
}

} // namespace obscura::cli
