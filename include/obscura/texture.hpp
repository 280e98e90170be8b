#pragma once
// Views of GL textures exchanged with the host, and CPU images.
#include "obscura/export.hpp"

#include <cstddef>
#include <vector>

namespace obscura {

class Context;

//! A 2D texture, either owned by an Obscura module (valid until that module's next call
//! or destruction) or owned by the host. `name` is the GL texture name, `internalFormat`
//! a GL sized internal format (e.g. 0x881A = GL_RGBA16F).
struct TextureView {
    unsigned name = 0;
    unsigned internalFormat = 0;
    int width = 0;  //!< pixels
    int height = 0; //!< pixels
    explicit operator bool() const noexcept { return name != 0; }
};

//! A float image in memory. Row 0 is the top row of the picture (the last row of a GL
//! texture), pixels are interleaved channels.
struct Image {
    int width = 0;
    int height = 0;
    int channels = 0;
    std::vector<float> pixels;

    float& at(int x, int y, int c) { return pixels[index(x, y, c)]; }
    float at(int x, int y, int c) const { return pixels[index(x, y, c)]; }
    std::size_t index(int x, int y, int c) const {
        return (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)) *
                   static_cast<std::size_t>(channels) + static_cast<std::size_t>(c);
    }
};

//! Reads level 0 of a 2D texture back to the CPU as float (synchronous: it waits for the
//! GPU). Channels follow the format: 1 for depth and R formats, 2 for RG, 3 for RGB and
//! 4 for RGBA; sRGB formats are returned linear, normalized formats in [0,1] or [-1,1],
//! integer formats as float values. Throws Error{InvalidArgument} for a non-2D, multisampled
//! or compressed texture.
OBSCURA_API Image readTexture(Context& context, const TextureView& texture);

} // namespace obscura
