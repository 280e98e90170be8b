#include "obscura/environment.hpp"

#include "core/compute.hpp"
#include "core/context_impl.hpp"
#include "core/gl_objects.hpp"
#include "core/pass_scope.hpp"
#include "core/shader_library.hpp"
#include "core/state_guard.hpp"
#include "core/validate.hpp"
#include "environment/environment_binding.hpp"
#include "environment/environment_data.hpp"
#include "obscura/context.hpp"
#include "obscura/error.hpp"
#include "shaders/environment/environment_bindings.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace obscura {

using namespace detail;

double EnvironmentImportance::solidAngle(int y) const { return texelSolidAngle(y, width, height); }

struct EnvironmentMap::Impl {
    explicit Impl(ContextImpl& c) : ctx(&c) {}

    ContextImpl* ctx;
    Texture cube, irradiance;
    Sampler cubeSampler;
    Buffer params;
    int cubeSize = 0, cubeLevels = 0, irradianceSize = 0;
    float intensity = 1.0f, rotation = 0.0f;
    std::array<glm::dvec3, 9> coefficients{}, terms{};
    std::optional<Sun> sun;
    EnvironmentImportance importance;
    std::size_t replaced = 0;
    std::vector<std::string> warnings;

    // The environment-frame direction of a world direction (environment.glsl's environmentLocal).
    glm::dvec3 local(const glm::dvec3& w) const {
        const double c = std::cos(double(rotation)), s = std::sin(double(rotation));
        return {w.x * c + w.z * s, w.y, w.z * c - w.x * s};
    }
    glm::dvec3 world(const glm::dvec3& l) const {
        const double c = std::cos(double(rotation)), s = std::sin(double(rotation));
        return {l.x * c - l.z * s, l.y, l.z * c + l.x * s};
    }

    void uploadParams() {
        shader::EnvironmentParams p{};
        for (int i = 0; i < 9; ++i) p.sh[i] = glm::vec4(glm::vec3(terms[std::size_t(i)]), 0.0f);
        p.intensity = intensity;
        p.rotationCos = static_cast<float>(std::cos(double(rotation)));
        p.rotationSin = static_cast<float>(std::sin(double(rotation)));
        p.cubeSize = static_cast<float>(cubeSize);
        p.cubeLevels = static_cast<float>(cubeLevels);
        uploadUniformBlock(*ctx, params, p, ENV_PARAMS_UBO_BINDING, "environment.params");
    }

