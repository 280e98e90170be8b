// Mesh files through assimp: every mesh of the file becomes one obscura::Mesh with the node
// transforms baked in, and every material its diffuse colour, emission and diffuse texture.
#include "obscura/assets.hpp"
#include "obscura/error.hpp"

#include <assimp/Importer.hpp>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <cmath>

namespace obscura::assets {
namespace {

glm::vec3 toVec3(const aiColor4D& c) { return {c.r, c.g, c.b}; }

// glTF keeps its colour in BASE_COLOR, most other formats in DIFFUSE.
Material convertMaterial(const aiMaterial& am, const std::filesystem::path& dir, const aiScene& scene) {
    Material m;
    aiString name;
    if (am.Get(AI_MATKEY_NAME, name) == AI_SUCCESS) m.name = name.C_Str();
    aiColor4D c;
    if (am.Get(AI_MATKEY_BASE_COLOR, c) == AI_SUCCESS || am.Get(AI_MATKEY_COLOR_DIFFUSE, c) == AI_SUCCESS)
        m.albedo = glm::clamp(toVec3(c), glm::vec3(0.0f), glm::vec3(1.0f));
    if (am.Get(AI_MATKEY_COLOR_EMISSIVE, c) == AI_SUCCESS) m.emission = glm::max(toVec3(c), glm::vec3(0.0f));
    aiString texPath;
    const bool hasTexture = am.GetTexture(aiTextureType_BASE_COLOR, 0, &texPath) == AI_SUCCESS ||
                            am.GetTexture(aiTextureType_DIFFUSE, 0, &texPath) == AI_SUCCESS;
    if (hasTexture && texPath.length > 0 && texPath.C_Str()[0] != '*' && !scene.GetEmbeddedTexture(texPath.C_Str())) {
        const std::filesystem::path file = dir / texPath.C_Str();
        if (std::filesystem::exists(file)) {
            m.albedoImage = std::make_shared<TextureImage>(readTextureImage(file));
            // The texture carries the colour; a constant factor other than 1 is kept as a tint.
        }
    }
    return m;
}

Mesh convertMesh(const aiMesh& am) {
    auto data = std::make_shared<MeshData>();
    data->positions.reserve(am.mNumVertices);
    for (unsigned i = 0; i < am.mNumVertices; ++i)
        data->positions.emplace_back(am.mVertices[i].x, am.mVertices[i].y, am.mVertices[i].z);
    if (am.HasNormals()) {
        data->normals.reserve(am.mNumVertices);
        for (unsigned i = 0; i < am.mNumVertices; ++i) {
            glm::vec3 n(am.mNormals[i].x, am.mNormals[i].y, am.mNormals[i].z);
            // assimp writes NaN normals for degenerate faces; the G-buffer falls back to the
            // face normal for a zero normal.
            if (!std::isfinite(n.x) || !std::isfinite(n.y) || !std::isfinite(n.z)) n = glm::vec3(0.0f);
            data->normals.push_back(n);
        }
    }
    if (am.HasTextureCoords(0)) {
        data->texcoords.reserve(am.mNumVertices);
        for (unsigned i = 0; i < am.mNumVertices; ++i)
            data->texcoords.emplace_back(am.mTextureCoords[0][i].x, am.mTextureCoords[0][i].y);
    }
    for (unsigned f = 0; f < am.mNumFaces; ++f) {
        const aiFace& face = am.mFaces[f];
        if (face.mNumIndices != 3) continue; // points and lines left after triangulation
        for (unsigned k = 0; k < 3; ++k) data->indices.push_back(face.mIndices[k]);
    }
    Mesh m;
    m.data = std::move(data);
    m.material = am.mMaterialIndex;
    m.name = am.mName.C_Str();
    return m;
}

} // namespace

LoadedScene loadMeshFile(const std::filesystem::path& path) {
    if (!std::filesystem::exists(path)) throw Error(ErrorCode::Io, "mesh file not found: " + path.string());
    Assimp::Importer importer;
    // Points and lines are dropped: the G-buffer draws triangles only.
    importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
    const aiScene* as = importer.ReadFile(
        path.string(), aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_GenNormals |
                           aiProcess_PreTransformVertices | aiProcess_SortByPType | aiProcess_FindInvalidData |
                           aiProcess_ValidateDataStructure);
    if (!as || !as->mRootNode || (as->mFlags & AI_SCENE_FLAGS_INCOMPLETE))
        throw Error(ErrorCode::Parse, "assimp cannot read " + path.string() + ": " + importer.GetErrorString());
    LoadedScene s;
    s.name = path.stem().string();
    const std::filesystem::path dir = path.parent_path();
    for (unsigned i = 0; i < as->mNumMaterials; ++i) s.scene.materials.push_back(convertMaterial(*as->mMaterials[i], dir, *as));
    if (s.scene.materials.empty()) s.scene.materials.push_back(Material{});
    for (unsigned i = 0; i < as->mNumMeshes; ++i) {
        Mesh m = convertMesh(*as->mMeshes[i]);
        if (m.data->indices.empty()) continue;
        if (m.material >= s.scene.materials.size()) m.material = 0;
        s.scene.meshes.push_back(std::move(m));
    }
    if (s.scene.meshes.empty()) throw Error(ErrorCode::Parse, path.string() + " contains no triangles");
    const Bounds b = sceneBounds(s.scene);
    s.camera = framingCamera(b);
    // A key light from above the camera's shoulder; irradiance pi makes a white surface facing
    // it exactly as bright as its albedo.
    Light key;
    key.type = LightType::Directional;
    key.direction = glm::normalize(glm::vec3(-0.3f, -1.0f, -0.45f));
    key.intensity = 3.14159265f;
    s.scene.lights.push_back(key);
    return s;
}

} // namespace obscura::assets
