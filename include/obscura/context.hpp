#pragma once
// obscura::Context: Obscura's handle on the host application's own OpenGL context.
//
// GL loader isolation
// -------------------
// Obscura never links libGL and exports no gl* or glad* symbol. It loads its own
// function table (glad2, --mx) through the host's getProcAddress, so it coexists with any
// loader the host uses (glad, GLEW, epoxy, its own). In the shared library every internal
// symbol has hidden visibility; in the static library the two glad entry points are renamed
// (obscura_glad_*), so neither build can collide with the host at link or load time.
//
// Host GL state
// -------------
// With StatePolicy::Preserve (the default) every public call that issues GL commands saves
// the state below on entry and restores it exactly on exit, even when it throws.
// This is the complete list; tests/gl/test_state.cpp checks every item:
//   - current program (GL_CURRENT_PROGRAM; one the host deleted while current is deleted by
//     GL as soon as we bind another, and 0 is current afterwards), vertex array
//     (GL_VERTEX_ARRAY_BINDING)
//   - draw and read framebuffers
//   - viewport, scissor box and depth range of viewport index 0 (the only index we use)
//   - enable bits: GL_BLEND (every draw buffer), GL_DEPTH_TEST, GL_STENCIL_TEST,
//     GL_CULL_FACE, GL_SCISSOR_TEST (index 0), GL_COLOR_LOGIC_OP, GL_PRIMITIVE_RESTART,
//     GL_PRIMITIVE_RESTART_FIXED_INDEX, GL_DEPTH_CLAMP, GL_FRAMEBUFFER_SRGB,
//     GL_POLYGON_OFFSET_FILL/LINE/POINT, GL_RASTERIZER_DISCARD, GL_SAMPLE_ALPHA_TO_COVERAGE,
//     GL_SAMPLE_COVERAGE, GL_SAMPLE_MASK, GL_PROGRAM_POINT_SIZE, GL_CLIP_DISTANCE0..7,
//     GL_POLYGON_SMOOTH, GL_DITHER (initial value: enabled), and, where the context has the
//     extension, GL_CONSERVATIVE_RASTERIZATION_NV or _INTEL, GL_DEPTH_BOUNDS_TEST_EXT,
//     GL_REPRESENTATIVE_FRAGMENT_TEST_NV, GL_BLACKHOLE_RENDER_INTEL,
//     GL_VIEWPORT_POSITION_W_SCALE_NV, and GL_SHADING_RATE_IMAGE_NV and
//     GL_SCISSOR_TEST_EXCLUSIVE_NV (both index 0); their parameters (depth bounds, exclusive
//     scissor box, shading rate image and palettes, W scaling coefficients) are not touched,
//     as our draws run with the tests off
//   - where the context has the extension, the window rectangles (EXT_window_rectangles:
//     mode and rectangles; initial value: exclusive, none) and the viewport swizzle of index
//     0 (NV_viewport_swizzle; initial value: the identity)
//   - blend func and equation (RGB and alpha, every draw buffer; KHR_blend_equation_advanced
//     equations included), blend color
//   - color mask (every draw buffer), depth mask, stencil write masks (front and back)
//   - stencil func, ref, value mask and ops (front and back), depth func, logic op mode
//   - clip control (origin and depth mode)
//   - polygon mode, polygon offset factor and units, front face, cull face mode, provoking
//     vertex convention, GL_CLAMP_READ_COLOR
//   - active texture unit
//   - texture bindings of every target (1D, 1D array, 2D, 2D array, 2D multisample,
//     2D multisample array, 3D, cube, cube array, rectangle, buffer) and the sampler binding,
//     on every texture unit a call touches
//   - image unit bindings (name, level, layered, layer, access, format) on every image unit
//     a call touches
//   - indexed uniform and shader storage buffer bindings (buffer, offset, size) on every
//     binding point a call touches
//   - pixel pack and unpack state: alignment, row length, image height, skip pixels, skip
//     rows, skip images, swap bytes, LSB first
//   - bound buffers: array, copy read, copy write, pixel pack, pixel unpack, draw indirect,
//     dispatch indirect, query, texture, uniform, shader storage, atomic counter and
//     transform feedback (generic bindings)
//   - with a debugOutput callback: the debug callback and its user parameter,
//     GL_DEBUG_OUTPUT and GL_DEBUG_OUTPUT_SYNCHRONOUS
// Nothing outside this list is changed (clear values, hints, point size and line width,
// other viewport indices, the draw buffers of framebuffers we do not own are never touched).
// Object state of host objects is never modified either. Other extensions' state that could
// reshape a draw is neither saved nor reset: a host that sets it must reset it before calling
// us. NV_sample_locations' state belongs to each framebuffer: ours keep the default
// locations, and a host FBO we draw into keeps the host's.
//
// Memory barriers: Obscura reads the host's textures (depth, normals, albedo, radiance)
// through texture fetches. A host that wrote them with image stores or from a compute
// shader calls glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT) before handing them over, as
// GL requires of any reader; rasterized writes need nothing. Obscura's own outputs need no
// barrier of the host's: a call ends with glMemoryBarrier for texture fetches, image access,
// texture and buffer updates (read-backs), shader storage and framebuffer use.
//
// Creating a Context and destroying it or a module issue no state change other than
// deleting Obscura's own objects (where the host bound or attached one of our textures, GL
// unbinds it as for any deleted object). Output textures are valid until the module's next
// call that resizes them, or its destruction.
//
// With StatePolicy::Clobber nothing is saved: each other call leaves every item above at its GL
// initial value (program 0, VAO 0, framebuffers 0, units unbound, enables off, stencil masks
// 0xFF, last-vertex convention, ...), except
// the viewport and scissor box of index 0, which keep the last values we set. Engines that
// keep their own state cache choose this and invalidate their cache after our calls.
//
// Obscura calls glGetError only around allocations of textures and buffers (to report
// GL_OUT_OF_MEMORY); an error the host left pending at that moment is consumed. Allocations
// happen on first use and when sizes change, not every frame.
//
// Preconditions of every call: the host's context is current on the calling thread,
// transform feedback is not active (we throw InvalidState), and no conditional rendering
// is active. Queries the host keeps active across our calls (samples passed, primitives
// generated, time elapsed) include our work. One Context per GL context; a Context and
// the modules created from it must only be used from the thread where that GL context is
// current. Destroy modules before their Context, with the GL context current.
#include "obscura/error.hpp"
#include "obscura/export.hpp"

