// JSON scene description (format: docs/scene-format.md). Errors name the file and the JSON
// path of the offending value.
#include "obscura/assets.hpp"
#include "obscura/error.hpp"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>

namespace obscura::assets {
namespace {

// ordered_json keeps materials in file order, so their indices match the file.
using json = nlohmann::ordered_json;
constexpr float kDegrees = 3.14159265358979f / 180.0f;

class Parser {
public:
    explicit Parser(std::filesystem::path file) : file_(std::move(file)), dir_(file_.parent_path()) {}

    LoadedScene parse(const json& root) {
        if (!root.is_object()) fail("", "the top level must be an object");
        LoadedScene s;
        s.name = root.value("name", file_.stem().string());
        if (root.contains("units_per_metre")) s.unitsPerMetre = positive(root["units_per_metre"], "units_per_metre");
        if (root.contains("materials")) materials(root["materials"], s.scene);
        if (root.contains("meshes")) meshes(root["meshes"], s);
        if (root.contains("lights")) {
            const json& lights = array(root["lights"], "lights");
            for (std::size_t i = 0; i < lights.size(); ++i)
                s.scene.lights.push_back(light(lights[i], "lights[" + std::to_string(i) + "]"));
        }
        if (root.contains("environment")) s.scene.environment = environment(root["environment"]);
        if (root.contains("media")) {
            const json& media = array(root["media"], "media");
            for (std::size_t i = 0; i < media.size(); ++i)
                s.scene.media.push_back(medium(media[i], "media[" + std::to_string(i) + "]"));
        }
        if (s.scene.materials.empty()) s.scene.materials.push_back(Material{});
        s.camera = root.contains("camera") ? camera(root["camera"], framingCamera(sceneBounds(s.scene)))
                                           : framingCamera(sceneBounds(s.scene));
        return s;
    }

private:
    [[noreturn]] void fail(const std::string& where, const std::string& what) const {
        throw Error(ErrorCode::Parse, file_.string() + (where.empty() ? "" : ": " + where) + ": " + what);
    }

    const json& array(const json& j, const std::string& where) const {
        if (!j.is_array()) fail(where, "expected an array");
        return j;
    }

    float number(const json& j, const std::string& where) const {
        if (!j.is_number()) fail(where, "expected a number");
        const float v = j.get<float>();
        if (!std::isfinite(v)) fail(where, "expected a finite number");
        return v;
    }

    float positive(const json& j, const std::string& where) const {
        const float v = number(j, where);
        if (!(v > 0.0f)) fail(where, "expected a number > 0");
        return v;
    }

    glm::vec3 vec3(const json& j, const std::string& where) const {
        if (j.is_number()) return glm::vec3(number(j, where));
        if (!j.is_array() || j.size() != 3) fail(where, "expected [x, y, z]");
        return {number(j[0], where + "[0]"), number(j[1], where + "[1]"), number(j[2], where + "[2]")};
    }

    glm::vec3 colour(const json& j, const std::string& where) const {
        const glm::vec3 c = vec3(j, where);
        if (glm::any(glm::lessThan(c, glm::vec3(0.0f)))) fail(where, "colours must be >= 0");
        return c;
    }

    glm::mat4 transform(const json& j, const std::string& where) const {
        if (j.contains("matrix")) {
            const json& m = j["matrix"];
            if (!m.is_array() || m.size() != 16) fail(where + ".matrix", "expected 16 numbers (column-major)");
            float v[16];
            for (std::size_t i = 0; i < 16; ++i) v[i] = number(m[i], where + ".matrix[" + std::to_string(i) + "]");
            return glm::make_mat4(v);
        }
        glm::mat4 t(1.0f);
        if (j.contains("translate")) t = glm::translate(t, vec3(j["translate"], where + ".translate"));
        if (j.contains("rotate_deg")) {
            const glm::vec3 r = vec3(j["rotate_deg"], where + ".rotate_deg") * kDegrees;
            t = glm::rotate(t, r.z, {0, 0, 1});
            t = glm::rotate(t, r.y, {0, 1, 0});
            t = glm::rotate(t, r.x, {1, 0, 0});
        }
        if (j.contains("scale")) t = glm::scale(t, vec3(j["scale"], where + ".scale"));
        return t;
    }

