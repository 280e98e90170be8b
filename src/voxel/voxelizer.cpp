#include "obscura/voxelizer.hpp"

#include "core/compute.hpp"
#include "core/context_impl.hpp"
#include "core/mesh_cache.hpp"
#include "core/pass_scope.hpp"
#include "core/segment_batch.hpp"
#include "core/shader_library.hpp"
#include "core/validate.hpp"
#include "voxel/voxel_queries.hpp"
#include "obscura/context.hpp"
#include "shaders/voxel/voxel_bindings.h"

#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

namespace obscura {
namespace {

using namespace detail;

bool sameSettings(const VoxelizerSettings& a, const VoxelizerSettings& b) {
    return a.resolution == b.resolution && a.targets == b.targets && a.mode == b.mode && a.fitBox == b.fitBox &&
           a.margin == b.margin && a.boxMin == b.boxMin && a.boxMax == b.boxMax && a.dynamic == b.dynamic &&
           a.octree == b.octree && a.countOpenColumns == b.countOpenColumns;
}

int log2i(int v) {
    int l = 0;
    while ((1 << (l + 1)) <= v) ++l;
    return l;
}

void validateSettings(const VoxelizerSettings& s) {
    // A fitted box ignores boxMin and boxMax, whatever they hold.
    VoxelizerSettings checked = s;
    if (s.fitBox) checked.boxMin = VoxelizerSettings{}.boxMin, checked.boxMax = VoxelizerSettings{}.boxMax;
    obscura::validateSettings(VoxelizerSettings::table(), checked, "VoxelizerSettings");
    if (!s.fitBox) {
        if (glm::any(glm::lessThanEqual(s.boxMax, s.boxMin)))
            throw Error(ErrorCode::InvalidArgument, "VoxelizerSettings::boxMax must exceed boxMin on every axis, got boxMin (" +
                                                    std::to_string(s.boxMin.x) + ", " + std::to_string(s.boxMin.y) + ", " +
                                                    std::to_string(s.boxMin.z) + ") and boxMax (" + std::to_string(s.boxMax.x) +
                                                    ", " + std::to_string(s.boxMax.y) + ", " + std::to_string(s.boxMax.z) + ")");
    }
}

// The box: the scene's bounds grown by margin x the largest extent on every side, so an axis
// of zero extent still gets a thickness. Computed in double.
void fitBox(const Scene& scene, const VoxelizerSettings& s, glm::dvec3& lo, glm::dvec3& hi) {
    if (!s.fitBox) {
        lo = glm::dvec3(s.boxMin);
        hi = glm::dvec3(s.boxMax);
        return;
    }
    bool empty = true;
    for (const Mesh& m : scene.meshes) {
        const glm::dmat4 model(m.model);
        for (const glm::vec3& p : m.data->positions) {
            const glm::dvec3 w = glm::dvec3(model * glm::dvec4(glm::dvec3(p), 1.0));
            lo = empty ? w : glm::min(lo, w);
            hi = empty ? w : glm::max(hi, w);
            empty = false;
        }
    }
    if (empty)
        throw Error(ErrorCode::InvalidArgument, "voxelize: the scene has no CPU mesh vertices to fit the box to; set "
                                                "VoxelizerSettings::fitBox = false and give the box");
    const glm::dvec3 extent = hi - lo;
    double grow = std::max({extent.x, extent.y, extent.z}) * std::max(double(s.margin), 1e-6);
    // A single point: any non-zero size relative to its position.
    if (!(grow > 0.0)) grow = std::max({std::abs(lo.x), std::abs(lo.y), std::abs(lo.z), 1.0}) * 1e-3;
    lo -= grow;
    hi += grow;
}

} // namespace

struct Voxelizer::Impl {
    explicit Impl(ContextImpl& c) : ctx(c), meshes(c) {}

    ContextImpl& ctx;
    MeshCache meshes;
    VoxelGrid grid;
    VoxelizerSettings settings;
    std::vector<std::string> warnings;
    Texture texture, octree, scratch;
    Framebuffer solidFbo, surfaceFbo;
    Buffer params, counter;
    SegmentBatch batch{{VOXEL_SEGMENTS_SSBO, VOXEL_RESULTS_SSBO, VOXEL_LOC_COUNT, VOXEL_LOC_FIRST, VOXEL_WORKGROUP_1D, "voxel"}};
    // What the current grid was built from (static scenes are not voxelized again); weak, so
    // a new MeshData at a freed one's address is not mistaken for it.
    std::vector<std::pair<std::weak_ptr<const MeshData>, glm::mat4>> builtFrom;
    bool built = false;
    // Watertightness per CPU mesh, computed once per MeshData for solid mode's warnings.
    std::vector<std::pair<std::weak_ptr<const MeshData>, MeshClosure>> closures;

