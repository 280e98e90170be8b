#pragma once
// Batch segment queries on the GPU (voxel and screen-space visibility): segments uploaded as
// from/to vec4 pairs to one SSBO, one uvec4 result per segment in another, dispatched in
// chunks that respect GL's 65535 work groups per dispatch, results read back.
#include "core/gl_objects.hpp"

#include <glm/glm.hpp>

#include <cstddef>
#include <string>
#include <vector>

namespace obscura::detail {

struct ContextImpl;

struct SegmentBatchLayout {
    GLuint segmentsBinding = 0; //!< SSBO of vec4 from, to pairs
    GLuint resultsBinding = 0;  //!< SSBO of uvec4 per segment
    GLint countLocation = 0;    //!< uniform uint: segments in the batch
    GLint firstLocation = 0;    //!< uniform uint: first segment of this dispatch
    int workgroup = 64;         //!< local_size_x of the query shader
    std::string label;          //!< object labels and error messages, e.g. "voxel"
};

class SegmentBatch {
public:
    explicit SegmentBatch(SegmentBatchLayout layout) : layout_(std::move(layout)) {}

    //! Uploads the segments (anything with glm::vec3 `from` and `to`) and binds both buffers.
    //! Throws Error{InvalidArgument} beyond 2^26 segments (2 GiB of buffers).
    template <class Segment>
    void upload(ContextImpl& ctx, const std::vector<Segment>& segments) {
        std::vector<glm::vec4> packed;
        packed.reserve(segments.size() * 2);
        for (const Segment& s : segments) {
            packed.emplace_back(s.from, 0.0f);
            packed.emplace_back(s.to, 0.0f);
        }
        uploadPacked(ctx, packed);
    }
    //! Runs `program` (already in use, its other uniforms set) over the uploaded segments,
    //! timing only the dispatches as `pass`, and reads the results back.
    std::vector<glm::uvec4> run(ContextImpl& ctx, GLuint program, const char* pass);
    std::size_t memoryBytes() const { return capacity_ * (2 * sizeof(glm::vec4) + sizeof(glm::uvec4)); }

private:
    void uploadPacked(ContextImpl& ctx, const std::vector<glm::vec4>& packed);

    SegmentBatchLayout layout_;
    Buffer segments_, results_;
    std::size_t capacity_ = 0, count_ = 0;
};

} // namespace obscura::detail
