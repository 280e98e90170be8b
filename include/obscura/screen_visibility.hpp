#pragma once
// Visibility queries in screen space: the depth buffer of a G-buffer as an occluder, the
// GLSL functions of shaders/visibility/screen_march.glsl in batches (like Voxelizer::trace).
//
// A depth pixel stands for a piece of surface: the point o reconstructed at the pixel
// centre, the G-buffer's geometric normal n, and a back: `thickness` world units behind the
// tangent plane (along n, so independent of the depth one pixel's footprint spans at
// grazing angles), or the second depth layer of GBufferSettings::depthLayers = 2 or of
// HostGBuffer::backDepth (DepthPeeling; the constant thickness where that layer is empty),
// or the deeper of the two (PeelingOrConstant). A point is hidden when it projects into a
// pixel, lies behind that pixel's tangent plane (dot(s - o, n) < 0, so a ray leaving a
// plane never hits it again at any resolution; beyond the rounding of depth, positions and
// normals: where o may lie on the plane a segment from -> to starts on (within the start
// pixel's normal error of its tangent plane), e_o |from - o| + (e_from + e_o) |s - from| for
// a sample s, e being each pixel's normal error, GBufferView::normalError times its normal's
// alpha) and is not beyond the back. Points outside
// the image or behind the camera plane are visible (the border policy). The reach of a query
// is its segment: the radius check of the integrators is the segment's length.
//
// A segment from -> to is sampled at t_j = (j + jitter) / steps, j = 0 .. steps - 1:
//   View     the 3D points from + (to - from) t_j, projected to their pixels;
//   Texture  the same samples in texture space: clip coordinates and view z interpolated
//            linearly in t (perspective-correct), the view point reconstructed from the
//            texture coordinate. Classifies like View up to float rounding at pixel edges;
//   HiZ      the Texture samples, with runs of them skipped through a min/max view-z
//            pyramid of the depth buffer (built per call for the thickness): the same first
//            hidden sample as Texture, with fewer texel fetches where rays pass far from
//            surfaces. To test every pixel a segment crosses, take steps >= its length in
//            pixels.
#include "obscura/export.hpp"
#include "obscura/settings_table.hpp"
#include "obscura/gbuffer.hpp"

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace obscura {

class Context;

enum class ScreenMarch { View, Texture, HiZ };
enum class ScreenThickness {
    Constant,     //!< `thickness` world units behind every depth pixel
    DepthPeeling, //!< down to GBufferView::backDepth (GBufferSettings::depthLayers = 2, or HostGBuffer::backDepth)
    //! Hidden by either: within `thickness` or in front of backDepth. Thick closed objects
    //! are as deep as peeling finds them, thin parts (whose back lies within `thickness`)
    //! keep the constant slab that stands in for what is stacked behind them.
    PeelingOrConstant,
};

//! GBufferSettings::depthLayers that a thickness mode reads: 2 where it needs backDepth (in
//! post-process mode: HostGBuffer::backDepth).
constexpr int depthLayersFor(ScreenThickness mode) { return mode == ScreenThickness::Constant ? 1 : 2; }

namespace settings {

//! The march and thickness rows of every screen-space ray tracer (same names, same values).
template <class S>
Setting<S> screenMarchRow(ScreenMarch S::*member, std::string doc) {
    return choice("march", member,
                  {{"view", ScreenMarch::View}, {"texture", ScreenMarch::Texture}, {"hiz", ScreenMarch::HiZ}},
                  std::move(doc));
}

template <class S>
Setting<S> screenThicknessRow(ScreenThickness S::*member, std::string doc) {
    return choice("thicknessMode", member,
                  {{"constant", ScreenThickness::Constant},
                   {"depth_peeling", ScreenThickness::DepthPeeling},
                   {"peeling_or_constant", ScreenThickness::PeelingOrConstant}},
                  std::move(doc));
}

} // namespace settings

struct ScreenTraceSettings {
    ScreenMarch march = ScreenMarch::View;
    int steps = 32;
    float jitter = 0.5f;
    ScreenThickness thicknessMode = ScreenThickness::Constant;
    //! With DepthPeeling only where no back layer exists, with PeelingOrConstant everywhere
    //! (the deeper of it and the back layer).
    float thickness = 1.0f;

    static const SettingsTable<ScreenTraceSettings>& table(); //!< units and ranges (settings_table.hpp)
};

inline const SettingsTable<ScreenTraceSettings>& ScreenTraceSettings::table() {
    using S = ScreenTraceSettings;
    using namespace settings;
    static const SettingsTable<S> rows = {
        screenMarchRow(&S::march, "3D samples, 2D samples, or 2D samples skipping runs through a Hi-Z pyramid"),
        number("steps", &S::steps, "", "[1, 4096]", "samples per segment"),
        number("jitter", &S::jitter, "of the spacing", "[0, 1)", "offset of the samples"),
        screenThicknessRow(&S::thicknessMode, "constant thickness, the second depth layer, or the deeper of both"),
        number("thickness", &S::thickness, "world units", "(0, inf)", "how far behind a depth sample a point is inside"),
    };
    return rows;
}

//! A segment in the G-buffer camera's view space (world units). NaN or Inf: a miss.
struct ScreenSegment {
    glm::vec3 from{0.0f}, to{0.0f};
};

struct ScreenHit {
    bool hit = false;
    int sample = -1;           //!< index j of the first hidden sample; -1 for a miss
    float t = 1.0f;            //!< its parameter t_j on the segment; 1 for a miss
    std::uint32_t fetches = 0; //!< texel fetches the query made (the start's normal; depth, normal, back, pyramid)
};

class OBSCURA_API ScreenVisibility {
public:
    explicit ScreenVisibility(Context& context);
    ~ScreenVisibility();

    //! Traces view-space segments against the G-buffer's depth (passes "visibility.hiz" for
    //! the pyramid and "visibility.trace"). Throws Error{InvalidArgument} for settings out of
    //! range (enumerators included), a G-buffer without depth or normals, or a mode that reads a back layer (depthLayersFor) without one.
    std::vector<ScreenHit> trace(const GBufferView& view, const std::vector<ScreenSegment>& segments,
                                 const ScreenTraceSettings& settings);
    //! Whether each view-space point is hidden (screenHidden, with the settings' thickness).
    std::vector<std::uint8_t> hidden(const GBufferView& view, const std::vector<glm::vec3>& points,
                                     const ScreenTraceSettings& settings);

    //! GPU memory this module holds right now, bytes (segment buffers and the pyramid).
    std::size_t memoryBytes() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

} // namespace obscura
