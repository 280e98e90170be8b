#include "reference/ray_scene_impl.hpp"

#include "obscura/error.hpp"
#include "reference/hash.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace obscura::reference {
namespace {

float toEmbree(double t) {
    return t >= static_cast<double>(std::numeric_limits<float>::max()) ? std::numeric_limits<float>::infinity()
                                                                       : static_cast<float>(t);
}

void fillRay(RTCRay& ray, const glm::vec3& o, const glm::dvec3& d, double tfar) {
    ray.org_x = o.x;
    ray.org_y = o.y;
    ray.org_z = o.z;
    ray.dir_x = static_cast<float>(d.x);
    ray.dir_y = static_cast<float>(d.y);
    ray.dir_z = static_cast<float>(d.z);
    ray.tnear = 0.0f;
    ray.tfar = toEmbree(tfar);
    ray.time = 0.0f;
    ray.mask = 0xFFFFFFFFu;
    ray.id = 0;
    ray.flags = 0;
}

double srgbToLinear(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

// Bilinear, repeating, like the G-buffer's sampler at magnification. Rows are stored top
// first and uploaded flipped, so texcoord v = 0 is the bottom row.
glm::dvec3 sampleTexture(const TextureImage& img, glm::dvec2 uv) {
    const double x = (uv.x - std::floor(uv.x)) * img.width - 0.5;
    const double y = (1.0 - (uv.y - std::floor(uv.y))) * img.height - 0.5;
    const auto x0 = static_cast<int>(std::floor(x)), y0 = static_cast<int>(std::floor(y));
    const double fx = x - x0, fy = y - y0;
    glm::dvec3 result(0.0);
    for (int dy = 0; dy <= 1; ++dy)
        for (int dx = 0; dx <= 1; ++dx) {
            const int xi = ((x0 + dx) % img.width + img.width) % img.width;
            const int yi = ((y0 + dy) % img.height + img.height) % img.height;
            const std::uint8_t* px = &img.rgba[(static_cast<std::size_t>(yi) * img.width + xi) * 4];
            const double w = (dx ? fx : 1.0 - fx) * (dy ? fy : 1.0 - fy);
            for (int c = 0; c < 3; ++c) result[c] += w * srgbToLinear(px[c] / 255.0);
        }
    return result;
}

std::uint64_t hashScene(const Scene& s) {
    detail::Hasher h;
    // Bump the version whenever an estimator changes: cached references are then rendered again.
    h.add(std::string_view("obscura.reference.scene.v2"));
    for (const Mesh& m : s.meshes) {
        h.add(m.model).add(m.material);
        h.add(m.data->positions.size());
        h.bytes(m.data->positions.data(), m.data->positions.size() * sizeof(glm::vec3));
        h.bytes(m.data->indices.data(), m.data->indices.size() * sizeof(std::uint32_t));
        h.bytes(m.data->texcoords.data(), m.data->texcoords.size() * sizeof(glm::vec2));
        h.bytes(m.data->normals.data(), m.data->normals.size() * sizeof(glm::vec3));
    }
    for (const Material& m : s.materials) {
        h.add(m.albedo).add(m.emission);
        if (m.albedoImage) {
            h.add(m.albedoImage->width).add(m.albedoImage->height);
            h.bytes(m.albedoImage->rgba.data(), m.albedoImage->rgba.size());
        }
    }
    for (const Light& l : s.lights)
        h.add(l.type).add(l.color).add(l.intensity).add(l.position).add(l.direction).add(l.tangent).add(l.size)
            .add(l.innerAngle).add(l.outerAngle).add(l.radius);
    for (const Medium& m : s.media) {
        h.add(m.boxMin).add(m.boxMax).add(m.scattering).add(m.absorption).add(m.phase).add(m.anisotropy);
        h.add(m.density).add(m.heightFalloff);
        if (m.grid) {
            h.add(m.grid->size);
            for (float v : m.grid->values) h.add(v);
        }
    }
    if (s.environment) h.add(std::string_view(s.environment->path)).add(s.environment->intensity).add(s.environment->rotation);
    return h.value();
}

} // namespace

RayScene::RayScene(const Scene& scene) : impl_(std::make_unique<Impl>()) {
    validateScene(scene);
    if (!scene.meshRefs.empty())
        throw Error(ErrorCode::InvalidArgument, "the reference needs the triangles on the CPU: Scene::meshRefs (host GPU "
                                                "buffers) cannot be ray traced; pass them as Scene::meshes");
    for (std::size_t i = 0; i < scene.materials.size(); ++i)
        if (scene.materials[i].albedoTexture != 0 && !scene.materials[i].albedoImage)
            throw Error(ErrorCode::InvalidArgument, "Scene::materials[" + std::to_string(i) + "].albedoTexture is a host GL "
                                                    "texture the reference cannot read: give Material::albedoImage too");
    auto& d = *impl_;
    d.scene = scene;
    d.device.reset(rtcNewDevice(nullptr));
    if (!d.device) throw Error(ErrorCode::UnsupportedFeature, "Embree: rtcNewDevice failed");
    d.rtcScene.reset(rtcNewScene(d.device.get()));
    d.rtc = d.rtcScene.get();
    rtcSetSceneFlags(d.rtc, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(d.rtc, RTC_BUILD_QUALITY_HIGH);
    for (const Mesh& mesh : scene.meshes) {
        const MeshData& m = *mesh.data;
        const std::size_t count = (m.indices.empty() ? m.positions.size() : m.indices.size()) / 3;
        if (count == 0) continue;
        RTCGeometry geometry = rtcNewGeometry(d.device.get(), RTC_GEOMETRY_TYPE_TRIANGLE);
        auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                              3 * sizeof(float), m.positions.size()));
        const glm::dmat4 model(mesh.model);
        Impl::MeshRecord record;
        record.positions.reserve(m.positions.size());
        for (std::size_t i = 0; i < m.positions.size(); ++i) {
            const glm::vec3 w(model * glm::dvec4(glm::dvec3(m.positions[i]), 1.0));
            record.positions.push_back(w);
            v[3 * i] = w.x;
            v[3 * i + 1] = w.y;
            v[3 * i + 2] = w.z;
            if (d.bounds.empty) {
                d.bounds = {w, w, false};
            } else {
                d.bounds.min = glm::min(d.bounds.min, w);
                d.bounds.max = glm::max(d.bounds.max, w);
            }
        }
        record.indices = m.indices;
        if (record.indices.empty())
            for (std::uint32_t i = 0; i < m.positions.size(); ++i) record.indices.push_back(i);
        auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                    3 * sizeof(unsigned), count));
        std::copy(record.indices.begin(), record.indices.end(), idx);
        record.texcoords = m.texcoords;
        const glm::dmat3 normalMatrix = glm::transpose(glm::inverse(glm::dmat3(model)));
        for (const glm::vec3& n : m.normals) record.normals.emplace_back(normalMatrix * glm::dvec3(n));
        record.material = mesh.material;
        rtcCommitGeometry(geometry);
        const unsigned id = rtcAttachGeometry(d.rtc, geometry);
        rtcReleaseGeometry(geometry);
        if (d.meshes.size() <= id) d.meshes.resize(id + 1);
        d.meshes[id] = std::move(record);
        d.triangles += count;
    }
    rtcCommitScene(d.rtc);
    if (rtcGetDeviceError(d.device.get()) != RTC_ERROR_NONE)
        throw Error(ErrorCode::InvalidState, "Embree reported an error while building the scene");
    const glm::dvec3 extent = glm::max(glm::abs(glm::dvec3(d.bounds.min)), glm::abs(glm::dvec3(d.bounds.max)));
    d.floatError = d.bounds.empty ? 0.0 : std::ldexp(std::max({extent.x, extent.y, extent.z}), -20);
    if (scene.environment) d.environment = std::make_unique<detail::EnvironmentMap>(*scene.environment);
    // The environment by content, not by file name: a changed file is a different scene.
    d.hash = detail::Hasher().add(hashScene(scene)).add(d.environment ? d.environment->contentHash() : 0).value();
}

