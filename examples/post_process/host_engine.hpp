#pragma once
// A small engine of its own, as a host of Obscura's: its own GL loader (the examples' glad),
// its own G-buffer (reversed-Z 32F depth, smooth view-space shading normals, sRGB albedo,
// lit HDR colour) and its own display framebuffer, and GL state of its own that Obscura must
// leave as it found it. It knows nothing of Obscura: main.cpp is the integration.
#include "obscura/assets.hpp"
#include "obscura/camera.hpp"

#include <glad/gl.h>

#include <string>
#include <vector>

namespace obscura::examples {

class HostEngine {
public:
    //! Uploads the scene's meshes (vertex normals: the mesh's, else smooth ones across edges
    //! that turn by less than 45 degrees) for frames of `width` x `height`.
    HostEngine(const assets::LoadedScene& scene, int width, int height);
    ~HostEngine();
    HostEngine(const HostEngine&) = delete;
    HostEngine& operator=(const HostEngine&) = delete;

    //! The G-buffer pass, seen by `camera` (reversed-Z, GL_ZERO_TO_ONE): depth, normals,
    //! albedo, and Lambert shading by the scene's lights (unshadowed) plus emission.
    void renderGBuffer(const Camera& camera);
    //! Sets GL state an engine might leave set between its passes (its program, VAO and
    //! framebuffers bound, blending, scissor, culling, stencil, sRGB writes, ...).
    void setOwnState();
    //! Puts back what setOwnState() set to GL's initial values (the example's window shell
    //! draws with those).
    void resetOwnState();
    //! The state setOwnState() set, as GL reports it now: one line per item.
    std::vector<std::string> ownState() const;
    //! The display framebuffer's colour (GL_RGBA8, display-encoded), top row first.
    std::vector<unsigned char> readDisplay() const;

    GLuint depth() const { return depth_; }   //!< GL_DEPTH_COMPONENT32F
    GLuint normal() const { return normal_; } //!< GL_RGBA16F, view space, smooth
    GLuint albedo() const { return albedo_; } //!< GL_SRGB8_ALPHA8
    GLuint lit() const { return lit_; }       //!< GL_RGBA16F, W/(sr m^2)
    GLuint displayFramebuffer() const { return displayFbo_; }
    //! Twice the largest angle between a corner's normal and its face's, radians: what
    //! HostGBuffer::normalDeviation asks of smooth normals (at most pi/2).
    float normalDeviation() const { return normalDeviation_; }

private:
    int width_, height_;
    GLuint depth_ = 0, normal_ = 0, albedo_ = 0, lit_ = 0, gbufferFbo_ = 0;
    GLuint display_ = 0, displayFbo_ = 0, stateTexture_ = 0;
    GLuint program_ = 0, vao_ = 0, vertices_ = 0, lights_ = 0;
    GLsizei vertexCount_ = 0;
    int lightCount_ = 0;
    float normalDeviation_ = 0.0f;
    const Scene& scene_;
};

} // namespace obscura::examples
