#include "filters/guided_filters.hpp"

#include "core/compute.hpp"
#include "core/context_impl.hpp"
#include "core/pass_scope.hpp"
#include "core/shader_library.hpp"
#include "core/validate.hpp"
#include "shaders/filters/filter_bindings.h"

#include <algorithm>
#include <cstdint>
#include <vector>

namespace obscura::detail {
namespace {

GLenum valueFormat(const FilterImages& images) { return images.rgb ? GL_RGBA16F : GL_R16F; }

// The shader variant for the images; `lastStep`: the step that multiplies by images.modulate.
std::vector<std::string> variant(const FilterImages& images, const GuidedFilterSettings& s, bool lastStep) {
    std::vector<std::string> defines;
    if (images.rgb) defines.push_back("RGB");
    if (images.direction) defines.push_back("DIRECTION");
    if (lastStep && images.modulate) defines.push_back("MODULATE");
    if (s.geometryTiles) defines.push_back("TILES");
    return defines;
}

GLuint blurProgram(ContextImpl& ctx, const FilterImages& images, const GuidedFilterSettings& s, bool lastStep) {
    return ctx.shaders->program({"filters/guided_blur.comp.glsl"}, variant(images, s, lastStep));
}

GLuint upsampleProgram(ContextImpl& ctx, const FilterImages& images, const GuidedFilterSettings& s) {
    std::vector<std::string> defines = variant(images, s, true);
    if (s.refineThreshold > 0.0f) defines.push_back("REFINE");
    if (images.scale == 2) defines.push_back("HALF"); // the bilinear weights' zeros, known
    return ctx.shaders->program({"filters/joint_upsample.comp.glsl"}, defines);
}

GLuint tilesProgram(ContextImpl& ctx) { return ctx.shaders->program({"filters/geometry_tiles.comp.glsl"}, {}); }

// The value every channel of a background pixel gets, in the value image's format.
void clearValue(ContextImpl& ctx, GLuint texture, bool rgb, float background) {
    const glm::vec4 texel(background);
    ctx.gl.ClearTexImage(texture, 0, rgb ? GL_RGBA : GL_RED, GL_FLOAT, &texel);
}

// A guide (background) or direction (none) image, if any, to 0.
void clearToZero(ContextImpl& ctx, GLuint texture) {
    const glm::vec4 zero(0.0f);
    if (texture) ctx.gl.ClearTexImage(texture, 0, GL_RGBA, GL_FLOAT, &zero);
}

// The tiles of FILTER_WORKGROUP^2 pixels covering an image of `lowSize`.
glm::ivec2 tileGrid(glm::ivec2 lowSize) { return (lowSize + FILTER_WORKGROUP - 1) / FILTER_WORKGROUP; }

// Runs the program in use with the group counts at `offset` in `buffer`.
void dispatchIndirect(ContextImpl& ctx, const Buffer& buffer, GLintptr offset) {
    ctx.gl.BindBuffer(GL_DISPATCH_INDIRECT_BUFFER, buffer.get());
    ctx.gl.DispatchComputeIndirect(offset);
}

// The factor the last step multiplies by (MODULATE), if any.
void bindModulation(ContextImpl& ctx, const FilterImages& images) {
    if (!images.modulate) return;
    ctx.state.bindTexture(ctx, FILTER_MODULATE_UNIT, images.modulate);
    ctx.state.bindSampler(ctx, FILTER_MODULATE_UNIT, ctx.nearestClampSampler());
}

void bindImage(ContextImpl& ctx, int unit, GLuint texture, GLenum access, GLenum format) {
    ctx.state.bindImage(ctx, unit, texture, 0, GL_FALSE, 0, access, format);
}

// The value (and direction) images of one filter step: read from `in`, written to `out`.
void bindImages(ContextImpl& ctx, const FilterImages& images, GLuint valueIn, GLuint directionIn, GLuint valueOut,
                GLuint directionOut) {
    const GLenum format = valueFormat(images);
    bindImage(ctx, FILTER_VALUE_IN_IMAGE, valueIn, GL_READ_ONLY, format);
    bindImage(ctx, FILTER_VALUE_IMAGE, valueOut, GL_WRITE_ONLY, format);
    if (!images.direction) return;
    bindImage(ctx, FILTER_DIRECTION_IN_IMAGE, directionIn, GL_READ_ONLY, GL_RGBA16F);
    bindImage(ctx, FILTER_DIRECTION_IMAGE, directionOut, GL_WRITE_ONLY, GL_RGBA16F);
}

} // namespace

void GuidedFilters::upload(ContextImpl& ctx, const FilterImages& images, const GuidedFilterSettings& s) {
    shader::FilterParams p{};
    p.lowSize = images.size;
    p.scale = images.scale;
    p.blurTaps = s.taps;
    p.depthSigma = s.depthSigma;
    p.normalPower = s.normalPower;
    p.background = s.background;
    p.refineThreshold = s.refineThreshold;
    p.flags = s.unitRange ? FILTER_FLAG_UNIT_RANGE : 0;
    p.backgroundZ = s.backgroundZ;
    uploadUniformBlock(ctx, params_, p, FILTER_PARAMS_UBO_BINDING, "filters.params");
    bindImage(ctx, FILTER_GUIDE_IN_IMAGE, images.guide, GL_READ_ONLY, GL_RGBA32F);
}

void GuidedFilters::blur(ContextImpl& ctx, const FilterImages& images, const GuidedFilterSettings& s, const char* passName) {
    if (s.taps <= 0) return;
    PassScope pass(ctx, passName);
    upload(ctx, images, s);
    const GLenum format = valueFormat(images);
    const GLuint valueTemp = valueTemp_.ensure(ctx, format, images.size.x, images.size.y, "filters.blur_value");
    const GLuint directionTemp =
        images.direction ? directionTemp_.ensure(ctx, GL_RGBA16F, images.size.x, images.size.y, "filters.blur_direction") : 0;
    for (int d = 0; d < 2; ++d) { // horizontal into the temporaries, vertical back
        const bool horizontal = d == 0;
        // At full resolution the vertical pass is the last step.
        const bool lastStep = !horizontal && images.scale == 1;
        const GLuint program = blurProgram(ctx, images, s, lastStep);
        if (lastStep) bindModulation(ctx, images);
        ctx.gl.UseProgram(program);
        if (horizontal) bindImages(ctx, images, images.value, images.direction, valueTemp, directionTemp);
        else bindImages(ctx, images, valueTemp, directionTemp, images.value, images.direction);
        ctx.gl.ProgramUniform2i(program, FILTER_LOC_STEP, horizontal ? 1 : 0, horizontal ? 0 : 1);
        if (s.geometryTiles) dispatchGeometryTiles(ctx);
        else dispatchCompute2D(ctx, images.size.x, images.size.y, FILTER_WORKGROUP);
        ctx.gl.MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    }
}

void GuidedFilters::upsample(ContextImpl& ctx, const FilterImages& images, const GuidedFilterSettings& s, GLuint fullValue,
                             GLuint fullDirection, glm::ivec2 fullSize, const char* passName) {
    PassScope pass(ctx, passName);
    upload(ctx, images, s);
    bindModulation(ctx, images);
    if (s.geometryTiles) {
        // What the upsampling writes at background pixels, for the tiles it does not visit.
        clearValue(ctx, fullValue, images.rgb, s.background);
        clearToZero(ctx, fullDirection);
    }
    if (s.refineThreshold > 0.0f) startRefineList(ctx, fullSize);
    ctx.gl.UseProgram(upsampleProgram(ctx, images, s));
    bindImages(ctx, images, images.value, images.direction, fullValue, fullDirection);
    // One invocation per 2 x 2 quad of G-buffer pixels (see joint_upsample.comp.glsl).
    if (s.geometryTiles) dispatchIndirect(ctx, tiles_, 3 * sizeof(GLuint)); // the upsampling's header
    else dispatchCompute2D(ctx, (fullSize.x + 1) / 2, (fullSize.y + 1) / 2, FILTER_WORKGROUP);
    ctx.gl.MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT |
                         (s.refineThreshold > 0.0f ? GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT : 0));
}

