// A host application with its own global GL loader (a plain glad, glad_gl* pointers and
// gladLoadGL), its own EGL context, and, as a trap, functions with the exact names that an
// unrenamed glad --mx inside Obscura would define. Linked against the static library, a
// leaked glad symbol is a duplicate definition; against the shared one, an exported glad
// symbol would be interposed by the trap, which the program detects.
#include <glad/gl.h>

#include "obscura/obscura.hpp"

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstdio>
#include <cstdlib>

static int trapCalls = 0;
extern "C" int gladLoadGLContext(void*, void*) { return ++trapCalls, 0; }
extern "C" int gladLoadGLContextUserPtr(void*, void*, void*) { return ++trapCalls, 0; }

static int fail(const char* what) {
    std::fprintf(stderr, "host: %s\n", what);
    return 1;
}

static void* hostGetProcAddress(void*, const char* name) { return reinterpret_cast<void*>(eglGetProcAddress(name)); }
static GLADapiproc hostLoad(void*, const char* name) { return reinterpret_cast<GLADapiproc>(eglGetProcAddress(name)); }

int main() {
    auto getPlatformDisplay =
        reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
    EGLDisplay display = getPlatformDisplay ? getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr)
                                            : eglGetDisplay(EGL_DEFAULT_DISPLAY);
    if (!eglInitialize(display, nullptr, nullptr) || !eglBindAPI(EGL_OPENGL_API)) return fail("EGL init");
    const EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5, EGL_CONTEXT_OPENGL_PROFILE_MASK,
                              EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    EGLContext context = eglCreateContext(display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attribs);
    if (!context || !eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) return fail("EGL context");
    if (!gladLoadGLUserPtr(hostLoad, nullptr)) return fail("host glad");

    // The host renders something of its own first.
    GLuint hostTexture = 0, hostFbo = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &hostTexture);
    glTextureStorage2D(hostTexture, 1, GL_RGBA8, 4, 4);
    glCreateFramebuffers(1, &hostFbo);
    glNamedFramebufferTexture(hostFbo, GL_COLOR_ATTACHMENT0, hostTexture, 0);
    glBindFramebuffer(GL_FRAMEBUFFER, hostFbo);
    glViewport(0, 0, 4, 4);

    int status = 0;
    try {
        obscura::ContextDesc desc;
        desc.getProcAddress = hostGetProcAddress;
        obscura::Context ctx(desc);
        obscura::GBuffer gbuffer(ctx);
        obscura::Scene scene;
        scene.materials.push_back({});
        auto quad = std::make_shared<obscura::MeshData>();
        quad->positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
        quad->indices = {0, 1, 2, 0, 2, 3};
        scene.meshes.push_back({quad, glm::mat4(1.0f), 0, "quad"});
        const auto camera = obscura::Camera::perspective({{0, 0, 2}, {0, 0, 0}, {0, 1, 0}}, 0.8f, 1.0f, 0.1f, 10.0f);
        const auto view = gbuffer.render(scene, camera, {8, 8, true, {}});
        const obscura::Image normals = obscura::readTexture(ctx, view.normal);
        // The quad fills the view and faces the camera: every normal is (0, 0, 1).
        for (int i = 0; i < 64; ++i)
            if (normals.pixels[static_cast<std::size_t>(i) * 4 + 2] < 0.999f) {
                status = fail("wrong G-buffer normals");
                break;
            }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "host: obscura failed: %s\n", e.what());
        status = 1;
    }

    // The host's own loader still works, and its state is where it left it.
    GLint fbo = 0;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &fbo);
    if (fbo != static_cast<GLint>(hostFbo)) status = fail("host framebuffer binding changed");
    glClearColor(0.0f, 1.0f, 0.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    unsigned char pixel[4] = {};
    glReadPixels(1, 1, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, pixel);
    if (pixel[1] != 255 || pixel[0] != 0) status = fail("host rendering through its own loader failed");
    if (glGetError() != GL_NO_ERROR) status = fail("GL error pending");
    if (trapCalls != 0) status = fail("Obscura called the host's gladLoadGLContext: its loader is not isolated");
    glDeleteFramebuffers(1, &hostFbo);
    glDeleteTextures(1, &hostTexture);
    eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(display, context);
    if (status == 0) std::printf("host: OK (own loader and Obscura's coexist, trap untouched)\n");
    return status;
}
