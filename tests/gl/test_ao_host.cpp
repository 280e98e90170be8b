// Ambient occlusion in post-process mode: on a host's depth of every format and its normals an
// open plane stays open, and on a host's float depth layers and normals every method and
// thickness mode gives the G-buffer path's AO bit for bit; a host that renders with
// GL_UPPER_LEFT gets every method's AO in its own rows.
#include "ao_fixture.hpp"
#include "scene_builders.hpp"
#include "mirrored_view.hpp"

#include "obscura/assets.hpp"
#include "obscura/obscura.hpp"

#include <catch2/catch.hpp>

#include <map>
#include <tuple>
#include <vector>

using namespace obscura;
using test::AoFixture;
using test::AoVariant;
using test::floorScene;
using test::kAllVariants;
using test::lookAt;
using test::nameOf;

namespace {

// The open floor's AO through adopted host buffers (radius 2, 24 rays).
void checkAdoptedPlaneOpen(AoFixture& f, const GBufferView& adopted, const Scene& scene, const AoVariant& variant) {
    AmbientOcclusionSettings s = test::settingsOf(variant);
    s.radius = 2.0f;
    s.rays = 24;
    if (variant.method == AoMethod::Voxel) s.voxels = &f.voxelizer.voxelize(scene, {});
    test::checkOpenEverywhere(f, readTexture(f.ctx, f.ao.run(adopted, s).ao));
}

} // namespace

TEST_CASE("Post-process mode: on a host's 16-, 24- and 32-bit depth an open plane gives AO = 1", "[ao][host]") {
    // The host's depth pass leaves the floor's depth quantized to its format; the tangent-plane
    // tests allow for that precision (depthReconstructionError), so no method may find the
    // floor occluding itself. Standard depth with the near plane at 0.05: a 16-bit step is
    // 0.01 units of depth at the camera's distance, a 24-bit one 4e-5.
    AoFixture f;
    const Scene scene = floorScene();
    constexpr int W = 64, H = 48;
    const Camera camera = lookAt({0, 3, 6}, {0, 0, 0}, W, H);
    f.render(scene, camera, W, H);
    for (const GLenum format : {GL_DEPTH_COMPONENT32F, GL_DEPTH_COMPONENT24, GL_DEPTH_COMPONENT16})
        for (const bool hostNormals : {false, true}) {
            const GLuint depth = test::copyDepthAsHost(f.view.depth.name, W, H, format);
            HostGBuffer host;
            host.depth = {depth, format, W, H};
            if (hostNormals) host.normal = f.view.normal;
            GBuffer adopter(f.ctx);
            const GBufferView adopted = adopter.adopt(host, camera);
            for (const AoVariant variant : kAllVariants) {
                const AoMethod method = variant.method;
                CAPTURE(format, hostNormals, nameOf(method), static_cast<int>(variant.march));
                checkAdoptedPlaneOpen(f, adopted, scene, variant);
            }
            glDeleteTextures(1, &depth);
        }
    CHECK(test::drainGlErrors().empty());
}

