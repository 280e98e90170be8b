// The voxelizer against the CPU reference voxelizations (tier 3), its mipmaps against CPU
// OR-reductions, and its robustness and caching (tier 4).
#include "gl_fixture.hpp"
#include "scene_builders.hpp"
#include "voxel_checks.hpp"

#include "obscura/assets.hpp"
#include "obscura/obscura.hpp"
#include "obscura/reference.hpp"

#include <catch2/catch.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <random>

using namespace obscura;
using test::countSet;

namespace {

const std::string kModels = OBSCURA_ASSIMP_MODELS;

VoxelizerSettings surfaceSettings(int resolution, int targets = 1) {
    VoxelizerSettings s;
    s.resolution = resolution;
    s.targets = targets;
    return s;
}

// The GPU surface voxelization contains every voxel of the CPU one (its triangles overlap
// them exactly), and every voxel it adds is one that a triangle misses by less than the
// shader's growth of the box against float rounding: 1e-5 + 2^-21 E voxel for a triangle of
// extent E, E at most the grid's largest dimension (the CPU bound uses twice that). On real
// models that adds fewer than 1 % (`fewExtras`); on scenes built from round numbers, whose
// triangles pass exactly through voxel edges, it may add more.
void checkConservativeSuperset(const DenseVoxels& gpu, const Scene& scene, const VoxelGrid& grid,
                               bool fewExtras = true) {
    const DenseVoxels exact = reference::voxelizeSurface(scene, grid);
    const int largest = std::max({grid.dims.x, grid.dims.y, grid.dims.z});
    const double grow = 2.0 * (1e-5 + std::ldexp(static_cast<double>(largest), -21));
    const test::VoxelDiff d = test::compareVoxels(gpu, exact);
    const test::VoxelDiff beyond = test::compareVoxels(gpu, reference::voxelizeSurface(scene, grid, grow));
    INFO("CPU " << d.expected << " voxels, GPU " << d.actual << ", missing " << d.missing << ", extra " << d.extra
                << ", extra beyond " << grow << " voxel " << beyond.extra);
    CHECK(d.expected > 0);
    CHECK(d.missing == 0);
    CHECK(beyond.extra == 0);
    if (fewExtras) CHECK(static_cast<double>(d.extra) < 0.01 * static_cast<double>(d.expected));
}

Scene loadedScene(const std::string& source) { return assets::loadScene(source).scene; }

// A soup of random triangles, each inside a cube of `size` voxels placed uniformly in the
// grid's interior (positions in world units; the box is fit to them).
Scene triangleSoup(int count, float size, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    auto mesh = std::make_shared<MeshData>();
    for (int i = 0; i < count; ++i) {
        const glm::vec3 base(u(rng), u(rng), u(rng));
        for (int k = 0; k < 3; ++k) mesh->positions.push_back(base + size * glm::vec3(u(rng), u(rng), u(rng)));
    }
    return test::singleMeshScene(mesh);
}

} // namespace

TEST_CASE("Surface voxelization is a conservative superset of the CPU separating-axis voxelization",
          "[voxel][reference]") {
    test::GlFixture gl;
    Context ctx(gl.desc());
    Voxelizer voxelizer(ctx);
    for (const std::string& source : {std::string("cornell"), kModels + "/PLY/Wuson.ply", kModels + "/OBJ/spider.obj"}) {
        CAPTURE(source);
        const Scene scene = loadedScene(source);
        const VoxelGrid& grid = voxelizer.voxelize(scene, surfaceSettings(64));
        checkConservativeSuperset(voxelizer.download(), scene, grid);
        CHECK(voxelizer.warnings().empty());
    }
}

