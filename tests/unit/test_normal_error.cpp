// adoptedNormalError against the encodings it bounds, simulated: host normals rounded to their
// format, normalized in float and stored as half floats rounded toward zero (the worst
// rounding GL allows a store; llvmpipe's).
#include "obscura/gbuffer.hpp"
#include "obscura/error.hpp"

#include <catch2/catch.hpp>
#include <glm/glm.hpp>

#include <cmath>
#include <cstdint>
#include <cstring>

using namespace obscura;

namespace {

float halfTowardZero(float x) {
    if (std::abs(x) < std::ldexp(1.0f, -14)) return std::trunc(x * std::ldexp(1.0f, 24)) * std::ldexp(1.0f, -24);
    std::uint32_t bits = 0;
    std::memcpy(&bits, &x, sizeof bits);
    bits &= ~0x1FFFu; // a half keeps 10 of float's 23 mantissa bits
    std::memcpy(&x, &bits, sizeof x);
    return x;
}

glm::vec3 halfTowardZero(glm::vec3 v) { return {halfTowardZero(v.x), halfTowardZero(v.y), halfTowardZero(v.z)}; }

// What adopt() stores for the true normal n sent in `encoding` with `bits` per channel.
glm::vec3 adoptedNormal(glm::dvec3 n, NormalEncoding encoding, int bits) {
    glm::vec3 host;
    if (encoding == NormalEncoding::Unsigned) {
        const double steps = std::ldexp(1.0, bits) - 1.0;
        for (int c = 0; c < 3; ++c) host[c] = float(std::round((n[c] * 0.5 + 0.5) * steps) / steps * 2.0 - 1.0);
    } else {
        host = bits <= 16 ? halfTowardZero(glm::vec3(n)) : glm::vec3(n);
    }
    return halfTowardZero(glm::normalize(host));
}

// The largest distance from the true normal over a spiral of unit normals, with the axes and
// diagonals (where every component rounds at once) added.
double largestError(NormalEncoding encoding, int bits) {
    double largest = 0.0;
    const auto check = [&](glm::dvec3 n) {
        n = glm::normalize(n);
        largest = std::max(largest, glm::length(glm::dvec3(adoptedNormal(n, encoding, bits)) - n));
    };
    constexpr int kCount = 200000;
    const double golden = 3.14159265358979323846 * (3.0 - std::sqrt(5.0));
    for (int i = 0; i < kCount; ++i) {
        const double z = 1.0 - 2.0 * (i + 0.5) / kCount, r = std::sqrt(1.0 - z * z);
        check({r * std::cos(golden * i), r * std::sin(golden * i), z});
    }
    for (int x = -1; x <= 1; ++x)
        for (int y = -1; y <= 1; ++y)
            for (int z = -1; z <= 1; ++z)
                if (x || y || z) check({x, y, z});
    return largest;
}

} // namespace

TEST_CASE("adoptedNormalError bounds the simulated encodings and is within 3x of the largest error seen", "[unit][gbuffer]") {
    struct Case {
        NormalEncoding encoding;
        int bits;
    };
    for (const Case c : {Case{NormalEncoding::Unsigned, 8}, Case{NormalEncoding::Unsigned, 10},
                         Case{NormalEncoding::Unsigned, 16}, Case{NormalEncoding::Signed, 16},
                         Case{NormalEncoding::Signed, 32}}) {
        const double bound = adoptedNormalError(c.encoding, c.bits), seen = largestError(c.encoding, c.bits);
        CAPTURE(static_cast<int>(c.encoding), c.bits, bound, seen);
        CHECK(seen <= bound);
        CHECK(seen > bound / 3.0); // 16-bit floats: two roundings that seldom add up fully (0.41)
    }
    CHECK(adoptedNormalError(NormalEncoding::Signed, 32) < 1.001f * kHalfNormalError); // 2^-23 on top of our store
    CHECK_THROWS_AS(adoptedNormalError(NormalEncoding::Unsigned, 0), Error);
    // adopt() takes unsigned normals down to the fewest bits whose bound fits kMaxNormalError.
    CHECK(adoptedNormalError(NormalEncoding::Unsigned, 4) <= kMaxNormalError);
    CHECK(adoptedNormalError(NormalEncoding::Unsigned, 3) > kMaxNormalError);
}
