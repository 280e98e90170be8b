#pragma once
// The geometry-aware filters integrators run on their reduced-resolution results
// (shaders/filters/): a separable blur guided by (view normal, view z), and joint bilateral
// upsampling to the G-buffer's resolution. Internal: modules own one each.
#include "core/gl_objects.hpp"
#include "obscura/ambient_occlusion.hpp"

#include <glm/glm.hpp>

#include <string>

namespace obscura::detail {

struct ContextImpl;

struct GuidedFilterSettings {
    int taps = 0;                //!< blur samples each side, [0, 16]; 0: no blur
    float depthSigma = 0.05f;    //!< relative view-depth difference weighted e^-1/2, (0, 1]
    float normalPower = 16.0f;   //!< normal weight exponent, [0, 256]
    bool unitRange = false;      //!< clamp values to [0, 1]
    float background = 0.0f;    //!< upsampling: the value of background pixels
    //! upsampling: pixels whose similar neighbours carry less than this share of their
    //! bilinear weight are listed for refinement at full resolution, [0, 1]; 0: none
    float refineThreshold = 0.0f;
    //! reduced resolution: the blur and the upsampling run over the tiles that
    //! GuidedFilters::findGeometryTiles listed this frame (geometry_tiles.glsl), its list
    //! still bound
    bool geometryTiles = false;
    //! 0: background pixels hold nothing (guide w = 0; the upsampling writes `background`).
    //! Else the view z (< 0) they stand at: the blur and the upsampling weigh them by depth as
    //! any other pixel, the normals unread (normalPower 0). Media: fog in front of the sky.
    float backgroundZ = 0.0f;
};

//! The images one integrator filters: a value (GL_R16F, or GL_RGBA16F with `rgb`) and an
//! optional direction (GL_RGBA16F unit vectors, filtered as offsets from their pixels' normals),
//! at the low resolution.
struct FilterImages {
    GLuint guide = 0;
    GLuint value = 0;
    GLuint direction = 0; //!< 0: none
    bool rgb = false;
    glm::ivec2 size{0};   //!< low resolution
    int scale = 1;        //!< to the full resolution
    //! With `rgb`: a texture of the G-buffer's size whose rgb the last step (the upsampling,
    //! or at full resolution the blur's second pass) multiplies each written pixel's rgb by;
    //! 0: none. Indirect light's albedo, which the guide does not see; read as a reflectance
    //! (clampAlbedo: [0, 1], NaN as 0).
    GLuint modulate = 0;
};

//! Whether a result at 1 / `scale` of the G-buffer's resolution with `taps` of blur is
//! blurred or upsampled, and so needs a guide image from its integrator.
inline bool filtersRun(int scale, int taps) { return scale > 1 || taps > 0; }


class GuidedFilters {
public:
    //! Whether the tiles of an image of `lowSize` fit one indirect dispatch: at most 65535, the
    //! group count per dimension every GL 4.5 implementation takes (about 4096 x 4096 G-buffer
    //! pixels at half resolution). Larger images run every tile.
    static bool geometryTilesFit(glm::ivec2 lowSize);
    //! Lists the tiles of FILTER_WORKGROUP^2 pixels at the low resolution (images.size) with a
    //! G-buffer pixel that is not background, for the integrator (dispatchGeometryTiles) and
    //! the filters (GuidedFilterSettings::geometryTiles), and leaves the list bound at
    //! FILTER_TILES_SSBO for them. Also gives `images` what the tiles and pixels the
    //! integrator skips (tiledGeometryPixel) must hold for the filters, which read them across
    //! tile edges (guide 0: background; the value `background`, the direction 0: finite, for
    //! weights of 0); in the pass, so that its time counts what running over tiles costs. The
    //! caller has bound the frame block and the G-buffer's depth (VIS_DEPTH_UNIT). Pass
    //! `passName`.
    void findGeometryTiles(ContextImpl& ctx, const FilterImages& images, float background, const char* passName);
    //! After findGeometryTiles: runs the program in use (TILES, FILTER_WORKGROUP^2 pixels a
    //! group) once per listed tile.
    void dispatchGeometryTiles(ContextImpl& ctx);
    //! Blurs the images in place (through temporaries of the same size). Pass "<pass>.blur".
    void blur(ContextImpl& ctx, const FilterImages& images, const GuidedFilterSettings& s, const char* passName);
    //! Writes the full-resolution images from the low-resolution ones; the caller has bound
    //! the frame block and the G-buffer's depth and normal (VIS_DEPTH_UNIT, VIS_NORMAL_UNIT).
    //! With a refinement threshold, it also lists the pixels with too little similar weight
    //! (refine_list.glsl), at most refineCapacity (a quarter of the G-buffer's pixels, at most
    //! 65535 groups' worth), for dispatchRefinement to
    //! overwrite; every pixel is blended as without it, so that an overflowed list leaves
    //! blended values. With
    //! geometry tiles, the images are cleared to the background values first.
    void upsample(ContextImpl& ctx, const FilterImages& images, const GuidedFilterSettings& s, GLuint fullValue,
                  GLuint fullDirection, glm::ivec2 fullSize, const char* passName);
    //! After an upsample with a refinement threshold: runs the program in use (an integrator's
    //! REFINE variant, FILTER_REFINE_GROUP invocations a group) once per listed pixel, with the
    //! list bound at FILTER_REFINE_SSBO. The caller binds the program's inputs and outputs.
    void dispatchRefinement(ContextImpl& ctx);
    //! After an upsample with a refinement threshold: the pixels it asked to refine and how
    //! many the refinement computed (all of them, or none past the list's capacity). Waits for
    //! the GPU.
    RefinementCount refinementCount(ContextImpl& ctx) const;
    //! Compiles the programs findGeometryTiles (with s.geometryTiles), blur and upsample
    //! (images.scale > 1) use for such images and settings, ahead of time: of `images` only
    //! which textures are given (not 0), `rgb` and `scale` matter.
    static void prepare(ContextImpl& ctx, const FilterImages& images, const GuidedFilterSettings& s);
    //! The most pixels an upsample to fullSize lists for refinement.
    static std::size_t refineCapacity(glm::ivec2 fullSize);
    std::size_t memoryBytes() const;

private:
    void upload(ContextImpl& ctx, const FilterImages& images, const GuidedFilterSettings& s);
    void startRefineList(ContextImpl& ctx, glm::ivec2 fullSize);
    Buffer params_, refineList_, tiles_;
    std::size_t refineListBytes_ = 0, tilesBytes_ = 0;
    SizedTexture valueTemp_, directionTemp_;
};

} // namespace obscura::detail
