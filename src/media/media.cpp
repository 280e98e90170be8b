#include "obscura/media.hpp"

#include "core/compute.hpp"
#include "core/context_impl.hpp"
#include "core/frame_uniforms.hpp"
#include "core/pass_scope.hpp"
#include "core/shader_library.hpp"
#include "core/texture_info.hpp"
#include "core/validate.hpp"
#include "gbuffer/light_records.hpp"
#include "filters/guided_filters.hpp"
#include "media/airlight_table.hpp"
#include "media/shadow_volumes.hpp"
#include "shaders/visibility/visibility_bindings.h"
#include "obscura/context.hpp"
#include "shaders/media/media_bindings.h"
#include "visibility/screen_inputs.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace obscura {
namespace {

using namespace detail;

// One comparison per sample, with the nearest comparison sampler.
ShadowMaskSettings hardShadows() {
    ShadowMaskSettings s;
    s.filter = ShadowFilter::Hard;
    return s;
}

void validate(const MediaInputs& in, const MediaSettings& s, const Camera& camera) {
    validateSettings(MediaSettings::table(), s, "MediaSettings");
    if (in.media.size() > MEDIA_MAX_MEDIA)
        throw Error(ErrorCode::InvalidArgument, "MediaInputs::media holds " + std::to_string(in.media.size()) +
                                                    " media; at most " + std::to_string(MEDIA_MAX_MEDIA) + " are supported");
    const auto grids = std::count_if(in.media.begin(), in.media.end(), [](const Medium& m) { return m.density == MediumDensity::Grid; });
    if (grids > 1)
        throw Error(ErrorCode::InvalidArgument, "MediaInputs::media holds " + std::to_string(grids) +
                                                    " density grids; one per run is supported");
    if (s.method == MediaMethod::Analytic)
        for (std::size_t i = 0; i < in.media.size(); ++i)
            if (in.media[i].density != MediumDensity::Constant)
                throw Error(ErrorCode::InvalidArgument, "MediaSettings::method Analytic takes homogeneous media, but "
                                                        "MediaInputs::media[" + std::to_string(i) + "].density is not Constant "
                                                        "(Sun et al.'s closed form needs a constant sigma)");
    Scene scene; // validateScene's checks of each medium and light
    scene.media.assign(in.media.begin(), in.media.end());
    scene.lights.assign(in.lights.begin(), in.lights.end());
    validateScene(scene);
    if (in.shadows) validateLightShadows(*in.shadows, hardShadows(), in.lights.size(), camera, "MediaInputs");
}

int phaseCode(PhaseFunction p) {
    switch (p) {
    case PhaseFunction::Isotropic: return MEDIA_PHASE_ISOTROPIC;
    case PhaseFunction::HenyeyGreenstein: return MEDIA_PHASE_HG;
    case PhaseFunction::Rayleigh: return MEDIA_PHASE_RAYLEIGH;
    case PhaseFunction::Schlick: return MEDIA_PHASE_SCHLICK;
    }
    return MEDIA_PHASE_ISOTROPIC;
}

shader::MediumData mediumData(const Medium& m) {
    shader::MediumData d{};
    d.boxMin = m.boxMin;
    d.boxMax = m.boxMax;
    d.phase = static_cast<float>(phaseCode(m.phase));
    d.g = m.phase == PhaseFunction::Schlick ? static_cast<float>(schlickK(m.anisotropy)) : m.anisotropy;
    d.scattering = m.scattering;
    d.extinction = m.scattering + m.absorption;
    d.density = static_cast<float>(m.density == MediumDensity::Height ? MEDIA_DENSITY_HEIGHT
                                   : m.density == MediumDensity::Grid ? MEDIA_DENSITY_GRID
                                                                      : MEDIA_DENSITY_CONSTANT);
    d.heightFalloff = m.heightFalloff;
    return d;
}

// The farthest view distance (-z) of the boxes' corners: where the froxel grid need not go past.
float farthestMediaDepth(std::span<const Medium> media, const glm::mat4& view) {
    double farthest = 0.0;
    for (const Medium& m : media)
        for (int c = 0; c < 8; ++c) {
            const glm::dvec3 corner(c & 1 ? m.boxMax.x : m.boxMin.x, c & 2 ? m.boxMax.y : m.boxMin.y,
                                    c & 4 ? m.boxMax.z : m.boxMin.z);
            farthest = std::max(farthest, -(glm::dmat4(view) * glm::dvec4(corner, 1.0)).z);
        }
    // Boxes all behind the camera: any range will do (the grid holds nothing).
    return farthest > 0.0 ? static_cast<float>(farthest) : 1.0f;
}

const char* passName(MediaMethod m) {
    switch (m) {
    case MediaMethod::RayMarch: return "media.raymarch";
    case MediaMethod::Analytic: return "media.analytic";
    case MediaMethod::Bounded: return "media.bounded";
    case MediaMethod::Froxel: return "media.froxel";
    }
    return "media";
}

bool marches(MediaMethod m) { return m == MediaMethod::RayMarch || m == MediaMethod::Bounded; }

// A march blurred or at reduced resolution: the filters run on it.
bool filtered(const MediaSettings& s) { return marches(s.method) && filtersRun(static_cast<int>(s.resolution), s.blurRadius); }

// The view z (< 0) the filters give background pixels: past every medium, so that their fog
// blends with the background's and not with surfaces in front.
float backgroundZ(std::span<const Medium> media, const glm::mat4& view) { return -2.0f * farthestMediaDepth(media, view); }

// The march's program: shadowed, bounded, and writing the filters' guide.
std::vector<std::string> marchDefines(const MediaSettings& s, bool shadowed, bool bounded) {
    std::vector<std::string> defines;
    if (shadowed) defines.push_back("SHADOWS");
    if (bounded) defines.push_back("BOUNDED");
    if (filtered(s)) defines.push_back("GUIDE");
    return defines;
}

// Depth-aware only: the guide's normals are all (0, 0, 1) (media have none).
GuidedFilterSettings filterSettings(const MediaSettings& s, float background) {
    GuidedFilterSettings f;
    f.taps = s.blurRadius;
    f.depthSigma = s.blurDepthSigma;
    f.normalPower = 0.0f;
    f.backgroundZ = background;
    return f;
}

} // namespace

