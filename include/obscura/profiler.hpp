#pragma once
// Per-pass GPU timing.
//
// On hardware, each pass is bracketed by two GL_TIMESTAMP queries, read back later without
// stalling. Timestamps (not GL_TIME_ELAPSED) nest, and do not clash with a time-elapsed
// query the host may have active around our calls.
//
// On a software renderer (llvmpipe & co.) GPU timer queries under-report by an order of
// magnitude (docs/integration.md), so each pass is bracketed with glFinish and a steady clock
// instead.
// Every result says which clock produced it.
#include "obscura/export.hpp"

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

namespace obscura {

namespace detail {
struct ContextImpl;
class ProfilerImpl;
}

enum class ClockSource {
    GpuTimestamp,      //!< GL_TIMESTAMP queries, non-stalling
    WallClockFinish,   //!< glFinish + std::chrono::steady_clock (software renderers)
};

//! "gpu_timer_query" or "wall_clock_finish": the `clock` column of bench reports.
OBSCURA_API const char* toString(ClockSource clock) noexcept;

struct PassTiming {
    std::string name;   //!< stable pass name, e.g. "gbuffer.render"
    double ms = 0.0;    //!< milliseconds
    ClockSource clock = ClockSource::GpuTimestamp;
};

struct PassStatistics {
    std::string name;
    std::size_t samples = 0; //!< frames measured (bounded by the history length)
    double medianMs = 0.0;
    double meanMs = 0.0;
    double minMs = 0.0;
    double maxMs = 0.0;
    ClockSource clock = ClockSource::GpuTimestamp;
};

class OBSCURA_API Profiler {
public:
    explicit Profiler(detail::ContextImpl& ctx);
    ~Profiler();

    ClockSource clock() const noexcept;
    //! Overrides the automatic choice (e.g. to compare both clocks). Discards pending results.
    void setClock(ClockSource clock);
    //! Disabled, passes are not timed (and no queries or glFinish are issued). The default is
    //! ContextDesc::profiling's: off for Off, and for TimerQueries where they are not
    //! trustworthy; this overrides it, with clock() as it is.
    void setEnabled(bool enabled) noexcept;
    bool enabled() const noexcept;

    //! Most recent completed timing of every pass, in first-seen order. Collects whatever
    //! GPU results are available without waiting.
    std::vector<PassTiming> latest();
    //! Median/min/max over the last `historyLength()` completed timings of each pass.
    //! With wait = true, first waits for every pending GPU result (for benchmarks).
    std::vector<PassStatistics> statistics(bool wait = false);
    //! Forgets all history and pending results.
    void reset();
    static constexpr std::size_t historyLength() { return 256; }

    //! Internal: pass scopes use this.
    detail::ProfilerImpl& impl() noexcept { return *impl_; }

private:
    detail::ContextImpl& ctx_;
    std::unique_ptr<detail::ProfilerImpl> impl_;
};

} // namespace obscura
