// Combine, tone mapping and output into a host framebuffer, against the formulas of
// compose.hpp evaluated on the CPU from the same inputs.
#include "gl_fixture.hpp"
#include "scene_builders.hpp"

#include "obscura/assets.hpp"
#include "obscura/obscura.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>

using namespace obscura;

namespace {

// A host texture of one constant value (the host's own AO or indirect light).
struct ConstantTexture {
    GLuint name = 0;
    ConstantTexture(GLenum format, int width, int height, glm::vec4 value) {
        glCreateTextures(GL_TEXTURE_2D, 1, &name);
        glTextureStorage2D(name, 1, format, width, height);
        glClearTexImage(name, 0, GL_RGBA, GL_FLOAT, &value);
    }
    ~ConstantTexture() { glDeleteTextures(1, &name); }
    TextureView view(GLenum format, int width, int height) const { return {name, format, width, height}; }
};

double luminance(glm::dvec3 c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }

// Half an 8-bit sRGB code step at linear value v, in linear units: 0.5 / 255 times the
// decode's slope, taken at the upper end of the step (the slope grows with the code).
double halfSrgbStep(double v) {
    const double code = (v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055) + 0.5 / 255.0;
    const double slope = code <= 0.04045 ? 1.0 / 12.92 : 2.4 / 1.055 * std::pow((code + 0.055) / 1.055, 1.4);
    return 0.5 / 255.0 * slope;
}

using CameraOf = std::function<Camera(const assets::CameraSpec&, int width, int height)>;

struct Frame {
    test::GlFixture gl;
    Context ctx{gl.desc()};
    GBuffer gbuffer{ctx};
    Composer composer{ctx};
    GBufferView view;
    Image direct, albedo, positions; // positions' alpha: 0 on background pixels
    static constexpr int W = 32, H = 24;
    int width, height;

    //! The Cornell box at width x height, through its own camera unless `cameraOf` gives one.
    explicit Frame(int w = W, int h = H, const CameraOf& cameraOf = {}) : width(w), height(h) {
        const assets::LoadedScene cornell = assets::builtinScene("cornell");
        const Camera camera = cameraOf ? cameraOf(cornell.camera, w, h) : assets::makeCamera(cornell.camera, w, h);
        view = gbuffer.render(cornell.scene, camera, {w, h, true, {}});
        direct = readTexture(ctx, view.directRadiance);
        albedo = readTexture(ctx, view.albedo);
        positions = readTexture(ctx, gbuffer.positions(view));
    }
};

} // namespace

namespace {

// The combine of compose.hpp on frame f, every formula with and without indirect light,
// against its definition from the frame's own inputs.
void checkCombineFormulas(Frame& f) {
    const int W = f.width, H = f.height;
    const ConstantTexture ao(GL_R16F, W, H, glm::vec4(0.5f));
    const ConstantTexture indirect(GL_RGBA16F, W, H, glm::vec4(0.1f, 0.2f, 0.3f, 1.0f));
    for (CombineFormula formula : {CombineFormula::Standard, CombineFormula::Thesis, CombineFormula::Physical})
        for (bool withIndirect : {true, false}) {
            CAPTURE(static_cast<int>(formula), withIndirect);
            ComposeSettings s;
            s.formula = formula;
            s.ambient = glm::vec3(0.4f, 0.3f, 0.2f);
            s.indirectScale = 2.0f;
            s.exposure = 0.01f; // the Cornell light is ~ 1e2 W/(sr m^2): keep the values in [0, 1]
            s.toneMapper = ToneMapper::None;
            s.srgb = false;
            s.gamma = 1.0f;
            const TextureView l1View = withIndirect ? indirect.view(GL_RGBA16F, W, H) : TextureView{};
            const TextureView display = f.composer.compose({f.view, ao.view(GL_R16F, W, H), l1View}, s);
            const Image shown = readTexture(f.ctx, display), radiance = readTexture(f.ctx, f.composer.radiance());
            REQUIRE(shown.width == W);
            REQUIRE(shown.height == H);
            for (int y = 0; y < H; ++y)
                for (int x = 0; x < W; ++x)
                    for (int c = 0; c < 3; ++c) {
                        // Background pixels: L_dir alone (no AO, ambient or indirect term).
                        const bool surface = f.positions.at(x, y, 3) > 0.0f;
                        const double rho = f.albedo.at(x, y, c), l = f.direct.at(x, y, c), a = surface ? 0.5 : 1.0;
                        const double kl1 = withIndirect && surface ? s.indirectScale * 0.1 * (c + 1) : 0.0;
                        const double ambient = rho * a * s.ambient[c];
                        // Standard: both; Physical: the indirect light, where given, replaces
                        // the ambient term.
                        const double expected = formula == CombineFormula::Thesis     ? ambient + kl1 + a * l
                                                : formula == CombineFormula::Standard ? l + ambient + kl1
                                                : withIndirect                        ? l + kl1
                                                                                      : l + ambient;
                        const double error = radiance.at(x, y, c) - expected;
                        CAPTURE(x, y, c, expected, error, rho, l);
                        // radiance() is before the exposure (the tone mapper applies it). It is
                        // stored as RGBA16F, which may round toward zero: 2^-10 of it. Of the
                        // inputs, L_dir and the AO are read back as the shader reads them, but
                        // the indirect light is 0.1 (c + 1) rounded to half floats: 2^-10 of
                        // k L1 <= expected. Float arithmetic: 2^-20 of it (a few operations). The
                        // albedo is sRGB-encoded 8-bit: GL does not fix how exactly the shader's
                        // and the read-back's decodes agree (llvmpipe's differ by ~0.3 of a step
                        // at code 105): half a code step of rho in the ambient term.
                        const bool ambientUsed = formula != CombineFormula::Physical || !withIndirect;
                        const double rhoSlack = ambientUsed ? a * s.ambient[c] * halfSrgbStep(rho) : 0.0;
                        const double halfRounding = std::ldexp(expected + kl1, -10);
                        const double floatSlack = std::ldexp(expected, -20) + 1e-6;
                        CHECK(std::abs(error) <= halfRounding + rhoSlack + floatSlack);
                        // RGBA8 after the exposure (one more float product, inside floatSlack)
                        // and the clamp: the GL converts to one of the two nearest of the 255 steps
                        // (nearest preferred, not required: NVIDIA 580 is off by more than half),
                        // from a value off by the exposure times the above.
                        const double shownSlack = s.exposure * (halfRounding + rhoSlack + floatSlack);
                        CHECK(std::abs(shown.at(x, y, c) - std::min(s.exposure * expected, 1.0)) <= 1.0 / 255.0 + shownSlack);
                    }
        }
}

} // namespace

