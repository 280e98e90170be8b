// Host shading normals at silhouettes. A smooth (vertex-normal) sphere's interpolated normal
// may face a little away from the camera where the sphere's outline is; turned around, as
// adopt() once did, it points into the sphere, and AO there was about 0.004 (one to three
// black dots per frame). adopt() now bends such a normal just enough to face the camera, and
// still turns a back face's normal (a two-sided surface seen from behind) around.
#include "ao_fixture.hpp"

#include "obscura/obscura.hpp"

#include <catch2/catch.hpp>

#include <cmath>

using namespace obscura;
using test::AoFixture;

namespace {

// An icosphere of radius 1 whose vertex normals are its positions (smooth shading): at two
// subdivisions (320 faces) a vertex normal is up to about 10 degrees off its faces' normals.
Scene smoothSphere() {
    auto mesh = std::make_shared<MeshData>(*test::icosphereMesh(2));
    mesh->normals = mesh->positions;
    return test::singleMeshScene(mesh, glm::mat4(1.0f));
}

// The largest angle between a face's normal and the vertex normals of its corners, radians:
// interpolated normals lie within it (they are normalized blends of those corners').
float largestShadingDeviation(const MeshData& mesh) {
    float largest = 0.0f;
    for (std::size_t i = 0; i < mesh.indices.size(); i += 3) {
        const glm::vec3 a = mesh.positions[mesh.indices[i]], b = mesh.positions[mesh.indices[i + 1]],
                        c = mesh.positions[mesh.indices[i + 2]];
        const glm::vec3 face = glm::normalize(glm::cross(b - a, c - a));
        for (int k = 0; k < 3; ++k) {
            const glm::vec3 n = glm::normalize(mesh.normals[mesh.indices[i + std::size_t(k)]]);
            largest = std::max(largest, std::acos(glm::clamp(glm::dot(n, face), -1.0f, 1.0f)));
        }
    }
    return largest;
}

glm::vec3 texel(const Image& image, int x, int y) { return {image.at(x, y, 0), image.at(x, y, 1), image.at(x, y, 2)}; }

} // namespace