TEST_CASE("Post-process mode: on a host's 8-, 10- and 16-bit normals an open plane gives AO = 1", "[ao][host]") {
    // The encodings tilt the floor's stored tangent plane by up to GBufferView::normalError
    // (adoptedNormalError), which adopt() reports and the screen tests allow for. Without
    // that (the G-buffer's own 2^-10 in its place) the horizon method found the floor above
    // its own plane on 2582 of 2944 pixels with 8-bit normals (AO 0.971) and on 141 with
    // 10-bit ones (0.9995), the ray march one ray of 24 on one pixel with 8-bit world-space
    // normals. Perspective, and the grazing orthographic view of the plane test above.
    AoFixture f;
    const Scene scene = floorScene();
    constexpr int W = 64, H = 48;
    const LookAt look{{0, 3, 6}, {0, 0, 0}, {0, 1, 0}};
    const Camera cameras[] = {lookAt(look.eye, look.target, W, H),
                              Camera::orthographic({{1, 1.5f, 5}, {0, 0, 0}, {0, 1, 0}}, 4.8f, float(W) / H, 0.05f, 100.0f)};
    for (int c = 0; c < 2; ++c) {
        const Camera& camera = cameras[c];
        f.render(scene, camera, W, H);
        const Image normals = readTexture(f.ctx, f.view.normal);
        const GLuint depth = test::copyDepthAsHost(f.view.depth.name, W, H, GL_DEPTH_COMPONENT32F);
        for (const GLenum format : {GL_RGBA8, GL_RGB10_A2, GL_RGBA16})
            for (const NormalSpace space : {NormalSpace::View, NormalSpace::World}) {
                const GLuint normal = test::hostNormalTexture(normals, camera, format, space);
                const HostGBuffer host = test::unsignedNormalHost(depth, normal, format, space, W, H);
                GBuffer adopter(f.ctx);
                const GBufferView adopted = adopter.adopt(host, camera);
                for (const AoVariant variant : kAllVariants) {
                    CAPTURE(c, format, static_cast<int>(space), nameOf(variant.method), static_cast<int>(variant.march));
                    checkAdoptedPlaneOpen(f, adopted, scene, variant);
                }
                glDeleteTextures(1, &normal);
            }
        glDeleteTextures(1, &depth);
    }
    CHECK(test::drainGlErrors().empty());
}

TEST_CASE("Post-process mode: on a host's 32-bit float depth layers and normals of an occluded scene every method "
          "and thickness mode gives the G-buffer path's AO bit for bit", "[ao][host]") {
    // The open plane above shows nothing is lost to a coarser host format; here the inputs are
    // the same values (the host's depth passes write 32-bit float depth exactly, its normals
    // are the G-buffer's texture), in a scene where most pixels are occluded: adoption must
    // give every method, thickness mode, resolution and output the same numbers, so that
    // post-process mode computes what the bench measures. The host's second depth layer
    // (HostGBuffer::backDepth) must also change what the peeling modes find, or it was not read.
    AoFixture f;
    const assets::LoadedScene cornell = assets::builtinScene("cornell");
    constexpr int W = 48, H = 40;
    const Camera camera = test::cornellCamera(W, H);
    f.render(cornell.scene, camera, W, H, 2);
    const GLuint depth = test::copyDepthAsHost(f.view.depth.name, W, H, GL_DEPTH_COMPONENT32F);
    const GLuint back = test::copyDepthAsHost(f.view.backDepth.name, W, H, GL_DEPTH_COMPONENT32F);
    HostGBuffer host;
    host.depth = {depth, GL_DEPTH_COMPONENT32F, W, H};
    host.normal = f.view.normal;
    host.backDepth = {back, 0, 0, 0}; // format and size as GL reports them
    GBuffer adopter(f.ctx);
    GBufferView adopted = adopter.adopt(host, camera);
    CHECK(adopted.backDepth.name == back);
    CHECK(adopted.backDepth.internalFormat == GL_DEPTH_COMPONENT32F);
    CHECK((adopted.backDepth.width == W && adopted.backDepth.height == H));
    // adopt() must assume a host's 16-bit float normals were rounded before its own store
    // (adoptedNormalError: 2^-9); these are the G-buffer's, rounded once.
    CHECK(adopted.normalError == adoptedNormalError(NormalEncoding::Signed, 16));
    adopted.normalError = f.view.normalError;
    std::vector<AoVariant> variants(std::begin(kAllVariants), std::end(kAllVariants)); // Constant first
    for (const ScreenThickness peeled : {ScreenThickness::DepthPeeling, ScreenThickness::PeelingOrConstant}) {
        for (const ScreenMarch march : {ScreenMarch::View, ScreenMarch::Texture, ScreenMarch::HiZ})
            variants.push_back({AoMethod::RayMarch, march, peeled});
        variants.push_back({AoMethod::Points, ScreenMarch::View, peeled});
    }
    std::map<std::tuple<AoMethod, ScreenMarch, AoResolution>, std::vector<float>> constantAo;
    for (const AoVariant variant : variants)
        for (const AoResolution resolution : {AoResolution::Full, AoResolution::Half}) {
            CAPTURE(nameOf(variant.method), static_cast<int>(variant.march), static_cast<int>(variant.thickness),
                    static_cast<int>(resolution));
            AmbientOcclusionSettings s = test::settingsOf(variant);
            // The peeling-or-constant case with a slab below the blocks' size, so that it
            // differs from the constant too.
            if (variant.thickness == ScreenThickness::PeelingOrConstant) s.thickness = 15.0f;
            s.radius = 150.0f;
            s.rays = 16;
            s.resolution = resolution;
            s.blurRadius = resolution == AoResolution::Full ? 0 : 2;
            s.bentNormals = true;
            if (variant.method == AoMethod::Voxel) s.voxels = &f.voxelizer.voxelize(cornell.scene, {});
            const AmbientOcclusionView own = f.ao.run(f.view, s);
            const Image ownAo = readTexture(f.ctx, own.ao);
            const Image ownBent = s.bentNormals ? readTexture(f.ctx, own.bentNormal) : Image{};
            const AmbientOcclusionView post = f.ao.run(adopted, s);
            const Image postAo = readTexture(f.ctx, post.ao);
            int occluded = 0;
            for (float v : ownAo.pixels) occluded += v < 0.9f;
            // An open scene would only repeat the plane test (no pixel below 1). A quarter, and
            // an eighth for the peeling modes: the points with peeling or a 15-unit slab find
            // the fewest, about a fifth.
            CHECK(occluded > W * H / (variant.thickness == ScreenThickness::Constant ? 4 : 8));
            CHECK(postAo.pixels == ownAo.pixels);
            if (s.bentNormals) CHECK(readTexture(f.ctx, post.bentNormal).pixels == ownBent.pixels);
            const auto key = std::tuple{variant.method, variant.march, resolution};
            if (variant.thickness == ScreenThickness::Constant) {
                constantAo[key] = ownAo.pixels;
            } else {
                REQUIRE(constantAo.count(key) == 1);
                CHECK(postAo.pixels != constantAo[key]);
            }
        }
    glDeleteTextures(1, &depth);
    glDeleteTextures(1, &back);
    CHECK(test::drainGlErrors().empty());
}

