#include "obscura/compose.hpp"

#include "core/compute.hpp"
#include "core/context_impl.hpp"
#include "core/pass_scope.hpp"
#include "core/shader_library.hpp"
#include "core/texture_info.hpp"
#include "core/validate.hpp"
#include "visibility/screen_inputs.hpp"
#include "obscura/context.hpp"
#include "shaders/compose/compose_bindings.h"

#include <algorithm>
#include <cstdio>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace obscura {
namespace {

using namespace detail;

void validateSettings(const ComposeSettings& s) {
    obscura::validateSettings(ComposeSettings::table(), s, "ComposeSettings");
}

// An input that is empty (when optional), or readable as `kind` and exactly the G-buffer's size.
// Compose reads each with texelFetch at level 0 through a float sampler (requireReadableAs):
// a colour input that is depth, stencil or integer would read undefined values there, a
// depth-stencil depth in stencil mode too, and a base level other than 0 another level.
bool checkInput(ContextImpl& ctx, const TextureView& view, const char* what, SampledAs kind, int width, int height) {
    if (!view) return false;
    const TextureInfo info = queryTexture2D(ctx, view.name, what);
    requireReadableAs(ctx, view.name, info, what, kind);
    if (info.width != width || info.height != height)
        throw Error(ErrorCode::InvalidArgument, std::string(what) + " is " + std::to_string(info.width) + "x" +
                                                    std::to_string(info.height) + ", the G-buffer " + std::to_string(width) +
                                                    "x" + std::to_string(height));
    return true;
}

// Why drawing into `framebuffer` would write nothing or undefined values, if it would: its
// first draw buffer is GL_NONE or has no image attached, or that image is integer (the output
// shader writes floats, which GL leaves undefined in an integer buffer). Asked before any
// state is changed, so that a refusal leaves the host's state as it was under every
// StatePolicy: GL_DRAW_BUFFER0 can only be queried on the bound draw framebuffer, whose
// binding is put back at once.
std::optional<std::string> firstDrawBufferProblem(ContextImpl& ctx, GLuint framebuffer) {
    GLint bound = 0;
    ctx.gl.GetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &bound);
    ctx.gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer);
    GLint firstDrawBuffer = GL_NONE;
    ctx.gl.GetIntegerv(GL_DRAW_BUFFER0, &firstDrawBuffer);
    ctx.gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(bound));
    const std::string nothing = "its first draw buffer is GL_NONE or has no image attached, so nothing would be written";
    if (firstDrawBuffer == GL_NONE) return nothing;
    if (framebuffer == 0) return std::nullopt;
    const auto attachment = [&](GLenum pname) {
        GLint value = GL_NONE;
        ctx.gl.GetNamedFramebufferAttachmentParameteriv(framebuffer, static_cast<GLenum>(firstDrawBuffer), pname, &value);
        return value;
    };
    if (attachment(GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE) == GL_NONE) return nothing;
    const GLint type = attachment(GL_FRAMEBUFFER_ATTACHMENT_COMPONENT_TYPE);
    if (type == GL_INT || type == GL_UNSIGNED_INT)
        return "its first draw buffer is an integer image, into which the float output would write undefined values";
    return std::nullopt;
}

// The colour attachment of `framebuffer` that is level 0 of `source`, if one is. The draw
// samples that level (base level 0, a sampler without mipmaps), and GL 4.5 (9.3.1) leaves a
// draw undefined while a level it samples is attached at any attachment point, drawn to or
// not: a feedback loop.
std::optional<int> attachmentSampling(ContextImpl& ctx, GLuint framebuffer, GLuint source) {
    if (framebuffer == 0) return std::nullopt;
    GLint attachments = 0;
    ctx.gl.GetIntegerv(GL_MAX_COLOR_ATTACHMENTS, &attachments);
    for (int i = 0; i < attachments; ++i) {
        const auto attachment = [&](GLenum pname) {
            GLint value = GL_NONE;
            ctx.gl.GetNamedFramebufferAttachmentParameteriv(framebuffer, GL_COLOR_ATTACHMENT0 + GLenum(i), pname, &value);
            return value;
        };
        if (attachment(GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE) == GL_TEXTURE &&
            static_cast<GLuint>(attachment(GL_FRAMEBUFFER_ATTACHMENT_OBJECT_NAME)) == source &&
            attachment(GL_FRAMEBUFFER_ATTACHMENT_TEXTURE_LEVEL) == 0)
            return i;
    }
    return std::nullopt;
}