    void materials(const json& j, Scene& scene) {
        if (!j.is_object()) fail("materials", "expected an object of name: material");
        for (const auto& [name, m] : j.items()) {
            const std::string where = "materials." + name;
            Material mat;
            mat.name = name;
            if (m.contains("albedo")) mat.albedo = colour(m["albedo"], where + ".albedo");
            if (glm::any(glm::greaterThan(mat.albedo, glm::vec3(1.0f)))) fail(where + ".albedo", "must be <= 1");
            if (m.contains("emission")) mat.emission = colour(m["emission"], where + ".emission");
            if (m.contains("albedo_texture")) {
                if (!m["albedo_texture"].is_string()) fail(where + ".albedo_texture", "expected a file name");
                mat.albedoImage = std::make_shared<TextureImage>(readTextureImage(dir_ / m["albedo_texture"].get<std::string>()));
            }
            materialIndex_[name] = static_cast<std::uint32_t>(scene.materials.size());
            scene.materials.push_back(std::move(mat));
        }
    }

    std::uint32_t materialRef(const json& j, const std::string& where) const {
        if (!j.is_string()) fail(where, "expected a material name");
        const auto it = materialIndex_.find(j.get<std::string>());
        if (it == materialIndex_.end()) fail(where, "no material named \"" + j.get<std::string>() + "\"");
        return it->second;
    }

    // Appends another scene's meshes (and, unless overridden, its materials and lights).
    void merge(LoadedScene&& from, const glm::mat4& t, std::optional<std::uint32_t> material, LoadedScene& into) {
        const auto offset = static_cast<std::uint32_t>(into.scene.materials.size());
        if (!material)
            for (auto& m : from.scene.materials) into.scene.materials.push_back(std::move(m));
        for (Mesh& m : from.scene.meshes) {
            m.model = t * m.model;
            m.material = material ? *material : m.material + offset;
            into.scene.meshes.push_back(std::move(m));
        }
    }

    void meshes(const json& j, LoadedScene& s) {
        array(j, "meshes");
        for (std::size_t i = 0; i < j.size(); ++i) {
            const std::string where = "meshes[" + std::to_string(i) + "]";
            const json& m = j[i];
            const glm::mat4 t = m.contains("transform") ? transform(m["transform"], where + ".transform") : glm::mat4(1.0f);
            std::optional<std::uint32_t> material;
            if (m.contains("material")) material = materialRef(m["material"], where + ".material");
            if (m.contains("file")) {
                if (!m["file"].is_string()) fail(where + ".file", "expected a file name");
                merge(loadMeshFile(dir_ / m["file"].get<std::string>()), t, material, s);
            } else if (m.contains("builtin")) {
                if (!m["builtin"].is_string()) fail(where + ".builtin", "expected a built-in scene name");
                LoadedScene b = builtinScene(m["builtin"].get<std::string>());
                for (Light l : b.scene.lights) {
                    l.position = glm::vec3(t * glm::vec4(l.position, 1.0f));
                    l.direction = glm::mat3(t) * l.direction;
                    s.scene.lights.push_back(l);
                }
                merge(std::move(b), t, material, s);
            } else if (m.contains("positions")) {
                s.scene.meshes.push_back(inlineMesh(m, where, t, material.value_or(0)));
            } else {
                fail(where, "needs one of \"file\", \"builtin\" or \"positions\"");
            }
        }
    }

    Mesh inlineMesh(const json& m, const std::string& where, const glm::mat4& t, std::uint32_t material) {
        auto data = std::make_shared<MeshData>();
        const auto floats = [&](const char* key, int arity) {
            std::vector<float> v;
            if (!m.contains(key)) return v;
            const json& a = m[key];
            if (!a.is_array() || a.size() % static_cast<std::size_t>(arity) != 0)
                fail(where + "." + key, "expected a flat array with a multiple of " + std::to_string(arity) + " numbers");
            for (std::size_t i = 0; i < a.size(); ++i) v.push_back(number(a[i], where + "." + key + "[" + std::to_string(i) + "]"));
            return v;
        };
        const auto p = floats("positions", 3), n = floats("normals", 3);
        for (std::size_t i = 0; i < p.size(); i += 3) data->positions.emplace_back(p[i], p[i + 1], p[i + 2]);
        for (std::size_t i = 0; i < n.size(); i += 3) data->normals.emplace_back(n[i], n[i + 1], n[i + 2]);
        if (m.contains("indices")) {
            const json& idx = m["indices"];
            if (!idx.is_array()) fail(where + ".indices", "expected an array of integers");
            for (const auto& v : idx) {
                if (!v.is_number_unsigned()) fail(where + ".indices", "expected non-negative integers");
                data->indices.push_back(v.get<std::uint32_t>());
            }
        }
        Mesh mesh;
        mesh.data = std::move(data);
        mesh.model = t;
        mesh.material = material;
        return mesh;
    }