TEST_CASE("Post-process mode: a host that renders with GL_UPPER_LEFT and passes its projection mirrored in y gets "
          "every method's AO mirrored", "[ao][host]") {
    // glClipControl(GL_UPPER_LEFT) stores a host's rows top down. Such a host passes its
    // projection with row 1 negated (camera.hpp), which maps its rows to Obscura's bottom-up
    // ones. Every method must then see the scene as from the unmirrored camera: row y of its
    // AO is row H - 1 - y of the unmirrored AO but for sampling noise, since each pixel
    // rotates its samples by its own texel of the 64 x 64 noise texture (the two are
    // different estimates of one value); checkMirroredLikeBaselines says against what. The
    // Cornell box is not symmetric top to bottom (floor, blocks, ceiling light): the horizon
    // method with slices walked in unmirrored screen directions was 12.7 (full) and 3.4 (half
    // resolution) times its baseline off. Then the same with the G-buffer's own projection
    // mirrored in x (no clip origin does that, but the methods take either axis), where the
    // columns are compared; the box's red and green walls differ only in colour, but its
    // blocks stand off centre (the unmirrored horizon slices: 10.4 and 2.6 times off).
    AoFixture f;
    const assets::LoadedScene cornell = assets::builtinScene("cornell");
    constexpr int W = 48, H = 40;
    const Camera camera = test::cornellCamera(W, H);
    const Camera mirrored = test::mirrored(camera, 1);
    f.render(cornell.scene, camera, W, H);
    GBuffer shiftedGBuffer(f.ctx);
    const GBufferView shifted = shiftedGBuffer.render(cornell.scene, test::shiftedOnePixel(camera, W), {W, H, false, {}});
    const Image shiftedPositions = readTexture(f.ctx, shiftedGBuffer.positions(shifted));
    // The host's depth is rasterized with GL_UPPER_LEFT and the unmirrored projection, its
    // normals are the G-buffer's with the mirrored projection (the same view-space normals).
    GBuffer mirroredGBuffer(f.ctx);
    const GBufferView mirroredOwn = mirroredGBuffer.render(cornell.scene, mirrored, {W, H, false, {}});
    const GLuint depth = test::rasterizeDepthAsHost(cornell.scene, camera, W, H, GL_DEPTH_COMPONENT32F, GL_UPPER_LEFT);
    // GL_UPPER_LEFT negates y_ndc in the viewport transform, so the host's depth is what the
    // mirrored projection rasterizes, with the same coverage. Float rounding aside: llvmpipe
    // interpolates the two in a different order (322 of the 1920 texels 1 or 2 ulp apart, at
    // most 1.2e-7).
    const Image hostDepth = readTexture(f.ctx, {depth, GL_DEPTH_COMPONENT32F, W, H});
    const Image mirroredDepth = readTexture(f.ctx, mirroredOwn.depth);
    double worst = 0.0;
    std::size_t coverageDiffers = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            worst = std::max(worst, std::abs(double(hostDepth.at(x, y, 0)) - double(mirroredDepth.at(x, y, 0))));
            coverageDiffers += f.geometry(x, y) != (hostDepth.at(x, H - 1 - y, 0) < 1.0f);
        }
    CHECK(worst <= 4.0 * std::ldexp(1.0, -24)); // 4 ulp of depths in [0.5, 1)
    CHECK(coverageDiffers == 0);
    HostGBuffer host;
    host.depth = {depth, GL_DEPTH_COMPONENT32F, W, H};
    host.normal = mirroredOwn.normal;
    GBuffer adopter(f.ctx), mirroredInX(f.ctx);
    const GBufferView views[2] = {mirroredInX.render(cornell.scene, test::mirrored(camera, 0), {W, H, false, {}}),
                                  adopter.adopt(host, mirrored)};
    for (const int axis : {1, 0}) {
        const GBufferView& mirroredView = views[axis];
        for (const AoVariant variant : kAllVariants) {
            CAPTURE(axis, nameOf(variant.method), static_cast<int>(variant.march));
            AmbientOcclusionSettings s = test::settingsOf(variant);
            s.radius = 150.0f;
            s.rays = 32;
            s.bentNormals = true;
            if (variant.method == AoMethod::Voxel) s.voxels = &f.voxelizer.voxelize(cornell.scene, {});
            // AO and bent normal (view space, which the mirrored projection shares) of each run.
            const auto run = [&](const GBufferView& view) {
                const AmbientOcclusionView out = f.ao.run(view, s);
                return std::pair{readTexture(f.ctx, out.ao), readTexture(f.ctx, out.bentNormal)};
            };
            const auto full = run(f.view), shiftedFull = run(shifted), mirroredFull = run(mirroredView);
            s.resolution = AoResolution::Half;
            s.blurRadius = 2;
            const auto half = run(f.view), mirroredHalf = run(mirroredView);
            double lowest = 1.0;
            for (float a : full.first.pixels) lowest = std::min(lowest, double(a));
            CHECK(lowest < 0.5); // the box's corners and the blocks' feet are occluded
            test::checkMirroredLikeBaselines(test::mirroredDifferences(f.positions, shiftedPositions, 1, full.first,
                                                                       mirroredFull.first, shiftedFull.first, half.first,
                                                                       mirroredHalf.first, axis));
            test::checkMirroredLikeBaselines(test::mirroredDifferences(f.positions, shiftedPositions, 3, full.second,
                                                                       mirroredFull.second, shiftedFull.second,
                                                                       half.second, mirroredHalf.second, axis));
        }
    }
    glDeleteTextures(1, &depth);
    CHECK(test::drainGlErrors().empty());
}
