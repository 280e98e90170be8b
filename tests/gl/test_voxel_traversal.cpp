// Visibility in voxel space: exact (b) and hierarchical (c) traversal agree on every segment,
// (b) is checked by a brute-force search over every occupied voxel, and marching (a) is
// checked against what sampling can and cannot miss.
#include "gl_fixture.hpp"
#include "scene_builders.hpp"
#include "voxel_checks.hpp"

#include "obscura/assets.hpp"
#include "obscura/obscura.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <numeric>

using namespace obscura;

namespace {

const std::string kModels = OBSCURA_ASSIMP_MODELS;

std::vector<VoxelHit> traceWith(Voxelizer& v, const std::vector<VoxelSegment>& segments, VoxelTraversal method,
                                int steps = 64) {
    TraversalSettings s;
    s.method = method;
    s.marchSteps = steps;
    return v.trace(segments, s);
}

double meanFetches(const std::vector<VoxelHit>& hits) {
    return std::accumulate(hits.begin(), hits.end(), 0.0, [](double a, const VoxelHit& h) { return a + h.fetches; }) /
           static_cast<double>(hits.size());
}

// The segments are quantized to 2^-12 voxel after clipping (VOXEL_FIXED_SHIFT), and their
// float endpoints carry a relative error of 2^-24 of up to 1.1 x 1024 voxels: a voxel the
// segment passes by or through by less than this may be seen either way.
constexpr double kPositionTolerance = 1.0 / 2048.0;

} // namespace

TEST_CASE("Exact and hierarchical traversal agree on a million segments", "[voxel][traversal]") {
    test::GlFixture gl;
    Context ctx(gl.desc());
    Voxelizer voxelizer(ctx);
    struct Case {
        std::string scene;
        int resolution, targets;
        std::size_t segments;
    };
    // A room (large empty interior) and a model (sparse, with thin parts): 10^6 segments in
    // all, at a depth that spans two render targets for the first. Then the octree's odd
    // sizes (three targets: 384 slices; 256 columns over 128 slices: the top levels round
    // up) and the largest grid, where fixed-point coordinates reach 2^23.
    for (const Case& c : {Case{"cornell", 32, 2, 500000}, Case{kModels + "/PLY/Wuson.ply", 64, 1, 500000},
                          Case{kModels + "/PLY/Wuson.ply", 32, 3, 100000}, Case{"cornell", 256, 1, 100000},
                          Case{"cornell", 2048, 1, 20000}}) {
        CAPTURE(c.scene, c.resolution, c.targets);
        VoxelizerSettings s;
        s.resolution = c.resolution;
        s.targets = c.targets;
        voxelizer.voxelize(assets::loadScene(c.scene).scene, s);
        auto segments = test::segmentMix(voxelizer.download(), c.segments, 11);
        // Through the grid's centre from endpoints far outside it, up to the accepted 2^24 voxels.
        const glm::vec3 centre = glm::vec3(voxelizer.grid().dims) * 0.5f + 0.25f;
        segments.push_back({centre - glm::vec3(1.6e7f, 1.5e7f, 1.4e7f), centre + glm::vec3(1.6e7f, 1.5e7f, 1.4e7f)});
        segments.push_back({centre - glm::vec3(1e7f, 0.0f, 0.0f), centre + glm::vec3(1e7f, 0.0f, 0.0f)});
        const auto exact = traceWith(voxelizer, segments, VoxelTraversal::Exact);
        const auto hier = traceWith(voxelizer, segments, VoxelTraversal::Hierarchical);
        std::size_t disagree = 0, hits = 0;
        for (std::size_t i = 0; i < segments.size(); ++i) {
            const VoxelHit &b = exact[i], &h = hier[i];
            hits += b.hit;
            // The same voxel from the same exact crossing time n/d; t is float(n)/float(d),
            // which GLSL allows 2.5 ulp of error (a few 1e-7 in [0, 1]).
            const bool same = b.hit == h.hit && b.voxel == h.voxel && std::abs(b.t - h.t) <= 1e-6f;
            if (!same && disagree++ < 5)
                UNSCOPED_INFO("segment " << i << " (" << segments[i].from.x << ", " << segments[i].from.y << ", "
                                         << segments[i].from.z << ") -> (" << segments[i].to.x << ", "
                                         << segments[i].to.y << ", " << segments[i].to.z << "): exact " << b.hit << " "
                                         << b.t << " voxel " << b.voxel.x << "," << b.voxel.y << "," << b.voxel.z
                                         << "; hierarchical " << h.hit << " " << h.t << " voxel " << h.voxel.x << ","
                                         << h.voxel.y << "," << h.voxel.z);
        }
        CHECK(disagree == 0);
        // Both kinds of answer are well represented; the two long ones cross the room's walls.
        if (c.scene == "cornell") CHECK((exact[segments.size() - 2].hit && exact[segments.size() - 1].hit));
        CHECK(hits > segments.size() / 5);
        CHECK(hits < segments.size() * 4 / 5);
        // Skipping empty cells must pay: fewer fetches on average.
        CHECK(meanFetches(hier) < meanFetches(exact));
    }
}

