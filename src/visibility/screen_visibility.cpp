#include "obscura/screen_visibility.hpp"

#include "core/compute.hpp"
#include "core/context_impl.hpp"
#include "core/frame_uniforms.hpp"
#include "core/texture_info.hpp"
#include "core/pass_scope.hpp"
#include "core/segment_batch.hpp"
#include "core/shader_library.hpp"
#include "core/validate.hpp"
#include "obscura/camera.hpp"
#include "obscura/context.hpp"
#include "obscura/error.hpp"
#include "shaders/visibility/visibility_bindings.h"
#include "visibility/hiz_pyramid.hpp"
#include "visibility/screen_inputs.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

namespace obscura {
namespace {

using namespace detail;

void validateSettings(const ScreenTraceSettings& s) {
    obscura::validateSettings(ScreenTraceSettings::table(), s, "ScreenTraceSettings");
}

} // namespace

struct ScreenVisibility::Impl {
    explicit Impl(ContextImpl& c) : ctx(c) {}

    ContextImpl& ctx;
    FrameUniforms frame;
    SegmentBatch batch{{VIS_SEGMENTS_SSBO, VIS_RESULTS_SSBO, VIS_LOC_COUNT, VIS_LOC_FIRST, VIS_WORKGROUP_1D, "visibility"}};
    HiZPyramid hiz;

    // Runs the batch shader over the segments; one uvec4 per segment.
    std::vector<glm::uvec4> run(const GBufferView& g, const std::vector<ScreenSegment>& queries, const ScreenTraceSettings& s) {
        const bool peeled = depthLayersFor(s.thicknessMode) == 2;
        const GBufferView view = checkScreenInputs(ctx, g, peeled, "ScreenTraceSettings");
        analyzeProjection(view.camera);
        StateScope scope(ctx);
        auto& gl = ctx.gl;
        frame.bind(ctx, view.camera, view.width, view.height, depthStepOf(ctx, view.depth.name), view.normalError);
        bindScreenInputs(ctx, view, peeled);
        batch.upload(ctx, queries); // first: it refuses oversized batches before any work
        if (s.march == ScreenMarch::HiZ) hiz.build(ctx, view, s.thickness, s.thicknessMode, "visibility.hiz");
        const GLuint program =
            ctx.shaders->program({"visibility/trace_screen.comp.glsl"}, screenMarchDefines(s.march, s.thicknessMode));
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
    return d.batch.memoryBytes() + d.hiz.memoryBytes() + d.frame.memoryBytes();
}

} // namespace obscura
