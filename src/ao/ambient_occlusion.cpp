#include "obscura/ambient_occlusion.hpp"

#include "core/compute.hpp"
#include "core/context_impl.hpp"
#include "core/frame_uniforms.hpp"
#include "core/pass_scope.hpp"
#include "core/shader_library.hpp"
#include "core/texture_info.hpp"
#include "core/validate.hpp"
#include "obscura/context.hpp"
#include "shaders/ao/ao_bindings.h"
#include "shaders/voxel/voxel_bindings.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace obscura {
namespace {

using namespace detail;

// The pass names (stable: profiler, debug groups, bench).
const char* passName(AoMethod m) {
    switch (m) {
    case AoMethod::RayMarch: return "ao.raymarch";
    case AoMethod::Points: return "ao.points";
    case AoMethod::Horizon: return "ao.horizon";
    case AoMethod::Voxel: return "ao.voxel";
    }
    return "ao";
}

void validateSettings(const AmbientOcclusionSettings& s) {
    if (!(s.radius > 0.0f) || !std::isfinite(s.radius))
        throw Error(ErrorCode::InvalidArgument,
                    "AmbientOcclusionSettings::radius must be in (0, inf) world units, got " + std::to_string(s.radius));
    requireInRange(s.rays, s.method == AoMethod::Horizon ? 2 : 1, 1024, "AmbientOcclusionSettings::rays", "");
    if (s.method == AoMethod::Horizon && s.rays % 2 != 0)
        throw Error(ErrorCode::InvalidArgument, "AmbientOcclusionSettings::rays must be even for the horizon method "
                                                "(two directions per slice), got " + std::to_string(s.rays));
    requireInRange(s.steps, 1, 256, "AmbientOcclusionSettings::steps", "");
    if (!(s.thickness >= 0.0f) || std::isinf(s.thickness))
        throw Error(ErrorCode::InvalidArgument, "AmbientOcclusionSettings::thickness must be in [0, inf) world units (0: "
                                                "the radius), got " + std::to_string(s.thickness));
    requireInRange(s.blurRadius, 0, 16, "AmbientOcclusionSettings::blurRadius", "taps");
    if (!(s.blurDepthSigma > 0.0f && s.blurDepthSigma <= 1.0f))
        throw Error(ErrorCode::InvalidArgument, "AmbientOcclusionSettings::blurDepthSigma must be in (0, 1], got " +
                                                    std::to_string(s.blurDepthSigma));
    requireInRange(s.blurNormalPower, 0.0, 256.0, "AmbientOcclusionSettings::blurNormalPower", "");
    if (s.method == AoMethod::Horizon && !s.cosineWeighted)
        throw Error(ErrorCode::InvalidArgument, "the horizon method integrates the cosine-weighted AO only: set "
                                                "AmbientOcclusionSettings::cosineWeighted");
    if (s.method == AoMethod::Voxel) {
        if (!s.voxels || s.voxels->texture == 0)
            throw Error(ErrorCode::InvalidArgument, "the voxel method needs AmbientOcclusionSettings::voxels, a grid from "
                                                    "Voxelizer::voxelize of the same scene");
        if (s.voxelTraversal == VoxelTraversal::Hierarchical && s.voxels->octree == 0)
            throw Error(ErrorCode::InvalidArgument, "hierarchical voxel traversal needs the grid's octree "
                                                    "(VoxelizerSettings::octree)");
    }
}

int falloffCode(ObscuranceFalloff f) {
    switch (f) {
    case ObscuranceFalloff::Linear: return AO_FALLOFF_LINEAR;
    case ObscuranceFalloff::Quadratic: return AO_FALLOFF_QUADRATIC;
    case ObscuranceFalloff::Smooth: return AO_FALLOFF_SMOOTH;
    case ObscuranceFalloff::None: break;
    }
    return AO_FALLOFF_NONE;
}

int traversalCode(VoxelTraversal t) {
    return t == VoxelTraversal::March ? VOXEL_METHOD_MARCH : t == VoxelTraversal::Exact ? VOXEL_METHOD_EXACT
                                                                                         : VOXEL_METHOD_HIERARCHICAL;
}

// Ping-pong pair of same-sized textures (the blur reads one and writes the other).
struct PingPong {
    SizedTexture a, b;
    std::size_t bytes() const { return a.bytes() + b.bytes(); }
};

} // namespace

struct AmbientOcclusion::Impl {
    explicit Impl(ContextImpl& c) : ctx(c) {}

    ContextImpl& ctx;
    FrameUniforms frame;
    Buffer params;
    PingPong ao, bent;
    SizedTexture guide, fullAo, fullBent;

