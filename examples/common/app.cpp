#include "app.hpp"

#include <glad/gl.h>
// glad first: GLFW must not include the system GL header.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>

#include "obscura/error.hpp"
#include "obscura/headless.hpp"
#include "obscura/profiler.hpp"
#include "obscura/scene.hpp"

#include <glm/geometric.hpp>

#include <EGL/egl.h>

#include <cstdio>
#include <cstring>

namespace obscura::examples {
namespace {

void* glfwLoader(void*, const char* name) { return reinterpret_cast<void*>(glfwGetProcAddress(name)); }
GLADapiproc glfwGladLoader(void*, const char* name) { return reinterpret_cast<GLADapiproc>(glfwGetProcAddress(name)); }
GLADapiproc eglGladLoader(void*, const char* name) { return reinterpret_cast<GLADapiproc>(eglGetProcAddress(name)); }

} // namespace

int runGuarded(const std::function<void()>& body) {
    try {
        body();
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s\n", e.what());
        return 1;
    }
}

ExampleScene loadExampleScene(const AppOptions& options, int width, int height, DepthMode mode) {
    ExampleScene s;
    s.loaded = assets::loadScene(options.scene);
    const Bounds bounds = sceneBounds(s.loaded.scene);
    const assets::CameraSpec spec =
        options.camera.empty() ? s.loaded.camera : assets::parseCameraSpec(options.camera, s.loaded.camera, bounds);
    s.camera = assets::makeCamera(spec, width, height, mode);
    if (!assets::boundsMayBeVisible(s.camera, bounds))
        std::fprintf(stderr, "warning: the whole scene lies outside the camera's view: the picture holds no geometry\n");
    s.diagonal = glm::length(bounds.max - bounds.min);
    return s;
}

namespace {
// A CLI11 check: the pictures are 8-bit display images, written as PNG whatever the name says.
std::string pngPath(const std::string& path) {
    return assets::lowerExtension(path) == ".png" ? std::string() : "must end in .png: the picture is an 8-bit display image";
}
} // namespace

void addAppOptions(CLI::App& cli, AppOptions& o) {
    cli.add_option("--scene", o.scene, "Built-in scene, JSON scene or mesh file")->capture_default_str();
    cli.add_option("--camera", o.camera, "ex,ey,ez,tx,ty,tz,ux,uy,uz,fovy_deg[,near,far]");
    cli.add_option("--size", o.size, "WxH pixels")->capture_default_str();
    cli.add_flag("--window", o.window, "Open a GLFW window (default: headless EGL)");
    cli.add_option("--frames", o.frames, "Frames to render; 0 = until the window is closed")->capture_default_str();
    cli.add_option("--out", o.out, "Write the last picture as FILE.png")->check(pngPath);
    cli.add_option("--screenshot", o.screenshot, "With --window: write the last frame as shown (panel included) as FILE.png")
        ->check(pngPath);
}

// The window's back buffer, top row first.
TextureImage readWindow(int width, int height) {
    TextureImage image;
    image.width = width;
    image.height = height;
    const std::size_t row = static_cast<std::size_t>(width) * 4;
    std::vector<std::uint8_t> bottomUp(row * static_cast<std::size_t>(height));
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    glReadBuffer(GL_BACK);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, bottomUp.data());
    image.rgba.resize(bottomUp.size());
    for (int y = 0; y < height; ++y)
        std::memcpy(&image.rgba[static_cast<std::size_t>(y) * row], &bottomUp[static_cast<std::size_t>(height - 1 - y) * row], row);
    return image;
}

struct App::Impl {
    std::unique_ptr<headless::HeadlessContext> headless;
    GLFWwindow* window = nullptr;
    GLuint texture = 0, framebuffer = 0;
    std::function<void()> panel;
    bool imgui = false;
    TextureImage screen; // the last frame with the panel, for --screenshot

    // The panel over what is on screen; ImGui's OpenGL 3 backend loads its own GL functions.
    void drawPanel() {
        if (!panel) return;
        if (!imgui) {
            ImGui::CreateContext();
            ImGui::GetIO().IniFilename = nullptr; // no imgui.ini next to the binary
            ImGui_ImplGlfw_InitForOpenGL(window, true);
            ImGui_ImplOpenGL3_Init("#version 450 core");
            imgui = true;
        }
        ImGui_ImplOpenGL3_NewFrame();
        ImGui_ImplGlfw_NewFrame();
        ImGui::NewFrame();
        panel();
        ImGui::Render();
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
        glViewport(0, 0, static_cast<GLsizei>(ImGui::GetIO().DisplaySize.x), static_cast<GLsizei>(ImGui::GetIO().DisplaySize.y));
        ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    }
};

