#pragma once
// Compute dispatch helpers shared by the modules.
#include "core/gl.hpp"

#include <cstddef>

namespace obscura::detail {

struct ContextImpl;

//! Enough groups of groupSize x groupSize invocations to cover width x height.
void dispatchCompute2D(ContextImpl& ctx, int width, int height, int groupSize);
//! Enough groups of groupSize invocations to cover count.
void dispatchCompute1D(ContextImpl& ctx, std::size_t count, int groupSize);
//! Makes image and buffer writes visible to what reads results next: later passes (texture
//! fetches, image loads, SSBO reads), the host sampling our textures, readbacks.
void barrierForReaders(ContextImpl& ctx);

} // namespace obscura::detail
