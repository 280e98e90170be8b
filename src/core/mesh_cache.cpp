#include "core/mesh_cache.hpp"

#include "core/context_impl.hpp"
#include "core/validate.hpp"
#include "shaders/common/common_bindings.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstring>
#include <string>

namespace obscura::detail {
namespace {

std::size_t typeSize(GLenum type) {
    switch (type) {
    case GL_FLOAT: return 4;
    case GL_HALF_FLOAT: return 2;
    case GL_DOUBLE: return 8;
    case GL_BYTE: case GL_UNSIGNED_BYTE: return 1;
    case GL_SHORT: case GL_UNSIGNED_SHORT: return 2;
    case GL_INT: case GL_UNSIGNED_INT: return 4;
    case GL_INT_2_10_10_10_REV: case GL_UNSIGNED_INT_2_10_10_10_REV: return 4;
    default: return 0;
    }
}

std::string meshName(std::size_t index) { return "Scene::meshRefs[" + std::to_string(index) + "]"; }

bool isPacked(GLenum type) { return type == GL_INT_2_10_10_10_REV || type == GL_UNSIGNED_INT_2_10_10_10_REV; }

std::size_t elementBytes(const VertexStream& s) {
    return isPacked(s.type) ? 4 : static_cast<std::size_t>(s.components) * typeSize(s.type);
}

GLint64 bufferSize(ContextImpl& ctx, GLuint buffer) {
    GLint64 size = 0;
    ctx.gl.GetNamedBufferParameteri64v(buffer, GL_BUFFER_SIZE, &size);
    return size;
}

// Checks a stream against GL's limits and the size of its buffer. `vertices` is the number
// of vertices read when known (non-indexed draws); indexed draws check the first element
// only, since index values live on the GPU.
void validateStream(const VertexStream& s, int components, const std::string& what, bool required, std::size_t vertices,
                    ContextImpl& ctx) {
    if (s.buffer == 0) {
        if (required) throw Error(ErrorCode::InvalidArgument, what + ": a buffer is required");
        return;
    }
    if (!ctx.gl.IsBuffer(s.buffer))
        throw Error(ErrorCode::InvalidArgument, what + ": " + std::to_string(s.buffer) + " is not a GL buffer");
    if (typeSize(s.type) == 0)
        throw Error(ErrorCode::InvalidArgument, what + ": unsupported attribute type " + std::to_string(s.type) +
                                                    " (GL_FLOAT, GL_HALF_FLOAT, GL_DOUBLE, an integer type or a packed "
                                                    "2_10_10_10 type)");
    if (isPacked(s.type) ? s.components != 4 : (s.components != components && !(components == 3 && s.components == 4)))
        throw Error(ErrorCode::InvalidArgument, what + ": needs " + std::to_string(isPacked(s.type) ? 4 : components) +
                                                    " components, got " + std::to_string(s.components));
    GLint maxStride = 0;
    ctx.gl.GetIntegerv(GL_MAX_VERTEX_ATTRIB_STRIDE, &maxStride);
    if (s.stride == 0 || s.stride > static_cast<unsigned>(maxStride))
        throw Error(ErrorCode::InvalidArgument, what + ": stride must be in [1, " + std::to_string(maxStride) +
                                                    "] bytes (GL_MAX_VERTEX_ATTRIB_STRIDE), got " + std::to_string(s.stride));
    const auto size = static_cast<std::uint64_t>(bufferSize(ctx, s.buffer));
    const std::uint64_t last = s.offset + (vertices > 0 ? (vertices - 1) * std::uint64_t(s.stride) : 0) + elementBytes(s);
    if (last > size)
        throw Error(ErrorCode::InvalidArgument, what + ": reads up to byte " + std::to_string(last) + " of a buffer of " +
                                                    std::to_string(size) + " bytes");
}

std::size_t indexSize(GLenum type) {
    return type == GL_UNSIGNED_INT ? 4 : type == GL_UNSIGNED_SHORT ? 2 : type == GL_UNSIGNED_BYTE ? 1 : 0;
}

// Reads one attribute of the host VAO (which must be bound) into a stream description.
VertexStream streamFromBoundVao(ContextImpl& ctx, int location, const std::string& what) {
    auto& gl = ctx.gl;
    GLint maxAttribs = 0;
    gl.GetIntegerv(GL_MAX_VERTEX_ATTRIBS, &maxAttribs);
    if (location < 0 || location >= maxAttribs)
        throw Error(ErrorCode::InvalidArgument, what + ": attribute location " + std::to_string(location) +
                                                    " outside [0, " + std::to_string(maxAttribs - 1) + "]");
    const auto loc = static_cast<GLuint>(location);
    GLint enabled = 0, size = 0, type = 0, normalized = 0, relative = 0, binding = 0, buffer = 0, stride = 0;
    gl.GetVertexAttribiv(loc, GL_VERTEX_ATTRIB_ARRAY_ENABLED, &enabled);
    if (!enabled) throw Error(ErrorCode::InvalidArgument, what + ": attribute " + std::to_string(location) +
                                                              " is not enabled in the host VAO");
    GLint divisor = 0;
    gl.GetVertexAttribiv(loc, GL_VERTEX_ATTRIB_ARRAY_DIVISOR, &divisor);
    if (divisor != 0)
        throw Error(ErrorCode::InvalidArgument, what + ": attribute " + std::to_string(location) +
                                                    " is instanced (divisor " + std::to_string(divisor) + "); meshes are "
                                                    "drawn once, per vertex");
    gl.GetVertexAttribiv(loc, GL_VERTEX_ATTRIB_ARRAY_SIZE, &size);
    gl.GetVertexAttribiv(loc, GL_VERTEX_ATTRIB_ARRAY_TYPE, &type);
    gl.GetVertexAttribiv(loc, GL_VERTEX_ATTRIB_ARRAY_NORMALIZED, &normalized);
    gl.GetVertexAttribiv(loc, GL_VERTEX_ATTRIB_RELATIVE_OFFSET, &relative);
    gl.GetVertexAttribiv(loc, GL_VERTEX_ATTRIB_BINDING, &binding);
    gl.GetIntegeri_v(GL_VERTEX_BINDING_BUFFER, static_cast<GLuint>(binding), &buffer);
    gl.GetIntegeri_v(GL_VERTEX_BINDING_STRIDE, static_cast<GLuint>(binding), &stride);
    GLint64 offset = 0;
    gl.GetInteger64i_v(GL_VERTEX_BINDING_OFFSET, static_cast<GLuint>(binding), &offset);
    VertexStream s;
    s.buffer = static_cast<unsigned>(buffer);
    s.offset = static_cast<std::size_t>(offset + relative);
    s.components = size;
    s.type = static_cast<unsigned>(type);
    s.normalized = normalized != 0;
    s.stride = stride > 0 ? static_cast<unsigned>(stride) : static_cast<unsigned>(static_cast<std::size_t>(size) * typeSize(s.type));
    return s;
}

void attachStream(ContextImpl& ctx, GLuint vao, GLuint attrib, const VertexStream& s) {
    auto& gl = ctx.gl;
    gl.VertexArrayVertexBuffer(vao, attrib, s.buffer, static_cast<GLintptr>(s.offset), static_cast<GLsizei>(s.stride));
    gl.VertexArrayAttribFormat(vao, attrib, s.components, s.type, s.normalized ? GL_TRUE : GL_FALSE, 0);
    gl.VertexArrayAttribBinding(vao, attrib, attrib);
    gl.EnableVertexArrayAttrib(vao, attrib);
}

void detachStream(ContextImpl& ctx, GLuint vao, GLuint attrib) {
    ctx.gl.DisableVertexArrayAttrib(vao, attrib);
    ctx.gl.VertexArrayVertexBuffer(vao, attrib, 0, 0, 16);
}

} // namespace

void drawMesh(ContextImpl& ctx, const DrawableMesh& mesh) {
    ctx.gl.BindVertexArray(mesh.vao);
    if (mesh.indexType != GL_NONE)
        ctx.gl.DrawElements(GL_TRIANGLES, mesh.count, mesh.indexType,
                            reinterpret_cast<const void*>(static_cast<std::uintptr_t>(mesh.indexOffset)));
    else
        ctx.gl.DrawArrays(GL_TRIANGLES, 0, mesh.count);
}

MeshCache::MeshCache(ContextImpl& ctx) : ctx_(ctx) {}

MeshCache::GpuMesh MeshCache::upload(const MeshData& d) {
    const std::size_t posBytes = d.positions.size() * sizeof(glm::vec3);
    const std::size_t nrmBytes = d.normals.size() * sizeof(glm::vec3);
    const std::size_t uvBytes = d.texcoords.size() * sizeof(glm::vec2);
    const std::size_t idxBytes = d.indices.size() * sizeof(std::uint32_t);
    std::vector<std::uint8_t> bytes(posBytes + nrmBytes + uvBytes + idxBytes);
    const auto put = [&](std::size_t at, const void* src, std::size_t size) {
        if (size) std::memcpy(bytes.data() + at, src, size);
    };
    put(0, d.positions.data(), posBytes);
    put(posBytes, d.normals.data(), nrmBytes);
    put(posBytes + nrmBytes, d.texcoords.data(), uvBytes);
    put(posBytes + nrmBytes + uvBytes, d.indices.data(), idxBytes);

    GpuMesh m;
    m.bytes = bytes.size();
    m.buffer = createBuffer(ctx_, static_cast<GLsizeiptr>(bytes.size()), bytes.data(), 0, "gbuffer.mesh");
    m.vao = createVertexArray(ctx_, "gbuffer.mesh");
    const GLuint vao = m.vao.get(), buf = m.buffer.get();
    attachStream(ctx_, vao, OBSCURA_ATTRIB_POSITION, {buf, 0, sizeof(glm::vec3), 3, GL_FLOAT, false});
    if (nrmBytes) attachStream(ctx_, vao, OBSCURA_ATTRIB_NORMAL, {buf, posBytes, sizeof(glm::vec3), 3, GL_FLOAT, false});
    if (uvBytes)
        attachStream(ctx_, vao, OBSCURA_ATTRIB_TEXCOORD, {buf, posBytes + nrmBytes, sizeof(glm::vec2), 2, GL_FLOAT, false});
    if (idxBytes) ctx_.gl.VertexArrayElementBuffer(vao, buf);
    m.drawable.vao = vao;
    m.drawable.indexType = idxBytes ? GL_UNSIGNED_INT : GL_NONE;
    m.drawable.indexOffset = posBytes + nrmBytes + uvBytes;
    m.drawable.count = static_cast<GLsizei>(idxBytes ? d.indices.size() : d.positions.size());
    m.drawable.hasNormals = nrmBytes > 0;
    m.drawable.hasTexcoords = uvBytes > 0;
    return m;
}

DrawableMesh MeshCache::cpuMesh(const std::shared_ptr<const MeshData>& data) {
    auto it = meshes_.find(data.get());
    // A dead entry at the same address belongs to an older MeshData: replace it.
    if (it != meshes_.end() && it->second.source.lock() != data) {
        meshes_.erase(it);
        it = meshes_.end();
    }
    if (it == meshes_.end()) {
        GpuMesh m = upload(*data);
        m.source = data;
        it = meshes_.emplace(data.get(), std::move(m)).first;
    }
    return it->second.drawable;
}

DrawableMesh MeshCache::hostMesh(std::size_t index, const MeshRef& ref) {
    const std::string what = meshName(index);
    auto& gl = ctx_.gl;
    VertexStream position = ref.position, normal = ref.normal, texcoord = ref.texcoord;
    GLuint elementBuffer = ref.indexBuffer;
    if (ref.vao != 0) {
        if (!gl.IsVertexArray(ref.vao))
            throw Error(ErrorCode::InvalidArgument, what + ": " + std::to_string(ref.vao) + " is not a GL vertex array");
        gl.BindVertexArray(ref.vao);
        position = streamFromBoundVao(ctx_, ref.positionLocation, what + ".positionLocation");
        normal = ref.normalLocation >= 0 ? streamFromBoundVao(ctx_, ref.normalLocation, what + ".normalLocation")
                                         : VertexStream{};
        texcoord = ref.texcoordLocation >= 0
                       ? streamFromBoundVao(ctx_, ref.texcoordLocation, what + ".texcoordLocation")
                       : VertexStream{};
        gl.BindVertexArray(0);
        GLint element = 0;
        gl.GetVertexArrayiv(ref.vao, GL_ELEMENT_ARRAY_BUFFER_BINDING, &element);
        elementBuffer = static_cast<GLuint>(element);
    }
    if (ref.count == 0 || ref.count % 3 != 0 || ref.count > static_cast<unsigned>(INT_MAX))
        throw Error(ErrorCode::InvalidArgument, what + ": count must be a positive multiple of 3 up to INT_MAX, got " +
                                                    std::to_string(ref.count));
    const std::size_t vertices = elementBuffer ? 0 : ref.count;
    validateStream(position, 3, what + ".position", true, vertices, ctx_);
    validateStream(normal, 3, what + ".normal", false, vertices, ctx_);
    validateStream(texcoord, 2, what + ".texcoord", false, vertices, ctx_);
    if (elementBuffer != 0) {
        if (!gl.IsBuffer(elementBuffer))
            throw Error(ErrorCode::InvalidArgument, what + ": index buffer " + std::to_string(elementBuffer) +
                                                        " is not a GL buffer");
        const std::size_t bytes = indexSize(ref.indexType);
        if (bytes == 0)
            throw Error(ErrorCode::InvalidArgument, what + ": indexType must be GL_UNSIGNED_INT, _SHORT or _BYTE");
        if (ref.indexOffset % bytes != 0)
            throw Error(ErrorCode::InvalidArgument, what + ": indexOffset " + std::to_string(ref.indexOffset) +
                                                        " is not a multiple of the index size");
        const std::uint64_t end = ref.indexOffset + std::uint64_t(ref.count) * bytes;
        const auto size = static_cast<std::uint64_t>(bufferSize(ctx_, elementBuffer));
        if (end > size)
            throw Error(ErrorCode::InvalidArgument, what + ": " + std::to_string(ref.count) + " indices from byte " +
                                                        std::to_string(ref.indexOffset) + " overrun the index buffer of " +
                                                        std::to_string(size) + " bytes");
    }

    while (hostVaos_.size() <= index) hostVaos_.push_back(createVertexArray(ctx_, "gbuffer.host_mesh"));
    const GLuint vao = hostVaos_[index].get();
    attachStream(ctx_, vao, OBSCURA_ATTRIB_POSITION, position);
    normal.buffer ? attachStream(ctx_, vao, OBSCURA_ATTRIB_NORMAL, normal) : detachStream(ctx_, vao, OBSCURA_ATTRIB_NORMAL);
    texcoord.buffer ? attachStream(ctx_, vao, OBSCURA_ATTRIB_TEXCOORD, texcoord)
                    : detachStream(ctx_, vao, OBSCURA_ATTRIB_TEXCOORD);
    gl.VertexArrayElementBuffer(vao, elementBuffer);

    DrawableMesh d;
    d.vao = vao;
    d.indexType = elementBuffer ? static_cast<GLenum>(ref.indexType) : GL_NONE;
    d.indexOffset = ref.indexOffset;
    d.count = static_cast<GLsizei>(ref.count);
    d.hasNormals = normal.buffer != 0;
    d.hasTexcoords = texcoord.buffer != 0;
    return d;
}

GLuint MeshCache::albedoTexture(const std::shared_ptr<const TextureImage>& image) {
    auto it = images_.find(image.get());
    if (it != images_.end() && it->second.source.lock() != image) {
        images_.erase(it);
        it = images_.end();
    }
    if (it == images_.end()) {
        const TextureImage& img = *image;
        if (img.width < 1 || img.height < 1 ||
            img.rgba.size() != static_cast<std::size_t>(img.width) * static_cast<std::size_t>(img.height) * 4)
            throw Error(ErrorCode::InvalidArgument, "Material::albedoImage: " + std::to_string(img.width) + "x" +
                                                        std::to_string(img.height) + " with " +
                                                        std::to_string(img.rgba.size()) + " bytes (need w*h*4)");
        requireImageSize(img.width, img.height, ctx_.info.maxTextureSize, "Material::albedoImage");
        const int levels = fullMipLevels(std::max(img.width, img.height));
        GpuImage g;
        g.source = image;
        g.texture = createTexture2D(ctx_, GL_SRGB8_ALPHA8, img.width, img.height, levels, "gbuffer.albedo_image");
        // Rows are stored top first; GL's first row is the bottom one. Flip while uploading so
        // that texcoord v = 0 is the bottom of the image (the usual OBJ/glTF-after-flip rule).
        std::vector<std::uint8_t> flipped(img.rgba.size());
        const std::size_t row = static_cast<std::size_t>(img.width) * 4;
        for (int y = 0; y < img.height; ++y)
            std::memcpy(&flipped[static_cast<std::size_t>(y) * row],
                        &img.rgba[static_cast<std::size_t>(img.height - 1 - y) * row], row);
        ctx_.gl.TextureSubImage2D(g.texture.get(), 0, 0, 0, img.width, img.height, GL_RGBA, GL_UNSIGNED_BYTE,
                                  flipped.data());
        ctx_.gl.GenerateTextureMipmap(g.texture.get());
        g.bytes = img.rgba.size() * 4 / 3;
        it = images_.emplace(image.get(), std::move(g)).first;
    }
    return it->second.texture.get();
}

void MeshCache::collectGarbage() {
    std::erase_if(meshes_, [](const auto& e) { return e.second.source.expired(); });
    std::erase_if(images_, [](const auto& e) { return e.second.source.expired(); });
}

std::size_t MeshCache::memoryBytes() const {
    std::size_t total = 0;
    for (const auto& e : meshes_) total += e.second.bytes;
    for (const auto& e : images_) total += e.second.bytes;
    return total;
}

} // namespace obscura::detail
