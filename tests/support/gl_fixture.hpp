#pragma once
// GL test fixture: an EGL surfaceless context plus the *test's own* global GL loader
// (a non-mx glad, like a typical host application), so tests can set and read GL state
// independently of Obscura's private function table.
//
// Catch2 lists test cases by running the binary at build time: never create a context at
// static initialisation, only inside a test case through this fixture.
#include <glad/gl.h>

#include "obscura/context.hpp"
#include "obscura/gbuffer.hpp"
#include "obscura/headless.hpp"

#include <functional>
#include <set>
#include <string>
#include <vector>

namespace obscura::test {

class GlFixture {
public:
    explicit GlFixture(bool debug = false);
    explicit GlFixture(const headless::HeadlessDesc& desc);
    ContextDesc desc(StatePolicy policy = StatePolicy::Preserve) const { return egl_.contextDesc(policy); }
    headless::HeadlessContext& egl() { return egl_; }

private:
    headless::HeadlessContext egl_;
};

//! Names of GL objects of every kind that exist now, among names [1, limit]. Object names
//! are generated in increasing order by Mesa, so a call that leaks an object leaves a name
//! here that was not present before.
std::set<std::string> liveGlObjects(unsigned limit = 4096);

//! Drains and returns pending GL errors (GL_NO_ERROR-free list).
std::vector<unsigned> drainGlErrors();

//! A host's depth texture: `depth` (a depth texture the size width x height) drawn into a new
//! GL_TEXTURE_2D of `format` (e.g. GL_DEPTH_COMPONENT24) by the host's own program, as a host
//! engine's depth pass would leave it (quantized to its format). The caller deletes it. Sets
//! the GL state the draw needs and leaves the defaults bound, the viewport set to the
//! texture (for test contexts only).
GLuint copyDepthAsHost(GLuint depth, int width, int height, GLenum format);

//! A host's depth pass over `scene` (its meshes; no MeshRefs) seen by `camera`, drawn directly
//! into a new GL_TEXTURE_2D of `format` by the host's own program: the rasterizer's depth at
//! the format's precision, not a quantized copy of ours. Clip control, clear value and depth
//! test follow the camera (reversed-Z: clear 0, GL_GREATER); `clipOrigin` GL_UPPER_LEFT
//! stores the rows top down, as a host does that renders so. The caller deletes it; state as
//! copyDepthAsHost.
GLuint rasterizeDepthAsHost(const Scene& scene, const Camera& camera, int width, int height, GLenum format,
                            GLenum clipOrigin = GL_LOWER_LEFT);

//! A host's depth (GL_DEPTH_COMPONENT32F) and smooth shading normals (GL_RGBA16F, view space,
//! unit): `scene`'s meshes (each with vertex normals; no MeshRefs) drawn by the host's own
//! program, the vertex normals interpolated and normalized per fragment, as engines shade.
//! Clip control, clear value and depth test follow the camera, as rasterizeDepthAsHost. The
//! caller deletes both.
struct HostShadingBuffers {
    GLuint depth = 0, normal = 0;
};
HostShadingBuffers rasterizeShadingNormalsAsHost(const Scene& scene, const Camera& camera, int width, int height);

//! A new host texture of `format` (a float or normalized RGBA one) from `image` (row 0 at the
//! top): each pixel's rgb through `map(pixel index in row order, rgb)`, alpha 1. The caller
//! deletes it.
GLuint hostRgbTexture(const Image& image, GLenum format, const std::function<glm::vec3(std::size_t, glm::vec3)>& map);

//! A host's normal target: `normals` (a G-buffer's view-space normals, read back) encoded as
//! n * 0.5 + 0.5 in a new texture of the normalized `format` (the driver rounds the floats to
//! its steps), in view or world space. The caller deletes it.
GLuint hostNormalTexture(const Image& normals, const Camera& camera, GLenum format, NormalSpace space);

//! Host buffers of GL_DEPTH_COMPONENT32F `depth` and `normal` (hostNormalTexture's encoding).
HostGBuffer unsignedNormalHost(GLuint depth, GLuint normal, GLenum format, NormalSpace space, int width, int height);

//! A compute program from `source` (GLSL without #version), whose `#include "path"` lines
//! are looked up in the source tree's shaders/ (the library's own GLSL functions, run by a
//! test's own main). A test fails (REQUIRE) if it does not compile, with the log mapped to
//! file:line. The caller deletes it.
GLuint libraryComputeProgram(const std::string& source);

//! Adds every shader file of the source tree to `ctx` (Context::addShaderSource), `file` with
//! its text `call` replaced by `replacement` and `prelude` inserted before its main(). A test
//! fails (REQUIRE) if `file` or `call` is not there.
void overrideShader(Context& ctx, const std::string& file, const std::string& call, const std::string& replacement,
                    const std::string& prelude = "");

//! One edit of overrideShaders: in `file`, `call` becomes `replacement`, `prelude` goes before
//! its main() (when it has one).
struct ShaderEdit {
    std::string file, call, replacement, prelude;
};

//! overrideShader with several edits, in one or more files.
void overrideShaders(Context& ctx, const std::vector<ShaderEdit>& edits);

} // namespace obscura::test
