#pragma once
// Input validation shared by every module: checks run before any GL work and throw
// Error{InvalidArgument} with what was given and what is accepted.
#include "obscura/error.hpp"

#include <glm/glm.hpp>

#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <string>
#include <vector>

namespace obscura::detail {

template <glm::length_t N, typename T, glm::qualifier Q>
bool allFinite(const glm::vec<N, T, Q>& v) {
    for (glm::length_t i = 0; i < N; ++i)
        if (!std::isfinite(v[i])) return false;
    return true;
}

template <glm::length_t C, glm::length_t R, typename T, glm::qualifier Q>
bool allFinite(const glm::mat<C, R, T, Q>& m) {
    for (glm::length_t i = 0; i < C; ++i)
        if (!allFinite(m[i])) return false;
    return true;
}

template <typename V>
void requireFinite(const V& value, const std::string& what) {
    if (!allFinite(value)) throw Error(ErrorCode::InvalidArgument, what + " contains NaN or Inf");
}

inline void requireFinite(float value, const std::string& what) {
    if (!std::isfinite(value)) throw Error(ErrorCode::InvalidArgument, what + " is NaN or Inf");
}

//! A number as people write it: 256, 0.5, 1e-06 (not 256.000000).
inline std::string shortNumber(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.7g", value);
    return text;
}

//! lo <= value <= hi, reported with the unit.
inline void requireInRange(double value, double lo, double hi, const std::string& what, const std::string& unit = {}) {
    if (!(value >= lo && value <= hi))
        throw Error(ErrorCode::InvalidArgument, what + " must be in [" + shortNumber(lo) + ", " + shortNumber(hi) + "]" +
                                                    (unit.empty() ? "" : " " + unit) + ", got " + shortNumber(value));
}

//! One of the enumerators listed: a value cast from an integer outside them (through the C++
//! API) would otherwise pick a shader path by accident or divide by a zero scale.
template <typename E>
void requireEnumerator(E value, std::initializer_list<E> allowed, const std::string& what) {
    for (const E e : allowed)
        if (value == e) return;
    throw Error(ErrorCode::InvalidArgument,
                what + " is not one of its enumerators, got " + std::to_string(static_cast<long long>(value)));
}

//! A render-target size: [1, maxSize] on each axis.
inline void requireImageSize(int width, int height, int maxSize, const std::string& what) {
    if (width < 1 || height < 1 || width > maxSize || height > maxSize)
        throw Error(ErrorCode::InvalidArgument, what + " size must be in [1, " + std::to_string(maxSize) +
                                                    "] pixels on each axis (GL_MAX_TEXTURE_SIZE), got " +
                                                    std::to_string(width) + "x" + std::to_string(height));
}

//! An input texture by what the API calls it, for requireNotOwnOutput.
struct NamedInput {
    const char* what; //!< e.g. "GBufferView::normal"
    unsigned name;    //!< GL texture name; 0: not given
};

//! Refuses an input that is one of `module`'s own output textures (`outputs`; 0s ignored):
//! its passes would read the texture while they write it, or reallocate it at a new size,
//! and GL leaves such a feedback undefined (a pass reads other pixels than it writes). A
//! host feeding a result back alternates two objects of the module instead.
inline void requireNotOwnOutput(std::initializer_list<NamedInput> inputs, const std::vector<unsigned>& outputs,
                                const std::string& module) {
    for (const NamedInput& input : inputs)
        for (const unsigned output : outputs)
            if (input.name != 0 && input.name == output)
                throw Error(ErrorCode::InvalidArgument,
                            std::string(input.what) + " (texture " + std::to_string(input.name) + ") is this " + module +
                                "'s own output, which the call writes while reading it: read a copy, or alternate two " +
                                module + " objects, each reading the other's last output");
}

} // namespace obscura::detail