TEST_CASE("Surface voxelization has no holes for triangles seen edge-on or smaller than a voxel",
          "[voxel][reference]") {
    test::GlFixture gl;
    Context ctx(gl.desc());
    Voxelizer voxelizer(ctx);
    SECTION("quads parallel to each projection axis, and tilted slightly off it") {
        // Edge-on quads are where single-axis slicemap voxelization leaves its holes.
        std::vector<test::AnalyticQuad> quads;
        quads.push_back({{glm::dvec3(0.1, 0.2, 0.1), {0.9, 0.2, 0.1}, {0.9, 0.2, 0.9}, {0.1, 0.2, 0.9}}}); // y = 0.2
        quads.push_back({{glm::dvec3(0.3, 0.1, 0.1), {0.3, 0.9, 0.1}, {0.3, 0.9, 0.9}, {0.3, 0.1, 0.9}}}); // x = 0.3
        quads.push_back({{glm::dvec3(0.1, 0.1, 0.6), {0.9, 0.1, 0.6}, {0.9, 0.9, 0.6}, {0.1, 0.9, 0.6}}}); // z = 0.6
        quads.push_back({{glm::dvec3(0.1, 0.5, 0.1), {0.9, 0.5, 0.1}, {0.9, 0.5003, 0.9}, {0.1, 0.5003, 0.9}}});
        const Scene scene = test::quadScene(quads);
        for (int targets : {1, 2}) {
            const VoxelGrid& grid = voxelizer.voxelize(scene, surfaceSettings(32, targets));
            checkConservativeSuperset(voxelizer.download(), scene, grid);
        }
    }
    SECTION("triangles of a tenth of a voxel") {
        // 2000 triangles in the unit cube; the box is about 1.04 units for 32 voxels, so
        // 0.003 units is about a tenth of a voxel.
        const Scene scene = triangleSoup(2000, 0.003f, 7);
        const VoxelGrid& grid = voxelizer.voxelize(scene, surfaceSettings(32));
        const DenseVoxels cpu = reference::voxelizeSurface(scene, grid);
        checkConservativeSuperset(voxelizer.download(), scene, grid);
        // Each triangle touches at least one voxel, so none can vanish.
        CHECK(countSet(cpu) >= 1500);
    }
}

TEST_CASE("Zero-area triangles set the voxels of their segment or point", "[voxel][stability]") {
    test::GlFixture gl;
    Context ctx(gl.desc());
    Voxelizer voxelizer(ctx);
    auto mesh = std::make_shared<MeshData>();
    mesh->positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0.5f},                       // a proper triangle
                       {0.2f, 0.2f, 0.2f}, {0.4f, 0.4f, 0.4f}, {0.6f, 0.6f, 0.6f}, // collinear
                       {0.7f, 0.1f, 0.9f}, {0.7f, 0.1f, 0.9f}, {0.7f, 0.1f, 0.9f}, // a point
                       {0.1f, 0.9f, 0.9f}, {0.1f, 0.9f, 0.9f}, {0.8f, 0.2f, 0.1f}}; // two equal corners
    const Scene scene = test::singleMeshScene(mesh);
    const VoxelGrid& grid = voxelizer.voxelize(scene, surfaceSettings(32));
    const DenseVoxels gpu = voxelizer.download();
    checkConservativeSuperset(gpu, scene, grid, false);
    // Every voxel holding a point of the segments is set (sampled densely along them).
    const auto setAt = [&](const glm::vec3& world) {
        const glm::ivec3 c(glm::floor(glm::dvec3(grid.worldToVoxel * glm::dvec4(glm::dvec3(world), 1.0))));
        return gpu.at(c.x, c.y, c.z) != 0;
    };
    for (int i = 0; i <= 100; ++i) {
        const float t = static_cast<float>(i) / 100.0f;
        CHECK(setAt(glm::mix(mesh->positions[3], mesh->positions[5], t)));
        CHECK(setAt(glm::mix(mesh->positions[9], mesh->positions[11], t)));
    }
    CHECK(setAt(mesh->positions[6]));
}

