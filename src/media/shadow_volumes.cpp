#include "media/shadow_volumes.hpp"

#include "core/compute.hpp"
#include "core/context_impl.hpp"
#include "core/pass_scope.hpp"
#include "core/shader_library.hpp"
#include "core/state_guard.hpp"
#include "gbuffer/light_records.hpp"
#include "obscura/error.hpp"
#include "shaders/media/media_bindings.h"
#include "shaders/shadows/shadow_bindings.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

namespace obscura::detail {
namespace {

// Distance along the spot's axis past which neither its map nor any medium reaches: where
// the cells whose map holds nothing end (their light reaches every medium, as media_shadow.glsl
// takes it).
float capDistance(const Light& light, const ShadowMapInfo& info, std::span<const Medium> media) {
    const glm::dvec3 eye(light.position), axis = glm::normalize(glm::dvec3(light.direction));
    double farthest = info.depthMapping[0].w;
    for (const Medium& m : media)
        for (int c = 0; c < 8; ++c) {
            const glm::dvec3 corner(c & 1 ? m.boxMax.x : m.boxMin.x, c & 2 ? m.boxMax.y : m.boxMin.y, c & 4 ? m.boxMax.z : m.boxMin.z);
            farthest = std::max(farthest, glm::dot(corner - eye, axis));
        }
    return static_cast<float>(1.01 * farthest);
}

// The vertices live in a storage buffer the vertex shader reads: GL 4.5 may allow none there,
// and a block as small as 2^27 bytes.
void checkLimits(ContextImpl& ctx, std::size_t bytes) {
    GLint blocks = 0, most = 0;
    ctx.gl.GetIntegerv(GL_MAX_VERTEX_SHADER_STORAGE_BLOCKS, &blocks);
    ctx.gl.GetIntegerv(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &most);
    if (blocks < 1)
        throw Error(ErrorCode::UnsupportedFeature, "MediaMethod::Bounded reads storage buffers in a vertex shader, and this "
                                                   "context allows none there (GL_MAX_VERTEX_SHADER_STORAGE_BLOCKS = 0)");
    if (bytes > std::size_t(std::max(most, 0)))
        throw Error(ErrorCode::InvalidArgument, "MediaSettings::volumeCell: the shadow volumes' vertices (" + std::to_string(bytes) +
                                                    " bytes) exceed GL_MAX_SHADER_STORAGE_BLOCK_SIZE = " + std::to_string(most) +
                                                    ": raise volumeCell or lower the shadow maps' resolution");
}

} // namespace

bool everyLightBounded(const MediaInputs& in) {
    if (!in.shadows || !in.shadows->depth || in.lights.empty()) return false;
    for (std::size_t i = 0; i < in.lights.size(); ++i)
        if (in.lights[i].type != LightType::Spot || !in.shadows->find(i)) return false;
    return true;
}

void ShadowVolumes::draw(ContextImpl& ctx, const MediaInputs& in, const LightRecords& records, int cellTexels, int width,
                         int height) {
    auto& gl = ctx.gl;
    const int cells = (in.shadows->resolution + cellTexels - 1) / cellTexels;
    const int perLight = (cells + 1) * (cells + 1) + 1;
    const std::size_t bytes = std::size_t(perLight) * in.lights.size() * sizeof(float) * 4;
    checkLimits(ctx, bytes);
    if (!vertices_ || vertexBytes_ < bytes) {
        vertices_ = createBuffer(ctx, static_cast<GLsizeiptr>(bytes), nullptr, 0, "media.shadow_volumes");
        vertexBytes_ = bytes;
    }
    ctx.state.bindStorageBuffer(ctx, MEDIA_VOLUME_SSBO, vertices_.get());
    {
        PassScope pass(ctx, "media.bounded.volume");
        const GLuint cellProgram = ctx.shaders->program({"media/media_volume.comp.glsl"}, {"CELLS"});
        const GLuint vertexProgram = ctx.shaders->program({"media/media_volume.comp.glsl"});
        ctx.state.bindTexture(ctx, SHADOW_DEPTH_READ_UNIT, in.shadows->depth);
        ctx.state.bindSampler(ctx, SHADOW_DEPTH_READ_UNIT, ctx.nearestClampSampler());
        const GLuint farthest = cells_.ensure(ctx, GL_R32F, cells, cells, "media.volume_cells");
        ctx.state.bindImage(ctx, MEDIA_CELLS_IMAGE, farthest, 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32F);
        for (std::size_t i = 0; i < in.lights.size(); ++i) {
            for (const GLuint program : {cellProgram, vertexProgram}) {
                gl.UseProgram(program);
                gl.Uniform4i(MEDIA_VOLUME_LOC_GRID, records.recordOf(i), cellTexels, cells, static_cast<GLint>(i) * perLight);
                gl.Uniform1f(MEDIA_VOLUME_LOC_CAP, capDistance(in.lights[i], *in.shadows->find(i), in.media));
                const int invocations = program == cellProgram ? cells : cells + 1;
                dispatchCompute2D(ctx, invocations, invocations, MEDIA_WORKGROUP);
                gl.MemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
            }
        }
        gl.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
    PassScope pass(ctx, "media.bounded.interval");
    const GLuint nearest = nearest_.ensure(ctx, GL_R32UI, width, height, "media.nearest_crossing");
    const GLuint farthest = farthest_.ensure(ctx, GL_R32UI, width, height, "media.farthest_crossing");
    // Depths as float bits: no crossing leaves the nearest at the largest float, the farthest at 0.
    const float most = std::numeric_limits<float>::max();
    std::uint32_t mostBits = 0, zero = 0;
    std::memcpy(&mostBits, &most, sizeof(mostBits));
    gl.ClearTexImage(nearest, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &mostBits);
    gl.ClearTexImage(farthest, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    if (!fbo_) fbo_ = createFramebuffer(ctx, "media.shadow_volumes"); // no attachments: image atomics only
    gl.NamedFramebufferParameteri(fbo_.get(), GL_FRAMEBUFFER_DEFAULT_WIDTH, width);
    gl.NamedFramebufferParameteri(fbo_.get(), GL_FRAMEBUFFER_DEFAULT_HEIGHT, height);
    gl.BindFramebuffer(GL_FRAMEBUFFER, fbo_.get());
    setViewport(ctx, 0, 0, width, height);
    DrawState state;
    state.depthClamp = true; // crossings before the near plane (or past the far) count too
    applyDrawState(ctx, state);
    ctx.state.bindImage(ctx, MEDIA_NEAR_IMAGE, nearest, 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
    ctx.state.bindImage(ctx, MEDIA_FAR_IMAGE, farthest, 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
    gl.UseProgram(ctx.shaders->program({"media/media_volume.vert.glsl", "media/media_volume.frag.glsl"}));
    gl.BindVertexArray(ctx.emptyVertexArray());
    const GLsizei triangles = 2 * cells * cells + 4 * cells;
    for (std::size_t i = 0; i < in.lights.size(); ++i) {
        gl.Uniform4i(MEDIA_VOLUME_LOC_GRID, records.recordOf(i), cellTexels, cells, static_cast<GLint>(i) * perLight);
        gl.DrawArrays(GL_TRIANGLES, 0, 3 * triangles);
    }
    applyDrawState(ctx, {});
    gl.MemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
}

void ShadowVolumes::release() noexcept {
    vertices_.reset();
    vertexBytes_ = 0;
    nearest_.release();
    farthest_.release();
    cells_.release();
    fbo_.reset();
}

std::size_t ShadowVolumes::memoryBytes() const { return vertexBytes_ + nearest_.bytes() + farthest_.bytes() + cells_.bytes(); }

} // namespace obscura::detail