TEST_CASE("Host shading normals past a silhouette are bent to face the camera, not turned into the surface",
          "[ao][host]") {
    // What a normal costs a method: its AO with the host's shading normals against its AO on
    // Obscura's own G-buffer of the same mesh, whose face normals are what every method is
    // built for (the reference, AO 1 on a convex surface, differs from that by the method's own
    // error at the outline, which is not this test's business). With a normal tilted by delta
    // from the face's, a method counts as hidden at most the directions between the two
    // tangent planes: their cosine-weighted share is sin(delta) / 2 (projected onto the tilted
    // normal's disc, where cosine-weighted directions are uniform, the wedge is half an
    // ellipse of semi-axes 1 and sin(delta): area pi sin(delta) / 2 of pi). delta comes from
    // the inputs: an interpolated normal lies within the mesh's largest angle between a face
    // and its corners' normals of its face, and a bent one within that plus the bend the
    // host's normal needs to face the camera by 1/64. A pixel's tolerance is that share, plus
    // the discrepancy of the method's N directions from the integral (the wedge's two boundary
    // curves, each ray near them on either side: 4/N), plus the R16F store's 2^-11. The host
    // declares how far its normals lie off the faces around them (HostGBuffer::normalDeviation:
    // twice that largest angle, as the header advises); without it the ray march's own
    // neighbours hid rays along the outline (20 pixels, AO 0.22 where the face normals give
    // 0.97), and with the angle once, not twice, 11 pixels by up to 0.14.
    AoFixture f;
    const Scene scene = smoothSphere();
    constexpr int W = 96, H = 72;
    const Camera camera = test::lookAt({0.0f, 0.6f, 3.2f}, {0.0f, 0.0f, 0.0f}, W, H);
    f.render(scene, camera, W, H);
    const test::HostShadingBuffers host = test::rasterizeShadingNormalsAsHost(scene, camera, W, H);
    HostGBuffer buffers;
    buffers.depth = {host.depth, GL_DEPTH_COMPONENT32F, W, H};
    buffers.normal = {host.normal, GL_RGBA16F, W, H};
    const float deviation = largestShadingDeviation(*scene.meshes[0].data);
    buffers.normalDeviation = 2.0f * deviation;
    GBuffer adopter(f.ctx);
    const GBufferView adopted = adopter.adopt(buffers, camera);
    const Image shading = readTexture(f.ctx, {host.normal, GL_RGBA16F, W, H});
    const Image faces = readTexture(f.ctx, f.view.normal);
    const Image bent = readTexture(f.ctx, adopted.normal);

    int facingAway = 0, pixels = 0;
    Image tolerance = faces;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            if (!f.geometry(x, y)) continue;
            ++pixels;
            const glm::vec3 toCamera = -glm::normalize(glm::vec3(f.positions.at(x, y, 0), f.positions.at(x, y, 1),
                                                                  f.positions.at(x, y, 2)));
            const glm::vec3 given = texel(shading, x, y), stored = texel(bent, x, y);
            const float facing = glm::dot(given, toCamera);
            CAPTURE(x, y, facing);
            CHECK(glm::dot(stored, toCamera) > 0.0f);
            // Bent just enough: to dot(n, toward camera) = 1/64, in the plane of the given normal
            // and the view ray (each within the half-float store's 2^-10 and more).
            const float bend = facing < 0.0f ? std::asin(1.0f / 64.0f) - std::asin(facing) : 0.0f;
            if (facing < 0.0f) {
                ++facingAway;
                CHECK(std::abs(glm::dot(stored, toCamera) - 1.0f / 64.0f) <= 1.0f / 512.0f);
                CHECK(std::abs(glm::dot(stored, glm::normalize(glm::cross(given, toCamera)))) <= 1.0f / 512.0f);
            }
            tolerance.at(x, y, 0) = 0.5f * std::sin(std::min(deviation + bend, 1.5707964f));
        }
    INFO(facingAway << " of " << pixels << " sphere pixels have a shading normal facing away from the camera");
    REQUIRE(facingAway > 0); // the case under test occurs

    constexpr int kRays = 32;
    for (const AoMethod method : {AoMethod::RayMarch, AoMethod::Points, AoMethod::Horizon})
        for (const AoResolution resolution : {AoResolution::Full, AoResolution::Half}) {
            AmbientOcclusionSettings s;
            s.method = method;
            s.resolution = resolution;
            s.radius = 0.5f;
            s.rays = kRays;
            s.steps = 16;
            CAPTURE(static_cast<int>(method), static_cast<int>(resolution));
            const Image own = f.run(scene, s);
            const Image ao = readTexture(f.ctx, f.ao.run(adopted, s).ao);
            int below = 0;
            double worst = 0.0;
            for (int y = 0; y < H; ++y)
                for (int x = 0; x < W; ++x) {
                    if (!f.geometry(x, y)) continue;
                    const double allowed = tolerance.at(x, y, 0) + 4.0 / kRays + 1.0 / 2048.0;
                    const double deficit = own.at(x, y, 0) - ao.at(x, y, 0);
                    worst = std::max(worst, deficit - allowed);
                    below += deficit > allowed;
                }
            INFO(below << " pixels darker than with face normals by more than their tolerance; the worst by " << worst);
            CHECK(below == 0);
        }
    glDeleteTextures(1, &host.depth);
    glDeleteTextures(1, &host.normal);
    CHECK(test::drainGlErrors().empty());
}

TEST_CASE("A back face's host normal, drawn two-sided, is turned toward the camera", "[ao][host]") {
    // A floor seen from below with its normals up (the host draws it two-sided): every normal
    // faces away from the camera and the depth's plane lies on its other side, so adopt()
    // turns it around (-n exactly), as before bending existed.
    AoFixture f;
    auto mesh = std::make_shared<MeshData>();
    mesh->positions = {{-5, 0, -5}, {5, 0, -5}, {5, 0, 5}, {-5, 0, -5}, {5, 0, 5}, {-5, 0, 5}};
    mesh->normals.assign(6, glm::vec3(0, 1, 0));
    const Scene scene = test::singleMeshScene(mesh, glm::mat4(1.0f));
    constexpr int W = 48, H = 36;
    const Camera camera = test::lookAt({0.5f, -2.0f, 3.0f}, {0.0f, 0.0f, 0.0f}, W, H);
    f.render(scene, camera, W, H);
    const test::HostShadingBuffers host = test::rasterizeShadingNormalsAsHost(scene, camera, W, H);
    HostGBuffer buffers;
    buffers.depth = {host.depth, GL_DEPTH_COMPONENT32F, W, H};
    buffers.normal = {host.normal, GL_RGBA16F, W, H};
    GBuffer adopter(f.ctx);
    const Image adopted = readTexture(f.ctx, adopter.adopt(buffers, camera).normal);
    const glm::vec3 down = glm::mat3(camera.view) * glm::vec3(0, -1, 0);
    int pixels = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            if (!f.geometry(x, y)) continue;
            ++pixels;
            CAPTURE(x, y);
            CHECK(glm::dot(texel(adopted, x, y), down) > 1.0f - 1.0f / 512.0f);
        }
    CHECK(pixels > W * H / 4);
    glDeleteTextures(1, &host.depth);
    glDeleteTextures(1, &host.normal);
    CHECK(test::drainGlErrors().empty());
}
