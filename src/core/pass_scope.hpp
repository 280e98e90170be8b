#pragma once
// A named GPU pass: a KHR_debug group for debuggers plus a profiler measurement.
// The name is the pass's stable identifier ("gbuffer.render").
#include <chrono>

namespace obscura::detail {

struct ContextImpl;

class PassScope {
public:
    PassScope(ContextImpl& ctx, const char* name);
    ~PassScope(); // noexcept: a failed measurement loses its sample only
    PassScope(const PassScope&) = delete;
    PassScope& operator=(const PassScope&) = delete;

private:
    ContextImpl& ctx_;
    int token_ = -1;
};

} // namespace obscura::detail
