#include "core/segment_batch.hpp"

#include "core/compute.hpp"
#include "core/context_impl.hpp"
#include "core/pass_scope.hpp"
#include "obscura/error.hpp"

#include <algorithm>

namespace obscura::detail {

void SegmentBatch::uploadPacked(ContextImpl& ctx, const std::vector<glm::vec4>& packed) {
    constexpr std::size_t kMaxSegments = std::size_t{1} << 26; // 2 GiB of segments and results
    const std::size_t count = packed.size() / 2;
    if (count > kMaxSegments)
        throw Error(ErrorCode::InvalidArgument, layout_.label + " queries: " + std::to_string(count) +
                                                    " in one call; at most " + std::to_string(kMaxSegments) + " are accepted");
    if (capacity_ < count) {
        segments_ = createBuffer(ctx, static_cast<GLsizeiptr>(count * 2 * sizeof(glm::vec4)), nullptr,
                                 GL_DYNAMIC_STORAGE_BIT, layout_.label + ".segments");
        results_ = createBuffer(ctx, static_cast<GLsizeiptr>(count * sizeof(glm::uvec4)), nullptr, GL_DYNAMIC_STORAGE_BIT,
                                layout_.label + ".results");
        capacity_ = count;
    }
    count_ = count;
    ctx.gl.NamedBufferSubData(segments_.get(), 0, static_cast<GLsizeiptr>(packed.size() * sizeof(glm::vec4)), packed.data());
    ctx.state.bindStorageBuffer(ctx, layout_.segmentsBinding, segments_.get());
    ctx.state.bindStorageBuffer(ctx, layout_.resultsBinding, results_.get());
}

std::vector<glm::uvec4> SegmentBatch::run(ContextImpl& ctx, GLuint program, const char* pass) {
    auto& gl = ctx.gl;
    gl.ProgramUniform1ui(program, layout_.countLocation, static_cast<GLuint>(count_));
    {
        // Only the queries are timed, not the transfers.
        PassScope scope(ctx, pass);
        const std::size_t perDispatch = std::size_t{65535} * static_cast<std::size_t>(layout_.workgroup);
        for (std::size_t first = 0; first < count_; first += perDispatch) {
            gl.ProgramUniform1ui(program, layout_.firstLocation, static_cast<GLuint>(first));
            dispatchCompute1D(ctx, std::min(perDispatch, count_ - first), layout_.workgroup);
        }
    }
    gl.MemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<glm::uvec4> raw(count_);
    gl.GetNamedBufferSubData(results_.get(), 0, static_cast<GLsizeiptr>(raw.size() * sizeof(glm::uvec4)), raw.data());
    return raw;
}

} // namespace obscura::detail
