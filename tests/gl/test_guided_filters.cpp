// The geometry-aware blur and the joint bilateral upsampling (shaders/filters/) against a
// CPU model of what they document, on values the test controls: ao.comp.glsl is replaced
// (Context::addShaderSource) by itself with the estimate swapped for a hash of the pixel,
// k / 256 for the AO (exact in half floats) and a hashed unit vector for the bent normal.
// Everything else is the module's own code: its guide, the blur's two passes through half
// float temporaries, the upsampling, the background handling, the image edges, and the
// refinement, whose pixels the integrator computes with the hash of their own G-buffer pixel.
#include "gl_fixture.hpp"

#include "obscura/assets.hpp"
#include "obscura/obscura.hpp"
#include "scene_builders.hpp"

#include <catch2/catch.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/packing.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <initializer_list>
#include <limits>
#include <string>

using namespace obscura;

namespace {

// The hash both sides compute: GLSL's uint arithmetic is C++'s std::uint32_t arithmetic.
const char* kHashGlsl = R"(
uint filterTestHash(ivec2 q, uint salt) {
    uint h = (uint(q.x) * 73856093u) ^ (uint(q.y) * 19349663u) ^ (salt * 83492791u);
    h ^= h >> 13; h *= 0x5bd1e995u; h ^= h >> 15;
    return h & 255u;
}
float filterTestValue(ivec2 q, uint salt) { return float(filterTestHash(q, salt)) / 256.0; }
vec3 filterTestDirection(ivec2 q) {
    return normalize(vec3(filterTestValue(q, 1u) - 0.5, filterTestValue(q, 2u) - 0.5, 0.75));
}
)";

// The filters' last step multiplies indirect light by each pixel's albedo (MODULATE). The
// model has no albedo (and could not repeat the texture unit's sRGB decoding exactly): the
// step is left out where the filters' arithmetic is checked.
const test::ShaderEdit kNoModulation{"filters/filter_common.glsl",
                                     "return vec4(v.rgb * clampAlbedo(texelFetch(filterModulate, texel, 0).rgb), v.a);",
                                     "return v;", ""};

std::uint32_t hashOf(int x, int y, std::uint32_t salt) {
    std::uint32_t h = (std::uint32_t(x) * 73856093u) ^ (std::uint32_t(y) * 19349663u) ^ (salt * 83492791u);
    h ^= h >> 13;
    h *= 0x5bd1e995u;
    h ^= h >> 15;
    return h & 255u;
}
float valueOf(int x, int y, std::uint32_t salt) { return float(hashOf(x, y, salt)) / 256.0f; }
glm::vec3 directionOf(int x, int y) {
    return glm::normalize(glm::vec3(valueOf(x, y, 1) - 0.5f, valueOf(x, y, 2) - 0.5f, 0.75f));
}

// readTexture's row 0 is the image's top; the shaders' pixel (0, 0) is GL's bottom row. The
// model works in GL's rows, as the low resolution's blocks do (odd heights differ).
Image glRows(Image image) {
    const std::size_t row = std::size_t(image.width) * image.channels;
    for (int y = 0; y < image.height / 2; ++y)
        std::swap_ranges(image.pixels.begin() + y * row, image.pixels.begin() + (y + 1) * row,
                         image.pixels.begin() + (image.height - 1 - y) * row);
    return image;
}

float toHalf(float v) { return glm::unpackHalf1x16(glm::packHalf1x16(v)); }
glm::vec3 toHalf(glm::vec3 v) { return {toHalf(v.x), toHalf(v.y), toHalf(v.z)}; }
glm::vec4 toHalf(glm::vec4 v) { return {toHalf(glm::vec3(v)), toHalf(v.w)}; }

// What the filters weigh with (filter_common.glsl): a low-resolution pixel's guide, or a
// G-buffer pixel's normal and view z; z = 0 is the background.
struct Guide {
    glm::dvec3 n{0.0};
    double z = 0.0;
};

// The filters' settings and inputs: `channels` of the value are compared (AO 1, GI 4).
struct Model {
    int width, height, scale, taps;
    double depthSigma, normalPower;
    bool unitRange;
    float background; // the value of background pixels
    Image positions, normals;
    double refineThreshold = 0.0;

    int lowWidth() const { return (width + scale - 1) / scale; }
    int lowHeight() const { return (height + scale - 1) / scale; }

    bool isBackground(int x, int y) const { return positions.at(x, y, 3) == 0.0f || normals.at(x, y, 3) == 0.0f; }
    glm::dvec3 normalAt(int x, int y) const { return {normals.at(x, y, 0), normals.at(x, y, 1), normals.at(x, y, 2)}; }

