#include "obscura/screen_visibility.hpp"

#include "core/compute.hpp"
#include "core/context_impl.hpp"
#include "core/frame_uniforms.hpp"
#include "core/pass_scope.hpp"
#include "core/segment_batch.hpp"
#include "core/shader_library.hpp"
#include "core/validate.hpp"
#include "obscura/camera.hpp"
#include "obscura/context.hpp"
#include "obscura/error.hpp"
#include "shaders/visibility/visibility_bindings.h"
#include "visibility/screen_inputs.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <string>

namespace obscura {
namespace {

using namespace detail;

void validateSettings(const ScreenTraceSettings& s) {
    requireInRange(s.steps, 1, 4096, "ScreenTraceSettings::steps", "samples");
    if (!(s.jitter >= 0.0f && s.jitter < 1.0f))
        throw Error(ErrorCode::InvalidArgument,
                    "ScreenTraceSettings::jitter must be in [0, 1) sample spacings, got " + std::to_string(s.jitter));
    if (!(s.thickness > 0.0f) || std::isinf(s.thickness))
        throw Error(ErrorCode::InvalidArgument,
                    "ScreenTraceSettings::thickness must be in (0, inf) world units, got " + std::to_string(s.thickness));
}

int marchCode(ScreenMarch m) {
    return m == ScreenMarch::View ? VIS_MARCH_VIEW : m == ScreenMarch::Texture ? VIS_MARCH_TEXTURE : VIS_MARCH_HIZ;
}

} // namespace

struct ScreenVisibility::Impl {
    explicit Impl(ContextImpl& c) : ctx(c) {}

    ContextImpl& ctx;
    FrameUniforms frame;
    SegmentBatch batch{{VIS_SEGMENTS_SSBO, VIS_RESULTS_SSBO, VIS_LOC_COUNT, VIS_LOC_FIRST, VIS_WORKGROUP_1D, "visibility"}};
    Texture hiz;
    glm::ivec2 hizSize{0};
    int hizLevels = 0;