TEST_CASE("The combine formulas match their definitions", "[compose]") {
    Frame f;
    checkCombineFormulas(f);
}

TEST_CASE("The combine formulas hold at 1x1 odd and non-square sizes and in orthographic and reversed-Z views",
          "[compose][stability]") {
    // The compose pass reads its inputs by pixel and runs over whole groups: a frame smaller
    // than a group, sizes that leave part of the last group outside, and depth that runs
    // otherwise (the background test reads depth) must give the same formulas.
    const CameraOf orthographic = [](const assets::CameraSpec& c, int w, int h) {
        return Camera::orthographic(c.lookAt, 330.0f, float(w) / float(h), c.nearPlane, c.farPlane, DepthMode::StandardZeroToOne);
    };
    const CameraOf reversed = [](const assets::CameraSpec& c, int w, int h) {
        return Camera::perspective(c.lookAt, glm::radians(c.fovyDegrees), float(w) / float(h), c.nearPlane, INFINITY,
                                   DepthMode::Reversed);
    };
    const CameraOf reversedOrthographic = [](const assets::CameraSpec& c, int w, int h) {
        return Camera::orthographic(c.lookAt, 400.0f, float(w) / float(h), c.nearPlane, c.farPlane, DepthMode::Reversed);
    };
    struct Case {
        const char* name;
        int width, height;
        CameraOf camera;
        bool backgroundInView = false;
    };
    for (const Case& c : {Case{"1x1", 1, 1, {}}, Case{"odd, orthographic", 7, 5, orthographic},
                          Case{"non-square, reversed-Z", 9, 16, reversed},
                          Case{"odd, orthographic reversed, background in view", 13, 11, reversedOrthographic, true}}) {
        CAPTURE(c.name);
        Frame f(c.width, c.height, c.camera);
        int background = 0;
        for (int y = 0; y < c.height; ++y)
            for (int x = 0; x < c.width; ++x) background += f.positions.at(x, y, 3) == 0.0f;
        CAPTURE(background);
        CHECK(background < c.width * c.height); // the box in view
        if (c.backgroundInView) CHECK(background > 0);
        checkCombineFormulas(f);
    }
}

