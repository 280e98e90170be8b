#include "gl_state.hpp"

#include <glad/gl.h>

#include <algorithm>
#include <sstream>
#include <tuple>

namespace obscura::test {
namespace {

struct Recorder {
    GlState state;
    void ints(const std::string& name, GLenum pname, int count = 1) {
        std::vector<GLint> v(static_cast<std::size_t>(std::max(count, 1)) + 4, 0);
        glGetIntegerv(pname, v.data());
        state[name] = std::vector<double>(v.begin(), v.begin() + count);
    }
    void floats(const std::string& name, GLenum pname, int count = 1) {
        std::vector<GLfloat> v(static_cast<std::size_t>(count) + 4, 0.0f);
        glGetFloatv(pname, v.data());
        state[name] = std::vector<double>(v.begin(), v.begin() + count);
    }
    void enabled(const std::string& name, GLenum cap) { state["enabled " + name] = {double(glIsEnabled(cap))}; }
    void indexedInt(const std::string& name, GLenum pname, GLuint i, int count = 1) {
        std::vector<GLint64> v(static_cast<std::size_t>(count) + 4, 0);
        glGetInteger64i_v(pname, i, v.data());
        state[name + "[" + std::to_string(i) + "]"] = std::vector<double>(v.begin(), v.begin() + count);
    }
};

} // namespace

GlState captureGlState() {
    Recorder r;
    r.ints("program", GL_CURRENT_PROGRAM);
    r.ints("vertex array", GL_VERTEX_ARRAY_BINDING);
    r.ints("draw framebuffer", GL_DRAW_FRAMEBUFFER_BINDING);
    r.ints("read framebuffer", GL_READ_FRAMEBUFFER_BINDING);
    r.ints("renderbuffer", GL_RENDERBUFFER_BINDING);
    r.ints("program pipeline", GL_PROGRAM_PIPELINE_BINDING);
    r.ints("transform feedback", GL_TRANSFORM_FEEDBACK_BINDING);
    GLint viewports = 0;
    glGetIntegerv(GL_MAX_VIEWPORTS, &viewports);
    for (GLuint i = 0; i < static_cast<GLuint>(viewports); ++i) {
        GLfloat vp[4];
        glGetFloati_v(GL_VIEWPORT, i, vp);
        r.state["viewport[" + std::to_string(i) + "]"] = {vp[0], vp[1], vp[2], vp[3]};
        r.indexedInt("scissor box", GL_SCISSOR_BOX, i, 4);
        GLdouble dr[2];
        glGetDoublei_v(GL_DEPTH_RANGE, i, dr);
        r.state["depth range[" + std::to_string(i) + "]"] = {dr[0], dr[1]};
        r.state["enabled scissor[" + std::to_string(i) + "]"] = {double(glIsEnabledi(GL_SCISSOR_TEST, i))};
        if (GLAD_GL_NV_scissor_exclusive) {
            r.state["enabled exclusive scissor[" + std::to_string(i) + "]"] = {double(glIsEnabledi(GL_SCISSOR_TEST_EXCLUSIVE_NV, i))};
            r.indexedInt("exclusive scissor box", GL_SCISSOR_BOX_EXCLUSIVE_NV, i, 4);
        }
        if (GLAD_GL_NV_shading_rate_image)
            r.state["enabled shading rate image[" + std::to_string(i) + "]"] = {double(glIsEnabledi(GL_SHADING_RATE_IMAGE_NV, i))};
        if (GLAD_GL_NV_viewport_swizzle)
            for (const auto& [name, query] : {std::pair{"x", GL_VIEWPORT_SWIZZLE_X_NV}, std::pair{"y", GL_VIEWPORT_SWIZZLE_Y_NV},
                                              std::pair{"z", GL_VIEWPORT_SWIZZLE_Z_NV}, std::pair{"w", GL_VIEWPORT_SWIZZLE_W_NV}})
                r.indexedInt(std::string("viewport swizzle ") + name, query, i, 1);
        if (GLAD_GL_NV_clip_space_w_scaling) {
            GLfloat coefficients[2];
            glGetFloati_v(GL_VIEWPORT_POSITION_W_SCALE_X_COEFF_NV, i, &coefficients[0]);
            glGetFloati_v(GL_VIEWPORT_POSITION_W_SCALE_Y_COEFF_NV, i, &coefficients[1]);
            r.state["viewport w scale[" + std::to_string(i) + "]"] = {coefficients[0], coefficients[1]};
        }
    }
    if (GLAD_GL_EXT_window_rectangles) {
        r.ints("window rectangle mode", GL_WINDOW_RECTANGLE_MODE_EXT);
        GLint count = 0;
        glGetIntegerv(GL_NUM_WINDOW_RECTANGLES_EXT, &count);
        r.state["window rectangles"] = {double(count)};
        for (GLuint i = 0; i < static_cast<GLuint>(count); ++i) r.indexedInt("window rectangle", GL_WINDOW_RECTANGLE_EXT, i, 4);
    }
    const std::pair<const char*, GLenum> caps[] = {
        {"depth test", GL_DEPTH_TEST}, {"stencil test", GL_STENCIL_TEST}, {"cull face", GL_CULL_FACE},
        {"color logic op", GL_COLOR_LOGIC_OP}, {"primitive restart", GL_PRIMITIVE_RESTART},
        {"primitive restart fixed", GL_PRIMITIVE_RESTART_FIXED_INDEX}, {"depth clamp", GL_DEPTH_CLAMP},
        {"framebuffer srgb", GL_FRAMEBUFFER_SRGB}, {"polygon offset fill", GL_POLYGON_OFFSET_FILL},
        {"polygon offset line", GL_POLYGON_OFFSET_LINE}, {"polygon offset point", GL_POLYGON_OFFSET_POINT},
        {"rasterizer discard", GL_RASTERIZER_DISCARD}, {"alpha to coverage", GL_SAMPLE_ALPHA_TO_COVERAGE},
        {"sample coverage", GL_SAMPLE_COVERAGE}, {"sample mask", GL_SAMPLE_MASK},
        {"program point size", GL_PROGRAM_POINT_SIZE}, {"multisample", GL_MULTISAMPLE}, {"dither", GL_DITHER},
        {"line smooth", GL_LINE_SMOOTH}, {"polygon smooth", GL_POLYGON_SMOOTH},
        {"sample shading", GL_SAMPLE_SHADING}, {"cube map seamless", GL_TEXTURE_CUBE_MAP_SEAMLESS},
        {"debug output", GL_DEBUG_OUTPUT}, {"debug output synchronous", GL_DEBUG_OUTPUT_SYNCHRONOUS},
        {"clip distance 0", GL_CLIP_DISTANCE0}, {"clip distance 1", GL_CLIP_DISTANCE1},
        {"clip distance 2", GL_CLIP_DISTANCE2}, {"clip distance 3", GL_CLIP_DISTANCE3},
        {"clip distance 4", GL_CLIP_DISTANCE4}, {"clip distance 5", GL_CLIP_DISTANCE5},
        {"clip distance 6", GL_CLIP_DISTANCE6}, {"clip distance 7", GL_CLIP_DISTANCE7}};
    for (const auto& [name, cap] : caps) r.enabled(name, cap);
    // Extensions' enables, where the context has them (glad sets the flags at load).
    const std::tuple<const char*, int, GLenum> extensionCaps[] = {
        {"conservative raster nv", GLAD_GL_NV_conservative_raster, GL_CONSERVATIVE_RASTERIZATION_NV},
        {"conservative raster intel", GLAD_GL_INTEL_conservative_rasterization, GL_CONSERVATIVE_RASTERIZATION_INTEL},
        {"depth bounds test", GLAD_GL_EXT_depth_bounds_test, GL_DEPTH_BOUNDS_TEST_EXT},
        {"representative fragment test", GLAD_GL_NV_representative_fragment_test, GL_REPRESENTATIVE_FRAGMENT_TEST_NV},
        {"blackhole render", GLAD_GL_INTEL_blackhole_render, GL_BLACKHOLE_RENDER_INTEL},
        {"viewport w scale", GLAD_GL_NV_clip_space_w_scaling, GL_VIEWPORT_POSITION_W_SCALE_NV}};
    for (const auto& [name, present, cap] : extensionCaps)
        if (present) r.enabled(name, cap);
    if (GLAD_GL_EXT_depth_bounds_test) r.floats("depth bounds", GL_DEPTH_BOUNDS_EXT, 2);
    GLint drawBuffers = 0;
    glGetIntegerv(GL_MAX_DRAW_BUFFERS, &drawBuffers);
    for (GLuint i = 0; i < static_cast<GLuint>(drawBuffers); ++i) {
        const std::string s = "[" + std::to_string(i) + "]";
        r.state["enabled blend" + s] = {double(glIsEnabledi(GL_BLEND, i))};
        r.indexedInt("blend src rgb", GL_BLEND_SRC_RGB, i);
        r.indexedInt("blend dst rgb", GL_BLEND_DST_RGB, i);
        r.indexedInt("blend src alpha", GL_BLEND_SRC_ALPHA, i);
        r.indexedInt("blend dst alpha", GL_BLEND_DST_ALPHA, i);
        r.indexedInt("blend equation rgb", GL_BLEND_EQUATION_RGB, i);
        r.indexedInt("blend equation alpha", GL_BLEND_EQUATION_ALPHA, i);
        GLboolean mask[4];
        glGetBooleani_v(GL_COLOR_WRITEMASK, i, mask);
        r.state["color mask" + s] = {double(mask[0]), double(mask[1]), double(mask[2]), double(mask[3])};
    }
    r.floats("blend color", GL_BLEND_COLOR, 4);
    r.ints("depth mask", GL_DEPTH_WRITEMASK);
    r.ints("stencil writemask", GL_STENCIL_WRITEMASK);
    r.ints("stencil back writemask", GL_STENCIL_BACK_WRITEMASK);
    const std::pair<const char*, GLenum> stencil[] = {
        {"stencil func", GL_STENCIL_FUNC}, {"stencil ref", GL_STENCIL_REF}, {"stencil value mask", GL_STENCIL_VALUE_MASK},
        {"stencil fail", GL_STENCIL_FAIL}, {"stencil depth fail", GL_STENCIL_PASS_DEPTH_FAIL},
        {"stencil depth pass", GL_STENCIL_PASS_DEPTH_PASS}, {"stencil back func", GL_STENCIL_BACK_FUNC},
        {"stencil back ref", GL_STENCIL_BACK_REF}, {"stencil back value mask", GL_STENCIL_BACK_VALUE_MASK},
        {"stencil back fail", GL_STENCIL_BACK_FAIL}, {"stencil back depth fail", GL_STENCIL_BACK_PASS_DEPTH_FAIL},
        {"stencil back depth pass", GL_STENCIL_BACK_PASS_DEPTH_PASS}};
    for (const auto& [name, pname] : stencil) r.ints(name, pname);
    r.ints("depth func", GL_DEPTH_FUNC);
    r.ints("logic op", GL_LOGIC_OP_MODE);
    r.ints("clip origin", GL_CLIP_ORIGIN);
    r.ints("clip depth mode", GL_CLIP_DEPTH_MODE);
    r.ints("polygon mode", GL_POLYGON_MODE, 2);
    r.floats("polygon offset factor", GL_POLYGON_OFFSET_FACTOR);
    r.floats("polygon offset units", GL_POLYGON_OFFSET_UNITS);
    r.ints("front face", GL_FRONT_FACE);
    r.ints("cull face mode", GL_CULL_FACE_MODE);
    r.ints("active texture", GL_ACTIVE_TEXTURE);
    r.ints("clamp read color", GL_CLAMP_READ_COLOR);
    r.ints("debug group stack depth", GL_DEBUG_GROUP_STACK_DEPTH);
    // Not on Obscura's list: it promises never to change these.
    r.floats("color clear value", GL_COLOR_CLEAR_VALUE, 4);
    r.floats("depth clear value", GL_DEPTH_CLEAR_VALUE);
    r.ints("stencil clear value", GL_STENCIL_CLEAR_VALUE);
    r.floats("line width", GL_LINE_WIDTH);
    r.floats("point size", GL_POINT_SIZE);
    r.ints("primitive restart index", GL_PRIMITIVE_RESTART_INDEX);
    r.ints("provoking vertex", GL_PROVOKING_VERTEX);
    r.ints("patch vertices", GL_PATCH_VERTICES);
    r.ints("fragment shader derivative hint", GL_FRAGMENT_SHADER_DERIVATIVE_HINT);
    r.ints("draw buffer (framebuffer 0 or bound)", GL_DRAW_BUFFER);
    r.ints("read buffer", GL_READ_BUFFER);
    const std::pair<const char*, GLenum> pixelStore[] = {
        {"pack alignment", GL_PACK_ALIGNMENT}, {"pack row length", GL_PACK_ROW_LENGTH},
        {"pack image height", GL_PACK_IMAGE_HEIGHT}, {"pack skip pixels", GL_PACK_SKIP_PIXELS},
        {"pack skip rows", GL_PACK_SKIP_ROWS}, {"pack skip images", GL_PACK_SKIP_IMAGES},
        {"pack swap bytes", GL_PACK_SWAP_BYTES}, {"pack lsb first", GL_PACK_LSB_FIRST},
        {"unpack alignment", GL_UNPACK_ALIGNMENT}, {"unpack row length", GL_UNPACK_ROW_LENGTH},
        {"unpack image height", GL_UNPACK_IMAGE_HEIGHT}, {"unpack skip pixels", GL_UNPACK_SKIP_PIXELS},
        {"unpack skip rows", GL_UNPACK_SKIP_ROWS}, {"unpack skip images", GL_UNPACK_SKIP_IMAGES},
        {"unpack swap bytes", GL_UNPACK_SWAP_BYTES}, {"unpack lsb first", GL_UNPACK_LSB_FIRST}};
    for (const auto& [name, pname] : pixelStore) r.ints(name, pname);
    const std::pair<const char*, GLenum> buffers[] = {
        {"array buffer", GL_ARRAY_BUFFER_BINDING}, {"element buffer (of bound VAO)", GL_ELEMENT_ARRAY_BUFFER_BINDING},
        {"copy read buffer", GL_COPY_READ_BUFFER_BINDING}, {"copy write buffer", GL_COPY_WRITE_BUFFER_BINDING},
        {"pixel pack buffer", GL_PIXEL_PACK_BUFFER_BINDING}, {"pixel unpack buffer", GL_PIXEL_UNPACK_BUFFER_BINDING},
        {"draw indirect buffer", GL_DRAW_INDIRECT_BUFFER_BINDING},
        {"dispatch indirect buffer", GL_DISPATCH_INDIRECT_BUFFER_BINDING}, {"query buffer", GL_QUERY_BUFFER_BINDING},
        {"texture buffer", GL_TEXTURE_BUFFER_BINDING}, {"uniform buffer", GL_UNIFORM_BUFFER_BINDING},
        {"shader storage buffer", GL_SHADER_STORAGE_BUFFER_BINDING},
        {"atomic counter buffer", GL_ATOMIC_COUNTER_BUFFER_BINDING},
        {"transform feedback buffer", GL_TRANSFORM_FEEDBACK_BUFFER_BINDING}};
    for (const auto& [name, pname] : buffers) r.ints(name, pname);

    GLint activeTexture = 0;
    glGetIntegerv(GL_ACTIVE_TEXTURE, &activeTexture);
    const std::pair<const char*, GLenum> targets[] = {
        {"1d", GL_TEXTURE_BINDING_1D}, {"1d array", GL_TEXTURE_BINDING_1D_ARRAY}, {"2d", GL_TEXTURE_BINDING_2D},
        {"2d array", GL_TEXTURE_BINDING_2D_ARRAY}, {"2d ms", GL_TEXTURE_BINDING_2D_MULTISAMPLE},
        {"2d ms array", GL_TEXTURE_BINDING_2D_MULTISAMPLE_ARRAY}, {"3d", GL_TEXTURE_BINDING_3D},
        {"cube", GL_TEXTURE_BINDING_CUBE_MAP}, {"cube array", GL_TEXTURE_BINDING_CUBE_MAP_ARRAY},
        {"rectangle", GL_TEXTURE_BINDING_RECTANGLE}, {"buffer", GL_TEXTURE_BINDING_BUFFER}};
    for (GLuint unit = 0; unit < 48; ++unit) {
        glActiveTexture(GL_TEXTURE0 + unit);
        for (const auto& [name, pname] : targets)
            r.ints("texture unit " + std::to_string(unit) + " " + name, pname);
        r.ints("sampler unit " + std::to_string(unit), GL_SAMPLER_BINDING);
    }
    glActiveTexture(static_cast<GLenum>(activeTexture));
    for (GLuint i = 0; i < 8; ++i) {
        r.indexedInt("image name", GL_IMAGE_BINDING_NAME, i);
        r.indexedInt("image level", GL_IMAGE_BINDING_LEVEL, i);
        r.indexedInt("image layer", GL_IMAGE_BINDING_LAYER, i);
        r.indexedInt("image access", GL_IMAGE_BINDING_ACCESS, i);
        r.indexedInt("image format", GL_IMAGE_BINDING_FORMAT, i);
        GLboolean layered = GL_FALSE;
        glGetBooleani_v(GL_IMAGE_BINDING_LAYERED, i, &layered);
        r.state["image layered[" + std::to_string(i) + "]"] = {double(layered)};
    }
    for (GLuint i = 0; i < 24; ++i) {
        r.indexedInt("ubo", GL_UNIFORM_BUFFER_BINDING, i);
        r.indexedInt("ubo start", GL_UNIFORM_BUFFER_START, i);
        r.indexedInt("ubo size", GL_UNIFORM_BUFFER_SIZE, i);
    }
    for (GLuint i = 0; i < 16; ++i) {
        r.indexedInt("ssbo", GL_SHADER_STORAGE_BUFFER_BINDING, i);
        r.indexedInt("ssbo start", GL_SHADER_STORAGE_BUFFER_START, i);
        r.indexedInt("ssbo size", GL_SHADER_STORAGE_BUFFER_SIZE, i);
    }
    for (GLuint i = 0; i < 8; ++i) r.indexedInt("atomic counter buffer", GL_ATOMIC_COUNTER_BUFFER_BINDING, i);
    void* callback = nullptr;
    void* user = nullptr;
    glGetPointerv(GL_DEBUG_CALLBACK_FUNCTION, &callback);
    glGetPointerv(GL_DEBUG_CALLBACK_USER_PARAM, &user);
    r.state["debug callback"] = {double(reinterpret_cast<std::uintptr_t>(callback))};
    r.state["debug callback user"] = {double(reinterpret_cast<std::uintptr_t>(user))};
    return r.state;
}

std::vector<std::string> diffGlState(const GlState& before, const GlState& after) {
    std::vector<std::string> out;
    const auto show = [](const std::vector<double>& v) {
        std::ostringstream s;
        for (std::size_t i = 0; i < v.size(); ++i) s << (i ? "," : "") << v[i];
        return s.str();
    };
    for (const auto& [name, value] : before) {
        const auto it = after.find(name);
        if (it == after.end()) out.push_back(name + ": missing after");
        else if (it->second != value) out.push_back(name + ": " + show(value) + " -> " + show(it->second));
    }
    return out;
}

} // namespace obscura::test