    // The integrator's guide: its G-buffer sample at i * scale, normal renormalized.
    Guide lowGuide(int i, int j) const {
        const int x = std::min(i * scale, width - 1), y = std::min(j * scale, height - 1);
        if (isBackground(x, y)) return {};
        return {glm::normalize(normalAt(x, y)), positions.at(x, y, 2)};
    }

    double weight(const Guide& a, const Guide& b) const {
        const double dz = (b.z - a.z) / (depthSigma * std::abs(a.z));
        const double c = glm::dot(a.n, b.n);
        return std::exp(-0.5 * dz * dz) * (normalPower > 0.0 ? std::pow(std::max(c, 0.0), normalPower) : 1.0);
    }

    glm::vec4 finish(glm::dvec4 v) const {
        return toHalf(glm::vec4(unitRange ? glm::clamp(v, glm::dvec4(0.0), glm::dvec4(1.0)) : v));
    }
};

// The low-resolution value and direction, as the integrator writes them.
struct LowImages {
    std::vector<glm::vec4> value;
    std::vector<glm::vec3> direction;
};

// The integrator's low-resolution images as the model sees them: `value` and `direction` at
// pixels with geometry, `background` and no direction elsewhere.
LowImages lowImages(const Model& m, glm::vec4 background, const std::function<glm::vec4(int, int)>& value,
                    const std::function<glm::vec3(int, int)>& direction) {
    LowImages low;
    for (int j = 0; j < m.lowHeight(); ++j)
        for (int i = 0; i < m.lowWidth(); ++i) {
            const bool geometry = m.lowGuide(i, j).z != 0.0;
            low.value.push_back(geometry ? value(i, j) : background);
            low.direction.push_back(geometry ? direction(i, j) : glm::vec3(0.0f));
        }
    return low;
}

// One separable pass: taps along `step`, background pixels left as they are. Directions are
// averaged as offsets from their own pixel's normal and added to the centre's.
LowImages blurPass(const Model& m, const LowImages& in, glm::ivec2 step) {
    LowImages out = in;
    const int w = m.lowWidth(), h = m.lowHeight();
    const double sigma = std::max(0.5 * m.taps, 0.5);
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i) {
            const Guide c = m.lowGuide(i, j);
            if (c.z == 0.0) continue;
            const std::size_t centre = std::size_t(j) * w + i;
            glm::dvec4 sum = in.value[centre];
            glm::dvec3 offset = glm::dvec3(in.direction[centre]) - c.n;
            double total = 1.0;
            for (int k = -m.taps; k <= m.taps; ++k) {
                const glm::ivec2 q = glm::ivec2(i, j) + k * step;
                if (k == 0 || q.x < 0 || q.y < 0 || q.x >= w || q.y >= h) continue;
                const Guide g = m.lowGuide(q.x, q.y);
                if (g.z == 0.0) continue;
                const double wk = std::exp(-0.5 * k * k / (sigma * sigma)) * m.weight(c, g);
                const std::size_t at = std::size_t(q.y) * w + q.x;
                sum += wk * glm::dvec4(in.value[at]);
                offset += wk * (glm::dvec3(in.direction[at]) - g.n);
                total += wk;
            }
            out.value[centre] = m.finish(sum / total);
            out.direction[centre] = toHalf(glm::vec3(glm::normalize(c.n + offset / total)));
        }
    return out;
}

// What a G-buffer pixel may hold: the upsampling's blend, or, where it lists the pixel for
// refinement, what the integrator writes there at full resolution. More pixels to refine
// than the list holds: none is refined. Both are allowed where the model cannot tell which
// the GPU did: a total weight within float rounding of the threshold, and every listed pixel
// when such pixels decide whether the list overflows.
struct Expected {
    std::vector<glm::vec4> value, direction;          // the blend
    std::vector<glm::vec4> refinedValue, refinedDirection;
    std::vector<char> refined, either;
    int qualifying = 0;                               // pixels below the threshold
    int surelyAsked = 0, possiblyAsked = 0;           // of them, outside and within the slack
    bool overflow = false;                            // surely more than the list holds
    bool maybeOverflow = false;                       // possibly
};

// The integrator's full-resolution value and direction at a G-buffer pixel.
struct FullResolution {
    std::function<glm::vec4(int, int)> value;
    std::function<glm::vec4(int, int)> direction;
};

// The refinement list's capacity (guided_filters.cpp): a quarter of the G-buffer's pixels.
int refineCapacity(const Model& m) { return (m.width * m.height + 3) / 4; }