TEST_CASE("Tone mappers and display encodings follow their formulas", "[compose]") {
    Frame f;
    // Drago with the frame's own maximum and its defaults, and with a given maximum (below the
    // frame's: values above it map past 1 and clamp), another bias and display maximum; and
    // dim frames, whose largest luminance after the exposure is about 1e-5, 1e-10 and 1e-28
    // (the Cornell light is ~ 1e2 W/(sr m^2)), which Drago maps to their own maximum as any
    // other; and the settings' far ends (tonemap.comp.glsl): the largest exposure and display
    // maximum, bias 1 (exponent 0) and a given maximum below the 1e-30 floor, where without
    // the floor L_d overflows; and a given maximum 1e58 times the frame's, whose ratio L / L_wmax
    // is 0 in float unless clamped, with pow(0, 0) at bias 1. These two guard GPUs only: on
    // llvmpipe the mapping's NaN and Inf there store into RGBA8 as the values expected (the
    // test passes without the clamp), and the RGBA8 display is all the mapper writes.
    struct Case {
        ToneMapper mapper;
        bool srgb;
        float gamma = 2.2f, dragoMax = 0.0f, dragoBias = 0.85f, dragoDisplayMax = 100.0f, exposure = 0.05f;
    };
    for (const Case& k : {Case{ToneMapper::Aces, true}, Case{ToneMapper::Aces, false}, Case{ToneMapper::Aces, false, 1.6f},
                          Case{ToneMapper::Drago, true}, Case{ToneMapper::Drago, false},
                          Case{ToneMapper::Drago, false, 3.0f, 0.5f, 0.7f, 250.0f}, Case{ToneMapper::Drago, true, 2.2f, 2.0f, 0.95f, 40.0f},
                          Case{ToneMapper::Drago, true, 2.2f, 0.0f, 0.85f, 100.0f, 1e-7f},
                          Case{ToneMapper::Drago, false, 2.2f, 0.0f, 1.0f, 100.0f, 1e-12f},
                          Case{ToneMapper::Drago, true, 2.2f, 0.0f, 0.85f, 100.0f, 1e-30f},
                          Case{ToneMapper::Drago, false, 1.0f, 1e-35f, 1.0f, 1e4f, 1e6f},
                          Case{ToneMapper::Drago, false, 2.2f, 1e30f, 1.0f, 100.0f, 1e-30f}}) {
        CAPTURE(static_cast<int>(k.mapper), k.srgb, k.gamma, k.dragoMax, k.dragoBias, k.dragoDisplayMax, k.exposure);
        ComposeSettings s;
        s.toneMapper = k.mapper;
        s.srgb = k.srgb;
        s.gamma = k.gamma;
        s.exposure = k.exposure;
        s.dragoMaxLuminance = k.dragoMax;
        s.dragoBias = k.dragoBias;
        s.dragoDisplayMax = k.dragoDisplayMax;
        const Image shown = readTexture(f.ctx, f.composer.compose({f.view, {}, {}}, s));
        const Image radiance = readTexture(f.ctx, f.composer.radiance());
        // What the mapper receives: radiance() times the exposure, in float.
        const auto exposed = [&](int x, int y) {
            return glm::dvec3(glm::vec3(radiance.at(x, y, 0), radiance.at(x, y, 1), radiance.at(x, y, 2)) * k.exposure);
        };
        double lmax = 0.0;
        for (int y = 0; y < Frame::H; ++y)
            for (int x = 0; x < Frame::W; ++x) lmax = std::max(lmax, luminance(exposed(x, y)));
        REQUIRE(lmax > 0.0);
        if (k.dragoMax > 0.0f) {
            // The given maxima straddle the frame's own, so that values past it clamp.
            if (k.dragoMax < 1.0f) CHECK(lmax > k.dragoMax);
            else CHECK(lmax < k.dragoMax);
            lmax = k.dragoMax;
        }
        lmax = std::max(lmax, 1e-30); // the floor (ComposeSettings::dragoMaxLuminance)
        // The display's error bound. The mapper reads the radiance as read back here, and
        // multiplies it by the exposure as `exposed` does; RGBA8 takes one of the two nearest
        // steps (1/255, as in the combine test). A relative error r of the mapped value moves
        // the display value by at most r times it: the clamp and the encodings (sRGB,
        // x^(1/gamma) with gamma >= 1) do not amplify relative errors. The mapping's relative
        // errors: float evaluation, 1e-5 (GLSL's log and pow: a few ulp each, about ten
        // operations, 2^-23 * 50; ln(1 + x) below 1/16 is a series of a few ulp, see
        // tonemap.comp.glsl); Drago's ln(1 + x) from 1/16 up, for x = L and L_max, whose
        // absolute error is 2^-20 (GLSL's log: 2^-21 absolute on [0.5, 2]; x + 1 rounds by
        // 2^-24), so 2^-20 / ln(1 + x) relative, at most 1.6e-5; and with the frame's
        // own maximum, that maximum: the shader takes it from the values before their
        // half-float store, the test from the stored ones, within 2^-10 of them, and ln L_d
        // moves with ln L_max by at most 1 (the log10 factor) + e / ln 2 (the bias term,
        // e = ln b / ln 0.5).
        const bool drago = k.mapper == ToneMapper::Drago;
        const double biasExponent = std::log(double(k.dragoBias)) / std::log(0.5);
        const double maxSlack = drago && k.dragoMax <= 0.0f ? (1.0 + biasExponent / std::log(2.0)) * std::ldexp(1.0, -10) : 0.0;
        // The shader's branch at 1/16 is on float values a few ulp from these.
        const auto logSlack = [&](double x) { return drago && x >= 0.0625 * (1.0 - 1e-6) ? std::ldexp(1.0, -20) / std::log1p(x) : 0.0; };
        for (int y = 0; y < Frame::H; ++y)
            for (int x = 0; x < Frame::W; ++x) {
                const glm::dvec3 l = exposed(x, y);
                const double lw = luminance(l);
                glm::dvec3 mapped;
                if (k.mapper == ToneMapper::Aces) {
                    for (int c = 0; c < 3; ++c)
                        mapped[c] = std::clamp(l[c] * (2.51 * l[c] + 0.03) / (l[c] * (2.43 * l[c] + 0.59) + 0.14), 0.0, 1.0);
                } else {
                    const double bias = k.dragoBias;
                    // log1p: a dim frame's L + 1 would round in double too.
                    const double ld = lw > 0.0 ? (k.dragoDisplayMax * 0.01 * std::log(10.0) / std::log1p(lmax)) * std::log1p(lw) /
                                                     std::log(2.0 + 8.0 * std::pow(lw / lmax, std::log(bias) / std::log(0.5)))
                                               : 0.0;
                    mapped = lw > 0.0 ? l * (ld / lw) : glm::dvec3(0.0);
                }
                const double relative = 1e-5 + maxSlack + (lw > 0.0 ? logSlack(lw) + logSlack(lmax) : 0.0);
                for (int c = 0; c < 3; ++c) {
                    const double v = std::clamp(mapped[c], 0.0, 1.0);
                    const double encoded = k.srgb ? (v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055)
                                                  : std::pow(v, 1.0 / k.gamma);
                    CAPTURE(x, y, c, v, encoded);
                    CHECK(std::abs(shown.at(x, y, c) - encoded) <= 1.0 / 255.0 + relative * encoded);
                }
            }
    }
}

// The Cornell box seen from outside, with sky around it, and the modules that light and
// compose it.
struct SkyFrame {
    test::GlFixture gl;
    Context ctx{gl.desc()};
    GBuffer gbuffer{ctx};
    AmbientOcclusion ao{ctx};
    IndirectLight gi{ctx};
    Composer composer{ctx};
    const assets::LoadedScene cornell = assets::builtinScene("cornell");
    static constexpr int W = 40, H = 30;
    static Camera camera(DepthMode mode = DepthMode::Standard) {
        return Camera::perspective({{278, 273, -1200}, {278, 273, 0}, {0, 1, 0}}, glm::radians(40.0f), float(W) / H, 10.0f,
                                   5000.0f, mode);
    }
};

