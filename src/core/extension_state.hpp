#pragma once
// The vendor extensions' part of the host state the guard saves and resets (context.hpp lists
// it), each only where the context has the extension, since GL refuses the enums elsewhere:
// enables that add, drop or reshape our draws' fragments, the window rectangles, and the
// viewport swizzle of index 0. The core GL 4.5 state is state_guard.cpp's.
#include "core/gl.hpp"

#include <cstddef>
#include <vector>

namespace obscura::detail {

struct ExtensionState {
    //! The enables of extension_state.cpp's table (where present).
    static constexpr std::size_t kEnableCount = 8;
    bool enables[kEnableCount]{};
    GLint windowRectangleMode = GL_EXCLUSIVE_EXT;
    std::vector<GLint> windowRectangles; //!< x, y, width, height per rectangle in use
    GLint viewportSwizzle[4]{};          //!< index 0

    //! Fills this in place: the saved state is reused call after call, so its storage is too.
    void save(GladGLContext& gl);
    void restore(GladGLContext& gl) const;
    //! GL's initial values: enables off, exclusive window rectangles with none, identity swizzle.
    static void applyBaseline(GladGLContext& gl);
};

} // namespace obscura::detail
