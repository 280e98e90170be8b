#pragma once
#include <cstddef>

namespace obscura::detail {

//! One shader stage resolved and embedded at build time (see cmake/embed_shaders.cpp).
struct EmbeddedShader {
    const char* path;         //!< relative to shaders/, e.g. "gbuffer/gbuffer.frag.glsl"
    const char* text;         //!< resolved source with #line directives, without #version
    std::size_t size;         //!< bytes in text
    const char* const* files; //!< source-string number → original file
    std::size_t fileCount;
};

extern const EmbeddedShader kEmbeddedShaders[]; //!< terminated by a null path
extern const std::size_t kEmbeddedShaderCount;

} // namespace obscura::detail
