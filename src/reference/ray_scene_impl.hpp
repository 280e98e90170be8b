#pragma once
// Internals of RayScene shared by the integrators: Embree queries and surface attributes.
#include "obscura/reference.hpp"
#include "reference/environment.hpp"

#include <embree3/rtcore.h>

#include <memory>
#include <optional>
#include <vector>

namespace obscura::reference {

struct Hit {
    double distance = 0.0;
    glm::dvec3 normal{0.0}; //!< unit geometric normal, as wound
    unsigned geometry = 0, primitive = 0;
    double u = 0.0, v = 0.0; //!< barycentrics of vertices 1 and 2
};

struct RayScene::Impl {
    struct MeshRecord {
        std::vector<glm::vec3> positions; //!< world space, as given to Embree
        std::vector<glm::vec2> texcoords; //!< empty when the mesh has none
        std::vector<glm::vec3> normals;   //!< world-space vertex normals; empty when the mesh has none
        std::vector<std::uint32_t> indices;
        std::uint32_t material = 0;
    };

    struct DeviceDeleter {
        void operator()(RTCDeviceTy* d) const { rtcReleaseDevice(d); }
    };
    struct SceneDeleter {
        void operator()(RTCSceneTy* s) const { rtcReleaseScene(s); }
    };

    Scene scene;
    // Declared in this order so the scene is released before its device, also when the
    // constructor throws half-way.
    std::unique_ptr<RTCDeviceTy, DeviceDeleter> device;
    std::unique_ptr<RTCSceneTy, SceneDeleter> rtcScene;
    RTCScene rtc = nullptr; //!< rtcScene.get(), for the queries
    std::vector<MeshRecord> meshes; //!< by Embree geometry id
    Bounds bounds;
    //! 2^-20 of the largest coordinate magnitude in the scene: the float error of a
    //! ray/triangle intersection is relative to the triangle's coordinates, so every ray
    //! origin is lifted off its surface at least this much (see offsetOrigin).
    double floatError = 0.0;
    std::size_t triangles = 0;
    std::uint64_t hash = 0;
    std::unique_ptr<detail::EnvironmentMap> environment;

    //! Nearest hit in (tnear, tfar) along `direction` (unit) from `origin`.
    std::optional<Hit> intersect(const glm::vec3& origin, const glm::dvec3& direction, double tfar,
                                 double tnear = 0.0) const;
    //! Whether anything lies in (0, tfar) along the ray.
    bool occluded(const glm::vec3& origin, const glm::dvec3& direction, double tfar) const;
    glm::dvec3 albedo(const Hit& hit) const;
    //! The interpolated vertex normal (what the G-buffer shades with), on the side of
    //! `geometric` (the geometric normal already turned toward the viewer); `geometric`
    //! itself for meshes without normals.
    glm::dvec3 shadingNormal(const Hit& hit, const glm::dvec3& geometric) const;
    //! The radiance the hit's material emits toward `toward` (a direction away from the
    //! surface): its emission on the triangle's front side (Material::emission), else 0.
    glm::dvec3 emission(const Hit& hit, const glm::dvec3& toward) const;
};

} // namespace obscura::reference
