#pragma once
// How a module's pass reads an environment (shaders/environment/environment.glsl).
#include "obscura/environment.hpp"

namespace obscura {
namespace detail {
struct ContextImpl;
}

struct EnvironmentBinding {
    //! Binds the lookup block and both cubes with their samplers, inside the caller's StateScope.
    static void bind(detail::ContextImpl& ctx, const EnvironmentMap& environment);
};

} // namespace obscura
