#pragma once
// Integrator passes run their rays in batches on software renderers. Mesa's llvmpipe caps
// the loop iterations of a shader invocation: one counter per shader function (everything is
// inlined into main), set to LP_MAX_TGSI_LOOP_ITERATIONS = 65535 when the invocation starts
// and decremented at the end of every iteration of every loop; at 0 each loop leaves after
// its current iteration. Results past the cap are silently wrong (1024 hybrid GI rays through
// a fine voxel grid came out 30 % dark). A pass whose rays may take more iterations than
// kLoopBudget in all runs them in several dispatches, each adding its rays' partial sums to
// a buffer (shaders/common/ray_batch.glsl); on other renderers, one dispatch.
#include "core/gl.hpp"
#include "core/gl_objects.hpp"
#include "obscura/screen_visibility.hpp"
#include "obscura/voxelizer.hpp"

#include <glm/glm.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace obscura::detail {

struct ContextImpl;

class RayBatches {
public:
    //! Loop iterations one invocation may spend on its rays: the cap less a margin for the
    //! shader's other loops (a few dozen iterations).
    static constexpr std::int64_t kLoopBudget = 60000;

    //! Plans `items` rays (or slices) of at most `iterationsPerItem` loop iterations each, for
    //! `slots` pixels (each dispatch's largest pixel index + 1), each pixel's rays shared by
    //! `lanes` invocations (ray_batch.glsl's ray lanes).
    void plan(ContextImpl& ctx, int items, std::int64_t iterationsPerItem, std::size_t slots, int lanes);
    //! Runs `program`, in use, once per batch: `dispatch` dispatches it.
    template <class Dispatch> void run(ContextImpl& ctx, GLuint program, Dispatch dispatch) const {
        for (int b = 0; b < count_; ++b) {
            select(ctx, program, b);
            dispatch();
            barrier(ctx);
        }
    }
    std::size_t memoryBytes() const { return bytes_; }

private:
    void select(ContextImpl& ctx, GLuint program, int b) const;
    static void barrier(ContextImpl& ctx);

    int items_ = 0, perBatch_ = 0, count_ = 1;
    Buffer partials_;
    std::size_t bytes_ = 0;
};

//! The shader define for `lanes` ray lanes (none for 1, which the shaders default to).
void addRayLaneDefine(std::vector<std::string>& defines, int lanes);

//! Loop iterations of one screen-space ray of `steps` samples on a G-buffer of `size`: a
//! sample each, and for the Hi-Z march at most one descent per level per sample.
std::int64_t screenRayIterations(ScreenMarch march, int steps, glm::ivec2 size);
//! Loop iterations of one ray of `length` world units through `grid`: the march samples
//! `steps` times; the exact traversal visits at most sqrt(3) length / side + 4 voxels (side:
//! the smallest voxel side); the hierarchical one advances past at most that many cells and
//! descends at most once per advance plus once per level.
std::int64_t voxelRayIterations(const VoxelGrid& grid, VoxelTraversal traversal, double length, int steps);

} // namespace obscura::detail