TEST_CASE("Sky pixels compose to the background radiance with every formula and tone mapper", "[compose][stability]") {
    // The Cornell box seen from outside, with sky around it: AO there is 1 and indirect light 0
    // (ambient_occlusion.hpp, indirect_light.hpp), the albedo 0, so both formulas give the
    // background radiance L_dir; and no tone mapper or encoding may turn it into NaN or Inf.
    SkyFrame f;
    auto& [gl, ctx, gbuffer, ao, gi, composer, cornell] = f;
    constexpr int W = SkyFrame::W, H = SkyFrame::H;
    const Camera camera = SkyFrame::camera();
    GBufferSettings g{W, H, true, glm::vec3(0.25f, 0.5f, 2.0f)};
    const GBufferView view = gbuffer.render(cornell.scene, camera, g);
    const Image positions = readTexture(ctx, gbuffer.positions(view));
    AmbientOcclusionSettings a;
    a.radius = 100.0f;
    const TextureView aoView = ao.run(view, a).ao;
    IndirectLightSettings l;
    l.radius = 150.0f;
    const TextureView indirect = gi.run(view, l).radiance;
    int sky = 0;
    for (CombineFormula formula : {CombineFormula::Standard, CombineFormula::Thesis, CombineFormula::Physical})
        for (ToneMapper mapper : {ToneMapper::None, ToneMapper::Drago, ToneMapper::Aces}) {
            CAPTURE(static_cast<int>(formula), static_cast<int>(mapper));
            ComposeSettings s;
            s.formula = formula;
            s.toneMapper = mapper;
            s.ambient = glm::vec3(0.5f);
            const Image shown = readTexture(ctx, composer.compose({view, aoView, indirect}, s));
            const Image radiance = readTexture(ctx, composer.radiance());
            sky = 0;
            for (int y = 0; y < H; ++y)
                for (int x = 0; x < W; ++x) {
                    for (int c = 0; c < 3; ++c) {
                        CHECK(std::isfinite(shown.at(x, y, c)));
                        CHECK(std::isfinite(radiance.at(x, y, c)));
                    }
                    if (positions.at(x, y, 3) > 0.0f) continue;
                    ++sky;
                    // Exact: background radiance times AO = 1 plus zeros, in half floats.
                    for (int c = 0; c < 3; ++c) CHECK(radiance.at(x, y, c) == g.background[c]);
                }
        }
    CHECK(sky > W * H / 4);
}

TEST_CASE("Sky pixels of a host G-buffer keep their direct radiance whatever the host's albedo there", "[compose][stability]") {
    // A host's albedo need not be 0 on the sky, as ours is: a constant 0.75 everywhere. The
    // background pixels must still compose to the direct radiance alone (no rho AO L_amb, no
    // k L1), exactly: the direct radiance read back is what the shader reads, times 1, plus 0.
    // The surface pixels must still get the ambient term from the host's albedo (Physical,
    // no indirect light: L_dir + rho AO L_amb), within the half-float store's rounding.
    SkyFrame f;
    auto& [gl, ctx, gbuffer, ao, gi, composer, cornell] = f;
    constexpr int W = SkyFrame::W, H = SkyFrame::H;
    for (DepthMode mode : {DepthMode::Standard, DepthMode::Reversed}) {
        CAPTURE(static_cast<int>(mode));
        const Camera camera = SkyFrame::camera(mode);
        const GBufferView ours = gbuffer.render(cornell.scene, camera, {W, H, true, glm::vec3(0.25f, 0.5f, 2.0f)});
        const Image positions = readTexture(ctx, gbuffer.positions(ours));
        const Image direct = readTexture(ctx, ours.directRadiance);
        const ConstantTexture albedo(GL_RGBA16F, W, H, glm::vec4(0.75f)); // exact in half floats
        const GLuint depth = test::copyDepthAsHost(ours.depth.name, W, H, GL_DEPTH_COMPONENT32F);
        GBuffer hostGBuffer(ctx);
        HostGBuffer host;
        host.depth = {depth, GL_DEPTH_COMPONENT32F, W, H};
        host.albedo = albedo.view(GL_RGBA16F, W, H);
        host.directRadiance = ours.directRadiance;
        const GBufferView adopted = hostGBuffer.adopt(host, camera);
        AmbientOcclusionSettings a;
        a.radius = 100.0f;
        const TextureView aoView = ao.run(adopted, a).ao;
        const Image aoImage = readTexture(ctx, aoView);
        IndirectLightSettings l;
        l.radius = 150.0f;
        const TextureView indirect = gi.run(adopted, l).radiance;
        for (CombineFormula formula : {CombineFormula::Standard, CombineFormula::Thesis, CombineFormula::Physical})
            for (bool withIndirect : {true, false}) {
                CAPTURE(static_cast<int>(formula), withIndirect);
                ComposeSettings s;
                s.formula = formula;
                s.toneMapper = ToneMapper::None;
                s.ambient = glm::vec3(0.5f);
                composer.compose({adopted, aoView, withIndirect ? indirect : TextureView{}}, s);
                const Image radiance = readTexture(ctx, composer.radiance());
                int sky = 0, lit = 0;
                for (int y = 0; y < H; ++y)
                    for (int x = 0; x < W; ++x)
                        for (int c = 0; c < 3; ++c) {
                            CAPTURE(x, y, c);
                            if (positions.at(x, y, 3) == 0.0f) {
                                sky += c == 0;
                                CHECK(radiance.at(x, y, c) == direct.at(x, y, c));
                            } else if (formula == CombineFormula::Physical && !withIndirect) {
                                const double expected = direct.at(x, y, c) + 0.75 * aoImage.at(x, y, 0) * 0.5;
                                CHECK(std::abs(radiance.at(x, y, c) - expected) <= std::ldexp(expected, -10) + 1e-6);
                                lit += c == 0;
                            }
                        }
                CHECK(sky > W * H / 4);
                if (formula == CombineFormula::Physical && !withIndirect) CHECK(lit > W * H / 4);
            }
        glDeleteTextures(1, &depth);
    }
}

