// Included first by every *_bindings.h that declares a parameter block (the headers C++ and
// GLSL share): in C++ the GLSL
// types the parameter blocks use (glm's, whose sizes and alignments within a block written
// as below match std140 and std430) and the namespace the blocks live in. The tests read
// every block's fields from these headers and compare each field's offsetof with the offset
// the driver gives it (tests/gl/test_param_blocks.cpp).
//
// Blocks are written so that C++ and std140 agree without compiler-specific packing: every
// vec4 and mat4 at a multiple of 16 bytes, a vec2 or ivec2 at a multiple of 8, a vec3 or
// ivec3 at a multiple of 16 and followed by a 4-byte scalar, scalars in groups filling 16
// bytes, padding named padN.
#ifndef OBSCURA_BINDINGS_PREAMBLE_H
#define OBSCURA_BINDINGS_PREAMBLE_H

#ifdef __cplusplus
#include <glm/glm.hpp>

namespace obscura::shader {
using vec2 = glm::vec2;
using vec3 = glm::vec3;
using vec4 = glm::vec4;
using ivec2 = glm::ivec2;
using ivec3 = glm::ivec3;
using ivec4 = glm::ivec4;
using mat4 = glm::mat4;

} // namespace obscura::shader

#define OBSCURA_SHADER_BEGIN namespace obscura::shader {
#define OBSCURA_SHADER_END }
#else
#define OBSCURA_SHADER_BEGIN
#define OBSCURA_SHADER_END
#endif

#endif
