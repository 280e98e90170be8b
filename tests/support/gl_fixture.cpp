#include "gl_fixture.hpp"

#include <EGL/egl.h>
#include <stdexcept>

namespace obscura::test {
namespace {

GLADapiproc loadHostGl(void*, const char* name) { return reinterpret_cast<GLADapiproc>(eglGetProcAddress(name)); }

headless::HeadlessDesc headlessDesc(bool debug) {
    headless::HeadlessDesc d;
    d.debug = debug;
    return d;
}

} // namespace

GlFixture::GlFixture(bool debug) : GlFixture(headlessDesc(debug)) {}

GlFixture::GlFixture(const headless::HeadlessDesc& desc) : egl_(desc) {
    if (!gladLoadGLUserPtr(loadHostGl, nullptr)) throw std::runtime_error("test host: gladLoadGL failed");
}

std::set<std::string> liveGlObjects(unsigned limit) {
    std::set<std::string> live;
    for (GLuint n = 1; n <= limit; ++n) {
        if (glIsTexture(n)) live.insert("texture " + std::to_string(n));
        if (glIsBuffer(n)) live.insert("buffer " + std::to_string(n));
        if (glIsFramebuffer(n)) live.insert("framebuffer " + std::to_string(n));
        if (glIsVertexArray(n)) live.insert("vertex array " + std::to_string(n));
        if (glIsSampler(n)) live.insert("sampler " + std::to_string(n));
        if (glIsQuery(n)) live.insert("query " + std::to_string(n));
        if (glIsProgram(n)) live.insert("program " + std::to_string(n));
        if (glIsShader(n)) live.insert("shader " + std::to_string(n));
        if (glIsRenderbuffer(n)) live.insert("renderbuffer " + std::to_string(n));
    }
    return live;
}

std::vector<unsigned> drainGlErrors() {
    std::vector<unsigned> errors;
    for (GLenum e = glGetError(); e != GL_NO_ERROR && errors.size() < 64; e = glGetError()) errors.push_back(e);
    return errors;
}

} // namespace obscura::test
