#include "obscura/texture.hpp"

#include "core/context_impl.hpp"
#include "core/texture_info.hpp"
#include "obscura/context.hpp"

#include <cmath>
#include <cstring>

namespace obscura {

Image readTexture(Context& context, const TextureView& texture) {
    auto& ctx = context.impl();
    const detail::TextureInfo info = detail::queryTexture2D(ctx, texture.name, "readTexture");
    detail::StateScope scope(ctx);
    auto& gl = ctx.gl;

    Image image;
    image.width = info.width;
    image.height = info.height;
    image.channels = info.channels;
    const std::size_t rowValues = static_cast<std::size_t>(info.width) * static_cast<std::size_t>(info.channels);
    std::vector<float> raw(rowValues * static_cast<std::size_t>(info.height));
    const auto bytes = static_cast<GLsizei>(raw.size() * sizeof(float));
    if (info.integer) {
        // Integer textures cannot be read as GL_FLOAT; read the bits and convert.
        std::vector<std::int32_t> ints(raw.size());
        gl.GetTextureImage(texture.name, 0, info.pixelFormat, info.isSigned ? GL_INT : GL_UNSIGNED_INT, bytes, ints.data());
        for (std::size_t i = 0; i < ints.size(); ++i)
            raw[i] = info.isSigned ? static_cast<float>(ints[i]) : static_cast<float>(static_cast<std::uint32_t>(ints[i]));
    } else {
        gl.GetTextureImage(texture.name, 0, info.pixelFormat, GL_FLOAT, bytes, raw.data());
    }
    // Readback returns sRGB texels as stored (encoded); the contract is linear values.
    if (info.srgb)
        for (std::size_t i = 0; i < raw.size(); ++i)
            if (i % static_cast<std::size_t>(info.channels) < 3)
                raw[i] = raw[i] <= 0.04045f ? raw[i] / 12.92f : std::pow((raw[i] + 0.055f) / 1.055f, 2.4f);
    // GL rows start at the bottom; images start at the top.
    image.pixels.resize(raw.size());
    for (int y = 0; y < info.height; ++y)
        std::memcpy(&image.pixels[static_cast<std::size_t>(y) * rowValues],
                    &raw[static_cast<std::size_t>(info.height - 1 - y) * rowValues], rowValues * sizeof(float));
    return image;
}

} // namespace obscura