void GuidedFilters::startRefineList(ContextImpl& ctx, glm::ivec2 fullSize) {
    const std::size_t bytes = (FILTER_REFINE_HEADER_UINTS + refineCapacity(fullSize)) * sizeof(GLuint);
    if (!refineList_ || refineListBytes_ != bytes) {
        refineList_ = createBuffer(ctx, bytes, nullptr, GL_DYNAMIC_STORAGE_BIT, "filters.refine_list");
        refineListBytes_ = bytes;
    }
    const GLuint header[FILTER_REFINE_HEADER_UINTS] = {0, 1, 1, 0}; // no groups yet, none listed
    ctx.gl.NamedBufferSubData(refineList_.get(), 0, sizeof header, header);
    ctx.state.bindStorageBuffer(ctx, FILTER_REFINE_SSBO, refineList_.get());
}

bool GuidedFilters::geometryTilesFit(glm::ivec2 lowSize) {
    const glm::ivec2 tiles = tileGrid(lowSize);
    return std::int64_t(tiles.x) * std::int64_t(tiles.y) <= 65535;
}

void GuidedFilters::findGeometryTiles(ContextImpl& ctx, const FilterImages& images, float background, const char* passName) {
    PassScope pass(ctx, passName);
    clearToZero(ctx, images.guide);
    clearValue(ctx, images.value, images.rgb, background);
    clearToZero(ctx, images.direction);
    const int scale = images.scale;
    const glm::ivec2 tiles = tileGrid(images.size);
    // The codes, a mark per tile, two uints of pixel mask per tile (geometry_tiles.glsl).
    const std::size_t bytes = (FILTER_TILES_HEADER_UINTS + 4 * std::size_t(tiles.x) * std::size_t(tiles.y)) * sizeof(GLuint);
    if (!tiles_ || tilesBytes_ != bytes) {
        tiles_ = createBuffer(ctx, bytes, nullptr, GL_DYNAMIC_STORAGE_BIT, "filters.geometry_tiles");
        tilesBytes_ = bytes;
    }
    const GLuint quadGroupsPerSide = GLuint(scale / 2);
    // No groups listed yet, none done marking (geometry_tiles.glsl's header).
    const GLuint header[FILTER_TILES_HEADER_UINTS] = {0, 1, 1, 0, quadGroupsPerSide, quadGroupsPerSide, 0, 0};
    ctx.gl.NamedBufferSubData(tiles_.get(), 0, sizeof header, header);
    ctx.state.bindStorageBuffer(ctx, FILTER_TILES_SSBO, tiles_.get());
    const GLuint program = tilesProgram(ctx);
    ctx.gl.UseProgram(program);
    ctx.gl.ProgramUniform1i(program, FILTER_LOC_TILE_SCALE, scale);
    dispatchCompute2D(ctx, tiles.x, tiles.y, FILTER_WORKGROUP); // one invocation per tile
    ctx.gl.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
}

