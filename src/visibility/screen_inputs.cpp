#include "visibility/screen_inputs.hpp"

#include "core/context_impl.hpp"
#include "core/texture_info.hpp"
#include "core/validate.hpp"
#include "obscura/error.hpp"
#include "shaders/visibility/visibility_bindings.h"

namespace obscura::detail {
void bindNearest(ContextImpl& ctx, int unit, GLuint texture) {
    ctx.state.bindTexture(ctx, unit, texture);
    ctx.state.bindSampler(ctx, unit, ctx.nearestClampSampler());
}

void requireViewInput(ContextImpl& ctx, const TextureView& texture, const GBufferView& checked, const std::string& what,
                      SampledAs kind) {
    const std::string who = "GBufferView::" + what;
    const TextureInfo info = queryTexture2D(ctx, texture.name, who);
    requireReadableAs(ctx, texture.name, info, who, kind);
    if (info.width != checked.width || info.height != checked.height)
        throw Error(ErrorCode::InvalidArgument, who + " (" + std::to_string(info.width) + "x" + std::to_string(info.height) +
                                                    ") must have the depth's size (" + std::to_string(checked.width) + "x" +
                                                    std::to_string(checked.height) + ")");
}

GBufferView checkScreenInputs(ContextImpl& ctx, const GBufferView& view, bool needsBack, const std::string& owner) {
    const TextureInfo depth = queryTexture2D(ctx, view.depth.name, "GBufferView::depth");
    requireReadableAs(ctx, view.depth.name, depth, "GBufferView::depth", SampledAs::Depth);
    if (!(view.normalError >= 0.0f && view.normalError <= kMaxNormalError))
        throw Error(ErrorCode::InvalidArgument, "GBufferView::normalError must be in [0, kMaxNormalError = 0.25], got " +
                                                    std::to_string(view.normalError));
    GBufferView checked = view;
    checked.width = depth.width;
    checked.height = depth.height;
    requireViewInput(ctx, view.normal, checked, "normal", SampledAs::Normal);
    if (needsBack) {
        if (!view.backDepth)
            throw Error(ErrorCode::InvalidArgument, owner + ": depth peeling needs GBufferView::backDepth, the second "
                                                            "depth layer of GBufferSettings::depthLayers = 2 or HostGBuffer::backDepth");
        requireViewInput(ctx, view.backDepth, checked, "backDepth", SampledAs::Depth);
    }
    return checked;
}

void bindScreenInputs(ContextImpl& ctx, const GBufferView& view, bool peeled) {
    bindNearest(ctx, VIS_DEPTH_UNIT, view.depth.name);
    bindNearest(ctx, VIS_NORMAL_UNIT, view.normal.name);
    if (peeled) bindNearest(ctx, VIS_BACK_DEPTH_UNIT, view.backDepth.name);
}

std::vector<std::string> screenMarchDefines(ScreenMarch march, ScreenThickness thickness) {
    const int code = march == ScreenMarch::View ? VIS_MARCH_VIEW : march == ScreenMarch::Texture ? VIS_MARCH_TEXTURE : VIS_MARCH_HIZ;
    std::vector<std::string> defines{"SCREEN_MARCH=" + std::to_string(code)};
    for (std::string& d : screenThicknessDefines(thickness)) defines.push_back(std::move(d));
    return defines;
}

std::vector<std::string> screenThicknessDefines(ScreenThickness thickness) {
    if (thickness == ScreenThickness::Constant) return {};
    if (thickness == ScreenThickness::DepthPeeling) return {"SCREEN_PEELED"};
    return {"SCREEN_PEELED", "SCREEN_PEELED_OR_CONSTANT"};
}

} // namespace obscura::detail
