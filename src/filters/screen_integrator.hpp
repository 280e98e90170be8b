#pragma once
// The steps every screen integrator shares (AmbientOcclusion and IndirectLight; SSDO and the
// media passes next): the frame block and the G-buffer's inputs, the reduced resolution and
// its geometry tiles, the ray batches, the integrator pass, the geometry-aware blur, the
// upsampling and its refinement at full resolution, temporal accumulation, and the textures
// all of that writes. A module keeps what is its own: its settings and their checks, its
// parameter block, its programs (from the settings and a variant) and its extra inputs.
#include "core/frame_uniforms.hpp"
#include "core/gl_objects.hpp"
#include "core/ray_batches.hpp"
#include "filters/guided_filters.hpp"
#include "filters/temporal_history.hpp"
#include "obscura/ambient_occlusion.hpp"
#include "obscura/gbuffer.hpp"
#include "visibility/hiz_pyramid.hpp"

#include <glm/glm.hpp>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

namespace obscura::detail {

struct ContextImpl;

//! What one run is, decided by the module from its settings.
struct IntegratorShape {
    const char* module = "";  //!< "ao", "gi": names the passes "<module>.tiles", ".blur", ... and textures
    const char* pass = "";    //!< the integrator's pass, e.g. "ao.raymarch"
    int workgroup = 8;        //!< the integrator's local size, x and y
    int scale = 1;            //!< 1, 2 or 4: the G-buffer's resolution over the integrator's
    bool rgb = false;         //!< the value is GL_RGBA16F (else GL_R16F)
    bool direction = false;   //!< a direction output beside the value (bent normals)
    //! The filters' settings; geometryTiles is what the settings ask for (run() drops it where
    //! the tiles do not fit one dispatch).
    GuidedFilterSettings filter;
    GLuint modulate = 0;      //!< FilterImages::modulate (indirect light's albedo), 0: none
    int rayLanes = 1;
    int batchItems = 1;       //!< rays (or slices) per pixel, for the ray batches
    std::int64_t iterationsPerItem = 1;
    //! A Hi-Z pyramid to build first (ScreenMarch::HiZ), with this thickness and mode.
    bool hiz = false;
    float hizThickness = 0.0f;
    ScreenThickness hizMode = ScreenThickness::Constant;
    TemporalSettings temporal;
};

//! The shape's fields every integrator's settings give alike (AmbientOcclusionSettings and
//! IndirectLightSettings share these fields' names and meanings); the module sets the rest.
//! `unitRange`, `background`: GuidedFilterSettings' (values in [0, 1], the background value).
template <class Settings>
IntegratorShape integratorShape(const Settings& s, const char* module, const char* pass, int workgroup, bool unitRange,
                                float background) {
    IntegratorShape shape;
    shape.module = module;
    shape.pass = pass;
    shape.workgroup = workgroup;
    shape.scale = static_cast<int>(s.resolution);
    shape.filter = {s.blurRadius, s.blurDepthSigma, s.blurNormalPower, unitRange, background, s.refineThreshold,
                    s.geometryTiles};
    shape.rayLanes = s.rayLanes;
    shape.hizThickness = s.thickness > 0.0f ? s.thickness : s.radius;
    shape.temporal = s.temporal;
    return shape;
}

//! The image units a module's integrator writes its value, direction and guide at.
struct IntegratorImages {
    int value = 0, direction = 1, guide = 2;
};

//! The outputs of a run: the G-buffer's size.
struct IntegratorResult {
    TextureView value, direction;
};

class ScreenIntegrator {
public:
    //! The integrator's resolution: the view's divided by `scale`, rounded up.
    static glm::ivec2 reducedSize(const GBufferView& view, int scale);

    //! The textures a run of `shape` writes or reallocates (the others of an earlier run may be
    //! read): for requireNotOwnOutput.
    std::vector<GLuint> written(const IntegratorShape& shape) const;

    //! Binds the frame block of the view's camera (with the frame index's sampling shift), the
    //! view's depth, normals and back layer, and the noise texture; builds the Hi-Z pyramid
    //! where the shape asks for it. Inside the caller's StateScope, before its own inputs.
    void begin(ContextImpl& ctx, const GBufferView& view, bool peeled, std::uint32_t frameIndex, const IntegratorShape& shape);

    //! The rest of the run, after the module bound its parameter block and inputs: the tiles,
    //! the integrator pass (`program(variant)`: "TILES", "REFINE" or nullptr; `bindInputs`
    //! binds what the program reads besides the above, with it in use), the blur, the
    //! upsampling and refinement, the temporal accumulation. Ends with barrierForReaders.
    IntegratorResult run(ContextImpl& ctx, const GBufferView& view, const IntegratorShape& shape,
                         const IntegratorImages& images, const std::function<GLuint(const char*)>& program,
                         const std::function<void()>& bindInputs);

    //! Compiles what run() takes for `shape`: the integrator's variants (`program`, as run()
    //! calls it) and the passes around it.
    static void prepare(ContextImpl& ctx, const IntegratorShape& shape, const std::function<GLuint(const char*)>& program);

    //! The last run's refinement (zeros without one); reads a count back from the GPU.
    RefinementCount lastRefinement(ContextImpl& ctx) const;
    void resetHistory() noexcept { temporal_.reset(); }
    std::size_t memoryBytes() const;

private:
    FrameUniforms frame_;
    HiZPyramid hiz_;
    GuidedFilters filters_;
    RayBatches batches_;
    TemporalHistory temporal_;
    SizedTexture value_, direction_, guide_, fullValue_, fullDirection_;
    bool refinedLastRun_ = false;
};

} // namespace obscura::detail
