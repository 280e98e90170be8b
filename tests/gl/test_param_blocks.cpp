// Every parameter block C++ fills and GLSL reads (shaders/*/*_bindings.h): each field's
// offset in the C++ struct (offsetof, the headers' k<Block>Fields) equals the offset the
// driver gives the same member in a program that includes the header, and the block's size
// equals sizeof. A field moved in one language only, or padding a compiler adds, fails here.
#include "gl_fixture.hpp"
#include "shaders/ao/ao_bindings.h"
#include "shaders/common/common_bindings.h"
#include "shaders/compose/compose_bindings.h"
#include "shaders/filters/filter_bindings.h"
#include "shaders/gbuffer/gbuffer_bindings.h"
#include "shaders/gi/gi_bindings.h"
#include "shaders/shadows/shadow_bindings.h"
#include "shaders/voxel/voxel_bindings.h"

#include <catch2/catch.hpp>

#include <iterator>
#include <span>
#include <string>

using namespace obscura;

namespace {

struct Block {
    const char* header;  // under shaders/
    const char* type;    // the GLSL struct
    const char* layout;  // std140 (uniform) or std430 (buffer)
    std::span<const shader::BlockField> fields;
    std::size_t size;
};

// The member's name as the program interface lists it: arrays by their first element, an
// array of structs by its first element's first member.
std::string resourceName(const std::string& field) {
    if (field == "cascades") return "p.cascades[0].viewToLight";
    if (field == "poisson") return "p.poisson[0]";
    return "p." + field;
}

void checkBlock(const Block& b) {
    INFO(b.type);
    const bool uniform = std::string(b.layout) == "std140";
    const std::string source = std::string("#include \"") + b.header + "\"\nlayout(" + b.layout + ", binding = 0) " +
                               (uniform ? "uniform" : "buffer") + " Block { " + b.type +
                               " p; };\nlayout(local_size_x = 1) in;\nvoid main() {}\n";
    const GLuint program = test::libraryComputeProgram(source);
    const GLenum member = uniform ? GL_UNIFORM : GL_BUFFER_VARIABLE;
    for (const shader::BlockField& f : b.fields) {
        const std::string name = resourceName(f.name);
        INFO(name);
        const GLuint index = glGetProgramResourceIndex(program, member, name.c_str());
        REQUIRE(index != GL_INVALID_INDEX); // std140 and std430 members are active, used or not
        const GLenum property = GL_OFFSET;
        GLint offset = -1;
        glGetProgramResourceiv(program, member, index, 1, &property, 1, nullptr, &offset);
        CHECK(std::size_t(offset) == f.offset);
    }
    const GLuint block = glGetProgramResourceIndex(program, uniform ? GL_UNIFORM_BLOCK : GL_SHADER_STORAGE_BLOCK, "Block");
    REQUIRE(block != GL_INVALID_INDEX);
    const GLenum property = GL_BUFFER_DATA_SIZE;
    GLint size = 0;
    glGetProgramResourceiv(program, uniform ? GL_UNIFORM_BLOCK : GL_SHADER_STORAGE_BLOCK, block, 1, &property, 1, nullptr,
                           &size);
    CHECK(std::size_t(size) == b.size);
    glDeleteProgram(program);
}

} // namespace

TEST_CASE("Parameter blocks: every field at the same offset in C++ and GLSL", "[shaders][blocks]") {
    test::GlFixture gl;
    using namespace shader;
    const Block blocks[] = {
        {"common/common_bindings.h", "FrameData", "std140", kFrameDataFields, sizeof(FrameData)},
        {"ao/ao_bindings.h", "AoParams", "std140", kAoParamsFields, sizeof(AoParams)},
        {"gi/gi_bindings.h", "GiParams", "std140", kGiParamsFields, sizeof(GiParams)},
        {"compose/compose_bindings.h", "ComposeParams", "std140", kComposeParamsFields, sizeof(ComposeParams)},
        {"filters/filter_bindings.h", "FilterParams", "std140", kFilterParamsFields, sizeof(FilterParams)},
        {"filters/filter_bindings.h", "TemporalParams", "std140", kTemporalParamsFields, sizeof(TemporalParams)},
        {"voxel/voxel_bindings.h", "VoxelParams", "std140", kVoxelParamsFields, sizeof(VoxelParams)},
        {"shadows/shadow_bindings.h", "ShadowParams", "std430", kShadowParamsFields, sizeof(ShadowParams)},
        {"gbuffer/gbuffer_bindings.h", "LightData", "std430", kLightDataFields, sizeof(LightData)},
    };
    for (const Block& b : blocks) checkBlock(b);
}

TEST_CASE("Parameter blocks: an array of shadow records has the C++ stride, cascade by cascade", "[shaders][blocks]") {
    test::GlFixture gl;
    using namespace shader;
    const GLuint program = test::libraryComputeProgram(
        "#include \"shadows/shadow_bindings.h\"\nlayout(std430, binding = 0) buffer Block { ShadowParams p[]; };\n"
        "layout(local_size_x = 1) in;\nvoid main() {}\n");
    const auto offsetOf = [&](const std::string& name) {
        INFO(name);
        const GLuint index = glGetProgramResourceIndex(program, GL_BUFFER_VARIABLE, name.c_str());
        REQUIRE(index != GL_INVALID_INDEX);
        const GLenum props[] = {GL_OFFSET, GL_TOP_LEVEL_ARRAY_STRIDE};
        GLint values[2] = {-1, -1};
        glGetProgramResourceiv(program, GL_BUFFER_VARIABLE, index, 2, props, 2, nullptr, values);
        CHECK(std::size_t(values[1]) == sizeof(ShadowParams));
        return std::size_t(values[0]);
    };
    for (const BlockField& f : kShadowCascadeFields)
        for (int c = 0; c < SHADOW_MAX_MAPS; ++c)
            CHECK(offsetOf("p[0].cascades[" + std::to_string(c) + "]." + f.name) ==
                  offsetof(ShadowParams, cascades) + std::size_t(c) * sizeof(ShadowCascade) + f.offset);
    glDeleteProgram(program);
}