TEST_CASE("Solid voxelization equals the CPU parity fill on watertight meshes", "[voxel][reference]") {
    test::GlFixture gl;
    Context ctx(gl.desc());
    Voxelizer voxelizer(ctx);
    const glm::mat4 rotation = glm::rotate(glm::rotate(glm::mat4(1.0f), 0.7f, glm::vec3(0, 0, 1)), 0.4f, glm::vec3(1, 0, 0));
    const auto meshes = {std::pair{"rotated cube", test::singleMeshScene(test::cubeMesh(), rotation)},
                         std::pair{"icosphere", test::singleMeshScene(test::icosphereMesh(3), rotation)},
                         std::pair{"two overlapping cubes", test::singleMeshScene(test::cubeMesh(), rotation)}};
    for (auto [name, scene] : meshes) {
        if (std::string(name) == "two overlapping cubes") {
            // Overlapping closed surfaces: parity says the overlap is outside, on both sides.
            Mesh second = scene.meshes[0];
            second.model = glm::translate(rotation, glm::vec3(0.5f, 0.3f, 0.2f));
            scene.meshes.push_back(second);
        }
        REQUIRE(meshClosure(*scene.meshes[0].data).watertight());
        for (int targets : {1, 3}) {
            CAPTURE(name, targets);
            VoxelizerSettings s = surfaceSettings(64, targets);
            s.mode = VoxelMode::Solid;
            // The box is set by hand so that the solid fills part of the slices of every
            // target, and parts of the mesh lie outside the box in front and behind.
            s.fitBox = false;
            s.boxMin = glm::vec3(-1.2f, -1.2f, -0.4f * static_cast<float>(targets));
            s.boxMax = glm::vec3(1.3f, 1.25f, 0.3f * static_cast<float>(targets));
            const VoxelGrid& grid = voxelizer.voxelize(scene, s);
            const DenseVoxels cpu = reference::voxelizeSolid(scene, grid);
            const test::VoxelDiff d = test::compareVoxels(voxelizer.download(), cpu);
            INFO("CPU " << d.expected << " voxels, GPU " << d.actual << ", missing " << d.missing << ", extra " << d.extra);
            CHECK(d.expected > 1000);
            CHECK(d.differing() == 0);
            CHECK(grid.openColumns == 0);
            CHECK(voxelizer.warnings().empty());
        }
    }
}

TEST_CASE("Solid voxelization of an open mesh reports it and leaves its open columns empty", "[voxel][reference]") {
    test::GlFixture gl;
    Context ctx(gl.desc());
    Voxelizer voxelizer(ctx);
    auto sphere = test::icosphereMesh(3);
    auto open = std::make_shared<MeshData>(*sphere);
    open->indices.resize(open->indices.size() - 3 * 40); // a hole of 40 triangles
    const Scene scene = test::singleMeshScene(open, glm::rotate(glm::mat4(1.0f), 0.3f, glm::vec3(1, 1, 0)));

    VoxelizerSettings s = surfaceSettings(64);
    s.mode = VoxelMode::Solid;
    const VoxelGrid& grid = voxelizer.voxelize(scene, s);
    // The CPU parity fill, with the columns that end inside the solid (an odd number of
    // crossings, all inside the fitted box) cleared: what the GPU promises.
    DenseVoxels cpu = reference::voxelizeSolid(scene, grid);
    std::size_t openColumns = 0;
    for (int y = 0; y < grid.dims.y; ++y)
        for (int x = 0; x < grid.dims.x; ++x) {
            if (!cpu.at(x, y, grid.dims.z - 1)) continue;
            ++openColumns;
            for (int z = 0; z < grid.dims.z; ++z)
                cpu.voxels[(static_cast<std::size_t>(z) * grid.dims.y + y) * grid.dims.x + x] = 0;
        }
    CHECK(openColumns > 0);
    CHECK(grid.openColumns == openColumns);
    // One warning for the columns, one naming the mesh and its boundary edges.
    REQUIRE(voxelizer.warnings().size() == 2);
    CHECK_THAT(voxelizer.warnings()[0], Catch::Contains("odd number of times"));
    CHECK_THAT(voxelizer.warnings()[1], Catch::Contains("Scene::meshes[0]") && Catch::Contains("not watertight"));
    CHECK(test::compareVoxels(voxelizer.download(), cpu).differing() == 0);

    SECTION("without counting: the same grid, no read-back, no count") {
        VoxelizerSettings quiet = s;
        quiet.countOpenColumns = false;
        CHECK(voxelizer.voxelize(scene, quiet).openColumns == 0);
        CHECK(test::compareVoxels(voxelizer.download(), cpu).differing() == 0);
    }
}

TEST_CASE("A mesh open only where no column crosses it is still reported", "[voxel][reference]") {
    test::GlFixture gl;
    Context ctx(gl.desc());
    Voxelizer voxelizer(ctx);
    // The cube without its x = 1 face, which is parallel to z: every column still crosses the
    // top and bottom, so the parity fill cannot see the hole.
    auto cube = std::make_shared<MeshData>(*test::cubeMesh());
    cube->indices.erase(cube->indices.end() - 6, cube->indices.end());
    const Scene scene = test::singleMeshScene(cube);
    VoxelizerSettings s;
    s.resolution = 16;
    s.mode = VoxelMode::Solid;
    const VoxelGrid& grid = voxelizer.voxelize(scene, s);
    CHECK(grid.openColumns == 0);
    REQUIRE(voxelizer.warnings().size() == 1);
    CHECK_THAT(voxelizer.warnings()[0], Catch::Contains("4 boundary"));
    CHECK(test::compareVoxels(voxelizer.download(), reference::voxelizeSolid(scene, grid)).differing() == 0);
}

