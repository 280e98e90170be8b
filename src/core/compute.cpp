#include "core/compute.hpp"

#include "core/context_impl.hpp"

namespace obscura::detail {

void dispatchCompute2D(ContextImpl& ctx, int width, int height, int groupSize) {
    const auto groups = [groupSize](int n) { return static_cast<GLuint>((n + groupSize - 1) / groupSize); };
    ctx.gl.DispatchCompute(groups(width), groups(height), 1);
}

void dispatchCompute1D(ContextImpl& ctx, std::size_t count, int groupSize) {
    ctx.gl.DispatchCompute(static_cast<GLuint>((count + static_cast<std::size_t>(groupSize) - 1) / static_cast<std::size_t>(groupSize)),
                           1, 1);
}

void barrierForReaders(ContextImpl& ctx) {
    ctx.gl.MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT |
                         GL_FRAMEBUFFER_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

} // namespace obscura::detail