    void allocate(int r, int d, int k, bool withOctree) {
        const int levels = log2i(r) + 1;
        if (!texture || grid.dims != glm::ivec3(r, r, d)) {
            solidFbo.reset();
            surfaceFbo.reset();
            octree.reset();
            texture = createArrayTexture(GL_RGBA32UI, r, r, k, levels, "voxel.grid");
            scratch = createArrayTexture(GL_R32UI, r, r, (d + 31) / 32, 1, "voxel.scratch");
            grid.dims = {r, r, d};
            grid.targets = k;
        }
        if (withOctree && !octree) octree = createArrayTexture(GL_RGBA32UI, r / 2, r / 2, k, levels - 1, "voxel.octree");
        if (!withOctree) octree.reset(); // no stale levels, no memory held for them
    }

    const MeshClosure& closureOf(const std::shared_ptr<const MeshData>& data) {
        std::erase_if(closures, [](const auto& c) { return c.first.expired(); });
        for (const auto& [mesh, closure] : closures)
            if (mesh.lock() == data) return closure;
        closures.emplace_back(data, meshClosure(*data));
        return closures.back().second;
    }

    // Solid mode: a CPU mesh that is not closed is reported even where no column crosses it
    // an odd number of times.
    void warnAboutOpenMeshes(const Scene& scene) {
        for (std::size_t i = 0; i < scene.meshes.size(); ++i) {
            const MeshClosure& c = closureOf(scene.meshes[i].data);
            if (c.watertight()) continue;
            const std::string& name = scene.meshes[i].name;
            warnings.push_back("solid voxelization: Scene::meshes[" + std::to_string(i) + "]" +
                               (name.empty() ? "" : " (" + name + ")") + " is not watertight (" +
                               std::to_string(c.boundaryEdges) + " boundary and " + std::to_string(c.nonManifoldEdges) +
                               " non-manifold edges of " + std::to_string(c.edges) +
                               "); inside and outside follow the parity of the surfaces along z");
        }
    }

    Texture createArrayTexture(GLenum format, int w, int h, int layers, int levels, const char* label) {
        GLuint t = 0;
        drainGlErrors(ctx);
        ctx.gl.CreateTextures(GL_TEXTURE_2D_ARRAY, 1, &t);
        ++ctx.liveObjects;
        Texture tex(ctx, t);
        ctx.gl.ObjectLabel(GL_TEXTURE, t, -1, label);
        ctx.gl.TextureStorage3D(t, levels, format, w, h, layers);
        checkAllocation(ctx, std::string(label) + " (" + std::to_string(w) + "x" + std::to_string(h) + "x" +
                                 std::to_string(layers) + ")");
        return tex;
    }

    void uploadParams(int viewport) {
        shader::VoxelParams p{};
        p.dims = grid.dims;
        p.octreeLevels = grid.levels;
        p.targets = grid.targets;
        p.surfaceViewport = viewport;
        uploadUniformBlock(ctx, params, p, VOXEL_PARAMS_UBO_BINDING, "voxel.params");
    }

    // Draws every mesh with `program`, its model-to-voxel transform in double precision.
    void drawScene(const Scene& scene, const std::vector<DrawableMesh>& hostMeshes, GLuint program) {
        const auto draw = [&](const DrawableMesh& mesh, const glm::mat4& model) {
            const glm::dmat4 m = grid.worldToVoxel * glm::dmat4(model);
            ctx.gl.ProgramUniformMatrix4dv(program, VOXEL_LOC_MODEL_TO_VOXEL, 1, GL_FALSE, glm::value_ptr(m));
            drawMesh(ctx, mesh);
        };
        for (const Mesh& m : scene.meshes) draw(meshes.cpuMesh(m.data), m.model);
        for (std::size_t i = 0; i < scene.meshRefs.size(); ++i) draw(hostMeshes[i], scene.meshRefs[i].model);
    }