RayScene::~RayScene() = default;

const Scene& RayScene::scene() const noexcept { return impl_->scene; }
Bounds RayScene::bounds() const noexcept { return impl_->bounds; }
std::size_t RayScene::triangleCount() const noexcept { return impl_->triangles; }
std::uint64_t RayScene::contentHash() const noexcept { return impl_->hash; }

std::optional<Hit> RayScene::Impl::intersect(const glm::vec3& origin, const glm::dvec3& direction, double tfar,
                                             double tnear) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh;
    fillRay(rh.ray, origin, direction, tfar);
    rh.ray.tnear = static_cast<float>(tnear);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(rtc, &context, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
    Hit h;
    h.distance = rh.ray.tfar;
    h.normal = glm::normalize(glm::dvec3(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z));
    h.geometry = rh.hit.geomID;
    h.primitive = rh.hit.primID;
    h.u = rh.hit.u;
    h.v = rh.hit.v;
    return h;
}

bool RayScene::Impl::occluded(const glm::vec3& origin, const glm::dvec3& direction, double tfar) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay ray;
    fillRay(ray, origin, direction, tfar);
    rtcOccluded1(rtc, &context, &ray);
    return ray.tfar < 0.0f; // Embree sets tfar to -inf on occlusion
}

glm::dvec3 RayScene::Impl::albedo(const Hit& hit) const {
    const MeshRecord& m = meshes[hit.geometry];
    const Material& material = scene.materials[m.material];
    glm::dvec3 a(material.albedo);
    if (material.albedoImage && !m.texcoords.empty()) {
        const std::uint32_t* tri = &m.indices[3 * static_cast<std::size_t>(hit.primitive)];
        const glm::dvec2 uv = (1.0 - hit.u - hit.v) * glm::dvec2(m.texcoords[tri[0]]) + hit.u * glm::dvec2(m.texcoords[tri[1]]) +
                              hit.v * glm::dvec2(m.texcoords[tri[2]]);
        a *= sampleTexture(*material.albedoImage, uv);
    }
    return glm::clamp(a, glm::dvec3(0.0), glm::dvec3(1.0));
}

