#pragma once
// Example application shell: a headless EGL context (default) or a GLFW window (--window),
// scene loading from the command line, and presentation of 8-bit pictures. The examples
// are hosts: they bring their own GL loader (a plain glad) like an engine would.
#include "obscura/assets.hpp"
#include "obscura/context.hpp"

#include <CLI/CLI.hpp>

#include <functional>
#include <memory>
#include <string>

namespace obscura::examples {

struct AppOptions {
    std::string scene = "cornell"; //!< built-in name, JSON scene or mesh file
    std::string camera;            //!< ex,ey,ez,tx,ty,tz,ux,uy,uz,fovy_deg[,near,far]; empty = the scene's
    std::string size = "512x512";  //!< WxH pixels
    bool window = false;           //!< open a GLFW window instead of a headless context
    int frames = 1;                //!< frames to render; 0 = until the window is closed
    std::string out;               //!< write the last presented picture as PNG
    std::string screenshot;        //!< window: write the last frame as shown, panel included, as PNG
};

void addAppOptions(CLI::App& cli, AppOptions& options);

//! Runs an example's body; an exception is printed and gives exit status 1.
int runGuarded(const std::function<void()>& body);

//! Prints the context's per-pass statistics (median over the frames, and the clock).
void printPassTimes(Context& ctx);
//! Writes `shown` to options.out as PNG, if given, saying where the picture came from.
void writeShown(const AppOptions& options, bool windowed, const TextureImage& shown);

class App {
public:
    explicit App(const AppOptions& options);
    ~App();
    App(const App&) = delete;
    App& operator=(const App&) = delete;

    ContextDesc contextDesc() const;
    int width() const { return width_; }
    int height() const { return height_; }
    bool windowed() const;
    //! Headless: returns `picture`. In a window: draws it into the window's framebuffer, reads
    //! that framebuffer back (what is on screen), swaps and returns what was read.
    TextureImage present(const TextureImage& picture);
    //! Presents frames until done(): calls `render` for a new picture first and whenever
    //! `changed` was set (by the panel), clearing it. Returns the last presented picture;
    //! with --screenshot, writes the last frame as the window shows it (panel included).
    TextureImage presentUntilDone(bool& changed, const std::function<TextureImage()>& render);
    //! True once `frames` frames were presented or the window was closed.
    bool done(int presented) const;
    //! In a window: ImGui widgets drawn over each presented picture (after it was read back,
    //! so the panel is not part of the returned picture). Ignored headless.
    void setPanel(std::function<void()> widgets);

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
    int width_ = 0, height_ = 0, frames_ = 1;
    std::string screenshot_;
};

//! The scene of --scene seen through --camera (or the scene's own camera) at `width` x `height`,
//! with depth as `mode` says.
struct ExampleScene {
    assets::LoadedScene loaded;
    Camera camera;
    float diagonal = 0.0f; //!< of the scene's bounding box, world units
};
ExampleScene loadExampleScene(const AppOptions& options, int width, int height, DepthMode mode = DepthMode::Standard);

} // namespace obscura::examples