Expected upsample(const Model& m, const LowImages& low, const FullResolution& full = {}) {
    Expected e;
    const int w = m.lowWidth(), h = m.lowHeight();
    // The GPU's weights are float (exp2 of a float exponent): about 1e-6 relative.
    constexpr double kThresholdSlack = 1e-4;
    const auto noRefinement = [&] {
        e.refinedValue.push_back(glm::vec4(0.0f));
        e.refinedDirection.push_back(glm::vec4(0.0f));
        e.refined.push_back(0);
        e.either.push_back(0);
    };
    for (int y = 0; y < m.height; ++y)
        for (int x = 0; x < m.width; ++x) {
            if (m.isBackground(x, y)) {
                e.value.push_back(glm::vec4(m.background));
                e.direction.push_back(glm::vec4(0.0f));
                noRefinement();
                continue;
            }
            const Guide target{m.normalAt(x, y), m.positions.at(x, y, 2)};
            const glm::ivec2 base(x / m.scale, y / m.scale);
            const glm::dvec2 f = glm::dvec2(x - base.x * m.scale, y - base.y * m.scale) / double(m.scale);
            glm::dvec4 sum(0.0), nearest(m.background);
            glm::dvec3 offset(0.0), nearestOffset(0.0); // directions as in blurPass
            double total = 0.0, nearestDz = 1e30;
            for (int c = 0; c < 4; ++c) {
                const glm::ivec2 corner(c & 1, c >> 1);
                const glm::ivec2 q = glm::min(base + corner, glm::ivec2(w - 1, h - 1));
                const Guide g = m.lowGuide(q.x, q.y);
                if (g.z == 0.0) continue;
                const std::size_t at = std::size_t(q.y) * w + q.x;
                const double bilinear = (corner.x ? f.x : 1.0 - f.x) * (corner.y ? f.y : 1.0 - f.y);
                const double wc = bilinear * m.weight(target, g);
                sum += wc * glm::dvec4(low.value[at]);
                offset += wc * (glm::dvec3(low.direction[at]) - g.n);
                total += wc;
                if (std::abs(g.z - target.z) < nearestDz) {
                    nearestDz = std::abs(g.z - target.z);
                    nearest = low.value[at];
                    nearestOffset = glm::dvec3(low.direction[at]) - g.n;
                }
            }
            const bool weighted = total > 1e-6;
            e.value.push_back(m.finish(weighted ? sum / total : nearest));
            const glm::dvec3 direction = glm::normalize(target.n + (weighted ? offset / total : nearestOffset));
            e.direction.push_back(glm::vec4(toHalf(glm::vec3(direction)), 1.0f));
            if (m.refineThreshold > 0.0 && total < m.refineThreshold + kThresholdSlack) {
                e.refinedValue.push_back(full.value(x, y));
                e.refinedDirection.push_back(full.direction(x, y));
                e.refined.push_back(1);
                e.either.push_back(total > m.refineThreshold - kThresholdSlack);
                e.qualifying += total < m.refineThreshold;
            } else {
                noRefinement();
            }
        }
    const int surely = int(std::count(e.refined.begin(), e.refined.end(), 1)) - int(std::count(e.either.begin(), e.either.end(), 1));
    const int possibly = int(std::count(e.refined.begin(), e.refined.end(), 1));
    e.surelyAsked = surely;
    e.possiblyAsked = possibly;
    e.overflow = surely > refineCapacity(m);
    e.maybeOverflow = possibly > refineCapacity(m);
    if (e.overflow) {
        std::fill(e.refined.begin(), e.refined.end(), 0);
        std::fill(e.either.begin(), e.either.end(), 0);
    } else if (e.maybeOverflow) {
        for (std::size_t i = 0; i < e.refined.size(); ++i) e.either[i] |= e.refined[i];
    }
    return e;
}

// The difference of `gpu` (GL rows) from what each pixel may hold (Expected), the blend or
// the refined value; `refinedCount` counts the pixels that hold the refined one and not the
// blend (within `tolerance`).
double worstDifference(const Image& gpu, const Expected& e, bool directions, int channels, double tolerance,
                       int* refinedCount = nullptr) {
    const std::vector<glm::vec4>& blend = directions ? e.direction : e.value;
    const std::vector<glm::vec4>& refined = directions ? e.refinedDirection : e.refinedValue;
    double worst = 0.0;
    for (int y = 0; y < gpu.height; ++y)
        for (int x = 0; x < gpu.width; ++x) {
            const std::size_t i = std::size_t(y) * gpu.width + x;
            double toBlend = 0.0, toRefined = 0.0;
            for (int c = 0; c < channels; ++c) {
                toBlend = std::max(toBlend, double(std::abs(gpu.at(x, y, c) - blend[i][c])));
                toRefined = std::max(toRefined, double(std::abs(gpu.at(x, y, c) - refined[i][c])));
            }
            if (refinedCount && e.refined[i] && toRefined <= tolerance && toBlend > tolerance) ++*refinedCount;
            worst = std::max(worst, e.either[i] ? std::min(toBlend, toRefined) : e.refined[i] ? toRefined : toBlend);
        }
    return worst;
}