struct Media::Impl {
    explicit Impl(ContextImpl& c) : ctx(c) {}

    ContextImpl& ctx;
    FrameUniforms frame;
    LightRecords lights;
    Buffer params;
    shader::MediaParams current{};
    SizedTexture scattering, opticalDepth, applied;
    Texture table;
    int tableSize = 0;
    Texture froxelSource, froxelExtinction;
    glm::ivec3 froxelSize{0};
    Texture grid;                               // the density grid, R32F
    std::weak_ptr<const DensityGrid> gridSource; // what `grid` holds (not kept alive)
    std::size_t gridBytes = 0;
    ShadowVolumes volumes;          // Bounded
    GuidedFilters filters;          // marches at reduced resolution or blurred
    SizedTexture lowScattering, guide;

    // Uploads the one grid medium's values (once per grid), binds it linear and clamped.
    void bindGrid(std::span<const Medium> media) {
        const auto it = std::find_if(media.begin(), media.end(), [](const Medium& m) { return m.density == MediumDensity::Grid; });
        if (it == media.end()) {
            grid.reset();
            gridSource.reset();
            gridBytes = 0;
            return;
        }
        // The same grid object (DensityGrid is immutable once shared, scene.hpp) is uploaded once.
        const bool same = !gridSource.expired() && !gridSource.owner_before(it->grid) && !it->grid.owner_before(gridSource);
        if (!grid || !same) {
            const glm::ivec3 n = it->grid->size;
            grid = createTexture3D(ctx, GL_R32F, n.x, n.y, n.z, "media.density_grid");
            ctx.gl.TextureSubImage3D(grid.get(), 0, 0, 0, 0, n.x, n.y, n.z, GL_RED, GL_FLOAT, it->grid->values.data());
            gridSource = it->grid;
            gridBytes = it->grid->values.size() * sizeof(float);
        }
        ctx.state.bindTexture(ctx, MEDIA_GRID_UNIT, grid.get());
        ctx.state.bindSampler(ctx, MEDIA_GRID_UNIT, ctx.linearClampSampler());
    }