TEST_CASE("Drawing into a host framebuffer overwrites or multiplies its colour and keeps its alpha", "[compose]") {
    Frame f;
    GLuint color = 0, fbo = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &color);
    glTextureStorage2D(color, 1, GL_RGBA8, 20, 10);
    glCreateFramebuffers(1, &fbo);
    glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, color, 0);
    const ConstantTexture ao(GL_R16F, 8, 8, glm::vec4(0.5f));
    for (HostBlend blend : {HostBlend::Overwrite, HostBlend::Multiply}) {
        const glm::vec4 grey(0.8f, 0.6f, 0.4f, 0.2f);
        glClearTexImage(color, 0, GL_RGBA, GL_FLOAT, &grey);
        // Into the right half only.
        f.composer.drawToHost(ao.view(GL_R16F, 8, 8), {fbo, 10, 0, 10, 10, blend});
        std::vector<std::uint8_t> texels(20 * 10 * 4);
        glGetTextureImage(color, 0, GL_RGBA, GL_UNSIGNED_BYTE, static_cast<GLsizei>(texels.size()), texels.data());
        for (int y = 0; y < 10; ++y)
            for (int x = 0; x < 20; ++x)
                for (int c = 0; c < 4; ++c) {
                    const double before = grey[c];
                    double expected = before;
                    if (x >= 10 && c < 3) expected = blend == HostBlend::Overwrite ? 0.5 : 0.5 * before;
                    CAPTURE(x, y, c, expected);
                    CHECK(std::abs(texels[(static_cast<std::size_t>(y) * 20 + x) * 4 + c] / 255.0 - expected) <= 1.0 / 255.0);
                }
    }
    CHECK(test::drainGlErrors().empty());
    CHECK_THROWS_AS(f.composer.drawToHost(ao.view(GL_R16F, 8, 8), {fbo, 0, 0, 0, 10}), Error);
    CHECK_THROWS_AS(f.composer.drawToHost(ao.view(GL_R16F, 8, 8), {12345, 0, 0, 10, 10}), Error);
    CHECK_THROWS_AS(f.composer.drawToHost(ao.view(GL_R16F, 8, 8), {fbo, 0, 0, 10, 10, static_cast<HostBlend>(2)}), Error);
    // An origin GL would clamp (GL_VIEWPORT_BOUNDS_RANGE) shifted the source; one off the
    // framebuffer but within the range is drawn (partly clipped).
    const float* bounds = f.ctx.info().viewportBoundsRange;
    REQUIRE(bounds[0] <= -32768.0f);
    REQUIRE(bounds[1] >= 32767.0f);
    const int past = static_cast<int>(bounds[1]) + 1;
    CHECK_THROWS_WITH(f.composer.drawToHost(ao.view(GL_R16F, 8, 8), {fbo, past, 0, 10, 10}),
                      Catch::Contains("GL_VIEWPORT_BOUNDS_RANGE"));
    CHECK_THROWS_WITH(f.composer.drawToHost(ao.view(GL_R16F, 8, 8), {fbo, 0, -past - 1, 10, 10}),
                      Catch::Contains("GL_VIEWPORT_BOUNDS_RANGE"));
    CHECK_NOTHROW(f.composer.drawToHost(ao.view(GL_R16F, 8, 8), {fbo, -5, -5, 10, 10}));
    CHECK(test::drainGlErrors().empty());
    glDeleteFramebuffers(1, &fbo);
    glDeleteTextures(1, &color);
}

