#include "quantity_options.hpp"

#include "obscura/error.hpp"
#include "technique_registry.hpp"

#include <cfloat>
#include <functional>
#include <map>

namespace obscura::cli {
namespace {

using Setter = std::function<void(reference::Quantity&, const std::string&, const std::string&)>;

double distance(const std::string& key, const std::string& value) {
    if (value == "inf") return reference::kInfinity;
    return parseNumber(key, value, 1e-30, DBL_MAX, "world units, or inf for no limit");
}

template <typename Q>
Q& as(reference::Quantity& q) {
    return std::get<Q>(q);
}

struct IntegratorSpec {
    reference::Quantity defaults;
    std::map<std::string, Setter> keys;
};

const std::map<std::string, IntegratorSpec>& specs() {
    using namespace reference;
    using AmbientOcclusion = reference::AmbientOcclusion; // not obscura::AmbientOcclusion, the module
    static const std::map<std::string, IntegratorSpec> s = {
        {"ao",
         {AmbientOcclusion{},
          {{"radius", [](Quantity& q, const std::string& k, const std::string& v) { as<AmbientOcclusion>(q).radius = distance(k, v); }},
           {"cosine", [](Quantity& q, const std::string& k, const std::string& v) {
                as<AmbientOcclusion>(q).cosineWeighted = parseBool(k, v);
            }}}}},
        {"obscurance",
         {Obscurance{},
          {{"max_distance",
            [](Quantity& q, const std::string& k, const std::string& v) { as<Obscurance>(q).maxDistance = distance(k, v); }},
           {"cosine", [](Quantity& q, const std::string& k, const std::string& v) {
                as<Obscurance>(q).cosineWeighted = parseBool(k, v);
            }},
           {"falloff", [](Quantity& q, const std::string& k, const std::string& v) {
                static const std::map<std::string, ObscuranceFalloff> names = {{"none", ObscuranceFalloff::None},
                                                                               {"linear", ObscuranceFalloff::Linear},
                                                                               {"quadratic", ObscuranceFalloff::Quadratic},
                                                                               {"smooth", ObscuranceFalloff::Smooth}};
                const auto it = names.find(v);
                if (it == names.end())
                    throw Error(ErrorCode::Parse, "--set " + k + "=" + v + ": expected none, linear, quadratic or smooth");
                as<Obscurance>(q).falloff = it->second;
            }}}}},
        {"bent_normal",
         {BentNormal{},
          {{"radius", [](Quantity& q, const std::string& k, const std::string& v) { as<BentNormal>(q).radius = distance(k, v); }}}}},
        {"direct",
         {DirectLight{},
          {{"visibility",
            [](Quantity& q, const std::string& k, const std::string& v) { as<DirectLight>(q).visibility = parseBool(k, v); }}}}},
        {"indirect",
         {IndirectLight{},
          {{"radius", [](Quantity& q, const std::string& k, const std::string& v) { as<IndirectLight>(q).radius = distance(k, v); }},
           {"direct_visibility", [](Quantity& q, const std::string& k, const std::string& v) {
                as<IndirectLight>(q).directVisibility = parseBool(k, v);
            }}}}},
        {"shadow",
         {Shadow{},
          {{"light", [](Quantity& q, const std::string& k, const std::string& v) {
                as<Shadow>(q).light = static_cast<std::size_t>(parseInteger(k, v, 0, 1000000, ""));
            }}}}},
        {"media",
         {SingleScattering{},
          {{"medium", [](Quantity& q, const std::string& k, const std::string& v) {
                as<SingleScattering>(q).medium = static_cast<std::size_t>(parseInteger(k, v, 0, 1000000, ""));
            }},
           {"shadows",
            [](Quantity& q, const std::string& k, const std::string& v) { as<SingleScattering>(q).shadows = parseBool(k, v); }}}}},
        {"ibl",
         {ImageBasedLight{},
          {{"irradiance",
            [](Quantity& q, const std::string& k, const std::string& v) { as<ImageBasedLight>(q).irradianceOnly = parseBool(k, v); }},
           {"visibility",
            [](Quantity& q, const std::string& k, const std::string& v) { as<ImageBasedLight>(q).visibility = parseBool(k, v); }}}}},
    };
    return s;
}

} // namespace

std::vector<std::string> integratorNames() {
    std::vector<std::string> names;
    for (const auto& e : specs()) names.push_back(e.first);
    return names;
}

reference::Quantity parseQuantity(const std::string& integrator, const std::vector<std::string>& sets) {
    const auto it = specs().find(integrator);
    if (it == specs().end()) {
        std::string known;
        for (const auto& n : integratorNames()) known += " " + n;
        throw Error(ErrorCode::Parse, "unknown integrator \"" + integrator + "\" (known:" + known + ")");
    }
    reference::Quantity q = it->second.defaults;
    for (const auto& kv : sets) {
        const auto [key, value] = splitSetting(kv);
        const auto setter = it->second.keys.find(key);
        if (setter == it->second.keys.end()) {
            std::string known;
            for (const auto& k : it->second.keys) known += " " + k.first;
            throw Error(ErrorCode::Parse, integrator + " has no setting \"" + key + "\" (settings:" + known + ")");
        }
        setter->second(q, key, value);
    }
    return q;
}

} // namespace obscura::cli