App::App(const AppOptions& o) : impl_(std::make_unique<Impl>()), frames_(o.frames), screenshot_(o.screenshot) {
    std::tie(width_, height_) = assets::parseImageSize(o.size);
    if (!o.window && !screenshot_.empty()) throw Error(ErrorCode::InvalidArgument, "--screenshot needs --window");
    if (!o.window) {
        if (frames_ < 1) throw Error(ErrorCode::InvalidArgument, "--frames 0 needs --window");
        impl_->headless = std::make_unique<headless::HeadlessContext>();
        if (!gladLoadGLUserPtr(eglGladLoader, nullptr)) throw Error(ErrorCode::UnsupportedFeature, "glad: no GL");
        return;
    }
    if (!glfwInit()) throw Error(ErrorCode::UnsupportedFeature, "glfwInit failed (no display? try xvfb-run)");
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_RESIZABLE, GLFW_FALSE);
    impl_->window = glfwCreateWindow(width_, height_, "Obscura", nullptr, nullptr);
    if (!impl_->window) {
        glfwTerminate();
        throw Error(ErrorCode::UnsupportedFeature, "glfwCreateWindow: no OpenGL 4.5 core window");
    }
    glfwMakeContextCurrent(impl_->window);
    glfwSwapInterval(0);
    if (!gladLoadGLUserPtr(glfwGladLoader, nullptr)) throw Error(ErrorCode::UnsupportedFeature, "glad: no GL");
    int fw = 0, fh = 0;
    glfwGetFramebufferSize(impl_->window, &fw, &fh);
    if (fw != width_ || fh != height_)
        throw Error(ErrorCode::UnsupportedFeature, "the window's framebuffer is " + std::to_string(fw) + "x" +
                                                       std::to_string(fh) + ", not the requested size");
}

App::~App() {
    if (impl_->imgui) {
        ImGui_ImplOpenGL3_Shutdown();
        ImGui_ImplGlfw_Shutdown();
        ImGui::DestroyContext();
    }
    if (impl_->window) {
        glDeleteFramebuffers(1, &impl_->framebuffer);
        glDeleteTextures(1, &impl_->texture);
        glfwDestroyWindow(impl_->window);
        glfwTerminate();
    }
}

ContextDesc App::contextDesc() const {
    if (impl_->headless) return impl_->headless->contextDesc();
    ContextDesc d;
    d.getProcAddress = glfwLoader;
    d.profiling = Profiling::Always; // the examples print their pass times
    return d;
}

bool App::windowed() const { return impl_->window != nullptr; }

void App::setPanel(std::function<void()> widgets) { impl_->panel = std::move(widgets); }

TextureImage App::presentUntilDone(bool& changed, const std::function<TextureImage()>& render) {
    TextureImage picture, shown;
    int presented = 0;
    do {
        if (changed) {
            changed = false;
            picture = render();
        }
        shown = present(picture);
        ++presented;
    } while (!done(presented));
    if (!screenshot_.empty()) {
        assets::writePng(screenshot_, impl_->screen);
        std::printf("wrote %s (the window with its panel)\n", screenshot_.c_str());
    }
    return shown;
}

bool App::done(int presented) const {
    if (impl_->window && glfwWindowShouldClose(impl_->window)) return true;
    return frames_ > 0 && presented >= frames_;
}

TextureImage App::present(const TextureImage& picture) {
    if (!impl_->window) return picture;
    if (picture.width != width_ || picture.height != height_)
        throw Error(ErrorCode::InvalidArgument, "present: picture size differs from the window");
    const std::size_t row = static_cast<std::size_t>(width_) * 4;
    if (!impl_->texture) {
        glCreateTextures(GL_TEXTURE_2D, 1, &impl_->texture);
        glTextureStorage2D(impl_->texture, 1, GL_RGBA8, width_, height_);
        glCreateFramebuffers(1, &impl_->framebuffer);
        glNamedFramebufferTexture(impl_->framebuffer, GL_COLOR_ATTACHMENT0, impl_->texture, 0);
    }
    // Pictures start at the top row, GL images at the bottom one.
    std::vector<std::uint8_t> flipped(picture.rgba.size());
    for (int y = 0; y < height_; ++y)
        std::memcpy(&flipped[static_cast<std::size_t>(y) * row],
                    &picture.rgba[static_cast<std::size_t>(height_ - 1 - y) * row], row);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTextureSubImage2D(impl_->texture, 0, 0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, flipped.data());
    glBlitNamedFramebuffer(impl_->framebuffer, 0, 0, 0, width_, height_, 0, 0, width_, height_, GL_COLOR_BUFFER_BIT,
                           GL_NEAREST);
    // Read back what the window shows.
    TextureImage shown = readWindow(width_, height_);
    impl_->drawPanel();
    if (!screenshot_.empty()) impl_->screen = readWindow(width_, height_);
    glfwSwapBuffers(impl_->window);
    glfwPollEvents();
    return shown;
}

void printPassTimes(Context& ctx) {
    for (const PassStatistics& s : ctx.profiler().statistics(true))
        std::printf("%s: median %.3f ms over %zu frames (%s)\n", s.name.c_str(), s.medianMs, s.samples, toString(s.clock));
}

void writeShown(const AppOptions& options, bool windowed, const TextureImage& shown) {
    if (options.out.empty()) return;
    assets::writePng(options.out, shown);
    std::printf("wrote %s (%s)\n", options.out.c_str(), windowed ? "read back from the window" : "headless");
}

} // namespace obscura::examples