    shader::AoParams makeParams(const GBufferView& g, const AmbientOcclusionSettings& s, glm::ivec2 size, int scale) const {
        shader::AoParams p{};
        p.shape = glm::vec4(s.radius, s.thickness > 0.0f ? s.thickness : s.radius, 0.0f, 0.0f);
        p.counts = glm::ivec4(s.rays, s.steps, (s.cosineWeighted ? AO_FLAG_COSINE : 0) | (s.bentNormals ? AO_FLAG_BENT : 0),
                              falloffCode(s.falloff));
        p.sizes = glm::ivec4(size, scale, s.blurRadius);
        p.blur = glm::vec4(s.blurDepthSigma, s.blurNormalPower, 0.0f, 0.0f);
        p.viewToVoxel = glm::mat4(1.0f);
        if (s.method == AoMethod::Voxel) {
            const VoxelGrid& grid = *s.voxels;
            p.viewToVoxel = glm::mat4(grid.worldToVoxel * glm::inverse(glm::dmat4(g.camera.view)));
            // Rays start off the surface by a voxel diagonal (of the largest voxel side), so
            // the voxels of the surface itself are not taken for occluders.
            const glm::dvec3 voxelSize = (grid.boxMax - grid.boxMin) / glm::dvec3(grid.dims);
            p.shape.z = static_cast<float>(std::sqrt(3.0) * std::max({voxelSize.x, voxelSize.y, voxelSize.z}));
            p.voxel = glm::ivec4(traversalCode(s.voxelTraversal), 0, 0, 0);
        }
        return p;
    }

    void bindInputs(const GBufferView& g) {
        ctx.state.bindTexture(ctx, VIS_DEPTH_UNIT, g.depth.name);
        ctx.state.bindSampler(ctx, VIS_DEPTH_UNIT, ctx.nearestClampSampler());
        ctx.state.bindTexture(ctx, VIS_NORMAL_UNIT, g.normal.name);
        ctx.state.bindSampler(ctx, VIS_NORMAL_UNIT, ctx.nearestClampSampler());
        ctx.bindNoiseTexture();
    }

    void bindVoxels(const VoxelGrid& grid) {
        ctx.state.bindUniformBuffer(ctx, VOXEL_PARAMS_UBO_BINDING, grid.params);
        ctx.state.bindTexture(ctx, VOXEL_GRID_UNIT, grid.texture);
        ctx.state.bindSampler(ctx, VOXEL_GRID_UNIT, ctx.nearestClampSampler());
        if (grid.octree) {
            ctx.state.bindTexture(ctx, VOXEL_OCTREE_UNIT, grid.octree);
            ctx.state.bindSampler(ctx, VOXEL_OCTREE_UNIT, ctx.nearestClampSampler());
        }
    }

    void bindRead(int unit, GLuint texture) {
        ctx.state.bindTexture(ctx, unit, texture);
        ctx.state.bindSampler(ctx, unit, ctx.nearestClampSampler());
    }

    void bindWrite(int unit, GLuint texture, GLenum format) {
        ctx.state.bindImage(ctx, unit, texture, 0, GL_FALSE, 0, GL_WRITE_ONLY, format);
    }

    // Horizontal then vertical: a -> b -> a.
    void blur(glm::ivec2 size, bool withBent) {
        PassScope pass(ctx, "ao.blur");
        const GLuint program = ctx.shaders->program({"ao/ao_blur.comp.glsl"});
        ctx.gl.UseProgram(program);
        bindRead(AO_GUIDE_UNIT, guide.get());
        for (int d = 0; d < 2; ++d) {
            const bool forward = d == 0;
            bindRead(AO_INPUT_UNIT, forward ? ao.a.get() : ao.b.get());
            bindWrite(AO_OUT_IMAGE, forward ? ao.b.get() : ao.a.get(), GL_R16F);
            if (withBent) {
                bindRead(AO_BENT_INPUT_UNIT, forward ? bent.a.get() : bent.b.get());
                bindWrite(AO_BENT_OUT_IMAGE, forward ? bent.b.get() : bent.a.get(), GL_RGBA16F);
            }
            ctx.gl.ProgramUniform2i(program, AO_LOC_DIRECTION, forward ? 1 : 0, forward ? 0 : 1);
            dispatchCompute2D(ctx, size.x, size.y, AO_WORKGROUP);
            ctx.gl.MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
        }
    }

    void upsample(const GBufferView& g, bool withBent) {
        PassScope pass(ctx, "ao.upsample");
        ctx.gl.UseProgram(ctx.shaders->program({"ao/ao_upsample.comp.glsl"}));
        bindRead(AO_GUIDE_UNIT, guide.get());
        bindRead(AO_INPUT_UNIT, ao.a.get());
        bindWrite(AO_OUT_IMAGE, fullAo.ensure(ctx, GL_R16F, g.width, g.height, "ao.output"), GL_R16F);
        if (withBent) {
            bindRead(AO_BENT_INPUT_UNIT, bent.a.get());
            bindWrite(AO_BENT_OUT_IMAGE, fullBent.ensure(ctx, GL_RGBA16F, g.width, g.height, "ao.bent_normal"), GL_RGBA16F);
        }
        dispatchCompute2D(ctx, g.width, g.height, AO_WORKGROUP);
    }
};