// How many pixels the GPU refined (`refined`, counted by worstDifference) against the model.
// The box's edges and the background's give pixels to refine at any threshold above 0; at 1
// nearly all but the exact ones qualify, more than the list holds, and none is refined.
// Counted are the refined pixels whose blend differs from the refined value by more than
// the tolerance; a few coincide (values are multiples of 1/256), hence the 9/10.
// `reported`, the module's lastRefinement: the pixels the model lists, those within the
// threshold's slack maybe; all of them refined unless more than the list holds; at least the
// pixels seen refined. Without a threshold, nothing.
void checkRefinedCount(const Model& m, const Expected& expected, int refined, const RefinementCount& reported) {
    CAPTURE(m.refineThreshold, expected.qualifying, expected.overflow, refined, reported.asked, reported.refined);
    CHECK(reported.asked >= std::size_t(expected.surelyAsked));
    CHECK(reported.asked <= std::size_t(expected.possiblyAsked));
    CHECK(reported.refined == (reported.asked <= std::size_t(refineCapacity(m)) ? reported.asked : 0));
    CHECK(reported.refined >= std::size_t(refined));
    if (m.refineThreshold > 0.0) CHECK(expected.qualifying > 0);
    if (expected.overflow) {
        CHECK(refined == 0);
        return;
    }
    CHECK(refined <= std::min(expected.qualifying, refineCapacity(m)));
    if (!expected.maybeOverflow) CHECK(refined >= expected.qualifying * 9 / 10);
}

// Each step's result is rounded to a half float (to nearest in the shaders, roundedToHalf;
// the bent normal by the store, which GL leaves to the implementation: llvmpipe's truncate),
// and the GPU's float weights may put a value on the other side of a rounding boundary than
// the model's: one ulp, 2^-11 for values in [-1, 1], per step: the horizontal pass, the
// vertical pass and the output, 3 ulps in all (the bent normal is rounded once more, where
// the AO pass stores it).
// The weights' float error (about 1e-6 relative) adds at most 1e-5 to a weighted mean.
constexpr double kUlp = 1.0 / 2048.0;
constexpr double kTolerance = 3.0 * kUlp + 1e-5, kDirectionTolerance = 4.0 * kUlp + 1e-5;

// The AO module's last output (`out`, bent normals on) against the model's, within the
// tolerances above, and its refinement count.
void checkAoAgainstModel(Context& ctx, const AmbientOcclusion& ao, const AmbientOcclusionView& out, const Model& m,
                         const Expected& expected) {
    int refined = 0;
    CHECK(worstDifference(glRows(readTexture(ctx, out.ao)), expected, false, 1, kTolerance, &refined) <= kTolerance);
    CHECK(worstDifference(glRows(readTexture(ctx, out.bentNormal)), expected, true, 4, kDirectionTolerance) <=
          kDirectionTolerance);
    checkRefinedCount(m, expected, refined, ao.lastRefinement());
}

// The Cornell box seen from outside its open side: the background, its edge and the box's
// edges in view; odd sizes, so the low resolution's last row and column are partly outside.
constexpr int kWidth = 45, kHeight = 37;

struct FilterFixture {
    test::GlFixture gl;
    Context ctx{gl.desc()};
    GBuffer gbuffer{ctx};
    GBufferView view;
    Image positions, normals;

    //! scale: of the scene and the camera's distances (the same image, other view depths).
    void render(float scale = 1.0f) {
        assets::LoadedScene cornell = assets::builtinScene("cornell");
        for (Mesh& mesh : cornell.scene.meshes) mesh.model = glm::scale(glm::mat4(1.0f), glm::vec3(scale)) * mesh.model;
        const Camera camera =
            Camera::perspective({glm::vec3(278, 273, -700) * scale, glm::vec3(278, 273, 0) * scale, {0, 1, 0}},
                                glm::radians(45.0f), float(kWidth) / float(kHeight), 10.0f * scale, 5000.0f * scale);
        view = gbuffer.render(cornell.scene, camera, {kWidth, kHeight, true, {}});
        positions = glRows(readTexture(ctx, gbuffer.positions(view)));
        normals = glRows(readTexture(ctx, view.normal));
        int background = 0;
        for (int y = 0; y < kHeight; ++y)
            for (int x = 0; x < kWidth; ++x) background += positions.at(x, y, 3) == 0.0f;
        REQUIRE(background > 0);
        REQUIRE(background < kWidth * kHeight / 2);
    }

    Model model(int scale, int taps, bool unitRange, float background) const {
        return {kWidth, kHeight, scale, taps, 0.05, 16.0, unitRange, background, positions, normals};
    }
};