glm::dvec3 RayScene::Impl::shadingNormal(const Hit& hit, const glm::dvec3& geometric) const {
    const MeshRecord& m = meshes[hit.geometry];
    if (m.normals.empty()) return geometric;
    const std::uint32_t* tri = &m.indices[3 * static_cast<std::size_t>(hit.primitive)];
    const glm::dvec3 n = (1.0 - hit.u - hit.v) * glm::dvec3(m.normals[tri[0]]) + hit.u * glm::dvec3(m.normals[tri[1]]) +
                         hit.v * glm::dvec3(m.normals[tri[2]]);
    const double len = glm::length(n);
    if (!(len > 0.0) || !std::isfinite(len)) return geometric; // as the G-buffer falls back
    return glm::dot(n, geometric) < 0.0 ? -n / len : n / len;
}

glm::dvec3 RayScene::Impl::emission(const Hit& hit, const glm::dvec3& toward) const {
    const MeshRecord& m = meshes[hit.geometry];
    const std::uint32_t* tri = &m.indices[3 * static_cast<std::size_t>(hit.primitive)];
    const glm::dvec3 p0(m.positions[tri[0]]), p1(m.positions[tri[1]]), p2(m.positions[tri[2]]);
    const bool front = glm::dot(glm::cross(p1 - p0, p2 - p0), toward) > 0.0;
    return front ? glm::dvec3(scene.materials[m.material].emission) : glm::dvec3(0.0);
}

} // namespace obscura::reference
