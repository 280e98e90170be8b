#include "core/ray_batches.hpp"

#include "core/context_impl.hpp"
#include "obscura/error.hpp"
#include "shaders/common/common_bindings.h"

#include <algorithm>
#include <cmath>

namespace obscura::detail {

void RayBatches::plan(ContextImpl& ctx, int items, std::int64_t iterationsPerItem, std::size_t slots, int lanes) {
    items_ = items;
    const std::int64_t perItem = std::max<std::int64_t>(iterationsPerItem, 1);
    // An invocation runs every lanes-th ray of its batch.
    const std::int64_t perInvocation = (std::int64_t(items) + lanes - 1) / lanes;
    const bool capped = ctx.info.softwareRenderer && perInvocation * perItem > kLoopBudget;
    perBatch_ = capped ? static_cast<int>(std::max<std::int64_t>(kLoopBudget / perItem, 1) * lanes) : items;
    count_ = (items + perBatch_ - 1) / perBatch_;
    // Two vec4 per invocation (ray_batch.glsl's RayBatchPartial); one batch reads and writes
    // none, but its shader still declares the buffer: one entry is bound.
    const std::size_t bytes = (count_ > 1 ? std::max<std::size_t>(slots, 1) : 1) * 2 * 4 * sizeof(float);
    if (!partials_ || bytes_ < bytes) {
        partials_ = createBuffer(ctx, GLsizeiptr(bytes), nullptr, 0, "ray_batches.partials");
        bytes_ = bytes;
    }
}

void RayBatches::select(ContextImpl& ctx, GLuint program, int b) const {
    const int first = b * perBatch_, end = std::min(items_, first + perBatch_);
    ctx.gl.ProgramUniform4i(program, OBSCURA_LOC_RAY_BATCH, first, end, b > 0 ? 1 : 0, b + 1 == count_ ? 1 : 0);
    ctx.state.bindStorageBuffer(ctx, OBSCURA_RAY_BATCH_SSBO, partials_.get());
}

// The next batch reads the partial sums this one wrote.
void RayBatches::barrier(ContextImpl& ctx) { ctx.gl.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT); }

void addRayLaneDefine(std::vector<std::string>& defines, int lanes) {
    if (lanes > 1) defines.push_back("RAY_LANES=" + std::to_string(lanes));
}

std::int64_t screenRayIterations(ScreenMarch march, int steps, glm::ivec2 size) {
    if (march != ScreenMarch::HiZ) return std::int64_t(steps) + 1;
    const int top = static_cast<int>(std::floor(std::log2(double(std::max({size.x, size.y, 1})))));
    return std::int64_t(steps) * (top + 2) + 1;
}

std::int64_t voxelRayIterations(const VoxelGrid& grid, VoxelTraversal traversal, double length, int steps) {
    if (traversal == VoxelTraversal::March) return std::int64_t(steps) + 1;
    const glm::dvec3 sides = (grid.boxMax - grid.boxMin) / glm::dvec3(grid.dims);
    const double voxels = std::sqrt(3.0) * length / std::min({sides.x, sides.y, sides.z}) + 4.0;
    const double bound = traversal == VoxelTraversal::Hierarchical ? 2.0 * voxels + grid.levels + 1.0 : voxels;
    return static_cast<std::int64_t>(std::ceil(std::min(bound, 1e12)));
}

} // namespace obscura::detail