// One setup of the filters under test: the resolution, blur taps each side and refinement
// threshold, and the integrator's settings (AmbientOcclusionSettings or
// IndirectLightSettings) that ask for it.
struct FilterCase {
    AoResolution resolution;
    int taps;
    float refine;

    template <class Settings> Settings settings() const {
        Settings s;
        s.resolution = resolution;
        s.blurRadius = taps;
        s.refineThreshold = refine;
        return s;
    }
};

// Half and quarter resolution, each with every taps and refinement threshold given.
std::vector<FilterCase> filterCases(std::initializer_list<int> taps, std::initializer_list<float> refines) {
    std::vector<FilterCase> cases;
    for (const AoResolution resolution : {AoResolution::Half, AoResolution::Quarter})
        for (const int t : taps)
            for (const float refine : refines) cases.push_back({resolution, t, refine});
    return cases;
}

} // namespace

TEST_CASE("The half and quarter resolution blur and upsampling of AO and bent normals compute the documented "
          "guided filters", "[filters][ao]") {
    FilterFixture f;
    test::overrideShader(f.ctx, "ao/ao.comp.glsl", "const Estimate e = Estimate(sums.a.x, sums.a.yzw, sums.b.x);",
                         "const Estimate e = Estimate(1.0 - filterTestValue(pixel, 0u), filterTestDirection(pixel), 1.0);",
                         kHashGlsl);
    f.render();
    AmbientOcclusion ao(f.ctx);
    // Refined pixels hold the overridden estimate at their own G-buffer pixel.
    const FullResolution full{[](int x, int y) { return glm::vec4(valueOf(x, y, 0)); },
                              [](int x, int y) { return glm::vec4(toHalf(directionOf(x, y)), 1.0f); }};
    for (const FilterCase setup : filterCases({0, 1, 3}, {0.0f, 0.25f, 1.0f})) {
        const auto [resolution, taps, refine] = setup;
        CAPTURE(static_cast<int>(resolution), taps, refine);
        AmbientOcclusionSettings s = setup.settings<AmbientOcclusionSettings>();
        s.bentNormals = true;
        const AmbientOcclusionView out = ao.run(f.view, s);
        Model m = f.model(static_cast<int>(resolution), taps, true, 1.0f);
        m.refineThreshold = refine;
        LowImages low = lowImages(m, glm::vec4(1.0f), [](int i, int j) { return glm::vec4(valueOf(i, j, 0)); },
                                  [](int i, int j) { return toHalf(directionOf(i, j)); });
        if (taps > 0) low = blurPass(m, blurPass(m, low, {1, 0}), {0, 1});
        const Expected expected = upsample(m, low, full);
        checkAoAgainstModel(f.ctx, ao, out, m, expected);
    }
    // At full resolution nothing is refined, whatever the run before.
    ao.run(f.view, FilterCase{AoResolution::Full, 1, 0.25f}.settings<AmbientOcclusionSettings>());
    CHECK(ao.lastRefinement().asked == 0);
    CHECK(ao.lastRefinement().refined == 0);
}

namespace {

// At full resolution the blur's second pass is the last step: what it writes is the output,
// with no upsampling. Two roundings to half floats (the horizontal and the vertical pass; the
// bent normal once more where the AO pass stores it), each one ulp as above, and the weights'
// float error.
Expected blurredAtFullResolution(const Model& m, const LowImages& blurred) {
    Expected e;
    for (int y = 0; y < m.height; ++y)
        for (int x = 0; x < m.width; ++x) {
            const std::size_t i = std::size_t(y) * m.width + x;
            const bool geometry = m.lowGuide(x, y).z != 0.0;
            e.value.push_back(blurred.value[i]);
            e.direction.push_back(glm::vec4(blurred.direction[i], geometry ? 1.0f : 0.0f));
            e.refinedValue.push_back(glm::vec4(0.0f));
            e.refinedDirection.push_back(glm::vec4(0.0f));
            e.refined.push_back(0);
            e.either.push_back(0);
        }
    return e;
}

} // namespace