TEST_CASE("Exact traversal finds the first occupied voxel of a brute-force search", "[voxel][traversal]") {
    test::GlFixture gl;
    Context ctx(gl.desc());
    Voxelizer voxelizer(ctx);
    VoxelizerSettings s;
    s.resolution = 16;
    voxelizer.voxelize(assets::loadScene(kModels + "/PLY/Wuson.ply").scene, s);
    const DenseVoxels grid = voxelizer.download();
    std::vector<glm::dvec3> occupied;
    for (int z = 0; z < grid.dims.z; ++z)
        for (int y = 0; y < grid.dims.y; ++y)
            for (int x = 0; x < grid.dims.x; ++x)
                if (grid.at(x, y, z)) occupied.emplace_back(x, y, z);
    const auto segments = test::segmentMix(grid, 30000, 5);
    constexpr int kSteps = 1024;
    const auto exact = traceWith(voxelizer, segments, VoxelTraversal::Exact);
    const auto march = traceWith(voxelizer, segments, VoxelTraversal::March, kSteps);
    std::size_t robustHits = 0;
    for (std::size_t i = 0; i < segments.size(); ++i) {
        const glm::dvec3 from(segments[i].from), to(segments[i].to);
        const double length = glm::length(to - from);
        // In parameter units, the position tolerance along this segment.
        const double dt = length > 0.0 ? kPositionTolerance / length : 1.0;
        // The earliest voxel the segment passes through by more than the tolerance: the
        // box shrunk by it is still entered (a zero-length segment: strictly inside).
        double firstRobust = 2.0;
        double firstRobustExit = 2.0;
        for (const glm::dvec3& v : occupied)
            if (auto in = test::segmentBoxInterval(from, to, v + kPositionTolerance, v + 1.0 - kPositionTolerance))
                if (in->first < firstRobust) firstRobust = in->first, firstRobustExit = in->second;
        const VoxelHit& b = exact[i];
        CAPTURE(i, segments[i].from.x, segments[i].from.y, segments[i].from.z, segments[i].to.x, segments[i].to.y,
                segments[i].to.z, b.hit, b.t, b.voxel.x, b.voxel.y, b.voxel.z);
        if (firstRobust <= 1.0) {
            ++robustHits;
            REQUIRE(b.hit);
            REQUIRE(b.t <= firstRobust + dt + 1e-6);
        }
        if (b.hit) {
            // An occupied voxel that the segment enters at t, within the tolerance.
            REQUIRE(grid.at(b.voxel.x, b.voxel.y, b.voxel.z));
            const glm::dvec3 v(b.voxel);
            const auto grown = test::segmentBoxInterval(from, to, v - kPositionTolerance, v + 1.0 + kPositionTolerance);
            REQUIRE(grown);
            REQUIRE(b.t >= grown->first - 1e-6);
            if (auto shrunk = test::segmentBoxInterval(from, to, v + kPositionTolerance, v + 1.0 - kPositionTolerance))
                REQUIRE(b.t <= shrunk->first + 1e-6);
        }
        // Marching samples points of the segment: its hit is an occupied voxel that holds the
        // point at t (so the exact first hit, checked above against every robustly crossed
        // voxel, is no later than it); it must find a voxel it crosses for longer than its
        // sample spacing.
        const VoxelHit& a = march[i];
        REQUIRE(a.fetches <= static_cast<std::uint32_t>(kSteps));
        if (a.hit) {
            REQUIRE(grid.at(a.voxel.x, a.voxel.y, a.voxel.z));
            const glm::dvec3 v(a.voxel);
            const auto grown = test::segmentBoxInterval(from, to, v - kPositionTolerance, v + 1.0 + kPositionTolerance);
            REQUIRE(grown);
            REQUIRE(a.t >= grown->first - 1e-6);
            REQUIRE(a.t <= grown->second + 1e-6);
        }
        if (firstRobust <= 1.0 && firstRobustExit - firstRobust > 1.0 / kSteps) REQUIRE(a.hit);
    }
    CHECK(robustHits > segments.size() / 5);
}