    // Level 0 from the equirectangular source (with its own mips) on the GPU, then the mips.
    void buildCube(const Equirect& env) {
        PassScope pass(*ctx, "environment.cube");
        auto& gl = ctx->gl;
        const int sourceLevels = fullMipLevels(std::max(env.width, env.height));
        Texture source = createTexture2D(*ctx, GL_RGBA32F, env.width, env.height, sourceLevels, "environment.source");
        std::vector<float> rgba(env.texels.size() * 4);
        for (std::size_t i = 0; i < env.texels.size(); ++i)
            for (int k = 0; k < 4; ++k) rgba[i * 4 + std::size_t(k)] = k < 3 ? float(env.texels[i][k]) : 1.0f;
        gl.TextureSubImage2D(source.get(), 0, 0, 0, env.width, env.height, GL_RGBA, GL_FLOAT, rgba.data());
        gl.GenerateTextureMipmap(source.get());
        // Longitude wraps around; latitude ends at the poles.
        Sampler wrap = createSampler(*ctx, GL_LINEAR, GL_CLAMP_TO_EDGE, "environment.source_sampler");
        gl.SamplerParameteri(wrap.get(), GL_TEXTURE_WRAP_S, GL_REPEAT);
        gl.SamplerParameteri(wrap.get(), GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
        const GLuint program = ctx->shaders->program({"environment/equirect_to_cube.comp.glsl"});
        gl.UseProgram(program);
        ctx->state.bindTexture(*ctx, ENV_SOURCE_UNIT, source.get());
        ctx->state.bindSampler(*ctx, ENV_SOURCE_UNIT, wrap.get());
        ctx->state.bindImage(*ctx, ENV_CUBE_OUT_IMAGE, cube.get(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
        gl.ProgramUniform1i(program, 0, cubeSize);
        const GLuint groups = GLuint((cubeSize + ENV_WORKGROUP - 1) / ENV_WORKGROUP);
        gl.DispatchCompute(groups, groups, 6);
        // Mipmap generation reads level 0 through a path no single barrier bit names: all of them
        // (once per environment).
        gl.MemoryBarrier(GL_ALL_BARRIER_BITS);
        gl.GenerateTextureMipmap(cube.get());
    }

    void uploadIrradiance(const Equirect& reduced) {
        const std::vector<float> faces = irradianceCube(reduced, irradianceSize);
        ctx->gl.TextureSubImage3D(irradiance.get(), 0, 0, 0, 0, irradianceSize, irradianceSize, 6, GL_RGBA, GL_FLOAT,
                                  faces.data());
    }
};

EnvironmentMap::EnvironmentMap(Context& context, const Image& image, const EnvironmentSettings& s)
    : impl_(std::make_unique<Impl>(context.impl())) {
    validateSettings(EnvironmentSettings::table(), s, "EnvironmentSettings");
    auto& d = *impl_;
    auto& ctx = *d.ctx;
    Equirect env = cleanedEquirect(image, d.replaced);
    // (cubeSize's range is within GL 4.5's least GL_MAX_CUBE_MAP_TEXTURE_SIZE, 16384.)
    requireImageSize(env.width, env.height, ctx.info.maxTextureSize, "EnvironmentMap image");
    if (d.replaced > 0)
        d.warnings.push_back("environment: " + std::to_string(d.replaced) +
                             " texels were NaN, infinite or negative and are replaced by 0");
    d.sun = splitSun(env, s.sunThreshold);
    d.coefficients = projectSh(env);
    d.terms = irradianceShTerms(d.coefficients, s.shWindow);
    const Equirect reduced = reducedEquirect(env, s.convolutionWidth);
    d.importance = importanceTable(reduced);

    d.cubeSize = s.cubeSize;
    d.cubeLevels = fullMipLevels(s.cubeSize);
    d.irradianceSize = s.irradianceSize;
    StateScope scope(ctx);
    d.cube = createTextureCube(ctx, GL_RGBA16F, d.cubeSize, d.cubeLevels, "environment.cube");
    d.irradiance = createTextureCube(ctx, GL_RGBA32F, d.irradianceSize, 1, "environment.irradiance");
    d.cubeSampler = createSampler(ctx, GL_LINEAR, GL_CLAMP_TO_EDGE, "environment.cube_sampler");
    ctx.gl.SamplerParameteri(d.cubeSampler.get(), GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    d.buildCube(env);
    d.uploadIrradiance(reduced);
    d.uploadParams();
    barrierForReaders(ctx);
}

EnvironmentMap::~EnvironmentMap() = default;

void EnvironmentMap::setLookup(float intensity, float rotation) {
    requireFinite(intensity, "EnvironmentMap intensity");
    requireInRange(intensity, 0.0, INFINITY, "EnvironmentMap intensity");
    requireFinite(rotation, "EnvironmentMap rotation");
    auto& d = *impl_;
    d.intensity = intensity;
    d.rotation = static_cast<float>(std::remainder(double(rotation), 2.0 * 3.14159265358979323846));
    StateScope scope(*d.ctx);
    d.uploadParams();
}

float EnvironmentMap::intensity() const { return impl_->intensity; }
float EnvironmentMap::rotation() const { return impl_->rotation; }

EnvironmentView EnvironmentMap::view() const {
    const auto& d = *impl_;
    return {d.cube.get(), d.irradiance.get(), d.cubeSize, d.cubeLevels, d.irradianceSize};
}

glm::vec3 EnvironmentMap::shIrradiance(const glm::vec3& normal) const {
    const auto& d = *impl_;
    const glm::dvec3 e = evaluateShTerms(d.terms, d.local(glm::dvec3(normal)));
    return glm::vec3(glm::max(e, glm::dvec3(0.0)) * double(d.intensity));
}

std::array<glm::dvec3, 9> EnvironmentMap::shCoefficients() const { return impl_->coefficients; }

std::optional<Light> EnvironmentMap::sun() const {
    const auto& d = *impl_;
    if (!d.sun) return std::nullopt;
    Light light;
    light.type = LightType::Directional;
    const glm::dvec3 e = d.sun->irradiance * double(d.intensity);
    const double peak = std::max({e.r, e.g, e.b});
    light.intensity = static_cast<float>(peak);
    light.color = peak > 0.0 ? glm::vec3(e / peak) : glm::vec3(1.0f);
    light.direction = glm::vec3(-d.world(d.sun->towardSun));
    return light;
}

const EnvironmentImportance& EnvironmentMap::importance() const { return impl_->importance; }
std::size_t EnvironmentMap::replacedTexels() const { return impl_->replaced; }
const std::vector<std::string>& EnvironmentMap::warnings() const { return impl_->warnings; }

std::size_t EnvironmentMap::memoryBytes() const {
    const auto& d = *impl_;
    std::size_t cube = 0;
    for (int level = 0; level < d.cubeLevels; ++level) {
        const std::size_t edge = std::size_t(std::max(d.cubeSize >> level, 1));
        cube += 6 * edge * edge * bytesPerTexel(GL_RGBA16F);
    }
    return cube + 6 * std::size_t(d.irradianceSize) * std::size_t(d.irradianceSize) * bytesPerTexel(GL_RGBA32F) +
           sizeof(shader::EnvironmentParams);
}

void EnvironmentBinding::bind(ContextImpl& ctx, const EnvironmentMap& environment) {
    const auto& d = *environment.impl_;
    if (d.ctx != &ctx) throw Error(ErrorCode::InvalidArgument, "the EnvironmentMap belongs to another Context");
    ctx.state.bindUniformBuffer(ctx, ENV_PARAMS_UBO_BINDING, d.params.get());
    ctx.state.bindTexture(ctx, ENV_CUBE_UNIT, d.cube.get());
    ctx.state.bindSampler(ctx, ENV_CUBE_UNIT, d.cubeSampler.get());
    ctx.state.bindTexture(ctx, ENV_IRRADIANCE_UNIT, d.irradiance.get());
    ctx.state.bindSampler(ctx, ENV_IRRADIANCE_UNIT, ctx.linearClampSampler());
}

} // namespace obscura
