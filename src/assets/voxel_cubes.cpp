// Voxel grids as cube meshes (for the voxelize command's PLY and the voxelization example).
#include "obscura/assets.hpp"
#include "obscura/error.hpp"

#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>

namespace obscura::assets {
namespace {

// Hue per channel (the four 32-slice words of a texel), lightness per render target: one
// render target shows four distinct bands.
glm::vec3 groupColour(int group) {
    static const std::array<glm::vec3, 4> hues = {glm::vec3(0.85f, 0.22f, 0.18f), glm::vec3(0.25f, 0.70f, 0.25f),
                                                  glm::vec3(0.20f, 0.40f, 0.90f), glm::vec3(0.95f, 0.70f, 0.15f)};
    const float lightness = static_cast<float>((group / 4) % 8) / 8.0f;
    return glm::mix(hues[static_cast<std::size_t>(group % 4)], glm::vec3(0.95f), 0.6f * lightness);
}

bool setAt(const DenseVoxels& v, const glm::ivec3& c) {
    return glm::all(glm::greaterThanEqual(c, glm::ivec3(0))) && glm::all(glm::lessThan(c, v.dims)) && v.at(c.x, c.y, c.z);
}

// Adds the face of `cell` on side `sign` of `axis` as two counter-clockwise triangles.
void addFace(MeshData& m, const glm::dvec3& origin, const glm::dvec3& size, const glm::ivec3& cell, int axis, int sign) {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    glm::dvec3 corner(cell);
    if (sign > 0) corner[axis] += 1.0;
    glm::dvec3 du(0.0), dv(0.0);
    du[u] = 1.0;
    dv[v] = 1.0;
    if (sign < 0) std::swap(du, dv); // keeps the winding counter-clockwise seen from outside
    glm::vec3 normal(0.0f);
    normal[axis] = static_cast<float>(sign);
    const auto base = static_cast<std::uint32_t>(m.positions.size());
    for (const glm::dvec3& c : {corner, corner + du, corner + du + dv, corner + dv}) {
        m.positions.emplace_back(origin + c * size);
        m.normals.push_back(normal);
    }
    m.indices.insert(m.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
}

} // namespace

Scene voxelCubesScene(const DenseVoxels& voxels, const glm::dvec3& origin, const glm::dvec3& cellSize) {
    if (voxels.voxels.size() != static_cast<std::size_t>(voxels.dims.x) * voxels.dims.y * voxels.dims.z)
        throw Error(ErrorCode::InvalidArgument, "voxelCubesScene: the voxel array does not match its dims");
    if (!(cellSize.x > 0.0 && cellSize.y > 0.0 && cellSize.z > 0.0))
        throw Error(ErrorCode::InvalidArgument, "voxelCubesScene: cellSize must be positive on every axis");
    const int groups = (voxels.dims.z + 31) / 32;
    std::vector<std::shared_ptr<MeshData>> meshes(static_cast<std::size_t>(groups));
    for (auto& m : meshes) m = std::make_shared<MeshData>();
    for (int z = 0; z < voxels.dims.z; ++z)
        for (int y = 0; y < voxels.dims.y; ++y)
            for (int x = 0; x < voxels.dims.x; ++x) {
                const glm::ivec3 c(x, y, z);
                if (!voxels.at(x, y, z)) continue;
                for (int axis = 0; axis < 3; ++axis)
                    for (int sign : {-1, 1}) {
                        glm::ivec3 n = c;
                        n[axis] += sign;
                        if (!setAt(voxels, n)) addFace(*meshes[static_cast<std::size_t>(z / 32)], origin, cellSize, c, axis, sign);
                    }
            }
    Scene scene;
    for (int g = 0; g < groups; ++g) {
        if (meshes[static_cast<std::size_t>(g)]->positions.empty()) continue;
        Material material;
        material.albedo = groupColour(g);
        material.name = "target " + std::to_string(g / 4) + " channel " + "rgba"[g % 4];
        scene.materials.push_back(material);
        Mesh mesh;
        mesh.data = meshes[static_cast<std::size_t>(g)];
        mesh.material = static_cast<std::uint32_t>(scene.materials.size() - 1);
        mesh.name = material.name;
        scene.meshes.push_back(mesh);
    }
    return scene;
}

void writePly(const std::filesystem::path& path, const Scene& scene) {
    std::size_t vertices = 0, faces = 0;
    for (const Mesh& m : scene.meshes) {
        vertices += m.data->positions.size();
        faces += (m.data->indices.empty() ? m.data->positions.size() : m.data->indices.size()) / 3;
    }
    std::ofstream out(path, std::ios::binary);
    if (!out) throw Error(ErrorCode::Io, "cannot write " + path.string());
    out << "ply\nformat binary_little_endian 1.0\ncomment written by Obscura\nelement vertex " << vertices
        << "\nproperty float x\nproperty float y\nproperty float z\nproperty uchar red\nproperty uchar green\n"
           "property uchar blue\nelement face "
        << faces << "\nproperty list uchar uint vertex_indices\nend_header\n";
    const auto put = [&](const void* data, std::size_t bytes) { out.write(static_cast<const char*>(data), static_cast<std::streamsize>(bytes)); };
    static_assert(std::endian::native == std::endian::little, "the PLY writer assumes a little-endian host");
    for (const Mesh& m : scene.meshes) {
        const glm::vec3 albedo = m.material < scene.materials.size() ? scene.materials[m.material].albedo : glm::vec3(0.8f);
        const TextureImage encoded = encodeDisplay(Image{1, 1, 3, {albedo.r, albedo.g, albedo.b}}, PngEncoding::Srgb);
        for (const glm::vec3& p : m.data->positions) {
            const glm::vec3 w(m.model * glm::vec4(p, 1.0f));
            put(&w, sizeof w);
            put(encoded.rgba.data(), 3);
        }
    }
    std::uint32_t base = 0;
    for (const Mesh& m : scene.meshes) {
        const MeshData& d = *m.data;
        const std::size_t count = d.indices.empty() ? d.positions.size() : d.indices.size();
        for (std::size_t i = 0; i + 2 < count; i += 3) {
            const std::uint8_t three = 3;
            put(&three, 1);
            for (std::size_t k = 0; k < 3; ++k) {
                const std::uint32_t v = base + (d.indices.empty() ? static_cast<std::uint32_t>(i + k) : d.indices[i + k]);
                put(&v, 4);
            }
        }
        base += static_cast<std::uint32_t>(d.positions.size());
    }
    if (!out) throw Error(ErrorCode::Io, "failed writing " + path.string());
}

} // namespace obscura::assets