// The programs of compose()'s two passes and of drawToHost, in that order (no permutations:
// the settings are uniforms).
const std::vector<std::vector<std::string_view>>& programStages() {
    static const std::vector<std::vector<std::string_view>> stages = {
        {"compose/combine.comp.glsl"},
        {"compose/tonemap.comp.glsl"},
        {"compose/host_output.vert.glsl", "compose/host_output.frag.glsl"}};
    return stages;
}

} // namespace

struct Composer::Impl {
    explicit Impl(ContextImpl& c) : ctx(c) {}
    ContextImpl& ctx;
    Buffer params, luminance;
    SizedTexture radiance, display;
    int width = 0, height = 0;

};

bool combineReadsAo(const ComposeSettings& s, bool withIndirect) {
    if (s.formula == CombineFormula::Thesis) return true;
    const bool ambient = s.ambient.r > 0.0f || s.ambient.g > 0.0f || s.ambient.b > 0.0f;
    return ambient && (s.formula == CombineFormula::Standard || !withIndirect);
}

Composer::Composer(Context& context) : impl_(std::make_unique<Impl>(context.impl())) {}
Composer::~Composer() = default;

TextureView Composer::compose(const ComposeInputs& in, const ComposeSettings& s) {
    validateSettings(s);
    auto& d = *impl_;
    auto& ctx = d.ctx;
    const GBufferView& g = in.gbuffer;
    if (!g.depth || !g.directRadiance || !g.albedo)
        throw Error(ErrorCode::InvalidArgument, "compose needs the G-buffer's depth, direct radiance and albedo (GBuffer::render, "
                                                "or HostGBuffer::albedo and directRadiance with GBuffer::adopt)");
    const TextureInfo direct = queryTexture2D(ctx, g.directRadiance.name, "GBufferView::directRadiance");
    const int w = direct.width, h = direct.height;
    requireReadableAs(ctx, g.directRadiance.name, direct, "GBufferView::directRadiance", SampledAs::Rgb);
    checkInput(ctx, g.albedo, "GBufferView::albedo", SampledAs::Rgb, w, h);
    checkInput(ctx, g.depth, "GBufferView::depth", SampledAs::Depth, w, h);
    const DepthReconstruction reconstruction = depthReconstruction(g.camera);
    const bool hasAo = checkInput(ctx, in.ao, "ComposeInputs::ao", SampledAs::Colour, w, h);
    const bool hasIndirect = checkInput(ctx, in.indirect, "ComposeInputs::indirect", SampledAs::Rgb, w, h);
    requireNotOwnOutput({{"GBufferView::depth", g.depth.name},
                         {"GBufferView::albedo", g.albedo.name},
                         {"GBufferView::directRadiance", g.directRadiance.name},
                         {"ComposeInputs::ao", in.ao.name},
                         {"ComposeInputs::indirect", in.indirect.name}},
                        {d.radiance.get(), d.display.get()}, "Composer");

    StateScope scope(ctx);
    shader::ComposeParams p{};
    p.ambient = s.ambient;
    p.indirectScale = s.indirectScale;
    p.exposure = s.exposure;
    // A given maximum at its floor here: a GPU may flush a subnormal one to 0, "measured".
    p.dragoMaxLuminance = s.dragoMaxLuminance > 0.0f ? std::max(s.dragoMaxLuminance, 1e-30f) : 0.0f;
    p.dragoBias = s.dragoBias;
    p.dragoDisplayMax = s.dragoDisplayMax;
    p.gamma = s.gamma;
    p.clearDepth = reconstruction.clearDepth;
    p.farthestDepth = reconstruction.farthestDepth;
    p.formula = s.formula == CombineFormula::Thesis     ? COMPOSE_FORMULA_THESIS
                : s.formula == CombineFormula::Physical ? COMPOSE_FORMULA_PHYSICAL
                                                        : COMPOSE_FORMULA_STANDARD;
    p.toneMapper = s.toneMapper == ToneMapper::Drago ? COMPOSE_TONE_DRAGO
                   : s.toneMapper == ToneMapper::Aces ? COMPOSE_TONE_ACES
                                                      : COMPOSE_TONE_NONE;
    p.srgb = s.srgb ? 1 : 0;
    p.inputs = (hasAo ? COMPOSE_HAS_AO : 0) | (hasIndirect ? COMPOSE_HAS_INDIRECT : 0);
    p.size = glm::ivec2(w, h);
    uploadUniformBlock(ctx, d.params, p, COMPOSE_PARAMS_UBO_BINDING, "compose.params");
    if (!d.luminance) d.luminance = createBuffer(ctx, 4, nullptr, GL_DYNAMIC_STORAGE_BIT, "compose.luminance");
    const std::uint32_t zero = 0;
    ctx.gl.NamedBufferSubData(d.luminance.get(), 0, 4, &zero);
    ctx.state.bindStorageBuffer(ctx, COMPOSE_LUMINANCE_SSBO, d.luminance.get());
    const GLuint radiance = d.radiance.ensure(ctx, GL_RGBA16F, w, h, "compose.radiance");
    d.width = w;
    d.height = h;
    const GLuint display = d.display.ensure(ctx, GL_RGBA8, w, h, "compose.display");
    {
        PassScope pass(ctx, "compose.combine");
        ctx.gl.UseProgram(ctx.shaders->program(programStages()[0]));
        bindNearest(ctx, COMPOSE_DIRECT_UNIT, g.directRadiance.name);
        bindNearest(ctx, COMPOSE_ALBEDO_UNIT, g.albedo.name);
        bindNearest(ctx, COMPOSE_DEPTH_UNIT, g.depth.name);
        // Unused inputs read the radiance itself: a valid texture, never sampled.
        bindNearest(ctx, COMPOSE_AO_UNIT, hasAo ? in.ao.name : g.directRadiance.name);
        bindNearest(ctx, COMPOSE_INDIRECT_UNIT, hasIndirect ? in.indirect.name : g.directRadiance.name);
        ctx.state.bindImage(ctx, COMPOSE_RADIANCE_IMAGE, radiance, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
        dispatchCompute2D(ctx, w, h, COMPOSE_WORKGROUP);
        ctx.gl.MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
    }
    {
        PassScope pass(ctx, "compose.tonemap");
        ctx.gl.UseProgram(ctx.shaders->program(programStages()[1]));
        bindNearest(ctx, COMPOSE_RADIANCE_UNIT, radiance);
        ctx.state.bindImage(ctx, COMPOSE_DISPLAY_IMAGE, display, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA8);
        dispatchCompute2D(ctx, w, h, COMPOSE_WORKGROUP);
    }
    barrierForReaders(ctx);
    return {display, GL_RGBA8, w, h};
}

void Composer::prepare(const ComposeSettings& settings) {
    validateSettings(settings);
    auto& ctx = impl_->ctx;
    StateScope scope(ctx);
    for (const auto& stages : programStages()) ctx.shaders->program(stages);
}

TextureView Composer::radiance() const {
    const auto& d = *impl_;
    return {d.radiance.get(), GL_RGBA16F, d.width, d.height};
}

void Composer::drawToHost(const TextureView& source, const HostTarget& target) {
    auto& d = *impl_;
    auto& ctx = d.ctx;
    const TextureInfo info = queryTexture2D(ctx, source.name, "drawToHost source");
    requireReadableAs(ctx, source.name, info, "drawToHost source", SampledAs::Colour);
    requireEnumerator(target.blend, {HostBlend::Overwrite, HostBlend::Multiply}, "HostTarget::blend");
    requireEnumerator(target.encoding, {HostSourceEncoding::Auto, HostSourceEncoding::Linear, HostSourceEncoding::Display},
                      "HostTarget::encoding");
    if (target.width < 1 || target.height < 1)
        throw Error(ErrorCode::InvalidArgument, "HostTarget: width and height must be >= 1 pixel, got " +
                                                    std::to_string(target.width) + "x" + std::to_string(target.height));
    // GL clamps a larger viewport silently, which would stretch the source differently.
    if (target.width > ctx.info.maxViewportDims[0] || target.height > ctx.info.maxViewportDims[1])
        throw Error(ErrorCode::InvalidArgument, "HostTarget: " + std::to_string(target.width) + "x" +
                                                    std::to_string(target.height) + " is larger than GL_MAX_VIEWPORT_DIMS (" +
                                                    std::to_string(ctx.info.maxViewportDims[0]) + "x" +
                                                    std::to_string(ctx.info.maxViewportDims[1]) + ")");
    // Likewise an origin outside the bounds range, which would shift the source.
    const float* bounds = ctx.info.viewportBoundsRange;
    const double x = target.x, y = target.y; // exact: ints in double
    if (!(x >= bounds[0] && x <= bounds[1] && y >= bounds[0] && y <= bounds[1]))
        throw Error(ErrorCode::InvalidArgument, "HostTarget: x and y must lie in GL_VIEWPORT_BOUNDS_RANGE [" +
                                                    shortNumber(bounds[0]) + ", " + shortNumber(bounds[1]) + "], got (" +
                                                    std::to_string(target.x) + ", " + std::to_string(target.y) + ")");
    if (target.framebuffer != 0 && !ctx.gl.IsFramebuffer(target.framebuffer))
        throw Error(ErrorCode::InvalidArgument, "HostTarget::framebuffer " + std::to_string(target.framebuffer) +
                                                    " is not a framebuffer of this context");
    const GLenum status = ctx.gl.CheckNamedFramebufferStatus(target.framebuffer, GL_DRAW_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE)
        throw Error(ErrorCode::InvalidArgument, "HostTarget::framebuffer " + std::to_string(target.framebuffer) +
                                                    " is not complete (status 0x" + [&] {
                                                        char hex[16];
                                                        std::snprintf(hex, sizeof hex, "%X", status);
                                                        return std::string(hex);
                                                    }() + "; a surfaceless context has no default framebuffer)");
    if (const auto problem = firstDrawBufferProblem(ctx, target.framebuffer))
        throw Error(ErrorCode::InvalidArgument, "HostTarget::framebuffer " + std::to_string(target.framebuffer) + ": " + *problem);
    if (const auto i = attachmentSampling(ctx, target.framebuffer, source.name))
        throw Error(ErrorCode::InvalidArgument,
                    "HostTarget::framebuffer " + std::to_string(target.framebuffer) + " has level 0 of the source texture " +
                        std::to_string(source.name) + " at GL_COLOR_ATTACHMENT" + std::to_string(*i) +
                        ", which the draw samples: a feedback loop GL leaves undefined, attachment drawn to or not. "
                        "Draw a copy of it, or detach it");
    StateScope scope(ctx);
    ctx.gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, target.framebuffer);
    PassScope pass(ctx, "compose.output");
    setViewport(ctx, target.x, target.y, target.width, target.height);
    DrawState state;
    state.multiplyBlend = target.blend == HostBlend::Multiply;
    state.writeAlpha = false;
    // Only linear values are encoded (and, multiplied, blended in linear) by an sRGB target.
    const bool display = target.encoding == HostSourceEncoding::Display ||
                         (target.encoding == HostSourceEncoding::Auto && source.name != 0 && source.name == d.display.get());
    state.framebufferSrgb = !display;
    applyDrawState(ctx, state);
    // The shader writes location 0 only: the others would be undefined where their mask lets through.
    for (GLuint i = 1; i < static_cast<GLuint>(ctx.info.maxDrawBuffers); ++i)
        ctx.gl.ColorMaski(i, GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    const GLuint program = ctx.shaders->program(programStages()[2]);
    ctx.gl.UseProgram(program);
    ctx.gl.ProgramUniform1i(program, COMPOSE_LOC_SOURCE_CHANNELS, info.channels);
    ctx.state.bindTexture(ctx, COMPOSE_SOURCE_UNIT, source.name);
    ctx.state.bindSampler(ctx, COMPOSE_SOURCE_UNIT, ctx.linearClampSampler());
    ctx.gl.BindVertexArray(ctx.emptyVertexArray());
    ctx.gl.DrawArrays(GL_TRIANGLES, 0, 3);
}

std::size_t Composer::memoryBytes() const {
    const auto& d = *impl_;
    return d.radiance.bytes() + d.display.bytes() + (d.params ? sizeof(shader::ComposeParams) + 4 : 0);
}

} // namespace obscura