AmbientOcclusion::AmbientOcclusion(Context& context) : impl_(std::make_unique<Impl>(context.impl())) {}
AmbientOcclusion::~AmbientOcclusion() = default;

AmbientOcclusionView AmbientOcclusion::run(const GBufferView& g, const AmbientOcclusionSettings& s) {
    validateSettings(s);
    auto& d = *impl_;
    auto& ctx = d.ctx;
    analyzeProjection(g.camera);
    const TextureInfo depth = queryTexture2D(ctx, g.depth.name, "GBufferView::depth");
    if (!depth.depth) throw Error(ErrorCode::InvalidArgument, "GBufferView::depth is not a depth texture");
    const TextureInfo normal = queryTexture2D(ctx, g.normal.name, "GBufferView::normal");
    if (normal.width != depth.width || normal.height != depth.height)
        throw Error(ErrorCode::InvalidArgument, "GBufferView::normal (" + std::to_string(normal.width) + "x" +
                                                    std::to_string(normal.height) + ") must have the depth's size (" +
                                                    std::to_string(depth.width) + "x" + std::to_string(depth.height) + ")");
    GBufferView view = g;
    view.width = depth.width;
    view.height = depth.height;
    const int scale = static_cast<int>(s.resolution);
    const glm::ivec2 size((view.width + scale - 1) / scale, (view.height + scale - 1) / scale);

    StateScope scope(ctx);
    const shader::AoParams p = d.makeParams(view, s, size, scale);
    if (!d.params) d.params = createBuffer(ctx, sizeof p, nullptr, GL_DYNAMIC_STORAGE_BIT, "ao.params");
    ctx.gl.NamedBufferSubData(d.params.get(), 0, sizeof p, &p);
    ctx.state.bindUniformBuffer(ctx, AO_PARAMS_UBO_BINDING, d.params.get());
    d.frame.bind(ctx, view.camera, view.width, view.height);
    d.bindInputs(view);
    const GLuint aoTexture = d.ao.a.ensure(ctx, GL_R16F, size.x, size.y, "ao.occlusion");
    d.guide.ensure(ctx, GL_RGBA32F, size.x, size.y, "ao.guide");
    if (s.blurRadius > 0) d.ao.b.ensure(ctx, GL_R16F, size.x, size.y, "ao.occlusion_blur");
    if (s.bentNormals) {
        d.bent.a.ensure(ctx, GL_RGBA16F, size.x, size.y, "ao.bent");
        if (s.blurRadius > 0) d.bent.b.ensure(ctx, GL_RGBA16F, size.x, size.y, "ao.bent_blur");
    }
    {
        PassScope pass(ctx, passName(s.method));
        std::vector<std::string> defines = {"METHOD=" + std::to_string(static_cast<int>(s.method))};
        if (s.method == AoMethod::Voxel) defines.push_back("TRAVERSAL=" + std::to_string(traversalCode(s.voxelTraversal)));
        ctx.gl.UseProgram(ctx.shaders->program({"ao/ao.comp.glsl"}, defines));
        if (s.method == AoMethod::Voxel) d.bindVoxels(*s.voxels);
        d.bindWrite(AO_OUT_IMAGE, aoTexture, GL_R16F);
        d.bindWrite(AO_GUIDE_OUT_IMAGE, d.guide.get(), GL_RGBA32F);
        if (s.bentNormals) d.bindWrite(AO_BENT_OUT_IMAGE, d.bent.a.get(), GL_RGBA16F);
        dispatchCompute2D(ctx, size.x, size.y, AO_WORKGROUP);
        ctx.gl.MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    }
    if (s.blurRadius > 0) d.blur(size, s.bentNormals);
    AmbientOcclusionView out;
    out.width = view.width;
    out.height = view.height;
    if (scale == 1) {
        out.ao = {d.ao.a.get(), GL_R16F, size.x, size.y};
        if (s.bentNormals) out.bentNormal = {d.bent.a.get(), GL_RGBA16F, size.x, size.y};
    } else {
        d.upsample(view, s.bentNormals);
        out.ao = {d.fullAo.get(), GL_R16F, view.width, view.height};
        if (s.bentNormals) out.bentNormal = {d.fullBent.get(), GL_RGBA16F, view.width, view.height};
    }
    barrierForReaders(ctx);
    return out;
}

std::size_t AmbientOcclusion::memoryBytes() const {
    const auto& d = *impl_;
    return d.ao.bytes() + d.bent.bytes() + d.guide.bytes() + d.fullAo.bytes() + d.fullBent.bytes() + d.frame.memoryBytes() +
           (d.params ? sizeof(shader::AoParams) : 0);
}

} // namespace obscura