TEST_CASE("Mesh closure counts boundary and non-manifold edges by welded position", "[voxel]") {
    CHECK(meshClosure(*test::cubeMesh()).watertight());
    CHECK(meshClosure(*test::cubeMesh()).edges == 18);
    CHECK(meshClosure(*test::icosphereMesh(2)).watertight());
    // Unindexed triangles (vertices repeated) weld by position.
    MeshData soup;
    const MeshData cube = *test::cubeMesh();
    for (std::uint32_t i : cube.indices) soup.positions.push_back(cube.positions[i]);
    CHECK(meshClosure(soup).watertight());
    // A third triangle on an edge; a zero-area triangle changes nothing.
    MeshData fin = *test::cubeMesh();
    fin.positions.emplace_back(0.5f, -1.0f, 0.0f);
    fin.positions.emplace_back(0.5f, 0.0f, 0.0f);
    fin.indices.insert(fin.indices.end(), {0, 1, 8, 0, 9, 1});
    const MeshClosure c = meshClosure(fin);
    CHECK(c.nonManifoldEdges == 1);
    CHECK(c.boundaryEdges == 2);
    MeshData empty;
    CHECK_FALSE(meshClosure(empty).watertight());
    MeshData bad = *test::cubeMesh();
    bad.indices[4] = 99;
    CHECK_THROWS_AS(meshClosure(bad), Error);
}

TEST_CASE("Every render-target count lays slices out as documented", "[voxel][reference]") {
    test::GlFixture gl;
    Context ctx(gl.desc());
    Voxelizer voxelizer(ctx);
    // A sphere filling the box: every target holds part of it.
    const Scene scene = test::singleMeshScene(test::icosphereMesh(2), glm::rotate(glm::mat4(1.0f), 0.5f, glm::vec3(0, 1, 1)));
    for (int targets : {1, 2, 4, 8}) {
        for (VoxelMode mode : {VoxelMode::Surface, VoxelMode::Solid}) {
            CAPTURE(targets, mode == VoxelMode::Solid);
            VoxelizerSettings s = surfaceSettings(16, targets);
            s.mode = mode;
            const VoxelGrid& grid = voxelizer.voxelize(scene, s);
            REQUIRE(grid.dims == glm::ivec3(16, 16, 128 * targets));
            const DenseVoxels gpu = voxelizer.download();
            if (mode == VoxelMode::Surface) {
                checkConservativeSuperset(gpu, scene, grid);
            } else {
                CHECK(test::compareVoxels(gpu, reference::voxelizeSolid(scene, grid)).differing() == 0);
            }
            for (int t = 0; t < targets; ++t) // no target is empty
                CHECK(test::countSet(gpu, 128 * t, 128 * (t + 1)) > 0);
        }
    }
}

TEST_CASE("Quadtree and octree mipmaps are the OR-reductions of level 0", "[voxel]") {
    test::GlFixture gl;
    Context ctx(gl.desc());
    Voxelizer voxelizer(ctx);
    const Scene scene = loadedScene(kModels + "/PLY/Wuson.ply");
    // 256 columns with 128 slices: the octree's top levels have fewer slices than 2^L
    // (rounded up); 32 columns with 3 targets: a slice count that is not a power of two.
    for (auto [resolution, targets] : {std::pair{256, 1}, std::pair{32, 3}}) {
        CAPTURE(resolution, targets);
        const VoxelGrid& grid = voxelizer.voxelize(scene, surfaceSettings(resolution, targets));
        const DenseVoxels level0 = voxelizer.download();
        REQUIRE(grid.levels == static_cast<int>(std::log2(resolution)));
        DenseVoxels octree = level0;
        for (int level = 1; level <= grid.levels; ++level) {
            CAPTURE(level);
            octree = test::orReduce(octree, 2);
            CHECK(test::compareVoxels(voxelizer.download(level), octree).differing() == 0);
            CHECK(test::compareVoxels(voxelizer.downloadQuadtree(level), test::orReduce(level0, 1 << level, 1)).differing() == 0);
        }
        CHECK(octree.dims == glm::ivec3(1, 1, (grid.dims.z + resolution - 1) / resolution));
        CHECK(countSet(octree) == octree.voxels.size());
    }
}