    void ensureTable(int size) {
        if (table && tableSize == size) return;
        const std::vector<float> values = airlightTable(size);
        table = createTexture2D(ctx, GL_R32F, size, size, 1, "media.analytic_table");
        ctx.gl.TextureSubImage2D(table.get(), 0, 0, 0, size, size, GL_RED, GL_FLOAT, values.data());
        tableSize = size;
    }

    void ensureFroxels(glm::ivec3 size) {
        if (froxelSource && froxelSize == size) return;
        GLint most = 0;
        ctx.gl.GetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &most);
        if (glm::any(glm::greaterThan(size, glm::ivec3(most))))
            throw Error(ErrorCode::InvalidArgument,
                        "MediaSettings: the froxel grid (" + std::to_string(size.x) + "x" + std::to_string(size.y) + "x" +
                            std::to_string(size.z) + " with its first boundary) exceeds GL_MAX_3D_TEXTURE_SIZE = " +
                            std::to_string(most) + ": raise froxelTile or lower steps");
        Texture source = createTexture3D(ctx, GL_RGBA16F, size.x, size.y, size.z, "media.froxel_grid");
        Texture extinction = createTexture3D(ctx, GL_RGBA16F, size.x, size.y, size.z, "media.froxel_extinction");
        froxelSource = std::move(source);
        froxelExtinction = std::move(extinction);
        froxelSize = size;
    }

    void releaseUnused(const MediaSettings& s) {
        if (s.method != MediaMethod::Analytic || s.integral != AnalyticIntegral::Table) {
            table.reset();
            tableSize = 0;
        }
        if (s.method != MediaMethod::Bounded) volumes.release();
        if (!marches(s.method) || s.resolution == AoResolution::Full) lowScattering.release();
        if (!filtered(s)) {
            guide.release();
            filters = GuidedFilters{};
        }
        if (s.method != MediaMethod::Froxel) {
            froxelSource.reset();
            froxelExtinction.reset();
            froxelSize = glm::ivec3(0);
        }
    }

    void uploadParams(const GBufferView& g, const MediaInputs& in, const MediaSettings& s) {
        shader::MediaParams p{};
        for (std::size_t i = 0; i < in.media.size(); ++i) p.media[i] = mediumData(in.media[i]);
        p.viewToWorld = glm::mat4(glm::inverse(glm::dmat4(g.camera.view)));
        p.mediumCount = static_cast<int>(in.media.size());
        p.lightCount = static_cast<int>(in.lights.size());
        p.steps = s.steps;
        p.jitter = s.jitter ? 1 : 0;
        p.size = {g.width, g.height};
        p.tableSize = {s.tableSize, s.tableSize};
        p.tableMaxU = static_cast<float>(kAirlightTableMaxU);
        p.densitySteps = s.densitySteps;
        p.froxels = {(g.width + s.froxelTile - 1) / s.froxelTile, (g.height + s.froxelTile - 1) / s.froxelTile, s.steps};
        p.froxelRange = s.froxelRange > 0.0f ? s.froxelRange : farthestMediaDepth(in.media, g.camera.view);
        p.scale = marches(s.method) ? static_cast<int>(s.resolution) : 1;
        // The march's own output size: the G-buffer's divided by its scale, rounded up.
        p.size = (p.size + p.scale - 1) / p.scale;
        p.backgroundZ = backgroundZ(in.media, g.camera.view);
        current = p;
        uploadUniformBlock(ctx, params, current, MEDIA_PARAMS_UBO_BINDING, "media.params");
    }

    std::vector<std::string> shadowDefines(bool shadowed) const {
        return shadowed ? std::vector<std::string>{"SHADOWS"} : std::vector<std::string>{};
    }

    void bindOutputs(int width, int height) {
        const GLuint s = scattering.ensure(ctx, GL_RGBA16F, width, height, "media.scattering");
        const GLuint d = opticalDepth.ensure(ctx, GL_RGBA16F, width, height, "media.optical_depth");
        ctx.state.bindImage(ctx, MEDIA_OUT_IMAGE, s, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
        ctx.state.bindImage(ctx, MEDIA_DEPTH_OUT_IMAGE, d, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    }

    void runAnalytic(const GBufferView& g, const MediaSettings& s) {
        // The table is computed on the CPU once per size, outside the pass's timing.
        const bool tabled = s.integral == AnalyticIntegral::Table;
        if (tabled) ensureTable(s.tableSize);
        PassScope pass(ctx, passName(s.method));
        if (tabled) bindNearest(ctx, MEDIA_TABLE_UNIT, table.get());
        ctx.gl.UseProgram(ctx.shaders->program({"media/media_analytic.comp.glsl"}, {tabled ? "TABLE" : "QUADRATURE"}));
        bindOutputs(g.width, g.height);
        dispatchCompute2D(ctx, g.width, g.height, MEDIA_WORKGROUP);
        barrierForReaders(ctx);
    }

    // RayMarch and Bounded: the march at its resolution (Bounded with a light it cannot bound,
    // or unshadowed, is the plain march, as documented), then the optical depth per pixel, the
    // blur and the upsampling where the settings ask for them.
    void runMarch(const GBufferView& g, const MediaInputs& in, const MediaSettings& s, bool shadowed) {
        const bool bounded = s.method == MediaMethod::Bounded && shadowed && everyLightBounded(in);
        if (bounded) volumes.draw(ctx, in, lights, s.volumeCell, g.width, g.height);
        else volumes.release();
        const int scale = static_cast<int>(s.resolution);
        const glm::ivec2 low = current.size;
        bindOutputs(g.width, g.height);
        const GLuint value = scale > 1 ? lowScattering.ensure(ctx, GL_RGBA16F, low.x, low.y, "media.scattering_reduced")
                                       : scattering.get();
        const GLuint guideImage = filtered(s) ? guide.ensure(ctx, GL_RGBA32F, low.x, low.y, "media.guide") : 0;
        {
            PassScope pass(ctx, passName(s.method));
            ctx.gl.UseProgram(ctx.shaders->program({"media/media_march.comp.glsl"}, marchDefines(s, shadowed, bounded)));
            ctx.state.bindImage(ctx, MEDIA_OUT_IMAGE, value, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
            if (guideImage) ctx.state.bindImage(ctx, MEDIA_GUIDE_IMAGE, guideImage, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
            dispatchCompute2D(ctx, low.x, low.y, MEDIA_WORKGROUP);
            ctx.gl.MemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
        }
        if (scale > 1) {
            PassScope pass(ctx, "media.optical_depth");
            ctx.gl.UseProgram(ctx.shaders->program({"media/media_march.comp.glsl"}, {"OPTICAL_DEPTH"}));
            dispatchCompute2D(ctx, g.width, g.height, MEDIA_WORKGROUP);
        }
        if (guideImage) {
            const FilterImages images{guideImage, value, 0, true, low, scale, 0};
            const GuidedFilterSettings f = filterSettings(s, current.backgroundZ);
            filters.blur(ctx, images, f, "media.blur");
            if (scale > 1) {
                // The upsampling reads the depth; the normals it does not read (backgroundZ):
                // the depth stands at their unit too.
                bindNearest(ctx, VIS_DEPTH_UNIT, g.depth.name);
                bindNearest(ctx, VIS_NORMAL_UNIT, g.depth.name);
                filters.upsample(ctx, images, f, scattering.get(), 0, {g.width, g.height}, "media.upsample");
            }
        }
        barrierForReaders(ctx);
    }

    void runFroxels(const GBufferView& g, bool shadowed) {
        const glm::ivec3 cells = current.froxels;
        ensureFroxels({cells.x, cells.y, cells.z + 1});
        {
            PassScope pass(ctx, "media.froxel.inject");
            std::vector<std::string> defines = shadowDefines(shadowed);
            defines.insert(defines.begin(), "INJECT");
            ctx.gl.UseProgram(ctx.shaders->program({"media/media_froxel.comp.glsl"}, defines));
            ctx.state.bindImage(ctx, MEDIA_OUT_IMAGE, froxelSource.get(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
            ctx.state.bindImage(ctx, MEDIA_DEPTH_OUT_IMAGE, froxelExtinction.get(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
            const GLuint n = MEDIA_FROXEL_WORKGROUP;
            ctx.gl.DispatchCompute((GLuint(cells.x) + n - 1) / n, (GLuint(cells.y) + n - 1) / n, (GLuint(cells.z) + n - 1) / n);
            ctx.gl.MemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
        }
        {
            PassScope pass(ctx, "media.froxel.integrate");
            ctx.gl.UseProgram(ctx.shaders->program({"media/media_froxel.comp.glsl"}, {"INTEGRATE"}));
            ctx.state.bindImage(ctx, MEDIA_OUT_IMAGE, froxelSource.get(), 0, GL_TRUE, 0, GL_READ_WRITE, GL_RGBA16F);
            ctx.state.bindImage(ctx, MEDIA_DEPTH_OUT_IMAGE, froxelExtinction.get(), 0, GL_TRUE, 0, GL_READ_ONLY, GL_RGBA16F);
            dispatchCompute2D(ctx, cells.x, cells.y, MEDIA_WORKGROUP);
            barrierForReaders(ctx);
        }
        PassScope pass(ctx, "media.froxel.resolve");
        ctx.gl.UseProgram(ctx.shaders->program({"media/media_froxel.comp.glsl"}, {"RESOLVE"}));
        ctx.state.bindTexture(ctx, MEDIA_FROXEL_READ_UNIT, froxelSource.get());
        ctx.state.bindSampler(ctx, MEDIA_FROXEL_READ_UNIT, ctx.linearClampSampler());
        bindOutputs(g.width, g.height);
        dispatchCompute2D(ctx, g.width, g.height, MEDIA_WORKGROUP);
        barrierForReaders(ctx);
    }

    void release() {
        frame = FrameUniforms{};
        lights = LightRecords{};
        params.reset();
        scattering.release();
        opticalDepth.release();
        applied.release();
        table.reset();
        tableSize = 0;
        froxelSource.reset();
        froxelExtinction.reset();
        froxelSize = glm::ivec3(0);
        grid.reset();
        gridSource.reset();
        gridBytes = 0;
        volumes.release();
        filters = GuidedFilters{};
        lowScattering.release();
        guide.release();
    }
};

Media::Media(Context& context) : impl_(std::make_unique<Impl>(context.impl())) {}
Media::~Media() = default;

MediaView Media::run(const GBufferView& g, const MediaInputs& in, const MediaSettings& s) {
    auto& d = *impl_;
    auto& ctx = d.ctx;
    analyzeProjection(g.camera);
    validate(in, s, g.camera);
    const TextureInfo depth = queryTexture2D(ctx, g.depth.name, "GBufferView::depth");
    requireReadableAs(ctx, g.depth.name, depth, "GBufferView::depth", SampledAs::Depth);
    requireNotOwnOutput({{"GBufferView::depth", g.depth.name}},
                        {d.scattering.get(), d.opticalDepth.get(), d.applied.get()}, "Media");
    if (in.media.empty()) {
        d.release(); // no media: no pass, no memory
        return {};
    }
    GBufferView view = g;
    view.width = depth.width;
    view.height = depth.height;

    StateScope scope(ctx);
    d.releaseUnused(s);
    d.frame.bind(ctx, g.camera, view.width, view.height, depthStepOf(ctx, g.depth.name), 0.0f, s.frameIndex);
    ctx.bindNoiseTexture();
    // The analytic form has no shadows: it takes no maps.
    const ShadowMapSet* maps = s.method != MediaMethod::Analytic ? in.shadows : nullptr;
    const bool shadowed = d.lights.bindShadows(ctx, in.lights, g.camera, maps, hardShadows());
    d.lights.upload(ctx, in.lights, glm::dmat4(g.camera.view), "media.lights");
    d.uploadParams(view, in, s);
    bindNearest(ctx, MEDIA_DEPTH_UNIT, g.depth.name);
    d.bindGrid(in.media);
    if (s.method == MediaMethod::Froxel) d.runFroxels(view, shadowed);
    else if (marches(s.method)) d.runMarch(view, in, s, shadowed);
    else d.runAnalytic(view, s);
    return {{d.scattering.get(), GL_RGBA16F, view.width, view.height},
            {d.opticalDepth.get(), GL_RGBA16F, view.width, view.height},
            view.width,
            view.height};
}

TextureView Media::apply(const MediaView& view, const TextureView& lit) {
    auto& d = *impl_;
    auto& ctx = d.ctx;
    if (!view.scattering) return lit; // no media: the frame as it is
    const TextureInfo info = queryTexture2D(ctx, lit.name, "Media::apply lit");
    requireReadableAs(ctx, lit.name, info, "Media::apply lit", SampledAs::Rgb);
    if (info.width != view.width || info.height != view.height)
        throw Error(ErrorCode::InvalidArgument, "Media::apply: the lit frame (" + std::to_string(info.width) + "x" +
                                                    std::to_string(info.height) + ") must have the media view's size (" +
                                                    std::to_string(view.width) + "x" + std::to_string(view.height) + ")");
    requireNotOwnOutput({{"Media::apply lit", lit.name}}, {d.applied.get()}, "Media");
    StateScope scope(ctx);
    PassScope pass(ctx, "media.apply");
    ctx.gl.UseProgram(ctx.shaders->program({"media/media_apply.comp.glsl"}, {}));
    ctx.gl.Uniform2i(0, view.width, view.height);
    bindNearest(ctx, MEDIA_LIT_UNIT, lit.name);
    bindNearest(ctx, MEDIA_SCATTERING_UNIT, view.scattering.name);
    bindNearest(ctx, MEDIA_OPTICAL_DEPTH_UNIT, view.opticalDepth.name);
    const GLuint out = d.applied.ensure(ctx, GL_RGBA16F, view.width, view.height, "media.applied");
    ctx.state.bindImage(ctx, MEDIA_OUT_IMAGE, out, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    dispatchCompute2D(ctx, view.width, view.height, MEDIA_WORKGROUP);
    barrierForReaders(ctx);
    return {out, GL_RGBA16F, view.width, view.height};
}

void Media::prepare(const MediaSettings& s) {
    validateSettings(MediaSettings::table(), s, "MediaSettings");
    auto& ctx = impl_->ctx;
    StateScope scope(ctx);
    // With and without shadow maps: which one run() takes depends on its inputs.
    if (marches(s.method)) {
        const bool bounded = s.method == MediaMethod::Bounded;
        for (const bool shadowed : {false, true}) ctx.shaders->program({"media/media_march.comp.glsl"}, marchDefines(s, shadowed, false));
        if (bounded) {
            ctx.shaders->program({"media/media_march.comp.glsl"}, marchDefines(s, true, true));
            ctx.shaders->program({"media/media_volume.comp.glsl"});
            ctx.shaders->program({"media/media_volume.comp.glsl"}, {"CELLS"});
            ctx.shaders->program({"media/media_volume.vert.glsl", "media/media_volume.frag.glsl"});
        }
        if (s.resolution != AoResolution::Full) ctx.shaders->program({"media/media_march.comp.glsl"}, {"OPTICAL_DEPTH"});
        if (filtered(s))
            GuidedFilters::prepare(ctx, {1, 1, 0, true, {1, 1}, static_cast<int>(s.resolution), 0}, filterSettings(s, 0.0f));
    }
    if (s.method == MediaMethod::Analytic) {
        ctx.shaders->program({"media/media_analytic.comp.glsl"}, {s.integral == AnalyticIntegral::Table ? "TABLE" : "QUADRATURE"});
        if (s.integral == AnalyticIntegral::Table) impl_->ensureTable(s.tableSize);
    }
    if (s.method == MediaMethod::Froxel)
        for (const std::vector<std::string>& defines : {std::vector<std::string>{"INJECT"}, std::vector<std::string>{"INJECT", "SHADOWS"},
                                                         std::vector<std::string>{"INTEGRATE"}, std::vector<std::string>{"RESOLVE"}})
            ctx.shaders->program({"media/media_froxel.comp.glsl"}, defines);
    ctx.shaders->program({"media/media_apply.comp.glsl"}, {});
}

std::size_t Media::memoryBytes() const {
    const auto& d = *impl_;
    const std::size_t froxels = std::size_t(d.froxelSize.x) * std::size_t(d.froxelSize.y) * std::size_t(d.froxelSize.z);
    return d.scattering.bytes() + d.opticalDepth.bytes() + d.applied.bytes() + d.frame.memoryBytes() + d.lights.memoryBytes() +
           (d.params ? sizeof(shader::MediaParams) : 0) + std::size_t(d.tableSize) * std::size_t(d.tableSize) * 4 +
           froxels * 2 * bytesPerTexel(GL_RGBA16F) + d.gridBytes + d.volumes.memoryBytes() + d.filters.memoryBytes() +
           d.lowScattering.bytes() + d.guide.bytes();
}

} // namespace obscura
