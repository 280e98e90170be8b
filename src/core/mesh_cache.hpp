#pragma once
// GPU copies of the scene's geometry and material textures, kept across frames:
//  - CPU meshes (MeshData) are uploaded once and kept while the MeshData lives;
//  - host meshes (MeshRef) get a VAO of ours that points at the host's buffers, re-specified
//    every frame because the host may change its buffers at any time;
//  - CPU albedo images are uploaded once as sRGB textures with mipmaps.
#include "core/gl_objects.hpp"
#include "obscura/scene.hpp"

#include <cstddef>
#include <memory>
#include <unordered_map>
#include <vector>

namespace obscura::detail {

struct ContextImpl;

struct DrawableMesh {
    GLuint vao = 0;
    GLenum indexType = GL_NONE; //!< GL_NONE: non-indexed
    std::size_t indexOffset = 0;
    GLsizei count = 0;
    bool hasNormals = false;
    bool hasTexcoords = false;
};

//! Binds the mesh's VAO and draws it as triangles (the caller has set up the program).
void drawMesh(ContextImpl& ctx, const DrawableMesh& mesh);

class MeshCache {
public:
    explicit MeshCache(ContextImpl& ctx);

    DrawableMesh cpuMesh(const std::shared_ptr<const MeshData>& data);
    //! Validates the host objects (state must be inside a StateScope: reading a host VAO's
    //! layout binds it). Throws Error{InvalidArgument}.
    DrawableMesh hostMesh(std::size_t index, const MeshRef& ref);
    GLuint albedoTexture(const std::shared_ptr<const TextureImage>& image);
    //! Releases GPU copies of meshes and images that no longer exist.
    void collectGarbage();
    std::size_t memoryBytes() const;

private:
    struct GpuMesh {
        std::weak_ptr<const MeshData> source;
        Buffer buffer;
        VertexArray vao;
        DrawableMesh drawable;
        std::size_t bytes = 0;
    };
    struct GpuImage {
        std::weak_ptr<const TextureImage> source;
        Texture texture;
        std::size_t bytes = 0;
    };

    GpuMesh upload(const MeshData& data);

    ContextImpl& ctx_;
    std::unordered_map<const MeshData*, GpuMesh> meshes_;
    std::unordered_map<const TextureImage*, GpuImage> images_;
    std::vector<VertexArray> hostVaos_;
};

} // namespace obscura::detail