TEST_CASE("The full resolution blur of AO bent normals and indirect light computes the documented guided filter",
          "[filters][ao][gi]") {
    FilterFixture f;
    test::overrideShaders(f.ctx, {{"ao/ao.comp.glsl", "const Estimate e = Estimate(sums.a.x, sums.a.yzw, sums.b.x);",
                                   "const Estimate e = Estimate(1.0 - filterTestValue(pixel, 0u), filterTestDirection(pixel), 1.0);",
                                   kHashGlsl},
                                  {"filters/rgb_integrator_main.glsl", "vec4(clampRadiance(albedo * integratorIncident(sums.a.rgb)), 1.0)",
                                   "vec4(filterTestValue(pixel, 0u), filterTestValue(pixel, 1u), filterTestValue(pixel, 2u), 1.0)",
                                   kHashGlsl},
                                  kNoModulation});
    f.render();
    AmbientOcclusion ao(f.ctx);
    IndirectLight gi(f.ctx);
    constexpr double kValueTolerance = 2.0 * kUlp + 1e-5, kBentTolerance = 3.0 * kUlp + 1e-5;
    for (const int taps : {1, 3}) {
        CAPTURE(taps);
        AmbientOcclusionSettings s = FilterCase{AoResolution::Full, taps, 0.0f}.settings<AmbientOcclusionSettings>();
        s.bentNormals = true;
        const AmbientOcclusionView out = ao.run(f.view, s);
        const Model m = f.model(1, taps, true, 1.0f);
        const LowImages low = lowImages(m, glm::vec4(1.0f), [](int x, int y) { return glm::vec4(valueOf(x, y, 0)); },
                                        [](int x, int y) { return toHalf(directionOf(x, y)); });
        const Expected expected = blurredAtFullResolution(m, blurPass(m, blurPass(m, low, {1, 0}), {0, 1}));
        CHECK(worstDifference(glRows(readTexture(f.ctx, out.ao)), expected, false, 1, kValueTolerance) <= kValueTolerance);
        CHECK(worstDifference(glRows(readTexture(f.ctx, out.bentNormal)), expected, true, 4, kBentTolerance) <= kBentTolerance);
        // The blur moves values: a model of no blur is far off.
        CHECK(worstDifference(glRows(readTexture(f.ctx, out.ao)), blurredAtFullResolution(m, low), false, 1, kValueTolerance) >
              0.05);

        const Image radiance =
            glRows(readTexture(f.ctx, gi.run(f.view, FilterCase{AoResolution::Full, taps, 0.0f}.settings<IndirectLightSettings>()).radiance));
        const Model rgb = f.model(1, taps, false, 0.0f);
        const LowImages lowRgb = lowImages(
            rgb, glm::vec4(0.0f), [](int x, int y) { return glm::vec4(valueOf(x, y, 0), valueOf(x, y, 1), valueOf(x, y, 2), 1.0f); },
            [](int, int) { return glm::vec3(0.0f); });
        const Expected expectedRgb = blurredAtFullResolution(rgb, blurPass(rgb, blurPass(rgb, lowRgb, {1, 0}), {0, 1}));
        CHECK(worstDifference(radiance, expectedRgb, false, 4, kValueTolerance) <= kValueTolerance);
        CHECK(worstDifference(radiance, blurredAtFullResolution(rgb, lowRgb), false, 4, kValueTolerance) > 0.05);
    }
}

TEST_CASE("A subnormal blur depth sigma gives the guided filters' limit, in which only equal depths count",
          "[filters][ao][stability]") {
    // blurDepthSigma accepts any float in (0, 1]. At the smallest (2^-149), sigma |z| rounds
    // to 0 in float for |z| < 0.5 (the Cornell box scaled to a tenth of a unit here; a GPU that
    // flushes denormals makes it 0 at any z), so the guide's relative depth difference was
    // 0 / 0 for two samples at the same view z (the box's back wall faces the camera: its
    // pixels share their depth exactly), a NaN weight. The model, in double, computes the
    // limit: weight 1 at equal depth, 0 at any other. Same tolerances as the test above.
    FilterFixture f;
    test::overrideShader(f.ctx, "ao/ao.comp.glsl", "const Estimate e = Estimate(sums.a.x, sums.a.yzw, sums.b.x);",
                         "const Estimate e = Estimate(1.0 - filterTestValue(pixel, 0u), filterTestDirection(pixel), 1.0);",
                         kHashGlsl);
    f.render(1e-4f);
    double farthest = 0.0;
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) farthest = std::max(farthest, std::abs(double(f.positions.at(x, y, 2))));
    REQUIRE(farthest < 0.5);
    AmbientOcclusion ao(f.ctx);
    const FullResolution full{[](int x, int y) { return glm::vec4(valueOf(x, y, 0)); },
                              [](int x, int y) { return glm::vec4(toHalf(directionOf(x, y)), 1.0f); }};
    constexpr float kSigma = std::numeric_limits<float>::denorm_min();
    for (const FilterCase setup : filterCases({2}, {0.0f, 0.25f})) {
        const auto [resolution, taps, refine] = setup;
        CAPTURE(static_cast<int>(resolution), taps, refine);
        AmbientOcclusionSettings s = setup.settings<AmbientOcclusionSettings>();
        s.bentNormals = true;
        s.blurDepthSigma = kSigma;
        const AmbientOcclusionView out = ao.run(f.view, s);
        Model m = f.model(static_cast<int>(resolution), taps, true, 1.0f);
        m.depthSigma = kSigma;
        m.refineThreshold = refine;
        LowImages low = lowImages(m, glm::vec4(1.0f), [](int i, int j) { return glm::vec4(valueOf(i, j, 0)); },
                                  [](int i, int j) { return toHalf(directionOf(i, j)); });
        low = blurPass(m, blurPass(m, low, {1, 0}), {0, 1});
        const Expected expected = upsample(m, low, full);
        checkAoAgainstModel(f.ctx, ao, out, m, expected);
    }
}

