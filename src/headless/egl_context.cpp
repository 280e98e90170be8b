#include "obscura/headless.hpp"

#include "obscura/error.hpp"

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace obscura::headless {
namespace {

std::string eglErrorName(EGLint e) {
    switch (e) {
    case EGL_SUCCESS: return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
    default: return "EGL error " + std::to_string(e);
    }
}

[[noreturn]] void fail(const std::string& step) {
    throw Error(ErrorCode::UnsupportedFeature, "headless EGL: " + step + " failed (" + eglErrorName(eglGetError()) + ")");
}

bool hasClientExtension(const char* name) {
    const char* exts = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!exts) return false;
    const std::string all = std::string(" ") + exts + " ";
    return all.find(std::string(" ") + name + " ") != std::string::npos;
}

EGLDisplay platformDisplay(EGLenum platform, void* native) {
    auto getPlatformDisplay =
        reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (!getPlatformDisplay) return EGL_NO_DISPLAY;
    return getPlatformDisplay(platform, native, nullptr);
}

// The first EGL device that initializes; with `hardwareOnly`, Mesa's software device
// (EGL_MESA_device_software) is skipped, so a GPU is preferred over llvmpipe.
EGLDisplay deviceDisplay(bool hardwareOnly) {
    auto queryDevices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    auto queryDeviceString =
        reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(eglGetProcAddress("eglQueryDeviceStringEXT"));
    if (!queryDevices) return EGL_NO_DISPLAY;
    EGLDeviceEXT devices[16];
    EGLint count = 0;
    if (!queryDevices(16, devices, &count) || count == 0) return EGL_NO_DISPLAY;
    for (EGLint i = 0; i < count; ++i) {
        if (hardwareOnly && queryDeviceString) {
            const char* exts = queryDeviceString(devices[i], EGL_EXTENSIONS);
            if (exts && std::strstr(exts, "EGL_MESA_device_software")) continue;
        }
        EGLDisplay d = platformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[i]);
        EGLint major = 0, minor = 0;
        if (d != EGL_NO_DISPLAY && eglInitialize(d, &major, &minor)) return d;
    }
    return EGL_NO_DISPLAY;
}

// A GL version that exists: EGL would refuse another with EGL_BAD_MATCH, which says less.
void requireGlVersion(int major, int minor) {
    static constexpr int lastMinor[] = {5, 1, 3, 6}; // 1.5, 2.1, 3.3, 4.6
    if (major < 1 || major > 4 || minor < 0 || minor > lastMinor[major - 1])
        throw obscura::Error(obscura::ErrorCode::InvalidArgument,
                             "HeadlessDesc: GL " + std::to_string(major) + "." + std::to_string(minor) +
                                 " does not exist (1.0-1.5, 2.0-2.1, 3.0-3.3, 4.0-4.6)");
}

} // namespace

struct HeadlessContext::Impl {
    EGLDisplay display = EGL_NO_DISPLAY;
    EGLContext context = EGL_NO_CONTEXT;
    std::string platform;
};

HeadlessContext::HeadlessContext(const HeadlessDesc& desc) : impl_(std::make_unique<Impl>()) {
    requireGlVersion(desc.major, desc.minor);
    const char* forced = std::getenv("OBSCURA_EGL_PLATFORM");
    const std::string want = forced ? forced : "";
    auto& d = impl_->display;
    const bool deviceExt = hasClientExtension("EGL_EXT_platform_device");
    // A GPU first, then Mesa's surfaceless platform (llvmpipe without a GPU), then any device.
    if (want.empty() && deviceExt) {
        d = deviceDisplay(/*hardwareOnly=*/true);
        impl_->platform = "device";
    }
    if (d == EGL_NO_DISPLAY && (want.empty() || want == "surfaceless") &&
        hasClientExtension("EGL_MESA_platform_surfaceless")) {
        d = platformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY);
        impl_->platform = "surfaceless";
    }
    if (d == EGL_NO_DISPLAY && (want.empty() || want == "device") && deviceExt) {
        d = deviceDisplay(/*hardwareOnly=*/false);
        impl_->platform = "device";
    }
    if (d == EGL_NO_DISPLAY && (want.empty() || want == "default")) {
        d = eglGetDisplay(EGL_DEFAULT_DISPLAY);
        impl_->platform = "default";
    }
    if (d == EGL_NO_DISPLAY) fail("finding a display (platform " + (want.empty() ? std::string("any") : want) + ")");
    EGLint major = 0, minor = 0;
    if (!eglInitialize(d, &major, &minor)) fail("eglInitialize");
    if (!eglBindAPI(EGL_OPENGL_API)) fail("eglBindAPI(EGL_OPENGL_API)");

    const std::string displayExts = eglQueryString(d, EGL_EXTENSIONS) ? eglQueryString(d, EGL_EXTENSIONS) : "";
    EGLConfig config = nullptr;
    if (displayExts.find("EGL_KHR_no_config_context") == std::string::npos &&
        displayExts.find("EGL_MESA_configless_context") == std::string::npos) {
        const EGLint configAttribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
        EGLint n = 0;
        if (!eglChooseConfig(d, configAttribs, &config, 1, &n) || n == 0) fail("eglChooseConfig");
    }
    std::vector<EGLint> attribs = {EGL_CONTEXT_MAJOR_VERSION, desc.major, EGL_CONTEXT_MINOR_VERSION, desc.minor,
                                   EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                   desc.coreProfile ? EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT
                                                    : EGL_CONTEXT_OPENGL_COMPATIBILITY_PROFILE_BIT};
    if (desc.debug) attribs.insert(attribs.end(), {EGL_CONTEXT_OPENGL_DEBUG, EGL_TRUE});
    attribs.push_back(EGL_NONE);
    impl_->context = eglCreateContext(d, config, EGL_NO_CONTEXT, attribs.data());
    if (impl_->context == EGL_NO_CONTEXT)
        fail("creating an OpenGL " + std::to_string(desc.major) + "." + std::to_string(desc.minor) + " context");
    makeCurrent();
}

HeadlessContext::~HeadlessContext() {
    if (!impl_ || impl_->display == EGL_NO_DISPLAY) return;
    eglMakeCurrent(impl_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (impl_->context != EGL_NO_CONTEXT) eglDestroyContext(impl_->display, impl_->context);
    // The display is shared process-wide by EGL; terminating it would break other contexts.
}

void HeadlessContext::makeCurrent() {
    if (!eglMakeCurrent(impl_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, impl_->context)) fail("eglMakeCurrent");
}

const std::string& HeadlessContext::platform() const noexcept { return impl_->platform; }

void* HeadlessContext::getProcAddress(void*, const char* name) {
    return reinterpret_cast<void*>(eglGetProcAddress(name));
}

ContextDesc HeadlessContext::contextDesc(StatePolicy policy) const {
    ContextDesc desc;
    desc.getProcAddress = &HeadlessContext::getProcAddress;
    desc.statePolicy = policy;
    desc.profiling = Profiling::Always;
    return desc;
}

} // namespace obscura::headless