#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace obscura {

namespace detail {
struct ContextImpl;
}
class Profiler;

enum class StatePolicy {
    Preserve, //!< save and restore the listed host state around every call (default)
    Clobber,  //!< no save/restore; listed state is left at its GL initial values
};

//! A KHR_debug message raised while Obscura was issuing GL commands. The GL enums are
//! given as numbers (GL_DEBUG_SOURCE_*, GL_DEBUG_TYPE_*, GL_DEBUG_SEVERITY_*).
struct DebugMessage {
    unsigned source = 0;
    unsigned type = 0;
    unsigned id = 0;
    unsigned severity = 0;
    std::string text;
};

//! Obscura's own reports of a likely host mistake it cannot prove (DebugMessage::id, with
//! source GL_DEBUG_SOURCE_THIRD_PARTY, type GL_DEBUG_TYPE_OTHER and severity
//! GL_DEBUG_SEVERITY_MEDIUM). They go to ContextDesc::debugOutput where it is set, else into
//! the GL debug log (glDebugMessageInsert), which reaches the host's own GL debug callback
//! where it enabled GL_DEBUG_OUTPUT. With ContextDesc::strictChecks the call throws
//! Error{InvalidArgument} with the same text instead.
enum class Diagnostic : unsigned {
    //! GBuffer::adopt: the camera's ClipDepth is not the current GL_CLIP_DEPTH_MODE. The
    //! projection matrix alone cannot tell a [-1, 1] projection from a [0, 1] one (read as the
    //! other it is just another valid near plane), so a wrong ClipDepth gives quietly wrong
    //! AO and GI; a host whose depth pass ran under another clip control than the one current
    //! at adopt() gets a false alarm, once for each GBuffer while the mismatch lasts.
    ClipDepthMismatch = 0x0B5C0001u,
    //! GBuffer::adopt: at least 1 % of the host's depth pixels lie exactly on the camera's
    //! near plane (depth 0, or 1 with reversed-Z), where no rendered surface lies: a depth
    //! buffer cleared for the other depth convention, or a projection other than the one it
    //! was rendered with. Counted only while diagnostics can be delivered (debugOutput set,
    //! strictChecks, or the host's GL_DEBUG_OUTPUT enabled), and then once per depth texture,
    //! size and depth convention, as it reads a count back (a stall).
    DepthOnNearPlane = 0x0B5C0002u,
};

//! Resolves a GL function name in the host's current context (eglGetProcAddress,
//! glfwGetProcAddress, SDL_GL_GetProcAddress, wglGetProcAddress with its fallback, ...).
using GetProcAddressFn = void* (*)(void* userData, const char* name);
using DebugCallback = std::function<void(const DebugMessage&)>;

