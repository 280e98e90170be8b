#pragma once
// Shader source handling shared by the build-time embed tool and the runtime library:
// #include resolution with #line bookkeeping, stage detection, and mapping of driver logs
// back to the original file:line. Pure C++ (no GL), so it is unit-tested directly.
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace obscura::detail {

enum class ShaderStage { Vertex, TessControl, TessEvaluation, Geometry, Fragment, Compute };

//! Stage from the file name: "x.vert.glsl", ".tesc", ".tese", ".geom", ".frag", ".comp".
//! Files without a stage suffix are include-only.
std::optional<ShaderStage> stageFromPath(std::string_view path);
//! glslangValidator's -S name of a stage ("vert", "frag", ...).
const char* stageShortName(ShaderStage stage);

struct ResolvedSource {
    //! Text with every #include expanded in place and a `#line L S` directive at every file
    //! boundary, S being the index into `files`. There is no #version line: the compiler
    //! front end prepends it together with the permutation's #defines.
    std::string text;
    //! Source-string number → path relative to the shader root. files[0] is the stage file.
    std::vector<std::string> files;
    //! Permutations the stage file declares with `//! variant: A B=2` lines, each as
    //! "A B=2"; used to validate every declared permutation offline.
    std::vector<std::string> variants;
};

//! Returns the contents of a path relative to the shader root, or nullopt if absent.
using ShaderFileLookup = std::function<std::optional<std::string>(const std::string& path)>;

//! Expands `#include "path"` recursively. A path is looked up next to the including file
//! first, then relative to the shader root. Each file is included at most once per stage,
//! which makes include guards unnecessary and cycles harmless.
//! Throws std::runtime_error("file:line: message") for a missing or malformed include.
ResolvedSource resolveIncludes(const std::string& path, const ShaderFileLookup& lookup);

//! Rewrites the source-string:line references of a compiler log ("0:12(5):" from Mesa,
//! "0(12) :" from NVIDIA, "ERROR: 0:12:" from glslang/AMD) into "file:line" references.
std::string mapShaderLog(std::string_view log, const std::vector<std::string>& files);

//! Normalises "a/b/../c" to "a/c" and drops "./". Paths never escape the root.
std::string normalizeShaderPath(std::string_view path);

} // namespace obscura::detail