    Light light(const json& j, const std::string& where) const {
        Light l;
        const std::string type = j.value("type", "point");
        if (type == "point") l.type = LightType::Point;
        else if (type == "spot") l.type = LightType::Spot;
        else if (type == "directional") l.type = LightType::Directional;
        else if (type == "rect") l.type = LightType::Rect;
        else if (type == "sphere") l.type = LightType::Sphere;
        else fail(where + ".type", "expected \"point\", \"spot\", \"directional\", \"rect\" or \"sphere\"");
        if (j.contains("position")) l.position = vec3(j["position"], where + ".position");
        if (j.contains("direction")) l.direction = vec3(j["direction"], where + ".direction");
        if (j.contains("color")) l.color = colour(j["color"], where + ".color");
        if (j.contains("intensity")) l.intensity = number(j["intensity"], where + ".intensity");
        if (j.contains("radius")) l.radius = number(j["radius"], where + ".radius");
        if (j.contains("tangent")) l.tangent = vec3(j["tangent"], where + ".tangent");
        if (j.contains("size")) {
            const json& sz = j["size"];
            if (!sz.is_array() || sz.size() != 2) fail(where + ".size", "expected [width, height]");
            l.size = {positive(sz[0], where + ".size[0]"), positive(sz[1], where + ".size[1]")};
        }
        if (j.contains("inner_deg")) l.innerAngle = number(j["inner_deg"], where + ".inner_deg") * kDegrees;
        if (j.contains("outer_deg")) l.outerAngle = number(j["outer_deg"], where + ".outer_deg") * kDegrees;
        if (j.contains("casts_shadows")) {
            if (!j["casts_shadows"].is_boolean()) fail(where + ".casts_shadows", "expected true or false");
            l.castsShadows = j["casts_shadows"].get<bool>();
        }
        return l;
    }

    Environment environment(const json& j) const {
        Environment e;
        if (!j.contains("file") || !j["file"].is_string()) fail("environment.file", "expected a file name");
        e.path = (dir_ / j["file"].get<std::string>()).string();
        if (j.contains("intensity")) e.intensity = number(j["intensity"], "environment.intensity");
        if (j.contains("rotation_deg")) e.rotation = number(j["rotation_deg"], "environment.rotation_deg") * kDegrees;
        return e;
    }

    Medium medium(const json& j, const std::string& where) const {
        Medium m;
        m.boxMin = vec3(j.at("min"), where + ".min");
        m.boxMax = vec3(j.at("max"), where + ".max");
        if (j.contains("scattering")) m.scattering = colour(j["scattering"], where + ".scattering");
        if (j.contains("absorption")) m.absorption = colour(j["absorption"], where + ".absorption");
        if (j.contains("anisotropy")) m.anisotropy = number(j["anisotropy"], where + ".anisotropy");
        if (j.contains("phase")) {
            const std::string phase = j["phase"].is_string() ? j["phase"].get<std::string>() : "";
            if (phase == "isotropic") m.phase = PhaseFunction::Isotropic;
            else if (phase == "henyey_greenstein") m.phase = PhaseFunction::HenyeyGreenstein;
            else if (phase == "rayleigh") m.phase = PhaseFunction::Rayleigh;
            else if (phase == "schlick") m.phase = PhaseFunction::Schlick;
            else fail(where + ".phase", "expected \"isotropic\", \"henyey_greenstein\", \"rayleigh\" or \"schlick\"");
        }
        if (!(m.anisotropy > -1.0f && m.anisotropy < 1.0f)) fail(where + ".anisotropy", "must be in (-1, 1)");
        if (j.contains("density")) density(j["density"], where + ".density", m);
        return m;
    }

    // A grid from an EXR of z slices stacked top to bottom: width size.x, height size.y *
    // size.z; slice z is rows z * size.y to (z + 1) * size.y - 1, row j of it holding y = j;
    // channel 0.
    DensityGrid exrSlices(const std::filesystem::path& path, glm::ivec3 n, const std::string& where) const {
        const Image img = readImage(path);
        if (img.width != n.x || img.height != n.y * n.z)
            fail(where, path.string() + " is " + std::to_string(img.width) + "x" + std::to_string(img.height) +
                            "; slices of size [x, y, z] need x by y * z");
        DensityGrid g{n, std::vector<float>(std::size_t(n.x) * std::size_t(n.y) * std::size_t(n.z))};
        for (int z = 0; z < n.z; ++z)
            for (int y = 0; y < n.y; ++y)
                for (int x = 0; x < n.x; ++x)
                    g.values[(std::size_t(z) * std::size_t(n.y) + std::size_t(y)) * std::size_t(n.x) + std::size_t(x)] =
                        img.at(x, z * n.y + y, 0);
        return g;
    }