//! Which passes Profiler times (profiler.hpp).
enum class Profiling {
    //! None: no query, no glFinish. The default, for engines: a frame costs what its passes do.
    Off,
    //! GL_TIMESTAMP queries, read back later without stalling, where they are trustworthy (a
    //! hardware driver with timestamp bits); nothing on software renderers, whose queries
    //! under-report by about 20x. For engines that show pass times in their own overlay.
    TimerQueries,
    //! As TimerQueries on hardware; on software renderers (and without timestamp bits) glFinish
    //! and a steady clock around every pass, which stalls the pipeline at each pass: for tools,
    //! benchmarks and tests (the CLI, the examples and HeadlessContext::contextDesc use it).
    Always,
};

struct ContextDesc {
    GetProcAddressFn getProcAddress = nullptr; //!< required
    void* userData = nullptr;                  //!< passed to getProcAddress unchanged
    StatePolicy statePolicy = StatePolicy::Preserve;
    Profiling profiling = Profiling::Off;
    //! Optional. When set, GL debug output is enabled during our calls and every message
    //! they raise is passed here (the host's own callback is restored afterwards), and so are
    //! Obscura's own Diagnostic reports. GL's messages only arrive on debug contexts or
    //! drivers that report without one. It may be called from inside the driver: exceptions
    //! it throws are swallowed.
    DebugCallback debugOutput;
    //! Refuse with Error{InvalidArgument} what is otherwise only reported as a Diagnostic (a
    //! likely mistake that a host could also mean): for hosts that want to find such
    //! mistakes early, in development builds.
    bool strictChecks = false;
};

//! What Context found about the GL implementation.
struct ContextInfo {
    std::string vendor, renderer, version, glslVersion;
    int major = 0, minor = 0;
    bool coreProfile = false;      //!< always true: compatibility profiles are refused
    bool softwareRenderer = false; //!< llvmpipe, softpipe, SwiftShader, ...: the profiler uses wall clock
    int maxTextureSize = 0;        //!< GL_MAX_TEXTURE_SIZE, pixels
    int maxDrawBuffers = 0;
    int maxViewports = 0;
    int maxViewportDims[2] = {0, 0}; //!< GL_MAX_VIEWPORT_DIMS, pixels: HostTarget's largest width and height
    //! GL_VIEWPORT_BOUNDS_RANGE, pixels: where HostTarget's x and y may lie (at least
    //! [-32768, 32767] in GL 4.5)
    float viewportBoundsRange[2] = {0.0f, 0.0f};
    bool conservativeRaster = false; //!< GL_NV_conservative_raster or GL_INTEL_conservative_rasterization
    int timestampBits = 0;           //!< GL_QUERY_COUNTER_BITS of GL_TIMESTAMP; 0 = no GPU timer (wall clock used)
};

class OBSCURA_API Context {
public:
    //! Creates Obscura's context on the host's current GL context. Checks GL >= 4.5 core
    //! profile and every function, limit and format Obscura uses. Throws
    //! Error{UnsupportedFeature} naming everything that is missing. Issues no state change.
    explicit Context(const ContextDesc& desc);
    //! Deletes every GL object Obscura still owns. The GL context must be current.
    ~Context();

    const ContextInfo& info() const noexcept;
    StatePolicy statePolicy() const noexcept;
    Profiler& profiler() noexcept;

    //! Shader programs compiled so far, one entry per permutation, e.g.
    //! "gbuffer/gbuffer.vert.glsl + gbuffer/gbuffer.geom.glsl + ... [HAS_NORMALS]".
    //! Programs are compiled on first use only.
    std::vector<std::string> compiledPrograms() const;
    //! GL objects Obscura currently owns (textures, buffers, framebuffers, programs, ...)
    //! across this context and every module created from it. For leak diagnostics.
    std::size_t liveObjectCount() const noexcept;

    //! Development hook: adds or replaces the shader file `path` (relative to shaders/, e.g.
    //! "gbuffer/gbuffer.frag.glsl"). Affects programs compiled afterwards; its #includes are
    //! resolved against other added files. Errors point at file:line of the added text.
    void addShaderSource(const std::string& path, const std::string& text);

    //! Internal: used by Obscura's modules.
    detail::ContextImpl& impl() noexcept { return *impl_; }

private:
    std::unique_ptr<detail::ContextImpl> impl_;
};

} // namespace obscura
