// Settings tables (settings_table.hpp): the ranges as written are the ranges enforced, the
// defaults lie inside them, and tools' text round-trips. The bounds tested are each table's
// own, so a range edited in a header is tested as edited.
#include "obscura/ambient_occlusion.hpp"
#include "obscura/compose.hpp"
#include "obscura/directional_occlusion.hpp"
#include "obscura/environment.hpp"
#include "obscura/error.hpp"
#include "obscura/gbuffer.hpp"
#include "obscura/indirect_light.hpp"
#include "obscura/screen_visibility.hpp"
#include "obscura/settings_table.hpp"
#include "obscura/shadow_maps.hpp"
#include "obscura/voxelizer.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <set>
#include <string>

using namespace obscura;

namespace {

bool refused(const SettingDescription& row, double value) {
    try {
        row.check(value, "S");
        return false;
    } catch (const Error& e) {
        return e.code() == ErrorCode::InvalidArgument;
    }
}

// Every row of S's table: a unique key, the default accepted, NaN and Inf refused, and for
// intervals the bounds as the brackets say (open: refused; closed: accepted; beyond: refused).
template <class S>
void checkTable(const std::string& name, const S& defaults = S{}) {
    INFO(name);
    REQUIRE_NOTHROW(validateSettings(S::table(), defaults, name));
    std::set<std::string> keys;
    for (const Setting<S>& row : S::table()) {
        INFO(row.key);
        CHECK(keys.insert(row.key).second);
        CHECK(refused(row, std::numeric_limits<double>::quiet_NaN()));
        CHECK(refused(row, std::numeric_limits<double>::infinity()));
        // What tools write for the default reads back as the default.
        const std::vector<double> parsed = row.parse(row.format(row.values(defaults)));
        for (int c = 0; c < row.channels(); ++c)
            CHECK(static_cast<float>(parsed[std::size_t(c)]) == static_cast<float>(row.get(defaults, c)));
        if (row.type == SettingType::Flag || row.type == SettingType::Choice || !row.allowed.empty()) continue;
        if (std::isfinite(row.min)) {
            CHECK(refused(row, row.min) == row.minOpen);
            CHECK(refused(row, row.min - std::max(1.0, std::abs(row.min))));
        }
        if (std::isfinite(row.max)) {
            CHECK(refused(row, row.max) == row.maxOpen);
            CHECK(refused(row, row.max + std::max(1.0, std::abs(row.max))));
        }
    }
}

} // namespace

TEST_CASE("every module's settings table: unique keys, defaults inside, bounds as written", "[settings]") {
    checkTable<AmbientOcclusionSettings>("AmbientOcclusionSettings");
    checkTable<IndirectLightSettings>("IndirectLightSettings");
    checkTable<DirectionalOcclusionSettings>("DirectionalOcclusionSettings");
    checkTable<EnvironmentSettings>("EnvironmentSettings");
    checkTable<ComposeSettings>("ComposeSettings");
    GBufferSettings gbuffer; // the size has no default: the caller's image
    gbuffer.width = gbuffer.height = 64;
    checkTable<GBufferSettings>("GBufferSettings", gbuffer);
    checkTable<ScreenTraceSettings>("ScreenTraceSettings");
    checkTable<ShadowMapSettings>("ShadowMapSettings");
    checkTable<ShadowMaskSettings>("ShadowMaskSettings");
    checkTable<VoxelizerSettings>("VoxelizerSettings");
    checkTable<TraversalSettings>("TraversalSettings");
}

TEST_CASE("settings tables: keys, nested fields, parsing and messages", "[settings]") {
    const auto& ao = AmbientOcclusionSettings::table();
    REQUIRE(findSetting(ao, "blur_radius") != nullptr);
    CHECK(findSetting(ao, "blur_radius")->field == "blurRadius");
    CHECK(findSetting(ao, "temporal")->field == "temporal.enabled");
    CHECK(findSetting(ao, "temporal_max_frames")->field == "temporal.maxFrames");

    AmbientOcclusionSettings s;
    CHECK(applySetting(ao, s, "temporal_max_frames", "32"));
    CHECK(s.temporal.maxFrames == 32);
    CHECK(applySetting(ao, s, "resolution", "quarter"));
    CHECK(s.resolution == AoResolution::Quarter);
    CHECK_FALSE(applySetting(ao, s, "no_such_key", "1"));
    CHECK_THROWS_WITH(applySetting(ao, s, "rays", "2.5"), Catch::EndsWith("rays=2.5: must be a whole number"));
    CHECK_THROWS_WITH(applySetting(ao, s, "radius", "0"), Catch::EndsWith("radius=0: must be in (0, inf) world units"));
    CHECK_THROWS_WITH(applySetting(ao, s, "ray_lanes", "3"), Catch::EndsWith("ray_lanes=3: must be one of 1|2|4|8|16"));
    CHECK_THROWS_WITH(applySetting(ao, s, "march", "fast"), Catch::EndsWith("march=fast: expected one of view|texture|hiz"));
    // Checked as the float field holds the value: 1e-50 would be 0, 1e39 infinite.
    CHECK_THROWS_WITH(applySetting(ao, s, "radius", "1e-50"), Catch::EndsWith("must be in (0, inf) world units"));
    CHECK_THROWS_WITH(applySetting(ao, s, "radius", "1e39"), Catch::EndsWith("must be in (0, inf) world units"));
    ShadowMaskSettings mask;
    CHECK_THROWS_AS(applySetting(ShadowMaskSettings::table(), mask, "light_bleed_reduction", "0.99999999"), Error);
    CHECK(SettingDescription::keyOf("shadowFilter.pcfRadius") == "shadow_filter_pcf_radius");

    // The validator's message names the struct, the field, the range and the value.
    s = {};
    s.blurDepthSigma = 0.0f;
    CHECK_THROWS_WITH(validateSettings(ao, s, "AmbientOcclusionSettings"),
                      Catch::EndsWith("AmbientOcclusionSettings::blurDepthSigma must be in (0, 1], got 0"));
    s = {};
    s.method = static_cast<AoMethod>(7);
    CHECK_THROWS_WITH(validateSettings(ao, s, "AmbientOcclusionSettings"),
                      Catch::Contains("AmbientOcclusionSettings::method is not one of its enumerators"));

    // Colours: grey or r:g:b, each channel in the range.
    ComposeSettings c;
    CHECK(applySetting(ComposeSettings::table(), c, "ambient", "0.1:0.2:0.3"));
    CHECK(c.ambient == glm::vec3(0.1f, 0.2f, 0.3f));
    CHECK(applySetting(ComposeSettings::table(), c, "ambient", "2"));
    CHECK(c.ambient == glm::vec3(2.0f));
    CHECK_THROWS_WITH(applySetting(ComposeSettings::table(), c, "ambient", "1:2"), Catch::Contains("r:g:b"));
    CHECK_THROWS_WITH(applySetting(ComposeSettings::table(), c, "ambient", "0:0:-1"), Catch::Contains(": b: must be in"));
}

TEST_CASE("settings tables refuse malformed ranges when built", "[settings]") {
    struct T {
        float x = 0.0f;
    };
    CHECK_THROWS_AS(settings::number("x", &T::x, "", "[1, 0]", ""), std::logic_error);
    CHECK_THROWS_AS(settings::number("x", &T::x, "", "[0, inf]", ""), std::logic_error);
    CHECK_THROWS_AS(settings::number("x", &T::x, "", "0..1", ""), std::logic_error);
    CHECK_NOTHROW(settings::number("x", &T::x, "", "(-inf, 0]", ""));
}
