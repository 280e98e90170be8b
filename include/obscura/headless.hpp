#pragma once
// obscura::headless: an OpenGL 4.5 context without a window, through EGL.
//
// Used by Obscura's tests, examples, benchmarks and CLI. Platform order: an EGL device that
// is not Mesa's software device (a GPU, e.g. NVIDIA headless), then Mesa's surfaceless
// platform (llvmpipe on machines without a GPU), then any EGL device, then the default
// display. OBSCURA_EGL_PLATFORM=surfaceless|device|default forces one. The context renders
// only into framebuffer objects.
#include "obscura/context.hpp"
#include "obscura/export.hpp"

#include <memory>
#include <string>

namespace obscura::headless {

struct HeadlessDesc {
    //! The requested GL version, one that exists (1.0-1.5, 2.0-2.1, 3.0-3.3, 4.0-4.6);
    //! drivers may return a newer one. Obscura's Context needs 4.5.
    int major = 4;
    int minor = 5;
    bool coreProfile = true;
    bool debug = false;     //!< EGL_CONTEXT_OPENGL_DEBUG: enables KHR_debug messages
};

class OBSCURA_API HeadlessContext {
public:
    //! Creates the context and makes it current on this thread. Throws obscura::Error
    //! {UnsupportedFeature} naming the EGL step that failed.
    explicit HeadlessContext(const HeadlessDesc& desc = {});
    ~HeadlessContext();

    void makeCurrent();
    //! "surfaceless", "device" or "default".
    const std::string& platform() const noexcept;

    //! eglGetProcAddress, in the form ContextDesc expects (userData unused).
    static void* getProcAddress(void* userData, const char* name);
    //! A ContextDesc for obscura::Context on this context, with Profiling::Always (tools and
    //! tests time their passes; an engine's own ContextDesc defaults to Profiling::Off).
    ContextDesc contextDesc(StatePolicy policy = StatePolicy::Preserve) const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

} // namespace obscura::headless
