#pragma once
// Compiles embedded shaders lazily: one program per (stage files, #defines) permutation,
// compiled on first request and cached for the life of the Context.
#include "core/gl.hpp"
#include "core/gl_objects.hpp"

#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace obscura::detail {

struct ContextImpl;

//! Permutation defines: "NAME" or "NAME=VALUE".
using Defines = std::vector<std::string>;

class ShaderLibrary {
public:
    explicit ShaderLibrary(ContextImpl& ctx);

    //! The linked program for these stage files (paths relative to shaders/) and defines.
    //! Throws Error{ShaderCompile} with the log mapped to file:line.
    GLuint program(const std::vector<std::string_view>& stages, const Defines& defines = {});

    std::vector<std::string> compiledPrograms() const;
    void addSource(const std::string& path, const std::string& text);

private:
    struct StageSource {
        std::string text;
        std::vector<std::string> files;
    };
    StageSource source(std::string_view path) const;
    GLuint compileStage(std::string_view path, const StageSource& src, const std::string& preamble,
                        const std::string& key);

    ContextImpl& ctx_;
    std::map<std::string, Program> programs_;
    std::map<std::string, std::string> overrides_;
};

} // namespace obscura::detail
