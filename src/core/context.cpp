#include "obscura/context.hpp"

#include "core/context_impl.hpp"
#include "core/sampling.hpp"
#include "core/shader_library.hpp"
#include "core/validate.hpp"
#include "shaders/common/common_bindings.h"

#include <algorithm>
#include <cctype>
#include <set>
#include <string>
#include <vector>

namespace obscura {
namespace detail {
namespace {

struct LoaderTrampoline {
    const ContextDesc* desc;
    std::set<std::string> missing; //!< names the host's getProcAddress could not resolve
};

GLADapiproc loadThroughHost(void* user, const char* name) {
    auto* t = static_cast<LoaderTrampoline*>(user);
    void* p = t->desc->getProcAddress(t->desc->userData, name);
    if (!p) t->missing.insert(name);
    return reinterpret_cast<GLADapiproc>(p);
}

bool hasVendorSuffix(const std::string& name) {
    for (const char* suffix : {"ARB", "EXT", "KHR", "NV", "INTEL", "AMD", "OES"}) {
        const std::string s = suffix;
        if (name.size() > s.size() && name.compare(name.size() - s.size(), s.size(), s) == 0) return true;
    }
    return false;
}

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return s;
}

bool isSoftwareRenderer(const std::string& renderer) {
    const std::string r = lower(renderer);
    for (const char* marker : {"llvmpipe", "softpipe", "swrast", "swiftshader", "software rasterizer", "lavapipe",
                               "microsoft basic render", "gdi generic"})
        if (r.find(marker) != std::string::npos) return true;
    return false;
}

std::string glString(GladGLContext& gl, GLenum name) {
    const auto* s = reinterpret_cast<const char*>(gl.GetString(name));
    return s ? s : "";
}

bool hasExtension(GladGLContext& gl, const char* ext) {
    GLint n = 0;
    gl.GetIntegerv(GL_NUM_EXTENSIONS, &n);
    for (GLint i = 0; i < n; ++i) {
        const auto* e = reinterpret_cast<const char*>(gl.GetStringi(GL_EXTENSIONS, static_cast<GLuint>(i)));
        if (e && std::string(e) == ext) return true;
    }
    return false;
}

// Limits Obscura relies on (GL 4.5 core minimums or above what our passes use).
struct LimitCheck {
    GLenum pname;
    const char* name;
    GLint minimum;
};
constexpr LimitCheck kLimits[] = {
    {GL_MAX_TEXTURE_SIZE, "GL_MAX_TEXTURE_SIZE", 4096},
    {GL_MAX_DRAW_BUFFERS, "GL_MAX_DRAW_BUFFERS", 8},
    {GL_MAX_COLOR_ATTACHMENTS, "GL_MAX_COLOR_ATTACHMENTS", 8},
    {GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS, "GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS", 32},
    {GL_MAX_IMAGE_UNITS, "GL_MAX_IMAGE_UNITS", 8},
    {GL_MAX_UNIFORM_BUFFER_BINDINGS, "GL_MAX_UNIFORM_BUFFER_BINDINGS", 16},
    {GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS, "GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS", 8},
    {GL_MAX_COMPUTE_SHADER_STORAGE_BLOCKS, "GL_MAX_COMPUTE_SHADER_STORAGE_BLOCKS", 8},
    {GL_MAX_COMPUTE_WORK_GROUP_INVOCATIONS, "GL_MAX_COMPUTE_WORK_GROUP_INVOCATIONS", 256},
    {GL_MAX_GEOMETRY_OUTPUT_VERTICES, "GL_MAX_GEOMETRY_OUTPUT_VERTICES", 64},
    {GL_MAX_VIEWPORTS, "GL_MAX_VIEWPORTS", 1},
};

// Formats we render to; GL 4.5 requires them, but a driver that misreports is caught here.
struct FormatCheck {
    GLenum format;
    const char* name;
};
constexpr FormatCheck kRenderableFormats[] = {
    {GL_RGBA16F, "GL_RGBA16F"}, {GL_RGBA32F, "GL_RGBA32F"},           {GL_R32F, "GL_R32F"},
    {GL_RGBA32UI, "GL_RGBA32UI"}, {GL_SRGB8_ALPHA8, "GL_SRGB8_ALPHA8"}, {GL_DEPTH_COMPONENT32F, "GL_DEPTH_COMPONENT32F"},
};

std::vector<std::string> checkFeatures(ContextImpl& ctx, const std::set<std::string>& missingFunctions) {
    std::vector<std::string> problems;
    for (const auto& f : missingFunctions)
        if (!hasVendorSuffix(f)) problems.push_back("function " + f);
    auto& gl = ctx.gl;
    for (const auto& l : kLimits) {
        GLint v = 0;
        gl.GetIntegerv(l.pname, &v);
        if (v < l.minimum)
            problems.push_back(std::string(l.name) + " >= " + std::to_string(l.minimum) + " (have " + std::to_string(v) + ")");
    }
    for (const auto& f : kRenderableFormats) {
        GLint support = GL_NONE;
        gl.GetInternalformativ(GL_TEXTURE_2D, f.format, GL_FRAMEBUFFER_RENDERABLE, 1, &support);
        if (support != GL_FULL_SUPPORT) problems.push_back(std::string("renderable ") + f.name);
    }
    return problems;
}

std::string joinProblems(const std::vector<std::string>& problems) {
    std::string s;
    for (const auto& p : problems) s += "\n  - " + p;
    return s;
}

} // namespace

ContextImpl::ContextImpl(const ContextDesc& d) : desc(d) {}
ContextImpl::~ContextImpl() = default;

GLuint ContextImpl::emptyVertexArray() {
    if (!emptyVao) emptyVao = createVertexArray(*this, "obscura.empty_vao");
    return emptyVao.get();
}

GLuint ContextImpl::nearestClampSampler() {
    if (!nearestClamp) nearestClamp = createSampler(*this, GL_NEAREST, GL_CLAMP_TO_EDGE, "obscura.nearest_clamp");
    return nearestClamp.get();
}

GLuint ContextImpl::linearClampSampler() {
    if (!linearClamp) linearClamp = createSampler(*this, GL_LINEAR, GL_CLAMP_TO_EDGE, "obscura.linear_clamp");
    return linearClamp.get();
}

void ContextImpl::bindNoiseTexture() {
    if (!noise) {
        std::vector<glm::vec2> texels;
        for (int y = 0; y < OBSCURA_NOISE_SIZE; ++y)
            for (int x = 0; x < OBSCURA_NOISE_SIZE; ++x) texels.push_back(noiseTexel(x, y));
        GLuint t = 0;
        gl.CreateTextures(GL_TEXTURE_2D, 1, &t);
        ++liveObjects;
        noise = Texture(*this, t);
        gl.ObjectLabel(GL_TEXTURE, t, -1, "obscura.noise");
        gl.TextureStorage2D(t, 1, GL_RG32F, OBSCURA_NOISE_SIZE, OBSCURA_NOISE_SIZE);
        gl.TextureSubImage2D(t, 0, 0, 0, OBSCURA_NOISE_SIZE, OBSCURA_NOISE_SIZE, GL_RG, GL_FLOAT, texels.data());
    }
    state.bindTexture(*this, OBSCURA_NOISE_TEXTURE_UNIT, noise.get());
    state.bindSampler(*this, OBSCURA_NOISE_TEXTURE_UNIT, nearestClampSampler());
}

} // namespace detail