TEST_CASE("Voxelization is robust to flat scenes and far offsets and tiny or invalid input", "[voxel][stability]") {
    test::GlFixture gl;
    Context ctx(gl.desc());
    Voxelizer voxelizer(ctx);
    SECTION("bounds of zero extent on one axis") {
        const Scene scene = test::quadScene({{{glm::dvec3(0, 0, 2), {3, 0, 2}, {3, 1, 2}, {0, 1, 2}}}});
        const VoxelGrid& grid = voxelizer.voxelize(scene, surfaceSettings(32));
        CHECK(grid.boxMax.z > grid.boxMin.z);
        checkConservativeSuperset(voxelizer.download(), scene, grid);
    }
    SECTION("a scene 1e5 units from the origin, by its transform or by its vertices") {
        const Scene near = loadedScene("cornell");
        const VoxelGrid grid0 = voxelizer.voxelize(near, surfaceSettings(64));
        const std::size_t nearCount = countSet(voxelizer.download());
        Scene byTransform = near, byVertices = near;
        const glm::vec3 offset(1e5f, -1e5f, 1e5f);
        for (Mesh& m : byTransform.meshes) m.model = glm::translate(glm::mat4(1.0f), offset) * m.model;
        for (Mesh& m : byVertices.meshes) {
            auto moved = std::make_shared<MeshData>(*m.data);
            for (glm::vec3& p : moved->positions) p = glm::vec3(m.model * glm::vec4(p, 1.0f)) + offset;
            m.data = moved;
            m.model = glm::mat4(1.0f);
        }
        for (const Scene* far : {&byTransform, &byVertices}) {
            const VoxelGrid& grid = voxelizer.voxelize(*far, surfaceSettings(64));
            CHECK(glm::length(grid.boxMin - grid0.boxMin - glm::dvec3(offset)) < 0.1);
            const DenseVoxels gpu = voxelizer.download();
            checkConservativeSuperset(gpu, *far, grid);
            // The same shape: float positions at 1e5 are spaced 1/128 unit apart, far below the
            // Cornell box's 8.6-unit voxels, so few voxels may change.
            CHECK(std::abs(static_cast<double>(countSet(gpu)) - static_cast<double>(nearCount)) < 0.01 * static_cast<double>(nearCount));
        }
    }
    SECTION("triangles reaching far beyond a set box, and far from the origin") {
        // A floor 1e7 units wide under a box of a few units (a level's local region), and a
        // triangle 1e12 units away: clipped to the grid in double before the float test.
        const Scene scene = test::quadScene({{{glm::dvec3(-1e7, 0.3, -1e7), {-1e7, 0.3, 1e7}, {1e7, 0.3, 1e7}, {1e7, 0.3, -1e7}}},
                                             {{glm::dvec3(1e12, 0, 0), {1e12, 1, 0}, {1e12, 1, 1}, {1e12, 0, 1}}}});
        VoxelizerSettings s = surfaceSettings(32);
        s.fitBox = false;
        s.boxMin = glm::vec3(-1.0f, -0.2f, -1.0f);
        s.boxMax = glm::vec3(1.0f, 1.0f, 1.0f);
        const VoxelGrid& grid = voxelizer.voxelize(scene, s);
        const DenseVoxels gpu = voxelizer.download();
        checkConservativeSuperset(gpu, scene, grid, false);
        // The floor at y = 0.3 is the slice y = (0.3 + 0.2) / 1.2 * 32 = 13.33: one full layer.
        CHECK(countSet(gpu) == static_cast<std::size_t>(32 * 128));
    }
    SECTION("NaN vertices are rejected before any GL work") {
        Scene scene = test::singleMeshScene(test::icosphereMesh(1));
        auto bad = std::make_shared<MeshData>(*scene.meshes[0].data);
        bad->positions[5].y = std::nanf("");
        scene.meshes[0].data = bad;
        const auto before = test::liveGlObjects();
        try {
            voxelizer.voxelize(scene, surfaceSettings(32));
            FAIL("no error");
        } catch (const Error& e) {
            CHECK(e.code() == ErrorCode::InvalidArgument);
            CHECK_THAT(e.what(), Catch::Contains("NaN"));
        }
        CHECK(test::drainGlErrors().empty());
        CHECK(test::liveGlObjects() == before);
    }
    SECTION("settings out of range") {
        const Scene scene = test::singleMeshScene(test::cubeMesh());
        for (auto change : std::vector<void (*)(VoxelizerSettings&)>{
                 [](VoxelizerSettings& s) { s.resolution = 48; }, [](VoxelizerSettings& s) { s.resolution = 4096; },
                 [](VoxelizerSettings& s) { s.targets = 0; }, [](VoxelizerSettings& s) { s.targets = 9; },
                 [](VoxelizerSettings& s) { s.margin = -0.1f; },
                 [](VoxelizerSettings& s) { s.fitBox = false, s.boxMax.x = s.boxMin.x; },
                 [](VoxelizerSettings& s) { s.fitBox = false, s.boxMin.y = std::nanf(""); },
                 [](VoxelizerSettings& s) { s.mode = static_cast<VoxelMode>(2); }}) { // ran the Solid pass before
            VoxelizerSettings s;
            change(s);
            CHECK_THROWS_AS(voxelizer.voxelize(scene, s), Error);
        }
        CHECK_THROWS_AS(voxelizer.voxelize(Scene{}, VoxelizerSettings{}), Error);
    }
}

