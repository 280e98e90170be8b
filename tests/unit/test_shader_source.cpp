// Shader source handling without GL: include resolution, #line bookkeeping, log mapping.
#include "core/shader_source.hpp"

#include <catch2/catch.hpp>

#include <map>

using namespace obscura::detail;

namespace {
ShaderFileLookup lookupIn(const std::map<std::string, std::string>& files) {
    return [files](const std::string& p) -> std::optional<std::string> {
        const auto it = files.find(p);
        return it == files.end() ? std::nullopt : std::optional<std::string>(it->second);
    };
}
} // namespace

TEST_CASE("Stages are recognised by their suffix", "[unit][shaders]") {
    CHECK(stageFromPath("a/b.vert.glsl") == ShaderStage::Vertex);
    CHECK(stageFromPath("b.frag.glsl") == ShaderStage::Fragment);
    CHECK(stageFromPath("b.comp.glsl") == ShaderStage::Compute);
    CHECK(stageFromPath("b.geom.glsl") == ShaderStage::Geometry);
    CHECK_FALSE(stageFromPath("common/depth.glsl"));
    CHECK_FALSE(stageFromPath("gbuffer/gbuffer_bindings.h"));
    CHECK(std::string(stageShortName(ShaderStage::TessEvaluation)) == "tese");
}

TEST_CASE("Paths are normalised and never leave the root", "[unit][shaders]") {
    CHECK(normalizeShaderPath("gbuffer/../common/depth.glsl") == "common/depth.glsl");
    CHECK(normalizeShaderPath("./a//b/./c.glsl") == "a/b/c.glsl");
    CHECK(normalizeShaderPath("../../x.glsl") == "x.glsl");
}

TEST_CASE("Includes expand in place with #line directives once per file", "[unit][shaders]") {
    const auto lookup = lookupIn({
        {"m/main.comp.glsl", "//! variant: A B=2\n#include \"inc.glsl\"\nvoid main() {}\n#include \"../common/c.glsl\"\n"},
        {"m/inc.glsl", "#include \"../common/c.glsl\"\nfloat f();\n"},
        {"common/c.glsl", "const int C = 1;\n#include <glm/glm.hpp>\n"},
    });
    const ResolvedSource r = resolveIncludes("m/main.comp.glsl", lookup);
    CHECK(r.files == std::vector<std::string>{"m/main.comp.glsl", "m/inc.glsl", "common/c.glsl"});
    CHECK(r.variants == std::vector<std::string>{"A B=2"});
    // c.glsl appears once; the second #include keeps the line count with an empty line.
    CHECK(r.text == "#line 1 0\n//! variant: A B=2\n"
                    "#line 1 1\n"
                    "#line 1 2\nconst int C = 1;\n#include <glm/glm.hpp>\n"
                    "#line 2 1\nfloat f();\n"
                    "#line 3 0\nvoid main() {}\n\n");
}

TEST_CASE("Missing and malformed includes are reported at their file and line", "[unit][shaders]") {
    const auto lookup = lookupIn({{"a.frag.glsl", "\n\n#include \"nope.glsl\"\n"}, {"b.frag.glsl", "#include nope\n"}});
    CHECK_THROWS_WITH(resolveIncludes("a.frag.glsl", lookup), Catch::Contains("a.frag.glsl:3") && Catch::Contains("nope.glsl"));
    CHECK_THROWS_WITH(resolveIncludes("b.frag.glsl", lookup), Catch::Contains("b.frag.glsl:1") && Catch::Contains("quoted"));
    CHECK_THROWS_WITH(resolveIncludes("c.frag.glsl", lookup), Catch::Contains("not found"));
}

TEST_CASE("Driver logs are mapped back to file:line", "[unit][shaders]") {
    const std::vector<std::string> files = {"g/main.frag.glsl", "common/depth.glsl"};
    // Mesa
    CHECK(mapShaderLog("1:12(5): error: `x' undeclared", files) == "common/depth.glsl:12:5: error: `x' undeclared");
    // NVIDIA
    CHECK(mapShaderLog("0(7) : error C1008: undefined variable", files) == "g/main.frag.glsl:7 : error C1008: undefined variable");
    // glslang / AMD
    CHECK(mapShaderLog("ERROR: 1:3: 'y' : undeclared identifier", files) == "ERROR: common/depth.glsl:3: 'y' : undeclared identifier");
    CHECK(mapShaderLog("9:1(1): error", files) == "<source 9>:1:1: error");
}
