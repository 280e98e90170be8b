#include "gl_fixture.hpp"

#include <EGL/egl.h>
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>
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

void overrideShader(Context& ctx, const std::string& file, const std::string& call, const std::string& replacement,
                    const std::string& prelude) {
    namespace fs = std::filesystem;
    const fs::path root = OBSCURA_SHADER_DIR;
    bool replaced = false;
    for (const auto& entry : fs::recursive_directory_iterator(root)) {
        if (!entry.is_regular_file()) continue;
        std::ifstream in(entry.path());
        std::stringstream text;
        text << in.rdbuf();
        std::string source = text.str();
        const std::string path = fs::relative(entry.path(), root).generic_string();
        if (path == file) {
            const auto at = source.find(call);
            REQUIRE(at != std::string::npos);
            source.replace(at, call.size(), replacement);
            source.insert(source.find("void main()"), prelude);
            replaced = true;
        }
        ctx.addShaderSource(path, source);
    }
    REQUIRE(replaced);
}

} // namespace obscura::test
