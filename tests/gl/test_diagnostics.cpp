// Diagnostics: likely host mistakes that no check can prove are reported through the debug
// callback (or the GL debug log), and refused with ContextDesc::strictChecks.
#include "gl_fixture.hpp"
#include "obscura/obscura.hpp"
#include "scene_builders.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <string>
#include <vector>

using namespace obscura;

namespace {

constexpr int W = 32, H = 24;

// What a host's GL debug callback received from the third-party source.
std::vector<std::pair<unsigned, std::string>> hostLog;
void GLAD_API_PTR hostCallback(GLenum source, GLenum, GLuint id, GLenum, GLsizei, const GLchar* message, const void*) {
    if (source == GL_DEBUG_SOURCE_THIRD_PARTY) hostLog.emplace_back(id, message);
}

struct DiagnosticsFixture {
    test::GlFixture gl;
    std::vector<DebugMessage> messages;
    Scene scene = test::cornerScene(false);

    ContextDesc desc(bool strict = false) {
        ContextDesc d = gl.desc();
        d.debugOutput = [this](const DebugMessage& m) {
            if (m.source == GL_DEBUG_SOURCE_THIRD_PARTY) messages.push_back(m);
        };
        d.strictChecks = strict;
        return d;
    }
    std::size_t count(Diagnostic what) const {
        return std::size_t(std::count_if(messages.begin(), messages.end(),
                                         [&](const DebugMessage& m) { return m.id == static_cast<unsigned>(what); }));
    }
};

Camera camera(DepthMode mode) {
    return Camera::perspective({{4, 3, 5}, {0, 0.5f, 0}, {0, 1, 0}}, 0.9f, float(W) / H, 0.1f, 100.0f, mode);
}

} // namespace

TEST_CASE("A camera's ClipDepth other than the current clip control is reported, and refused when strict",
          "[diagnostics][host]") {
    // The README's snippet once passed ClipDepth::ZeroToOne; a default-GL host (glm::perspective,
    // GL_NEGATIVE_ONE_TO_ONE) copying it got quietly wrong AO. The matrix cannot tell, the
    // context's clip control can.
    DiagnosticsFixture f;
    Context ctx(f.desc());
    GBuffer ours(ctx), adopter(ctx);
    const Camera standard = camera(DepthMode::Standard);
    const GBufferView view = ours.render(f.scene, standard, {W, H, false, {}});
    HostGBuffer host;
    host.depth = view.depth;
    adopter.adopt(host, standard); // default clip control, NegativeOneToOne: consistent
    CHECK(f.count(Diagnostic::ClipDepthMismatch) == 0);
    Camera claimed = standard;
    claimed.clipDepth = ClipDepth::ZeroToOne; // the copied snippet
    adopter.adopt(host, claimed);
    REQUIRE(f.count(Diagnostic::ClipDepthMismatch) == 1);
    adopter.adopt(host, claimed); // the next frames: said once while it lasts
    CHECK(f.count(Diagnostic::ClipDepthMismatch) == 1);
    const DebugMessage& m = f.messages.back();
    CHECK(m.type == GL_DEBUG_TYPE_OTHER);
    CHECK(m.severity == GL_DEBUG_SEVERITY_MEDIUM);
    CHECK_THAT(m.text, Catch::Contains("ClipDepth is ZeroToOne") && Catch::Contains("GL_NEGATIVE_ONE_TO_ONE"));
    // A host that renders with glClipControl(GL_ZERO_TO_ONE) and says so: nothing to report.
    glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
    adopter.adopt(host, claimed);
    CHECK(f.count(Diagnostic::ClipDepthMismatch) == 1);
    adopter.adopt(host, standard);
    CHECK(f.count(Diagnostic::ClipDepthMismatch) == 2);
    glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);

    SECTION("strict: refused before any GL work") {
        Context strict(f.desc(true));
        GBuffer g(strict);
        const auto objects = test::liveGlObjects();
        for (int frame = 0; frame < 2; ++frame) // refused every time
            CHECK_THROWS_WITH(g.adopt(host, claimed), Catch::Contains("GL_CLIP_DEPTH_MODE") && Catch::Contains("strictChecks"));
        CHECK(test::liveGlObjects() == objects);
        CHECK_NOTHROW(g.adopt(host, standard));
    }
    SECTION("without a debugOutput callback: into the GL debug log, where the host's own callback reads it") {
        ContextDesc plain = f.gl.desc();
        Context quiet(plain);
        GBuffer g(quiet);
        hostLog.clear();
        glDebugMessageCallback(hostCallback, nullptr);
        glEnable(GL_DEBUG_OUTPUT);
        glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
        g.adopt(host, claimed);
        glDisable(GL_DEBUG_OUTPUT);
        glDisable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
        glDebugMessageCallback(nullptr, nullptr);
        REQUIRE(hostLog.size() == 1);
        CHECK(hostLog[0].first == static_cast<unsigned>(Diagnostic::ClipDepthMismatch));
        CHECK_THAT(hostLog[0].second, Catch::Contains("GL_CLIP_DEPTH_MODE"));
    }
    CHECK(test::drainGlErrors().empty());
}

TEST_CASE("Host depth whose background lies on the camera's near plane is reported", "[diagnostics][host]") {
    // A reversed-Z camera (near -> 1, background 0) with a depth buffer rendered and cleared
    // the standard way (background 1): every background pixel reads as a surface on the near
    // plane. Rendered the way the camera says, nothing is reported.
    DiagnosticsFixture f;
    Context ctx(f.desc());
    GBuffer adopter(ctx);
    const Camera reversed = camera(DepthMode::Reversed);
    const GLuint right = test::rasterizeDepthAsHost(f.scene, reversed, W, H, GL_DEPTH_COMPONENT32F);
    const GLuint wrong = test::rasterizeDepthAsHost(f.scene, camera(DepthMode::StandardZeroToOne), W, H, GL_DEPTH_COMPONENT32F);
    glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE); // the reversed camera's, so that only the depth is wrong
    HostGBuffer host;
    host.depth = {right, 0, 0, 0};
    adopter.adopt(host, reversed);
    CHECK(f.count(Diagnostic::DepthOnNearPlane) == 0);
    host.depth = {wrong, 0, 0, 0};
    adopter.adopt(host, reversed);
    REQUIRE(f.count(Diagnostic::DepthOnNearPlane) == 1);
    CHECK_THAT(f.messages.back().text, Catch::Contains("near plane") && Catch::Contains("background must hold 0"));
    // Counted once per depth texture, size and convention (a read-back): not every frame.
    adopter.adopt(host, reversed);
    CHECK(f.count(Diagnostic::DepthOnNearPlane) == 1);
    CHECK(f.count(Diagnostic::ClipDepthMismatch) == 0);
    // Nobody to tell: the count (a read-back) is not taken.
    {
        Context quiet(f.gl.desc());
        GBuffer g(quiet);
        g.adopt(host, reversed);
        for (const std::string& p : quiet.compiledPrograms()) CHECK(p.find("COUNT_NEAR_PLANE") == std::string::npos);
    }
    glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
    glDeleteTextures(1, &right);
    glDeleteTextures(1, &wrong);
    CHECK(test::drainGlErrors().empty());
}