TEST_CASE("Point occupancy and zero-length segments answer the voxel holding the point", "[voxel][traversal]") {
    test::GlFixture gl;
    Context ctx(gl.desc());
    Voxelizer voxelizer(ctx);
    VoxelizerSettings s;
    s.resolution = 32;
    s.mode = VoxelMode::Solid;
    voxelizer.voxelize(test::singleMeshScene(test::icosphereMesh(2)), s);
    const DenseVoxels grid = voxelizer.download();
    std::vector<VoxelSegment> points;
    for (int z = -1; z <= grid.dims.z; z += 3)
        for (int y = -1; y <= grid.dims.y; ++y)
            for (int x = -1; x <= grid.dims.x; ++x) {
                const glm::vec3 p = glm::vec3(x, y, z) + glm::vec3(0.25f, 0.5f, 0.75f);
                points.push_back({p, p});
                // On the voxel's lower faces and corner: it belongs to the voxel above.
                points.push_back({glm::vec3(x, y, z), glm::vec3(x, y, z)});
            }
    std::vector<glm::vec3> positions;
    for (const VoxelSegment& p : points) positions.push_back(p.from);
    const std::vector<std::uint8_t> occupied = voxelizer.occupancy(positions);
    for (VoxelTraversal method : {VoxelTraversal::Exact, VoxelTraversal::Hierarchical}) {
        const auto hits = traceWith(voxelizer, points, method);
        std::size_t wrong = 0, set = 0;
        for (std::size_t i = 0; i < points.size(); ++i) {
            const glm::ivec3 c(glm::floor(points[i].from));
            const bool inGrid = glm::all(glm::greaterThanEqual(c, glm::ivec3(0))) && glm::all(glm::lessThan(c, grid.dims));
            const bool expected = inGrid && grid.at(c.x, c.y, c.z);
            set += expected;
            wrong += hits[i].hit != expected || (expected && (hits[i].voxel != c || hits[i].t != 0.0f));
            wrong += (occupied[i] != 0) != expected;
        }
        CHECK(set > 100);
        CHECK(wrong == 0);
    }
}

TEST_CASE("Batches larger than one dispatch are answered in full", "[voxel][traversal]") {
    test::GlFixture gl;
    Context ctx(gl.desc());
    Voxelizer voxelizer(ctx);
    VoxelizerSettings s;
    s.resolution = 16;
    s.mode = VoxelMode::Solid;
    voxelizer.voxelize(test::singleMeshScene(test::icosphereMesh(2)), s);
    const DenseVoxels grid = voxelizer.download();
    // GL guarantees 65535 work groups of 64 per dispatch: 4194240 queries, then more.
    const std::size_t count = std::size_t{65535} * 64 + 1000;
    std::vector<glm::vec3> points(count);
    for (std::size_t i = 0; i < count; ++i) {
        const std::size_t v = (i * 2654435761u) % grid.voxels.size(); // every voxel, scattered
        points[i] = glm::vec3(static_cast<float>(v % 16), static_cast<float>((v / 16) % 16), static_cast<float>(v / 256)) + 0.5f;
    }
    const std::vector<std::uint8_t> occupied = voxelizer.occupancy(points);
    std::size_t wrong = 0, set = 0;
    for (std::size_t i = 0; i < count; ++i) {
        const glm::ivec3 c(points[i]);
        set += grid.at(c.x, c.y, c.z);
        wrong += occupied[i] != grid.at(c.x, c.y, c.z);
    }
    CHECK(set > count / 10);
    CHECK(wrong == 0);
}

TEST_CASE("Traversal rejects misuse and answers non-finite segments with a miss", "[voxel][traversal][stability]") {
    test::GlFixture gl;
    Context ctx(gl.desc());
    Voxelizer voxelizer(ctx);
    const std::vector<VoxelSegment> one = {{glm::vec3(0.0f), glm::vec3(1.0f)}};
    CHECK_THROWS_AS(voxelizer.trace(one, {}), Error); // nothing voxelized yet
    VoxelizerSettings s;
    s.resolution = 16;
    s.octree = false;
    voxelizer.voxelize(test::singleMeshScene(test::cubeMesh()), s);
    CHECK_THROWS_AS(traceWith(voxelizer, one, VoxelTraversal::Hierarchical), Error);
    CHECK_THROWS_AS(traceWith(voxelizer, one, VoxelTraversal::March, 0), Error);
    // An integer outside the enumerators would skip the octree check and run the hierarchical shader.
    CHECK_THROWS_AS(traceWith(voxelizer, one, static_cast<VoxelTraversal>(3)), Error);
    const float nan = std::nanf(""), inf = INFINITY;
    const std::vector<VoxelSegment> bad = {{glm::vec3(nan, 1, 1), glm::vec3(8.0f)},
                                           {glm::vec3(1.0f), glm::vec3(inf, 1, 1)},
                                           {glm::vec3(-inf), glm::vec3(inf)},
                                           // finite, but beyond the accepted 2^24 voxels (and
                                           // their difference overflows)
                                           {glm::vec3(-3e38f), glm::vec3(3e38f)},
                                           {glm::vec3(2e7f, 1, 1), glm::vec3(-2e7f, 1, 1)}};
    s.octree = true;
    voxelizer.voxelize(test::singleMeshScene(test::cubeMesh()), s);
    for (VoxelTraversal method : {VoxelTraversal::Exact, VoxelTraversal::Hierarchical, VoxelTraversal::March})
        for (const VoxelHit& h : traceWith(voxelizer, bad, method)) {
            CHECK_FALSE(h.hit);
            CHECK(h.t == 1.0f);
        }
    const float big = 3e38f;
    for (std::uint8_t o : voxelizer.occupancy({glm::vec3(nan, 1, 1), glm::vec3(inf, 1, 1), glm::vec3(-big, big, 0)}))
        CHECK(o == 0);
    CHECK(test::drainGlErrors().empty());
}