    // "density": {"type": "height", "falloff": k} | {"type": "grid", "size": [x, y, z],
    // "file": raw little-endian float32, x fastest, or an EXR of stacked z slices} |
    // {"type": "noise", "size": [x, y, z], "seed": n, "octaves": o}.
    void density(const json& j, const std::string& where, Medium& m) const {
        if (!j.is_object() || !j.contains("type") || !j["type"].is_string()) fail(where, "expected {\"type\": ...}");
        const std::string type = j["type"].get<std::string>();
        if (type == "height") {
            m.density = MediumDensity::Height;
            m.heightFalloff = number(j.at("falloff"), where + ".falloff");
            if (m.heightFalloff < 0.0f) fail(where + ".falloff", "must be >= 0 (1/world unit)");
            return;
        }
        if (type != "grid" && type != "noise") fail(where + ".type", "expected \"height\", \"grid\" or \"noise\"");
        const glm::vec3 size = vec3(j.at("size"), where + ".size");
        const glm::ivec3 n(size);
        if (glm::any(glm::notEqual(glm::vec3(n), size)) || glm::any(glm::lessThan(n, glm::ivec3(1))) ||
            glm::any(glm::greaterThan(n, glm::ivec3(1024))))
            fail(where + ".size", "expected three whole numbers in [1, 1024]");
        m.density = MediumDensity::Grid;
        if (type == "noise") {
            const std::uint32_t seed = j.contains("seed") ? j["seed"].get<std::uint32_t>() : 1u;
            const int octaves = j.contains("octaves") ? int(number(j["octaves"], where + ".octaves")) : 3;
            m.grid = std::make_shared<DensityGrid>(noiseDensityGrid(n, seed, std::clamp(octaves, 1, 8)));
            return;
        }
        const std::filesystem::path path = dir_ / j.at("file").get<std::string>();
        if (lowerExtension(path) == ".exr") {
            m.grid = std::make_shared<DensityGrid>(exrSlices(path, n, where + ".file"));
            return;
        }
        std::ifstream in(path, std::ios::binary);
        if (!in) fail(where + ".file", "cannot open " + path.string());
        DensityGrid g{n, std::vector<float>(std::size_t(n.x) * std::size_t(n.y) * std::size_t(n.z))};
        in.read(reinterpret_cast<char*>(g.values.data()), std::streamsize(g.values.size() * sizeof(float)));
        if (in.gcount() != std::streamsize(g.values.size() * sizeof(float)))
            fail(where + ".file", path.string() + " holds fewer than size.x * size.y * size.z float32 values");
        m.grid = std::make_shared<DensityGrid>(std::move(g));
    }

    CameraSpec camera(const json& j, CameraSpec c) const {
        if (j.contains("eye")) c.lookAt.eye = vec3(j["eye"], "camera.eye");
        if (j.contains("target")) c.lookAt.target = vec3(j["target"], "camera.target");
        if (j.contains("up")) c.lookAt.up = vec3(j["up"], "camera.up");
        if (j.contains("fovy_deg")) c.fovyDegrees = positive(j["fovy_deg"], "camera.fovy_deg");
        if (j.contains("near")) c.nearPlane = positive(j["near"], "camera.near");
        if (j.contains("far")) c.farPlane = positive(j["far"], "camera.far");
        return c;
    }

    std::filesystem::path file_, dir_;
    std::map<std::string, std::uint32_t> materialIndex_;
};

} // namespace

LoadedScene loadJsonScene(const std::filesystem::path& path) {
    std::ifstream in(path);
    if (!in) throw Error(ErrorCode::Io, "cannot open scene file " + path.string());
    json root;
    try {
        root = json::parse(in);
    } catch (const json::exception& e) {
        throw Error(ErrorCode::Parse, path.string() + ": " + e.what());
    }
    try {
        return Parser(path).parse(root);
    } catch (const json::exception& e) {
        throw Error(ErrorCode::Parse, path.string() + ": " + e.what());
    }
}

} // namespace obscura::assets
