#pragma once
// Techniques the CLI (render, and later bench) can run, registered by the technique's own
// source file, so a new technique appears in every tool without editing them.
#include "obscura/assets.hpp"
#include "obscura/context.hpp"

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace obscura::cli {

//! One output buffer of a technique, read back.
struct TechniqueOutput {
    std::string name;            //!< e.g. "normal"
    Image image;                 //!< raw values (what EXR files contain)
    Image display;               //!< mapped for an 8-bit PNG
    assets::PngEncoding encoding = assets::PngEncoding::Srgb;
};

//! A `--set key=value` setting: name, unit and range as documented in the settings struct.
struct SettingInfo {
    std::string key, unit, range, description;
};

struct FrameSetup {
    const assets::LoadedScene& scene;
    Camera camera;
    int width = 0, height = 0;
};

//! A technique instance bound to a Context. run() renders one frame; outputs() reads back.
class TechniqueRun {
public:
    virtual ~TechniqueRun() = default;
    virtual void set(const std::string& key, const std::string& value) = 0;
    virtual void run(const FrameSetup& frame) = 0;
    virtual std::vector<TechniqueOutput> outputs(const std::vector<std::string>& names) = 0;
};

struct TechniqueInfo {
    std::string name;                  //!< "<module>.<method>", or "gbuffer"
    std::string description;
    std::vector<std::string> outputs;  //!< first = default
    std::vector<SettingInfo> settings;
    std::function<std::unique_ptr<TechniqueRun>(Context&)> create;
};

const std::map<std::string, TechniqueInfo>& techniques();
void registerTechnique(TechniqueInfo info);

struct TechniqueRegistrar {
    explicit TechniqueRegistrar(TechniqueInfo info) { registerTechnique(std::move(info)); }
};

//! Parses a boolean setting value ("1/0/true/false/on/off"); throws Error{Parse}.
bool parseBool(const std::string& key, const std::string& value);
//! Parses a number in [lo, hi]; throws Error{Parse} naming the key, the range and the unit.
double parseNumber(const std::string& key, const std::string& value, double lo, double hi, const std::string& unit);

} // namespace obscura::cli
