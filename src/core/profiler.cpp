#include "obscura/profiler.hpp"

#include "core/context_impl.hpp"
#include "core/pass_scope.hpp"
#include "obscura/error.hpp"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <deque>
#include <map>
#include <string>
#include <vector>

namespace obscura {
namespace detail {

class ProfilerImpl {
public:
    explicit ProfilerImpl(ContextImpl& ctx) : ctx_(ctx) {}

    ClockSource clock = ClockSource::GpuTimestamp;
    bool enabled = false; // ContextDesc::profiling decides

    // May throw (allocating queries); end() must not, since it runs in a destructor.
    int begin(const char* name) {
        if (!enabled) return -1;
        const std::size_t id = passId(name);
        if (clock == ClockSource::WallClockFinish) {
            ctx_.gl.Finish();
            open_.push_back({id, std::chrono::steady_clock::now(), 0, 0});
        } else {
            const GLuint start = acquireQuery(), stop = acquireQuery();
            ctx_.gl.QueryCounter(start, GL_TIMESTAMP);
            open_.push_back({id, {}, start, stop});
        }
        return static_cast<int>(open_.size()) - 1;
    }

    void end(int token) noexcept {
        if (token < 0 || static_cast<std::size_t>(token) >= open_.size()) return;
        const Open o = open_[static_cast<std::size_t>(token)];
        open_.resize(static_cast<std::size_t>(token));
        try {
            if (clock == ClockSource::WallClockFinish) {
                ctx_.gl.Finish();
                const std::chrono::duration<double, std::milli> ms = std::chrono::steady_clock::now() - o.start;
                record(o.pass, ms.count());
            } else {
                ctx_.gl.QueryCounter(o.endQuery, GL_TIMESTAMP);
                pending_.push_back(o);
            }
        } catch (...) {
            // Out of memory for the history: this sample is lost, the frame goes on.
        }
    }

    // Reads finished query pairs in submission order; stops at the first unfinished one
    // unless `wait` (then it blocks until all are done).
    void collect(bool wait) {
        auto& gl = ctx_.gl;
        while (!pending_.empty()) {
            const Open& o = pending_.front();
            if (!wait) {
                GLint ready = GL_FALSE;
                gl.GetQueryObjectiv(o.endQuery, GL_QUERY_RESULT_AVAILABLE, &ready);
                if (!ready) break;
            }
            GLuint64 t0 = 0, t1 = 0;
            gl.GetQueryObjectui64v(o.startQuery, GL_QUERY_RESULT, &t0);
            gl.GetQueryObjectui64v(o.endQuery, GL_QUERY_RESULT, &t1);
            record(o.pass, t1 >= t0 ? static_cast<double>(t1 - t0) * 1e-6 : 0.0);
            freeQueries_.push_back(o.startQuery);
            freeQueries_.push_back(o.endQuery);
            pending_.pop_front();
        }
    }

    void reset() {
        for (const Open& o : pending_) {
            freeQueries_.push_back(o.startQuery);
            freeQueries_.push_back(o.endQuery);
        }
        pending_.clear();
        history_.clear();
    }

    std::vector<PassTiming> latest() const {
        std::vector<PassTiming> out;
        for (std::size_t id = 0; id < names_.size(); ++id) {
            const auto it = history_.find(id);
            if (it != history_.end() && !it->second.empty())
                out.push_back({names_[id], it->second.back(), clock});
        }
        return out;
    }

    std::vector<PassStatistics> statistics() const {
        std::vector<PassStatistics> out;
        for (std::size_t id = 0; id < names_.size(); ++id) {
            const auto it = history_.find(id);
            if (it == history_.end() || it->second.empty()) continue;
            std::vector<double> v(it->second.begin(), it->second.end());
            std::sort(v.begin(), v.end());
            const std::size_t n = v.size();
            const double median = n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
            double sum = 0.0;
            for (double x : v) sum += x;
            out.push_back({names_[id], n, median, sum / static_cast<double>(n), v.front(), v.back(), clock});
        }
        return out;
    }

private:
    struct Open {
        std::size_t pass;
        std::chrono::steady_clock::time_point start;
        GLuint startQuery;
        GLuint endQuery;
    };

    std::size_t passId(const char* name) {
        for (std::size_t i = 0; i < names_.size(); ++i)
            if (names_[i] == name) return i;
        names_.emplace_back(name);
        return names_.size() - 1;
    }

    GLuint acquireQuery() {
        if (!freeQueries_.empty()) {
            const GLuint q = freeQueries_.back();
            freeQueries_.pop_back();
            return q;
        }
        queries_.push_back(createQuery(ctx_, GL_TIMESTAMP));
        return queries_.back().get();
    }

    void record(std::size_t pass, double ms) {
        auto& h = history_[pass];
        h.push_back(ms);
        if (h.size() > Profiler::historyLength()) h.pop_front();
    }

    ContextImpl& ctx_;
    std::vector<std::string> names_;
    std::vector<Open> open_;
    std::deque<Open> pending_;
    std::vector<Query> queries_;
    std::vector<GLuint> freeQueries_;
    std::map<std::size_t, std::deque<double>> history_;
};

PassScope::PassScope(ContextImpl& ctx, const char* name) : ctx_(ctx) {
    token_ = ctx_.profiler->impl().begin(name); // first: it may throw, the group push cannot
    ctx_.gl.PushDebugGroup(GL_DEBUG_SOURCE_APPLICATION, 0, -1, name);
}

PassScope::~PassScope() {
    ctx_.profiler->impl().end(token_);
    ctx_.gl.PopDebugGroup();
}

} // namespace detail

const char* toString(ClockSource clock) noexcept {
    return clock == ClockSource::GpuTimestamp ? "gpu_timer_query" : "wall_clock_finish";
}

Profiler::Profiler(detail::ContextImpl& ctx) : ctx_(ctx), impl_(std::make_unique<detail::ProfilerImpl>(ctx)) {
    // Software renderers under-report timer queries; a context without timestamp bits has none.
    const bool gpuTimer = !ctx.info.softwareRenderer && ctx.info.timestampBits > 0;
    impl_->clock = gpuTimer ? ClockSource::GpuTimestamp : ClockSource::WallClockFinish;
    const Profiling mode = ctx.desc.profiling;
    impl_->enabled = mode == Profiling::Always || (mode == Profiling::TimerQueries && gpuTimer);
    if (const char* env = std::getenv("OBSCURA_PROFILER_CLOCK")) {
        const std::string v = env;
        if (v == "gpu") impl_->clock = ClockSource::GpuTimestamp;
        else if (v == "wall") impl_->clock = ClockSource::WallClockFinish;
    }
}

Profiler::~Profiler() = default;

ClockSource Profiler::clock() const noexcept { return impl_->clock; }

void Profiler::setClock(ClockSource clock) {
    impl_->reset();
    impl_->clock = clock;
}

void Profiler::setEnabled(bool enabled) noexcept { impl_->enabled = enabled; }
bool Profiler::enabled() const noexcept { return impl_->enabled; }

std::vector<PassTiming> Profiler::latest() {
    detail::StateScope scope(ctx_); // reading queries must not see a host GL_QUERY_BUFFER
    impl_->collect(false);
    return impl_->latest();
}

std::vector<PassStatistics> Profiler::statistics(bool wait) {
    detail::StateScope scope(ctx_);
    impl_->collect(wait);
    return impl_->statistics();
}

void Profiler::reset() {
    impl_->reset();
}

} // namespace obscura