TEST_CASE("Drawing into a host framebuffer writes row r of the source to row r of the rectangle whatever the host's "
          "clip origin", "[compose][host]") {
    // A GL_UPPER_LEFT host passes its projection mirrored in y (camera.hpp), so Obscura's
    // results already hold the host's rows: drawToHost must copy them row for row (the
    // rectangle in glViewport's window coordinates, which clip control does not change), not
    // flip them through the host's clip origin, and leave that origin as it was. Every texel
    // of the source differs from every other by at least 1/64 (k / 64, exact in R16F and in
    // the float target), so a flip or a shift shows. The source is sampled bilinearly at the
    // interpolated texel centre, whose rounding blends in a trace of the neighbours: up to
    // 1e-4 is allowed (llvmpipe: 3e-8).
    Frame f;
    constexpr int W = 8, H = 6, X = 3, Y = 2;
    GLuint source = 0, color = 0, fbo = 0;
    std::vector<float> values(W * H);
    for (int i = 0; i < W * H; ++i) values[std::size_t(i)] = float(i + 1) / 64.0f;
    glCreateTextures(GL_TEXTURE_2D, 1, &source);
    glTextureStorage2D(source, 1, GL_R16F, W, H);
    glTextureSubImage2D(source, 0, 0, 0, W, H, GL_RED, GL_FLOAT, values.data());
    glCreateTextures(GL_TEXTURE_2D, 1, &color);
    glTextureStorage2D(color, 1, GL_RGBA32F, W + X, H + Y);
    glCreateFramebuffers(1, &fbo);
    glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, color, 0);
    for (const GLenum origin : {GLenum(GL_LOWER_LEFT), GLenum(GL_UPPER_LEFT)}) {
        CAPTURE(origin);
        const glm::vec4 clear(-1.0f);
        glClearTexImage(color, 0, GL_RGBA, GL_FLOAT, &clear);
        glClipControl(origin, GL_NEGATIVE_ONE_TO_ONE);
        f.composer.drawToHost({source, GL_R16F, W, H}, {fbo, X, Y, W, H});
        GLint after = 0;
        glGetIntegerv(GL_CLIP_ORIGIN, &after);
        CHECK(GLenum(after) == origin);
        glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
        std::vector<float> texels(std::size_t(W + X) * (H + Y) * 4);
        glGetTextureImage(color, 0, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(texels.size() * sizeof(float)), texels.data());
        std::size_t wrong = 0;
        double worst = 0.0;
        for (int y = 0; y < H + Y; ++y)
            for (int x = 0; x < W + X; ++x) {
                const bool inside = x >= X && y >= Y;
                const float expected = inside ? values[std::size_t((y - Y) * W + (x - X))] : -1.0f;
                const double error = std::abs(double(texels[(std::size_t(y) * (W + X) + x) * 4]) - expected);
                worst = std::max(worst, error);
                wrong += error > 1e-4;
            }
        INFO("largest difference " << worst);
        CHECK(wrong == 0);
    }
    glDeleteFramebuffers(1, &fbo);
    glDeleteTextures(1, &color);
    glDeleteTextures(1, &source);
    CHECK(test::drainGlErrors().empty());
}

namespace {

double srgbEncoded(double v) { return v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055; }
double srgbDecoded(double e) { return e <= 0.04045 ? e / 12.92 : std::pow((e + 0.055) / 1.055, 2.4); }

// The 8-bit texels of `texture`'s first level, as stored (sRGB textures are read back encoded).
std::vector<std::uint8_t> storedBytes(GLuint texture, int width, int height) {
    std::vector<std::uint8_t> texels(std::size_t(width) * height * 4);
    glGetTextureImage(texture, 0, GL_RGBA, GL_UNSIGNED_BYTE, static_cast<GLsizei>(texels.size()), texels.data());
    return texels;
}

} // namespace