TEST_CASE("Static scenes are voxelized once and dynamic ones on every call", "[voxel]") {
    test::GlFixture gl;
    Context ctx(gl.desc());
    Voxelizer voxelizer(ctx);
    Scene scene = test::singleMeshScene(test::icosphereMesh(2));
    VoxelizerSettings s = surfaceSettings(32);
    const std::uint64_t first = voxelizer.voxelize(scene, s).version;
    CHECK(voxelizer.voxelize(scene, s).version == first);
    scene.meshes[0].model = glm::translate(glm::mat4(1.0f), glm::vec3(0.1f, 0, 0));
    const std::uint64_t moved = voxelizer.voxelize(scene, s).version;
    CHECK(moved > first);
    scene.meshes[0].data = std::make_shared<MeshData>(*scene.meshes[0].data); // new mesh data
    CHECK(voxelizer.voxelize(scene, s).version > moved);
    s.targets = 2;
    const std::uint64_t resized = voxelizer.voxelize(scene, s).version;
    CHECK(voxelizer.grid().dims.z == 256);
    s.dynamic = true;
    CHECK(voxelizer.voxelize(scene, s).version > resized);
    CHECK(voxelizer.voxelize(scene, s).version > resized + 1);

    // A new mesh in place of a freed one is a change even if it reuses the address.
    s.dynamic = false;
    const std::uint64_t before = voxelizer.voxelize(scene, s).version;
    scene.meshes[0].data.reset();
    scene.meshes[0].data = test::cubeMesh();
    CHECK(voxelizer.voxelize(scene, s).version > before);

    // Without the octree no octree is published (nor kept in memory).
    const std::size_t withOctree = voxelizer.memoryBytes();
    s.octree = false;
    CHECK(voxelizer.voxelize(scene, s).octree == 0);
    CHECK(voxelizer.grid().levels == 0);
    CHECK(voxelizer.memoryBytes() < withOctree);
}

TEST_CASE("A failed voxelization leaves no half-built grid to query", "[voxel][stability]") {
    test::GlFixture gl;
    Context ctx(gl.desc());
    Voxelizer voxelizer(ctx);
    Scene scene = test::singleMeshScene(test::cubeMesh());
    VoxelizerSettings s;
    s.resolution = 16;
    voxelizer.voxelize(scene, s);
    MeshRef bad;
    bad.vao = 12345; // not a VAO of this context: refused while preparing the draw
    bad.count = 3;
    scene.meshRefs.push_back(bad);
    CHECK_THROWS_AS(voxelizer.voxelize(scene, s), Error);
    CHECK_THROWS_AS(voxelizer.trace({{glm::vec3(0.0f), glm::vec3(1.0f)}}, {}), Error);
    CHECK(test::drainGlErrors().empty());
}
