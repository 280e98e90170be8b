#pragma once
// Final combine, tone mapping and output into the host's framebuffer.
//
// Combine (radiance, W/(sr m^2), per pixel; rho the albedo, L_dir the G-buffer's direct
// radiance, L1 the one-bounce indirect radiance of IndirectLight, AO of AmbientOcclusion):
//   Standard: L = L_dir + rho AO L_amb + k L1   (the default; what engines use)
//             (AO shades only the ambient term, the constant stand-in for the light that
//             neither the shadowed direct light nor the screen's one bounce carries, such as
//             the sky's: outdoors, sun shadows keep it where GI, which sees no sky, adds
//             nothing. The ambient and L1 overlap where the screen does see the light the
//             ambient stands for; keep L_amb for what the scene's GI cannot gather.)
//   Thesis:   L = rho AO L_amb + k L1 + AO L_dir
//             (the source thesis's L = f_d (AO pi L_amb + k E_ind) + L_dir AO with f_d = rho/pi,
//             E_ind = pi L1 / rho; AO darkens the direct light too, which is not physical)
//   Physical: L = L_dir + k L1          when ComposeInputs::indirect is given,
//             L = L_dir + rho AO L_amb    when it is not
//             (the indirect light replaces the ambient term, which is its constant stand-in:
//             with L1 given, L_amb and AO are not used; AO never darkens the direct light,
//             which shadow maps shadow. A host can keep L_amb set and toggle GI. Without a
//             sky term in L1, surfaces in shadow outdoors go black.)
// docs/compose.md shows the three side by side.
// Missing inputs count as absent: no AO = 1, no L1 = 0. Background pixels (depth at the
// camera's clear depth, or one no surface has: see HostGBuffer::depth) get L = L_dir with
// every formula: no AO, ambient or indirect term, whatever the albedo there.
//
// Tone mapping of exposure * L: None (clamp), Drago et al. 2003 (logarithmic, adapted to the
// frame's largest luminance or a given one), or ACES (Narkowicz's fit of the ACES RRT+ODT).
// Then the display encoding: the sRGB transfer function, or a plain gamma.
#include "obscura/ambient_occlusion.hpp"
#include "obscura/export.hpp"
#include "obscura/gbuffer.hpp"
#include "obscura/indirect_light.hpp"
#include "obscura/settings_table.hpp"
#include "obscura/texture.hpp"

#include <glm/glm.hpp>

#include <cstddef>
#include <memory>

namespace obscura {

class Context;

enum class CombineFormula { Thesis, Physical, Standard };
enum class ToneMapper { None, Drago, Aces };

struct ComposeSettings {
    CombineFormula formula = CombineFormula::Standard;
    glm::vec3 ambient{0.0f}; //!< Physical: only without indirect light
    float indirectScale = 1.0f;
    float exposure = 1.0f;
    ToneMapper toneMapper = ToneMapper::Aces;
    //! Either counts as at least 1e-30: a frame is mapped to its own maximum down to 1e-30
    //! after exposure (applied in float, after the half-float radiance(), so a small exposure
    //! costs no precision).
    float dragoMaxLuminance = 0.0f;
    float dragoBias = 0.85f;
    float dragoDisplayMax = 100.0f;
    bool srgb = true;
    float gamma = 2.2f;