TEST_CASE("The blur and upsampling keep an open faceted sphere's bent normals on its own normals", "[filters][ao]") {
    // Where nothing occludes, a bent normal is the pixel's normal. The filters average bent
    // normals as offsets from their pixels' normals (filter_common.glsl), so on a sphere of
    // 1280 facets (the G-buffer holds face normals, some 8 degrees apart from facet to facet)
    // every pixel keeps its own normal up to rounding: each of the three steps
    // (two blur passes and the upsampling) rounds its result to a half float, 1 ulp (2^-11 in
    // [-1, 1]) per component, as does the integrator's store: 4 ulps per component, and the
    // renormalization may move a component by the offset's length, sqrt(3) times that. A mean
    // of the directions themselves is off by the normals' turn across the blocks (measured
    // before this design: 0.08 to 0.32 here).
    test::GlFixture gl;
    Context ctx{gl.desc()};
    test::overrideShader(ctx, "ao/ao.comp.glsl", "const Estimate e = Estimate(sums.a.x, sums.a.yzw, sums.b.x);",
                         "const Estimate e = Estimate(0.0, normal, 1.0);", "");
    GBuffer gbuffer{ctx};
    const Camera camera = Camera::perspective({{0, 0, 3.2}, {0, 0, 0}, {0, 1, 0}}, glm::radians(45.0f),
                                              float(kWidth) / float(kHeight), 0.5f, 10.0f);
    const GBufferView view = gbuffer.render(test::singleMeshScene(test::icosphereMesh(3)), camera, {kWidth, kHeight, true, {}});
    const Image normals = readTexture(ctx, view.normal);
    AmbientOcclusion ao(ctx);
    const double tolerance = std::sqrt(3.0) * 4.0 * kUlp + 1e-5;
    for (const FilterCase setup : filterCases({0, 1, 3}, {0.0f, 0.25f})) {
        CAPTURE(static_cast<int>(setup.resolution), setup.taps, setup.refine);
        AmbientOcclusionSettings s = setup.settings<AmbientOcclusionSettings>();
        s.bentNormals = true;
        const Image bent = readTexture(ctx, ao.run(view, s).bentNormal);
        int geometry = 0;
        double worst = 0.0;
        for (int y = 0; y < kHeight; ++y)
            for (int x = 0; x < kWidth; ++x) {
                if (normals.at(x, y, 3) == 0.0f) continue;
                ++geometry;
                const glm::dvec3 n = glm::normalize(glm::dvec3(normals.at(x, y, 0), normals.at(x, y, 1), normals.at(x, y, 2)));
                for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(double(bent.at(x, y, c)) - n[c]));
            }
        CHECK(geometry > kWidth * kHeight / 3);
        CHECK(worst <= tolerance);
    }
}

TEST_CASE("The half and quarter resolution blur and upsampling of indirect light compute the documented guided "
          "filters", "[filters][gi]") {
    FilterFixture f;
    // The albedo the upsampling multiplies in is left out here (kNoModulation): the test of
    // that step is "Filtered indirect light takes each pixel's own albedo" in test_indirect_light_gather.cpp.
    test::overrideShaders(f.ctx, {{"filters/rgb_integrator_main.glsl", "vec4(clampRadiance(albedo * integratorIncident(sums.a.rgb)), 1.0)",
                                   "vec4(filterTestValue(pixel, 0u), filterTestValue(pixel, 1u), filterTestValue(pixel, 2u), 1.0)",
                                   kHashGlsl},
                                  kNoModulation});
    f.render();
    IndirectLight gi(f.ctx);
    const FullResolution full{[](int x, int y) { return glm::vec4(valueOf(x, y, 0), valueOf(x, y, 1), valueOf(x, y, 2), 1.0f); },
                              [](int, int) { return glm::vec4(0.0f); }};
    for (const FilterCase setup : filterCases({0, 2}, {0.0f, 0.25f})) {
        const auto [resolution, taps, refine] = setup;
        CAPTURE(static_cast<int>(resolution), taps, refine);
        const IndirectLightSettings s = setup.settings<IndirectLightSettings>();
        const Image radiance = glRows(readTexture(f.ctx, gi.run(f.view, s).radiance));
        Model m = f.model(static_cast<int>(resolution), taps, false, 0.0f);
        m.refineThreshold = refine;
        LowImages low = lowImages(
            m, glm::vec4(0.0f), [](int i, int j) { return glm::vec4(valueOf(i, j, 0), valueOf(i, j, 1), valueOf(i, j, 2), 1.0f); },
            [](int, int) { return glm::vec3(0.0f); });
        if (taps > 0) low = blurPass(m, blurPass(m, low, {1, 0}), {0, 1});
        const Expected expected = upsample(m, low, full);
        int refined = 0;
        CHECK(worstDifference(radiance, expected, false, 4, kTolerance, &refined) <= kTolerance);
        checkRefinedCount(m, expected, refined, gi.lastRefinement());
    }
    gi.run(f.view, FilterCase{AoResolution::Full, 0, 0.25f}.settings<IndirectLightSettings>());
    CHECK(gi.lastRefinement().asked == 0);
    CHECK(gi.lastRefinement().refined == 0);
}