Context::Context(const ContextDesc& desc) : impl_(std::make_unique<detail::ContextImpl>(desc)) {
    if (!desc.getProcAddress)
        throw Error(ErrorCode::InvalidArgument,
                    "ContextDesc::getProcAddress is null: pass the host's GL loader function "
                    "(eglGetProcAddress, glfwGetProcAddress, ...)");
    detail::requireEnumerator(desc.statePolicy, {StatePolicy::Preserve, StatePolicy::Clobber}, "ContextDesc::statePolicy");
    detail::requireEnumerator(desc.profiling, {Profiling::Off, Profiling::TimerQueries, Profiling::Always},
                              "ContextDesc::profiling");
    auto& ctx = *impl_;
    detail::LoaderTrampoline trampoline{&desc, {}};
    const int version = gladLoadGLContextUserPtr(&ctx.gl, detail::loadThroughHost, &trampoline);
    if (version == 0 || !ctx.gl.GetString)
        throw Error(ErrorCode::UnsupportedFeature,
                    "could not read GL_VERSION through getProcAddress: is the host's GL context current on "
                    "this thread?");
    auto& info = ctx.info;
    info.major = GLAD_VERSION_MAJOR(version);
    info.minor = GLAD_VERSION_MINOR(version);
    info.vendor = detail::glString(ctx.gl, GL_VENDOR);
    info.renderer = detail::glString(ctx.gl, GL_RENDERER);
    info.version = detail::glString(ctx.gl, GL_VERSION);
    if (info.major * 10 + info.minor < 45)
        throw Error(ErrorCode::UnsupportedFeature, "Obscura needs OpenGL 4.5 core profile; the "
                                                   "current context is " + info.version + " on " + info.renderer);
    info.glslVersion = detail::glString(ctx.gl, GL_SHADING_LANGUAGE_VERSION);
    GLint profile = 0;
    ctx.gl.GetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
    info.coreProfile = (profile & GL_CONTEXT_CORE_PROFILE_BIT) != 0;
    // Compatibility profiles carry state that changes shader output (alpha test, colour
    // clamping, separate back-face polygon modes) which the state guard does not cover.
    if (!info.coreProfile)
        throw Error(ErrorCode::UnsupportedFeature, "Obscura needs a core-profile context; the current context is " +
                                                       info.version + " (compatibility profile)");
    info.softwareRenderer = detail::isSoftwareRenderer(info.renderer);
    ctx.gl.GetIntegerv(GL_MAX_TEXTURE_SIZE, &info.maxTextureSize);
    ctx.gl.GetIntegerv(GL_MAX_DRAW_BUFFERS, &info.maxDrawBuffers);
    ctx.gl.GetIntegerv(GL_MAX_VIEWPORTS, &info.maxViewports);
    ctx.gl.GetIntegerv(GL_MAX_VIEWPORT_DIMS, info.maxViewportDims);
    ctx.gl.GetFloatv(GL_VIEWPORT_BOUNDS_RANGE, info.viewportBoundsRange);
    ctx.gl.GetQueryiv(GL_TIMESTAMP, GL_QUERY_COUNTER_BITS, &info.timestampBits);
    info.conservativeRaster = detail::hasExtension(ctx.gl, "GL_NV_conservative_raster") ||
                              detail::hasExtension(ctx.gl, "GL_INTEL_conservative_rasterization");

    const auto problems = detail::checkFeatures(ctx, trampoline.missing);
    if (!problems.empty())
        throw Error(ErrorCode::UnsupportedFeature, "the GL context (" + info.version + ", " + info.renderer +
                                                       ") lacks what Obscura needs:" + detail::joinProblems(problems));

    ctx.shaders = std::make_unique<detail::ShaderLibrary>(ctx);
    ctx.profiler = std::make_unique<Profiler>(ctx);
}

Context::~Context() {
    if (!impl_) return;
    // Deleting objects changes no binding the host made to its own objects; releasing
    // ours happens without a state scope.
    impl_->profiler.reset();
    impl_->shaders.reset();
}

const ContextInfo& Context::info() const noexcept { return impl_->info; }
StatePolicy Context::statePolicy() const noexcept { return impl_->desc.statePolicy; }
Profiler& Context::profiler() noexcept { return *impl_->profiler; }
std::vector<std::string> Context::compiledPrograms() const { return impl_->shaders->compiledPrograms(); }
std::size_t Context::liveObjectCount() const noexcept { return impl_->liveObjects; }
void Context::addShaderSource(const std::string& path, const std::string& text) {
    impl_->shaders->addSource(path, text);
}

} // namespace obscura
