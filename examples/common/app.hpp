#pragma once
// Example application shell: a headless EGL context (default) or a GLFW window (--window),
// scene loading from the command line, and presentation of 8-bit pictures. The examples
// are hosts: they bring their own GL loader (a plain glad) like an engine would.
#include "obscura/assets.hpp"
#include "obscura/context.hpp"

#include <CLI/CLI.hpp>

#include <memory>
#include <string>

namespace obscura::examples {

struct AppOptions {
    std::string scene = "cornell"; //!< built-in name, JSON scene or mesh file
    std::string camera;            //!< ex,ey,ez,tx,ty,tz,ux,uy,uz,fovy_deg; empty = the scene's
    std::string size = "512x512";  //!< WxH pixels
    bool window = false;           //!< open a GLFW window instead of a headless context
    int frames = 1;                //!< frames to render; 0 = until the window is closed
    std::string out;               //!< write the last presented picture as PNG
};

void addAppOptions(CLI::App& cli, AppOptions& options);

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
    //! True once `frames` frames were presented or the window was closed.
    bool done(int presented) const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
    int width_ = 0, height_ = 0, frames_ = 1;
};

} // namespace obscura::examples
