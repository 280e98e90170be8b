// Context creation: version and feature checks, software-renderer detection, clear errors.
#include "gl_fixture.hpp"
#include "obscura/obscura.hpp"

#include <EGL/egl.h>
#include <catch2/catch.hpp>

#include <cstdlib>
#include <cstring>

using namespace obscura;

namespace {

// A host loader that pretends one function does not exist.
struct HidingLoader {
    const char* hidden;
    static void* load(void* user, const char* name) {
        const auto* self = static_cast<const HidingLoader*>(user);
        if (std::strcmp(name, self->hidden) == 0) return nullptr;
        return reinterpret_cast<void*>(eglGetProcAddress(name));
    }
};

} // namespace

TEST_CASE("Context reports the GL implementation and picks the wall clock on llvmpipe", "[context]") {
    test::GlFixture gl;
    Context ctx(gl.desc());
    const ContextInfo& info = ctx.info();
    CHECK(info.major * 10 + info.minor >= 45);
    CHECK(info.coreProfile);
    CHECK(info.maxTextureSize >= 4096);
    CHECK(info.maxDrawBuffers >= 8);
    const bool llvmpipe = info.renderer.find("llvmpipe") != std::string::npos;
    CHECK(info.softwareRenderer == llvmpipe);
    if (llvmpipe) CHECK(ctx.profiler().clock() == ClockSource::WallClockFinish);
    CHECK(ctx.compiledPrograms().empty());
    CHECK(ctx.liveObjectCount() == 0);
    CHECK(test::drainGlErrors().empty());
}

TEST_CASE("A GL function the host cannot resolve is named in the error", "[context][bad-input]") {
    test::GlFixture gl;
    for (const char* fn : {"glClipControl", "glCreateTextures", "glDispatchCompute"}) {
        HidingLoader loader{fn};
        ContextDesc desc;
        desc.getProcAddress = &HidingLoader::load;
        desc.userData = &loader;
        try {
            Context ctx(desc);
            FAIL("Context accepted a loader without " << fn);
        } catch (const Error& e) {
            CHECK(e.code() == ErrorCode::UnsupportedFeature);
            CHECK_THAT(e.what(), Catch::Contains(fn));
        }
    }
    CHECK(test::drainGlErrors().empty());
}

TEST_CASE("A context older than GL 4.5 is rejected with its version", "[context][bad-input]") {
    // Mesa reports the overridden version for contexts created afterwards.
    ::setenv("MESA_GL_VERSION_OVERRIDE", "3.3", 1);
    headless::HeadlessDesc old;
    old.major = 3;
    old.minor = 3;
    test::GlFixture gl(old);
    ::unsetenv("MESA_GL_VERSION_OVERRIDE");
    // Mesa reads the override once per process: run this case in its own process (ctest does).
    const std::string version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
    INFO("GL_VERSION " << version << ": the override only works in a fresh process");
    REQUIRE(version.rfind("3.3", 0) == 0);
    try {
        Context ctx(gl.desc());
        FAIL("Context accepted a GL 3.3 context");
    } catch (const Error& e) {
        CHECK(e.code() == ErrorCode::UnsupportedFeature);
        CHECK_THAT(e.what(), Catch::Contains("4.5") && Catch::Contains("3.3"));
    }
}

TEST_CASE("A state policy outside its enumerators and a GL version that does not exist are refused",
          "[context][bad-input]") {
    test::GlFixture gl;
    ContextDesc desc = gl.desc();
    desc.statePolicy = static_cast<StatePolicy>(2); // behaved as Clobber before
    CHECK_THROWS_WITH(Context(desc), Catch::Contains("ContextDesc::statePolicy"));
    for (const auto& [major, minor] : {std::pair{4, 7}, std::pair{3, 4}, std::pair{0, 0}, std::pair{5, 0}, std::pair{4, -1}}) {
        CAPTURE(major, minor);
        headless::HeadlessDesc bad;
        bad.major = major;
        bad.minor = minor;
        try {
            headless::HeadlessContext context(bad);
            FAIL("created a GL " << major << "." << minor << " context");
        } catch (const Error& e) {
            CHECK(e.code() == ErrorCode::InvalidArgument);
            CHECK_THAT(e.what(), Catch::Contains("does not exist"));
        }
    }
}

TEST_CASE("A compatibility-profile context is refused", "[context][bad-input]") {
    headless::HeadlessDesc compat;
    compat.coreProfile = false;
    test::GlFixture gl(compat);
    try {
        Context ctx(gl.desc());
        FAIL("Context accepted a compatibility profile");
    } catch (const Error& e) {
        CHECK(e.code() == ErrorCode::UnsupportedFeature);
        CHECK_THAT(e.what(), Catch::Contains("core-profile"));
    }
}

TEST_CASE("A null getProcAddress and a missing current context give clear errors", "[context][bad-input]") {
    ContextDesc none;
    try {
        Context ctx(none);
        FAIL("accepted a null getProcAddress");
    } catch (const Error& e) {
        CHECK(e.code() == ErrorCode::InvalidArgument);
        CHECK_THAT(e.what(), Catch::Contains("getProcAddress"));
    }
    test::GlFixture gl;
    const EGLDisplay display = eglGetCurrentDisplay();
    const EGLContext current = eglGetCurrentContext();
    REQUIRE(eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT));
    try {
        Context ctx(gl.desc());
        FAIL("accepted a thread without a current context");
    } catch (const Error& e) {
        CHECK(e.code() == ErrorCode::UnsupportedFeature);
        CHECK_THAT(e.what(), Catch::Contains("current"));
    }
    REQUIRE(eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, current));
}
