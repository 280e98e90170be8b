#pragma once
// FNV-1a (64 bit) over typed values: cache keys for references.
#include <cstdint>
#include <cstring>
#include <string_view>
#include <type_traits>

namespace obscura::reference::detail {

class Hasher {
public:
    void bytes(const void* data, std::size_t size) {
        const auto* p = static_cast<const unsigned char*>(data);
        for (std::size_t i = 0; i < size; ++i) {
            h_ ^= p[i];
            h_ *= 1099511628211ULL;
        }
    }
    template <typename T>
    Hasher& add(const T& value) {
        static_assert(std::is_trivially_copyable_v<T>);
        bytes(&value, sizeof value);
        return *this;
    }
    Hasher& add(std::string_view s) {
        add(s.size());
        bytes(s.data(), s.size());
        return *this;
    }
    std::uint64_t value() const { return h_; }

private:
    std::uint64_t h_ = 14695981039346656037ULL;
};

} // namespace obscura::reference::detail