    void surfacePass(const Scene& scene, const std::vector<DrawableMesh>& hostMeshes) {
        PassScope pass(ctx, "voxel.surface");
        auto& gl = ctx.gl;
        const int viewport = std::max(grid.dims.x, grid.dims.z);
        uploadParams(viewport);
        const std::uint32_t zero = 0;
        gl.ClearTexImage(scratch.get(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
        if (!surfaceFbo) {
            // No attachments: the fragments only write through image atomics.
            surfaceFbo = createFramebuffer(ctx, "voxel.surface");
            gl.NamedFramebufferParameteri(surfaceFbo.get(), GL_FRAMEBUFFER_DEFAULT_WIDTH, viewport);
            gl.NamedFramebufferParameteri(surfaceFbo.get(), GL_FRAMEBUFFER_DEFAULT_HEIGHT, viewport);
        }
        gl.BindFramebuffer(GL_FRAMEBUFFER, surfaceFbo.get());
        setViewport(ctx, 0, 0, viewport, viewport);
        applyDrawState(ctx, {});
        ctx.state.bindImage(ctx, VOXEL_SCRATCH_IMAGE, scratch.get(), 0, GL_TRUE, 0, GL_READ_WRITE, GL_R32UI);
        const GLuint program = ctx.shaders->program(
            {"voxel/voxelize.vert.glsl", "voxel/voxelize_surface.geom.glsl", "voxel/voxelize_surface.frag.glsl"});
        gl.UseProgram(program);
        drawScene(scene, hostMeshes, program);
        gl.MemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
        gl.UseProgram(ctx.shaders->program({"voxel/pack_slices.comp.glsl"}));
        ctx.state.bindImage(ctx, VOXEL_OUT_IMAGE, texture.get(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA32UI);
        dispatchCompute2D(ctx, grid.dims.x, grid.dims.y, VOXEL_WORKGROUP_2D);
        barrierForReaders(ctx);
    }

    void solidPass(const Scene& scene, const std::vector<DrawableMesh>& hostMeshes, bool countOpen) {
        PassScope pass(ctx, "voxel.solid");
        auto& gl = ctx.gl;
        uploadParams(grid.dims.x);
        const std::uint32_t zero[4] = {0, 0, 0, 0};
        gl.ClearTexImage(texture.get(), 0, GL_RGBA_INTEGER, GL_UNSIGNED_INT, zero);
        gl.ClearTexImage(scratch.get(), 0, GL_RED_INTEGER, GL_UNSIGNED_INT, zero); // layer 0: the column parity
        ctx.state.bindImage(ctx, VOXEL_SCRATCH_IMAGE, scratch.get(), 0, GL_TRUE, 0, GL_READ_WRITE, GL_R32UI);
        if (!solidFbo) {
            solidFbo = createFramebuffer(ctx, "voxel.solid");
            GLenum buffers[VOXEL_MAX_TARGETS];
            for (int t = 0; t < grid.targets; ++t) {
                gl.NamedFramebufferTextureLayer(solidFbo.get(), GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(t), texture.get(), 0, t);
                buffers[t] = GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(t);
            }
            gl.NamedFramebufferDrawBuffers(solidFbo.get(), grid.targets, buffers);
            if (gl.CheckNamedFramebufferStatus(solidFbo.get(), GL_DRAW_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
                throw Error(ErrorCode::UnsupportedFeature, "the solid voxelization framebuffer (RGBA32UI layers) is incomplete");
        }
        gl.BindFramebuffer(GL_FRAMEBUFFER, solidFbo.get());
        setViewport(ctx, 0, 0, grid.dims.x, grid.dims.y);
        DrawState state;
        state.depthClamp = true; // geometry in front of the box still toggles its columns
        state.logicOp = GL_XOR;
        applyDrawState(ctx, state);
        const GLuint program = ctx.shaders->program({"voxel/voxelize.vert.glsl", "voxel/voxelize_solid.frag.glsl"},
                                                    {"SOLID", "TARGETS=" + std::to_string(grid.targets)});
        gl.UseProgram(program);
        drawScene(scene, hostMeshes, program);
        applyDrawState(ctx, {});
        gl.MemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
        // Columns with an odd number of crossings (open meshes): clear and count them.
        if (!counter) counter = createBuffer(ctx, 4, nullptr, GL_DYNAMIC_STORAGE_BIT, "voxel.open_columns");
        gl.NamedBufferSubData(counter.get(), 0, 4, zero);
        ctx.state.bindStorageBuffer(ctx, VOXEL_COUNTER_SSBO, counter.get());
        ctx.state.bindImage(ctx, VOXEL_OUT_IMAGE, texture.get(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA32UI);
        gl.UseProgram(ctx.shaders->program({"voxel/open_columns.comp.glsl"}));
        dispatchCompute2D(ctx, grid.dims.x, grid.dims.y, VOXEL_WORKGROUP_2D);
        barrierForReaders(ctx);
        if (!countOpen) return; // the read-back waits for the GPU: optional for per-frame use
        std::uint32_t open = 0;
        gl.GetNamedBufferSubData(counter.get(), 0, 4, &open);
        grid.openColumns = open;
        if (open > 0)
            warnings.push_back("solid voxelization: " + std::to_string(open) + " of " +
                               std::to_string(grid.dims.x * grid.dims.y) +
                               " columns crossed the mesh an odd number of times (the mesh is not watertight there); "
                               "they were left empty");
    }

    void mips(bool withOctree) {
        PassScope pass(ctx, "voxel.mips");
        auto& gl = ctx.gl;
        const int levels = log2i(grid.dims.x);
        const GLuint quad = ctx.shaders->program({"voxel/mip_quadtree.comp.glsl"});
        const GLuint oct = ctx.shaders->program({"voxel/mip_octree.comp.glsl"});
        for (int l = 1; l <= levels; ++l) {
            gl.UseProgram(quad);
            gl.ProgramUniform1i(quad, VOXEL_LOC_LEVEL, l);
            ctx.state.bindImage(ctx, VOXEL_IN_IMAGE, texture.get(), l - 1, GL_TRUE, 0, GL_READ_ONLY, GL_RGBA32UI);
            ctx.state.bindImage(ctx, VOXEL_OUT_IMAGE, texture.get(), l, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA32UI);
            dispatchCompute2D(ctx, grid.dims.x >> l, grid.dims.y >> l, VOXEL_WORKGROUP_2D);
            gl.MemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
            if (!withOctree) continue;
            gl.UseProgram(oct);
            gl.ProgramUniform1i(oct, VOXEL_LOC_LEVEL, l);
            if (l == 1) ctx.state.bindImage(ctx, VOXEL_IN_IMAGE, texture.get(), 0, GL_TRUE, 0, GL_READ_ONLY, GL_RGBA32UI);
            else ctx.state.bindImage(ctx, VOXEL_IN_IMAGE, octree.get(), l - 2, GL_TRUE, 0, GL_READ_ONLY, GL_RGBA32UI);
            ctx.state.bindImage(ctx, VOXEL_OUT_IMAGE, octree.get(), l - 1, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA32UI);
            dispatchCompute2D(ctx, grid.dims.x >> l, grid.dims.y >> l, VOXEL_WORKGROUP_2D);
            gl.MemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
        }
        grid.levels = withOctree ? levels : 0;
        barrierForReaders(ctx);
    }

    std::vector<glm::uvec4> runQueries(const std::vector<VoxelSegment>& queries, int method,
                                       const TraversalSettings& query);

    // The same meshes (alive, same transforms) and settings give the same box and grid.
    bool upToDate(const Scene& scene, const VoxelizerSettings& s) const {
        if (!built || s.dynamic || !scene.meshRefs.empty()) return false;
        if (!sameSettings(s, settings) || builtFrom.size() != scene.meshes.size()) return false;
        for (std::size_t i = 0; i < builtFrom.size(); ++i)
            if (builtFrom[i].first.lock() != scene.meshes[i].data || builtFrom[i].second != scene.meshes[i].model)
                return false;
        return true;
    }
};

Voxelizer::Voxelizer(Context& context) : impl_(std::make_unique<Impl>(context.impl())) {}
Voxelizer::~Voxelizer() = default;

const VoxelGrid& Voxelizer::voxelize(const Scene& scene, const VoxelizerSettings& settings) {
    validateSettings(settings);
    auto& d = *impl_;
    if (d.upToDate(scene, settings)) return d.grid; // validated when it was built
    validateScene(scene);
    glm::dvec3 lo(0.0), hi(0.0);
    fitBox(scene, settings, lo, hi);

    d.built = false; // until this build completes: a failure must not leave a half-built grid current
    StateScope scope(d.ctx);
    d.warnings.clear();
    d.meshes.collectGarbage();
    std::vector<DrawableMesh> hostMeshes;
    for (std::size_t i = 0; i < scene.meshRefs.size(); ++i) hostMeshes.push_back(d.meshes.hostMesh(i, scene.meshRefs[i]));
    d.allocate(settings.resolution, VOXEL_SLICES_PER_TARGET * settings.targets, settings.targets, settings.octree);
    d.grid.boxMin = lo;
    d.grid.boxMax = hi;
    const glm::dvec3 scale = glm::dvec3(d.grid.dims) / (hi - lo);
    d.grid.worldToVoxel = glm::dmat4(1.0);
    for (int a = 0; a < 3; ++a) {
        d.grid.worldToVoxel[a][a] = scale[a];
        d.grid.worldToVoxel[3][a] = -lo[a] * scale[a];
    }
    d.grid.openColumns = 0;
    if (settings.mode == VoxelMode::Surface) {
        d.surfacePass(scene, hostMeshes);
    } else {
        d.solidPass(scene, hostMeshes, settings.countOpenColumns);
        d.warnAboutOpenMeshes(scene);
    }
    d.mips(settings.octree);
    d.uploadParams(0); // the final block (octree levels included) for shaders that query the grid
    d.grid.texture = d.texture.get();
    d.grid.octree = settings.octree ? d.octree.get() : 0;
    d.grid.params = d.params.get();
    ++d.grid.version;
    d.settings = settings;
    d.builtFrom.clear();
    for (const Mesh& m : scene.meshes) d.builtFrom.emplace_back(m.data, m.model);
    d.built = true;
    return d.grid;
}

// Runs the batch query shader with METHOD = `method` on the segments; one uvec4 per segment.
std::vector<glm::uvec4> Voxelizer::Impl::runQueries(const std::vector<VoxelSegment>& queries, int method,
                                                    const TraversalSettings& query) {
    StateScope scope(ctx);
    auto& gl = ctx.gl;
    batch.upload(ctx, queries);
    uploadParams(0);
    ctx.state.bindTexture(ctx, VOXEL_GRID_UNIT, texture.get());
    ctx.state.bindSampler(ctx, VOXEL_GRID_UNIT, ctx.nearestClampSampler());
    if (octree) {
        ctx.state.bindTexture(ctx, VOXEL_OCTREE_UNIT, octree.get());
        ctx.state.bindSampler(ctx, VOXEL_OCTREE_UNIT, ctx.nearestClampSampler());
    }
    const GLuint program = ctx.shaders->program({"voxel/trace_segments.comp.glsl"}, {"METHOD=" + std::to_string(method)});
    gl.UseProgram(program);
    gl.ProgramUniform1i(program, VOXEL_LOC_STEPS, query.marchSteps);
    gl.ProgramUniform1ui(program, VOXEL_LOC_SEED, query.seed);
    return batch.run(ctx, program, "voxel.trace");
}

std::vector<VoxelHit> Voxelizer::trace(const std::vector<VoxelSegment>& segments, const TraversalSettings& settings) {
    auto& d = *impl_;
    if (!d.built) throw Error(ErrorCode::InvalidState, "Voxelizer::trace: voxelize a scene first");
    obscura::validateSettings(TraversalSettings::table(), settings, "TraversalSettings");
    if (settings.method == VoxelTraversal::Hierarchical && d.grid.levels == 0)
        throw Error(ErrorCode::InvalidState, "hierarchical traversal needs the octree: VoxelizerSettings::octree = true");
    std::vector<VoxelHit> hits(segments.size());
    if (segments.empty()) return hits;
    const std::vector<glm::uvec4> raw = d.runQueries(segments, voxelTraversalCode(settings.method), settings);
    for (std::size_t i = 0; i < raw.size(); ++i) {
        VoxelHit& h = hits[i];
        h.hit = raw[i].x != 0;
        std::memcpy(&h.t, &raw[i].y, 4);
        h.fetches = raw[i].z;
        if (h.hit) h.voxel = {static_cast<int>(raw[i].w & 2047u), static_cast<int>((raw[i].w >> 11) & 2047u),
                              static_cast<int>(raw[i].w >> 22)};
    }
    return hits;
}

std::vector<std::uint8_t> Voxelizer::occupancy(const std::vector<glm::vec3>& points) {
    auto& d = *impl_;
    if (!d.built) throw Error(ErrorCode::InvalidState, "Voxelizer::occupancy: voxelize a scene first");
    std::vector<std::uint8_t> out(points.size(), 0);
    if (points.empty()) return out;
    std::vector<VoxelSegment> segments(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) segments[i] = {points[i], points[i]};
    const std::vector<glm::uvec4> raw = d.runQueries(segments, VOXEL_METHOD_OCCUPANCY, {});
    for (std::size_t i = 0; i < raw.size(); ++i) out[i] = raw[i].x != 0 ? 1 : 0;
    return out;
}

namespace {

// Unpacks `layers` of RGBA32UI columns of `dims` (x, y, slices) into one byte per voxel.
DenseVoxels unpack(const std::vector<std::uint32_t>& words, glm::ivec3 dims) {
    DenseVoxels out;
    out.dims = dims;
    out.voxels.assign(static_cast<std::size_t>(dims.x) * dims.y * dims.z, 0);
    for (int y = 0; y < dims.y; ++y)
        for (int x = 0; x < dims.x; ++x)
            for (int z = 0; z < dims.z; ++z) {
                const std::size_t texel = (static_cast<std::size_t>(z >> 7) * dims.y + y) * dims.x + x;
                const std::uint32_t word = words[texel * 4 + static_cast<std::size_t>((z >> 5) & 3)];
                out.voxels[(static_cast<std::size_t>(z) * dims.y + y) * dims.x + x] = (word >> (z & 31)) & 1u;
            }
    return out;
}

} // namespace

DenseVoxels Voxelizer::download(int octreeLevel) {
    auto& d = *impl_;
    if (!d.built) throw Error(ErrorCode::InvalidState, "Voxelizer::download: voxelize a scene first");
    requireInRange(octreeLevel, 0, d.grid.levels, "download octreeLevel", "");
    StateScope scope(d.ctx);
    const int level = octreeLevel;
    const glm::ivec3 dims(d.grid.dims.x >> level, d.grid.dims.y >> level, (d.grid.dims.z + (1 << level) - 1) >> level);
    std::vector<std::uint32_t> words(static_cast<std::size_t>(dims.x) * dims.y * d.grid.targets * 4);
    d.ctx.gl.GetTextureImage(level == 0 ? d.texture.get() : d.octree.get(), level == 0 ? 0 : level - 1, GL_RGBA_INTEGER,
                             GL_UNSIGNED_INT, static_cast<GLsizei>(words.size() * 4), words.data());
    return unpack(words, dims);
}

DenseVoxels Voxelizer::downloadQuadtree(int level) {
    auto& d = *impl_;
    if (!d.built) throw Error(ErrorCode::InvalidState, "Voxelizer::downloadQuadtree: voxelize a scene first");
    requireInRange(level, 0, log2i(d.grid.dims.x), "downloadQuadtree level", "");
    StateScope scope(d.ctx);
    const glm::ivec3 dims(d.grid.dims.x >> level, d.grid.dims.y >> level, d.grid.dims.z);
    std::vector<std::uint32_t> words(static_cast<std::size_t>(dims.x) * dims.y * d.grid.targets * 4);
    d.ctx.gl.GetTextureImage(d.texture.get(), level, GL_RGBA_INTEGER, GL_UNSIGNED_INT, static_cast<GLsizei>(words.size() * 4),
                             words.data());
    return unpack(words, dims);
}

const VoxelGrid& Voxelizer::grid() const noexcept { return impl_->grid; }
const std::vector<std::string>& Voxelizer::warnings() const noexcept { return impl_->warnings; }

std::size_t Voxelizer::memoryBytes() const {
    const auto& d = *impl_;
    if (!d.texture) return d.meshes.memoryBytes();
    const std::size_t column = static_cast<std::size_t>(d.grid.targets) * 16;
    const std::size_t base = static_cast<std::size_t>(d.grid.dims.x) * d.grid.dims.y * column;
    std::size_t mips = 0;
    for (int l = 1; (d.grid.dims.x >> l) > 0; ++l) mips += base >> (2 * l);
    return d.meshes.memoryBytes() + base + mips + (d.octree ? mips : 0) + base /*scratch*/ +
           d.batch.memoryBytes();
}

} // namespace obscura
