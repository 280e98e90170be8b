#include "obscura/texture.hpp"

#include "core/context_impl.hpp"
#include "core/texture_info.hpp"
#include "obscura/context.hpp"

#include <algorithm>
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
    // Read in bands of rows: one call may not exceed GLsizei bytes.
    const std::size_t rowBytes = rowValues * sizeof(float);
    const int bandRows = static_cast<int>(std::max<std::size_t>(1, (std::size_t(1) << 28) / rowBytes));
    std::vector<std::int32_t> ints(info.integer ? rowValues * static_cast<std::size_t>(bandRows) : 0);
    for (int y0 = 0; y0 < info.height; y0 += bandRows) {
        const int rows = std::min(bandRows, info.height - y0);
        const auto bytes = static_cast<GLsizei>(rowBytes * static_cast<std::size_t>(rows));
        float* dst = &raw[static_cast<std::size_t>(y0) * rowValues];
        if (info.integer) {
            // Integer textures cannot be read as GL_FLOAT; read the bits and convert.
            gl.GetTextureSubImage(texture.name, 0, 0, y0, 0, info.width, rows, 1, info.pixelFormat,
                                  info.isSigned ? GL_INT : GL_UNSIGNED_INT, bytes, ints.data());
            for (std::size_t i = 0; i < rowValues * static_cast<std::size_t>(rows); ++i)
                dst[i] = info.isSigned ? static_cast<float>(ints[i]) : static_cast<float>(static_cast<std::uint32_t>(ints[i]));
        } else {
            gl.GetTextureSubImage(texture.name, 0, 0, y0, 0, info.width, rows, 1, info.pixelFormat, GL_FLOAT, bytes, dst);
        }
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