    static const SettingsTable<ComposeSettings>& table(); //!< units and ranges (settings_table.hpp)
};

inline const SettingsTable<ComposeSettings>& ComposeSettings::table() {
    using S = ComposeSettings;
    using namespace settings;
    static const SettingsTable<S> rows = {
        choice("formula", &S::formula,
               {{"standard", CombineFormula::Standard}, {"thesis", CombineFormula::Thesis},
                {"physical", CombineFormula::Physical}},
               "how AO, ambient and indirect light combine (CombineFormula)"),
        color("ambient", &S::ambient, "W/(sr m^2)", "[0, 65504]", "ambient radiance L_amb, per channel"),
        number("indirectScale", &S::indirectScale, "", "[0, 1e6]", "k, the weight of the indirect light"),
        number("exposure", &S::exposure, "", "(0, 1e6]", "multiplies the radiance before tone mapping"),
        choice("toneMapper", &S::toneMapper, {{"none", ToneMapper::None}, {"drago", ToneMapper::Drago}, {"aces", ToneMapper::Aces}},
               "tone mapping operator"),
        number("dragoMaxLuminance", &S::dragoMaxLuminance, "W/(sr m^2)", "[0, inf)",
               "Drago's largest scene luminance L_wmax after exposure; 0: the frame's own (a reduction pass)"),
        number("dragoBias", &S::dragoBias, "", "[0.5, 1]", "Drago's bias b"),
        number("dragoDisplayMax", &S::dragoDisplayMax, "cd/m^2", "(0, 1e4]", "Drago's display maximum L_dmax"),
        flag("srgb", &S::srgb, "display encoding: the sRGB transfer function, else x^(1/gamma)"),
        number("gamma", &S::gamma, "", "[1, 4]", "display gamma when srgb is off"),
    };
    return rows;
}

//! The inputs of the combine; ao and indirect may be empty.
struct ComposeInputs {
    GBufferView gbuffer;         //!< depth, direct radiance and albedo are required
    TextureView ao;              //!< AmbientOcclusionView::ao (the G-buffer's size) or empty
    TextureView indirect;        //!< IndirectLightView::radiance (the G-buffer's size) or empty
};

enum class HostBlend {
    Overwrite, //!< the host's colour becomes the source
    Multiply,  //!< the host's colour is multiplied by the source (e.g. AO onto a lit image)
};

//! What a source's values are. It matters only where the target's colour encoding is sRGB
//! (GL_FRAMEBUFFER_ATTACHMENT_COLOR_ENCODING == GL_SRGB): into linear targets values are
//! stored as they are either way. The default framebuffer's encoding is the window system's
//! choice (e.g. an sRGB-capable EGL or GLFW surface): query it on GL_BACK_LEFT, or pass
//! Display to store a source's values unchanged whatever it is.
enum class HostSourceEncoding {
    Auto,    //!< Display for this Composer's compose() result, Linear for any other source
    Linear,  //!< linear values (AO, radiance): sRGB-encoded on write, and Multiply blends in linear
    Display, //!< already display-encoded: stored as they are, and Multiply blends encoded values
};

//! A host framebuffer to draw into: `framebuffer` (0 = the default framebuffer), the
//! viewport rectangle in pixels, and how to blend. The source is stretched to the viewport;
//! one-channel sources are replicated to RGB, alpha is left as it was. Only the framebuffer's
//! first draw buffer (GL_DRAW_BUFFER0) is written; its other draw buffers keep their values.
//! The host's own GL_FRAMEBUFFER_SRGB setting is not used: `encoding` decides.
struct HostTarget {
    unsigned framebuffer = 0;
    //! Pixels. x, y: the viewport's lower-left corner, within ContextInfo::viewportBoundsRange
    //! (GL would clamp it); it may lie off the framebuffer. width, height: [1,
    //! ContextInfo::maxViewportDims].
    int x = 0, y = 0, width = 0, height = 0;
    HostBlend blend = HostBlend::Overwrite;
    HostSourceEncoding encoding = HostSourceEncoding::Auto;
};

//! Whether a combine with these settings reads the AO input (its result depends on it): the
//! thesis's formula always (AO darkens the direct light too); the others only as the ambient
//! term's factor, with an ambient above 0 and, for Physical, no indirect light. Where it does
//! not, a host need not run AO for the combine.
OBSCURA_API bool combineReadsAo(const ComposeSettings& settings, bool withIndirect);

class OBSCURA_API Composer {
public:
    explicit Composer(Context& context);
    ~Composer();

    //! Combines and tone maps into a GL_RGBA8 texture of display values (sRGB-encoded when
    //! settings.srgb; alpha 1), the G-buffer's size. Passes "compose.combine" (which also
    //! finds the frame's largest luminance, for Drago with an automatic maximum) and
    //! "compose.tonemap". Background pixels (the G-buffer's depth equal to its camera's clear
    //! depth, or one no surface has: NaN, Inf, outside [0, 1], beyond kMaxViewDistance) get
    //! their direct radiance only: no AO, ambient or indirect term, whatever the host's albedo
    //! there. Throws Error{InvalidArgument} for enumerators or settings out of range, without
    //! depth/radiance/albedo, and for inputs of the wrong size, with a base level other than
    //! 0, or of the wrong kind: depth must be a depth format (sampled as depth); radiance,
    //! albedo and indirect light normalized or float RGB/RGBA, AO normalized or float; and for
    //! an input that is this Composer's own output (radiance() fed back as the direct
    //! radiance: alternate two Composers).
    TextureView compose(const ComposeInputs& inputs, const ComposeSettings& settings);

    //! Compiles the programs compose() and drawToHost() take, ahead of time (nothing is
    //! allocated). Throws Error{InvalidArgument} for settings out of range.
    void prepare(const ComposeSettings& settings);

    //! The combined radiance of the last compose call, before its `exposure`, which the tone
    //! mapper multiplies it by (GL_RGBA16F, W/(sr m^2)).
    TextureView radiance() const;

    //! Draws `source` (any 2D float or normalized texture) into the host's framebuffer
    //! (pass "compose.output"). Leaves the host's GL state as it was (StatePolicy). Throws
    //! Error{InvalidArgument} for a source whose base level is not 0, for a target that is not
    //! a complete framebuffer of this context, whose first draw buffer is GL_NONE, has no
    //! image attached or an integer one (the output is float), that has the source's level 0
    //! at any colour attachment (a feedback loop), with an empty rectangle, one wider or
    //! taller than GL_MAX_VIEWPORT_DIMS (ContextInfo::maxViewportDims) or with its origin
    //! outside GL_VIEWPORT_BOUNDS_RANGE, or bad enumerators.
    void drawToHost(const TextureView& source, const HostTarget& target);

    std::size_t memoryBytes() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

} // namespace obscura