TEST_CASE("Drawing into a host framebuffer encodes linear sources for sRGB targets, stores display values as they "
          "are and writes only the first draw buffer", "[compose][host]") {
    Frame f;
    constexpr int W = Frame::W, H = Frame::H;
    // Attachment 0 holds sRGB-encoded bytes; attachment 1, a second draw buffer, plain ones.
    GLuint color[2] = {}, fbo = 0;
    glCreateTextures(GL_TEXTURE_2D, 2, color);
    glTextureStorage2D(color[0], 1, GL_SRGB8_ALPHA8, W, H);
    glTextureStorage2D(color[1], 1, GL_RGBA8, W, H);
    glCreateFramebuffers(1, &fbo);
    glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, color[0], 0);
    glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT1, color[1], 0);
    const GLenum both[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    glNamedFramebufferDrawBuffers(fbo, 2, both);
    const std::uint8_t before[4] = {200, 120, 30, 77}, second[4] = {10, 20, 30, 40};
    const ConstantTexture half(GL_R16F, 8, 8, glm::vec4(0.5f));
    const TextureView display = f.composer.compose({f.view, {}, {}}, {});
    const std::vector<std::uint8_t> shown = storedBytes(display.name, W, H);
    struct Case {
        HostSourceEncoding encoding;
        HostBlend blend;
        bool hostSrgb; // the host's own GL_FRAMEBUFFER_SRGB, which must neither matter nor change
        bool composed; // the source is compose()'s display texture, else the constant 0.5
    };
    for (const Case k : {Case{HostSourceEncoding::Auto, HostBlend::Overwrite, false, false},
                         Case{HostSourceEncoding::Auto, HostBlend::Multiply, true, false},
                         Case{HostSourceEncoding::Linear, HostBlend::Multiply, false, false},
                         Case{HostSourceEncoding::Display, HostBlend::Overwrite, true, false},
                         Case{HostSourceEncoding::Display, HostBlend::Multiply, false, false},
                         Case{HostSourceEncoding::Auto, HostBlend::Overwrite, true, true}}) {
        CAPTURE(static_cast<int>(k.encoding), static_cast<int>(k.blend), k.hostSrgb, k.composed);
        glClearTexImage(color[0], 0, GL_RGBA, GL_UNSIGNED_BYTE, before);
        glClearTexImage(color[1], 0, GL_RGBA, GL_UNSIGNED_BYTE, second);
        if (k.hostSrgb) glEnable(GL_FRAMEBUFFER_SRGB);
        else glDisable(GL_FRAMEBUFFER_SRGB);
        f.composer.drawToHost(k.composed ? display : half.view(GL_R16F, 8, 8), {fbo, 0, 0, W, H, k.blend, k.encoding});
        CHECK(glIsEnabled(GL_FRAMEBUFFER_SRGB) == (k.hostSrgb ? GL_TRUE : GL_FALSE));
        const std::vector<std::uint8_t> first = storedBytes(color[0], W, H), other = storedBytes(color[1], W, H);
        const bool linear = k.encoding != HostSourceEncoding::Display && !k.composed;
        std::size_t off = 0, otherChanged = 0;
        for (std::size_t i = 0; i < first.size(); ++i) {
            const int c = int(i % 4);
            otherChanged += other[i] != second[c];
            double expected = before[c] / 255.0; // alpha is left as it was
            if (c < 3) {
                const double source = k.composed ? shown[i] / 255.0 : 0.5;
                const double dst = before[c] / 255.0;
                if (linear) expected = srgbEncoded(k.blend == HostBlend::Multiply ? srgbDecoded(dst) * source : source);
                else expected = k.blend == HostBlend::Multiply ? dst * source : source;
            }
            // One code: the stored value rounds the exact one to 8 bits (half a code), and GL
            // lets the sRGB conversions approximate the curve without a bound; the other half
            // is an allowance for that, which llvmpipe keeps to (empirical, not promised).
            off += std::abs(first[i] - expected * 255.0) > 1.0;
        }
        CHECK(off == 0);
        CHECK(otherChanged == 0);
    }
    glDisable(GL_FRAMEBUFFER_SRGB);
    // With no first draw buffer nothing would be written: refused, and the host's state kept.
    const GLenum secondOnly[2] = {GL_NONE, GL_COLOR_ATTACHMENT1};
    glNamedFramebufferDrawBuffers(fbo, 2, secondOnly);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    CHECK_THROWS_AS(f.composer.drawToHost(half.view(GL_R16F, 8, 8), {fbo, 0, 0, W, H}), Error);
    GLint bound = -1;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &bound);
    CHECK(bound == 0);
    {
        // Refused before any state is set, so under Clobber too the host's state stays as it
        // was (README: bad input throws before any GL work), not at GL's initial values.
        Context clobbering(f.gl.desc(StatePolicy::Clobber));
        Composer composer(clobbering);
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0); // not the target: the check binds it and puts 0 back
        glEnable(GL_BLEND);
        glViewport(1, 2, 3, 4);
        CHECK_THROWS_AS(composer.drawToHost(half.view(GL_R16F, 8, 8), {fbo, 0, 0, W, H}), Error);
        GLint viewport[4] = {};
        glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &bound);
        glGetIntegerv(GL_VIEWPORT, viewport);
        CHECK(bound == 0);
        CHECK(glIsEnabled(GL_BLEND));
        CHECK((viewport[0] == 1 && viewport[1] == 2 && viewport[2] == 3 && viewport[3] == 4));
        glDisable(GL_BLEND);
    }
    // Nor where it names an attachment point with no image (a complete framebuffer all the same).
    const GLenum unattachedFirst[2] = {GL_COLOR_ATTACHMENT2, GL_COLOR_ATTACHMENT1};
    glNamedFramebufferDrawBuffers(fbo, 2, unattachedFirst);
    CHECK(glCheckNamedFramebufferStatus(fbo, GL_DRAW_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE);
    CHECK_THROWS_AS(f.composer.drawToHost(half.view(GL_R16F, 8, 8), {fbo, 0, 0, W, H}), Error);
    CHECK_THROWS_AS(f.composer.drawToHost(half.view(GL_R16F, 8, 8), {fbo, 0, 0, W, H, HostBlend::Overwrite,
                                                                     static_cast<HostSourceEncoding>(3)}),
                    Error);
    // Nor where the first draw buffer is an integer image (an engine's object IDs): the output
    // shader writes floats, which GL leaves undefined there (GL 4.5, 17.4.3). Refused by
    // name, both signednesses, and the image keeps what it held.
    for (const GLenum format : {GLenum(GL_RGBA8UI), GLenum(GL_R32I)}) {
        CAPTURE(format);
        GLuint ids = 0, idFbo = 0;
        glCreateTextures(GL_TEXTURE_2D, 1, &ids);
        glTextureStorage2D(ids, 1, format, W, H);
        const GLint marker[4] = {7, 7, 7, 7};
        glClearTexImage(ids, 0, format == GL_R32I ? GL_RED_INTEGER : GL_RGBA_INTEGER, GL_INT, marker);
        glCreateFramebuffers(1, &idFbo);
        glNamedFramebufferTexture(idFbo, GL_COLOR_ATTACHMENT0, ids, 0);
        REQUIRE(glCheckNamedFramebufferStatus(idFbo, GL_DRAW_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE);
        CHECK_THROWS_WITH(f.composer.drawToHost(half.view(GL_R16F, 8, 8), {idFbo, 0, 0, W, H}),
                          Catch::Contains("integer image"));
        std::vector<GLint> kept(std::size_t(W) * H * 4, 0);
        glGetTextureImage(ids, 0, GL_RGBA_INTEGER, GL_INT, GLsizei(kept.size() * sizeof(GLint)), kept.data());
        std::size_t changed = 0;
        for (std::size_t i = 0; i < kept.size(); i += 4) changed += kept[i] != 7;
        CHECK(changed == 0);
        glDeleteFramebuffers(1, &idFbo);
        glDeleteTextures(1, &ids);
    }
    CHECK(test::drainGlErrors().empty());
    glDeleteFramebuffers(1, &fbo);
    glDeleteTextures(2, color);
}

TEST_CASE("Compose refuses bad settings and inputs of the wrong size or kind", "[compose][bad-input]") {
    Frame f;
    const ConstantTexture small(GL_R16F, 8, 8, glm::vec4(1.0f));
    for (auto change : std::vector<void (*)(ComposeSettings&)>{
             [](ComposeSettings& s) { s.exposure = 0.0f; }, [](ComposeSettings& s) { s.gamma = 5.0f; },
             [](ComposeSettings& s) { s.ambient.x = -1.0f; }, [](ComposeSettings& s) { s.dragoBias = 0.1f; },
             [](ComposeSettings& s) { s.dragoMaxLuminance = NAN; },
             [](ComposeSettings& s) { s.formula = static_cast<CombineFormula>(3); },
             [](ComposeSettings& s) { s.toneMapper = static_cast<ToneMapper>(3); }}) {
        ComposeSettings s;
        change(s);
        CHECK_THROWS_AS(f.composer.compose({f.view, {}, {}}, s), Error);
    }
    CHECK_THROWS_AS(f.composer.compose({f.view, small.view(GL_R16F, 8, 8), {}}, {}), Error);
    HostGBuffer host;
    host.depth = f.view.depth;
    CHECK_THROWS_AS(f.composer.compose({f.gbuffer.adopt(host, f.view.camera), {}, {}}, {}), Error);
    // Inputs compose would read undefined values from, each refused by name: no depth, a
    // colour texture as depth, depth as albedo or AO, an integer AO, one-channel indirect
    // light and radiance, and a base level other than 0.
    const auto refused = [&](const ComposeInputs& in, const std::string& what) {
        CHECK_THROWS_WITH(f.composer.compose(in, {}), Catch::Contains(what));
    };
    GBufferView g = f.view;
    g.depth = {};
    refused({g, {}, {}}, "compose needs the G-buffer's depth");
    g = f.view;
    g.depth = f.view.directRadiance;
    refused({g, {}, {}}, "GBufferView::depth must have a depth format");
    g = f.view;
    g.albedo = f.view.depth;
    refused({g, {}, {}}, "GBufferView::albedo has format");
    const ConstantTexture mono(GL_R16F, Frame::W, Frame::H, glm::vec4(1.0f));
    g = f.view;
    g.directRadiance = mono.view(GL_R16F, Frame::W, Frame::H);
    refused({g, {}, {}}, "GBufferView::directRadiance has format");
    refused({f.view, f.view.depth, {}}, "ComposeInputs::ao has format");
    GLuint integer = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &integer);
    glTextureStorage2D(integer, 1, GL_R32UI, Frame::W, Frame::H);
    refused({f.view, {integer, GL_R32UI, Frame::W, Frame::H}, {}}, "ComposeInputs::ao has format");
    refused({f.view, {}, mono.view(GL_R16F, Frame::W, Frame::H)}, "ComposeInputs::indirect has format");
    GLuint stencil = 0, depthStencil = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &stencil);
    glTextureStorage2D(stencil, 1, GL_STENCIL_INDEX8, Frame::W, Frame::H);
    refused({f.view, {stencil, GL_STENCIL_INDEX8, Frame::W, Frame::H}, {}}, "ComposeInputs::ao has format");
    glCreateTextures(GL_TEXTURE_2D, 1, &depthStencil);
    glTextureStorage2D(depthStencil, 1, GL_DEPTH24_STENCIL8, Frame::W, Frame::H);
    glTextureParameteri(depthStencil, GL_DEPTH_STENCIL_TEXTURE_MODE, GL_STENCIL_INDEX);
    g = f.view;
    g.depth = {depthStencil, GL_DEPTH24_STENCIL8, Frame::W, Frame::H};
    refused({g, {}, {}}, "GBufferView::depth samples stencil");
    GLuint levels = 0; // two levels, the second sampled
    glCreateTextures(GL_TEXTURE_2D, 1, &levels);
    glTextureStorage2D(levels, 2, GL_R16F, Frame::W, Frame::H);
    glTextureParameteri(levels, GL_TEXTURE_BASE_LEVEL, 1);
    refused({f.view, {levels, GL_R16F, Frame::W, Frame::H}, {}}, "GL_TEXTURE_BASE_LEVEL");
    // drawToHost: the same base level rule for its source, and no rectangle GL would clamp.
    GLuint colour = 0, fbo = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &colour);
    glTextureStorage2D(colour, 1, GL_RGBA8, Frame::W, Frame::H);
    glCreateFramebuffers(1, &fbo);
    glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, colour, 0);
    REQUIRE(glCheckNamedFramebufferStatus(fbo, GL_DRAW_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE);
    CHECK_THROWS_WITH(f.composer.drawToHost({levels, GL_R16F, Frame::W, Frame::H}, {fbo, 0, 0, Frame::W, Frame::H}),
                      Catch::Contains("GL_TEXTURE_BASE_LEVEL"));
    const int widest = f.ctx.info().maxViewportDims[0], tallest = f.ctx.info().maxViewportDims[1];
    REQUIRE(widest > 0);
    REQUIRE(tallest > 0);
    CHECK_THROWS_WITH(f.composer.drawToHost(mono.view(GL_R16F, Frame::W, Frame::H), {fbo, 0, 0, widest + 1, Frame::H}),
                      Catch::Contains("GL_MAX_VIEWPORT_DIMS"));
    CHECK_THROWS_WITH(f.composer.drawToHost(mono.view(GL_R16F, Frame::W, Frame::H), {fbo, 0, 0, Frame::W, tallest + 1}),
                      Catch::Contains("GL_MAX_VIEWPORT_DIMS"));
    f.composer.drawToHost(mono.view(GL_R16F, Frame::W, Frame::H), {fbo, 0, 0, widest, Frame::H}); // the largest is taken
    glDeleteFramebuffers(1, &fbo);
    const GLuint textures[5] = {integer, levels, colour, stencil, depthStencil};
    glDeleteTextures(5, textures);
    CHECK(test::drainGlErrors().empty());
}