TEST_CASE("The blur and upsampling keep a constant image exactly constant as GLSL division and half stores allow",
          "[filters][ao][gi][stability]") {
    // A weighted mean written as sum / total of equal values may come out a float ulp below
    // them (GLSL allows division 2.5 ULP of error; here the products' rounding does it), and
    // llvmpipe's float-to-half stores round toward zero, so such a pixel lost a whole half
    // ulp (2^-11 below 1: an open plane's AO came out 0.99951). Values k / 256 are exact in
    // half floats; the geometry's pixels must hold them exactly, whatever their weights: by
    // the blends' offsets from a value they contain (weightedMean) alone, with the rounding
    // to nearest before the stores (roundedToHalf) turned off, and with both.
    constexpr int kAo = 179, kRed = 77, kGreen = 230, kBlue = 131;
    const auto constant = [](int k) { return std::to_string(k) + ".0 / 256.0"; };
    const std::vector<test::ShaderEdit> noRounding = {
        {"common/math.glsl", "float roundedToHalf(float v) { return", "float roundedToHalf(float v) { return v; return", ""},
        {"common/math.glsl", "vec4 roundedToHalf(vec4 v) { return", "vec4 roundedToHalf(vec4 v) { return v; return", ""}};
    for (const bool indirect : {false, true})
        for (const bool rounding : {true, false}) {
            CAPTURE(indirect, rounding);
            FilterFixture f;
            std::vector<test::ShaderEdit> edits = rounding ? std::vector<test::ShaderEdit>{} : noRounding;
            edits.push_back(kNoModulation); // a constant times the albedo is not constant
            if (indirect)
                edits.push_back({"filters/rgb_integrator_main.glsl", "vec4(clampRadiance(albedo * integratorIncident(sums.a.rgb)), 1.0)",
                                 "vec4(" + constant(kRed) + ", " + constant(kGreen) + ", " + constant(kBlue) + ", 1.0)", ""});
            else
                edits.push_back({"ao/ao.comp.glsl", "const Estimate e = Estimate(sums.a.x, sums.a.yzw, sums.b.x);",
                                 "const Estimate e = Estimate(1.0 - " + constant(kAo) + ", normal, 1.0);", ""});
            test::overrideShaders(f.ctx, edits);
            f.render();
            AmbientOcclusion ao(f.ctx);
            IndirectLight gi(f.ctx);
            const glm::vec4 expected = indirect ? glm::vec4(kRed, kGreen, kBlue, 256) / 256.0f : glm::vec4(kAo / 256.0f);
            const int channels = indirect ? 3 : 1;
            for (const FilterCase setup : filterCases({1, 3}, {0.0f, 0.25f})) {
                const auto [resolution, taps, refine] = setup;
                CAPTURE(static_cast<int>(resolution), taps, refine);
                const Image out = indirect ? glRows(readTexture(f.ctx, gi.run(f.view, setup.settings<IndirectLightSettings>()).radiance))
                                           : glRows(readTexture(f.ctx, ao.run(f.view, setup.settings<AmbientOcclusionSettings>()).ao));
                const Model m = f.model(static_cast<int>(resolution), taps, !indirect, indirect ? 0.0f : 1.0f);
                int geometry = 0, changed = 0;
                for (int y = 0; y < kHeight; ++y)
                    for (int x = 0; x < kWidth; ++x) {
                        if (m.isBackground(x, y)) continue;
                        ++geometry;
                        bool same = true;
                        for (int c = 0; c < channels; ++c) same = same && out.at(x, y, c) == expected[c];
                        changed += same ? 0 : 1;
                    }
                CHECK(geometry > kWidth * kHeight / 2);
                CHECK(changed == 0);
            }
        }
}