    // The pyramid over the view padded to powers of two, so that level L's cell i covers the
    // pixels [i 2^L, (i + 1) 2^L) with GL's halving mip sizes.
    void buildHiZ(const GBufferView& view, const ScreenTraceSettings& s) {
        const glm::ivec2 size(std::bit_ceil(static_cast<unsigned>(view.width)),
                              std::bit_ceil(static_cast<unsigned>(view.height)));
        const int levels = std::bit_width(static_cast<unsigned>(std::max(size.x, size.y)));
        if (!hiz || size != hizSize) {
            hiz = createTexture2D(ctx, GL_RG32F, size.x, size.y, levels, "visibility.hiz");
            hizSize = size;
            hizLevels = levels;
        }
        PassScope pass(ctx, "visibility.hiz");
        auto& gl = ctx.gl;
        const bool peeled = s.thicknessMode == ScreenThickness::DepthPeeling;
        GLuint program = ctx.shaders->program({"visibility/hiz_build.comp.glsl"},
                                              peeled ? Defines{"LEVEL0", "SCREEN_PEELED"} : Defines{"LEVEL0"});
        gl.UseProgram(program);
        gl.ProgramUniform1f(program, VIS_LOC_THICKNESS, s.thickness);
        ctx.state.bindImage(ctx, VIS_HIZ_WRITE_IMAGE, hiz.get(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RG32F);
        dispatchCompute2D(ctx, size.x, size.y, VIS_WORKGROUP_2D);
        program = ctx.shaders->program({"visibility/hiz_build.comp.glsl"}, {"REDUCE"});
        gl.UseProgram(program);
        for (int level = 1; level < levels; ++level) {
            gl.MemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
            ctx.state.bindImage(ctx, VIS_HIZ_READ_IMAGE, hiz.get(), level - 1, GL_FALSE, 0, GL_READ_ONLY, GL_RG32F);
            ctx.state.bindImage(ctx, VIS_HIZ_WRITE_IMAGE, hiz.get(), level, GL_FALSE, 0, GL_WRITE_ONLY, GL_RG32F);
            dispatchCompute2D(ctx, std::max(1, size.x >> level), std::max(1, size.y >> level), VIS_WORKGROUP_2D);
        }
        gl.MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
    }

    // Runs the batch shader over the segments; one uvec4 per segment.
    std::vector<glm::uvec4> run(const GBufferView& g, const std::vector<ScreenSegment>& queries, const ScreenTraceSettings& s) {
        const bool peeled = s.thicknessMode == ScreenThickness::DepthPeeling;
        const GBufferView view = checkScreenInputs(ctx, g, peeled, "ScreenTraceSettings");
        analyzeProjection(view.camera);
        StateScope scope(ctx);
        auto& gl = ctx.gl;
        frame.bind(ctx, view.camera, view.width, view.height);
        bindScreenInputs(ctx, view, peeled);
        batch.upload(ctx, queries); // first: it refuses oversized batches before any work
        if (s.march == ScreenMarch::HiZ) {
            buildHiZ(view, s);
            ctx.state.bindTexture(ctx, VIS_HIZ_UNIT, hiz.get());
            ctx.state.bindSampler(ctx, VIS_HIZ_UNIT, ctx.nearestClampSampler());
        }
        Defines defines{"MARCH=" + std::to_string(marchCode(s.march))};
        if (s.march == ScreenMarch::HiZ) defines.push_back("SCREEN_HIZ");
        if (peeled) defines.push_back("SCREEN_PEELED");
        const GLuint program = ctx.shaders->program({"visibility/trace_screen.comp.glsl"}, defines);
        gl.UseProgram(program);
        gl.ProgramUniform1i(program, VIS_LOC_STEPS, s.steps);
        gl.ProgramUniform1f(program, VIS_LOC_JITTER, s.jitter);
        gl.ProgramUniform1f(program, VIS_LOC_THICKNESS, s.thickness);
        return batch.run(ctx, program, "visibility.trace");
    }
};

ScreenVisibility::ScreenVisibility(Context& context) : impl_(std::make_unique<Impl>(context.impl())) {}
ScreenVisibility::~ScreenVisibility() = default;

std::vector<ScreenHit> ScreenVisibility::trace(const GBufferView& view, const std::vector<ScreenSegment>& segments,
                                               const ScreenTraceSettings& settings) {
    validateSettings(settings);
    std::vector<ScreenHit> hits(segments.size());
    if (segments.empty()) return hits;
    const std::vector<glm::uvec4> raw = impl_->run(view, segments, settings);
    for (std::size_t i = 0; i < raw.size(); ++i) {
        ScreenHit& h = hits[i];
        h.hit = raw[i].x != 0;
        h.sample = h.hit ? static_cast<int>(raw[i].y) : -1;
        h.fetches = raw[i].z;
        std::memcpy(&h.t, &raw[i].w, 4);
    }
    return hits;
}

std::vector<std::uint8_t> ScreenVisibility::hidden(const GBufferView& view, const std::vector<glm::vec3>& points,
                                                   const ScreenTraceSettings& settings) {
    ScreenTraceSettings s = settings;
    s.march = ScreenMarch::View;
    s.steps = 1;
    s.jitter = 0.0f; // the one sample is the segment's start: the point itself
    validateSettings(s);
    std::vector<std::uint8_t> out(points.size(), 0);
    if (points.empty()) return out;
    std::vector<ScreenSegment> segments(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) segments[i] = {points[i], points[i]};
    const std::vector<glm::uvec4> raw = impl_->run(view, segments, s);
    for (std::size_t i = 0; i < raw.size(); ++i) out[i] = raw[i].x != 0 ? 1 : 0;
    return out;
}

std::size_t ScreenVisibility::memoryBytes() const {
    const auto& d = *impl_;
    std::size_t hizBytes = 0;
    for (int level = 0; d.hiz && level < d.hizLevels; ++level)
        hizBytes += 8u * std::size_t(std::max(1, d.hizSize.x >> level)) * std::size_t(std::max(1, d.hizSize.y >> level));
    return d.batch.memoryBytes() + hizBytes + d.frame.memoryBytes();
}

} // namespace obscura