void GuidedFilters::prepare(ContextImpl& ctx, const FilterImages& images, const GuidedFilterSettings& s) {
    if (s.geometryTiles) tilesProgram(ctx);
    if (s.taps > 0) {
        blurProgram(ctx, images, s, false);
        blurProgram(ctx, images, s, images.scale == 1);
    }
    if (images.scale > 1) upsampleProgram(ctx, images, s);
}

void GuidedFilters::dispatchGeometryTiles(ContextImpl& ctx) { dispatchIndirect(ctx, tiles_, 0); }

void GuidedFilters::dispatchRefinement(ContextImpl& ctx) {
    dispatchIndirect(ctx, refineList_, 0);
    ctx.gl.MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
}

RefinementCount GuidedFilters::refinementCount(ContextImpl& ctx) const {
    if (!refineList_) return {};
    ctx.gl.MemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT); // the upsampling's atomic adds, before the read
    GLuint asked = 0;
    ctx.gl.GetNamedBufferSubData(refineList_.get(), (FILTER_REFINE_HEADER_UINTS - 1) * sizeof(GLuint), sizeof asked, &asked);
    const std::size_t capacity = refineListBytes_ / sizeof(GLuint) - FILTER_REFINE_HEADER_UINTS;
    return {asked, asked <= capacity ? std::size_t{asked} : 0};
}

// The refinement list holds up to a quarter of the G-buffer's pixels (bounded below): a few
// percent need it (2-3 % on 2CylinderEngine at 512x512, its thin parts' edges), and past
// the capacity the upsampling blends as without refinement.
std::size_t GuidedFilters::refineCapacity(glm::ivec2 fullSize) {
    // The list's groups are dispatched indirectly, and GL guarantees only 65535 groups a
    // dimension (llvmpipe has no more): past 16.8M pixels a quarter of them would pass it.
    const std::size_t quarter = (std::size_t(fullSize.x) * std::size_t(fullSize.y) + 3) / 4;
    return std::min(quarter, std::size_t{65535} * FILTER_REFINE_GROUP);
}

std::size_t GuidedFilters::memoryBytes() const {
    return valueTemp_.bytes() + directionTemp_.bytes() + refineListBytes_ + tilesBytes_ +
           (params_ ? sizeof(shader::FilterParams) : 0);
}

} // namespace obscura::detail
