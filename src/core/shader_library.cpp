#include "core/shader_library.hpp"

#include "core/context_impl.hpp"
#include "core/embedded_shaders.hpp"
#include "core/shader_source.hpp"
#include "obscura/error.hpp"

#include <algorithm>

namespace obscura::detail {
namespace {

GLenum glStage(ShaderStage s) {
    switch (s) {
    case ShaderStage::Vertex: return GL_VERTEX_SHADER;
    case ShaderStage::TessControl: return GL_TESS_CONTROL_SHADER;
    case ShaderStage::TessEvaluation: return GL_TESS_EVALUATION_SHADER;
    case ShaderStage::Geometry: return GL_GEOMETRY_SHADER;
    case ShaderStage::Fragment: return GL_FRAGMENT_SHADER;
    case ShaderStage::Compute: return GL_COMPUTE_SHADER;
    }
    return GL_NONE;
}

std::string preambleFor(const Defines& defines) {
    std::string p = "#version 450 core\n";
    for (const auto& d : defines) {
        const auto eq = d.find('=');
        p += "#define " + (eq == std::string::npos ? d + " 1" : d.substr(0, eq) + " " + d.substr(eq + 1)) + "\n";
    }
    return p;
}

std::string programKey(const std::vector<std::string_view>& stages, const Defines& defines) {
    std::string key;
    for (const auto& s : stages) key += (key.empty() ? "" : " + ") + std::string(s);
    if (!defines.empty()) {
        key += " [";
        for (std::size_t i = 0; i < defines.size(); ++i) key += (i ? " " : "") + defines[i];
        key += "]";
    }
    return key;
}

std::string infoLog(GladGLContext& gl, GLuint object, bool program) {
    GLint length = 0;
    program ? gl.GetProgramiv(object, GL_INFO_LOG_LENGTH, &length) : gl.GetShaderiv(object, GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
    program ? gl.GetProgramInfoLog(object, length, nullptr, log.data())
            : gl.GetShaderInfoLog(object, length, nullptr, log.data());
    log.resize(log.find('\0') == std::string::npos ? log.size() : log.find('\0'));
    return log;
}

} // namespace

ShaderLibrary::ShaderLibrary(ContextImpl& ctx) : ctx_(ctx) {}

void ShaderLibrary::addSource(const std::string& path, const std::string& text) {
    overrides_[normalizeShaderPath(path)] = text;
}

ShaderLibrary::StageSource ShaderLibrary::source(std::string_view path) const {
    const std::string key = normalizeShaderPath(path);
    if (overrides_.count(key)) {
        const ShaderFileLookup lookup = [&](const std::string& p) -> std::optional<std::string> {
            const auto it = overrides_.find(p);
            return it == overrides_.end() ? std::nullopt : std::optional<std::string>(it->second);
        };
        try {
            auto resolved = resolveIncludes(key, lookup);
            return {std::move(resolved.text), std::move(resolved.files)};
        } catch (const std::runtime_error& e) {
            throw Error(ErrorCode::ShaderCompile, e.what());
        }
    }
    for (std::size_t i = 0; i < kEmbeddedShaderCount; ++i) {
        const EmbeddedShader& s = kEmbeddedShaders[i];
        if (key == s.path) return {std::string(s.text, s.size), std::vector<std::string>(s.files, s.files + s.fileCount)};
    }
    throw Error(ErrorCode::ShaderCompile, "no shader named \"" + key + "\" is embedded in this build");
}

GLuint ShaderLibrary::compileStage(std::string_view path, const StageSource& src, const std::string& preamble,
                                   const std::string& key) {
    const auto stage = stageFromPath(path);
    if (!stage)
        throw Error(ErrorCode::ShaderCompile,
                    std::string(path) + " is not a stage file (expected *.vert/.geom/.frag/.comp/.tesc/.tese.glsl)");
    auto& gl = ctx_.gl;
    const GLuint shader = gl.CreateShader(glStage(*stage));
    const GLchar* strings[2] = {preamble.c_str(), src.text.c_str()};
    gl.ShaderSource(shader, 2, strings, nullptr);
    gl.CompileShader(shader);
    GLint ok = GL_FALSE;
    gl.GetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        const std::string raw = infoLog(gl, shader, false);
        gl.DeleteShader(shader);
        std::string log = raw;
        try {
            log = mapShaderLog(raw, src.files);
        } catch (const std::exception&) {
            // An unexpected log format: report it unmapped.
        }
        throw Error(ErrorCode::ShaderCompile, "compiling " + std::string(path) + " for " + key + " failed:\n" + log);
    }
    return shader;
}

GLuint ShaderLibrary::program(const std::vector<std::string_view>& stages, const Defines& defines) {
    const std::string key = programKey(stages, defines);
    if (const auto it = programs_.find(key); it != programs_.end()) return it->second.get();

    auto& gl = ctx_.gl;
    const std::string preamble = preambleFor(defines);
    std::vector<GLuint> shaders;
    const auto deleteShaders = [&] {
        for (GLuint s : shaders) gl.DeleteShader(s);
    };
    try {
        for (const auto& path : stages) shaders.push_back(compileStage(path, source(path), preamble, key));
    } catch (...) {
        deleteShaders();
        throw;
    }
    Program program = adoptProgram(ctx_, gl.CreateProgram());
    for (GLuint s : shaders) gl.AttachShader(program.get(), s);
    gl.LinkProgram(program.get());
    for (GLuint s : shaders) gl.DetachShader(program.get(), s);
    deleteShaders();
    GLint ok = GL_FALSE;
    gl.GetProgramiv(program.get(), GL_LINK_STATUS, &ok);
    if (!ok) throw Error(ErrorCode::ShaderCompile, "linking " + key + " failed:\n" + infoLog(gl, program.get(), true));
    gl.ObjectLabel(GL_PROGRAM, program.get(), static_cast<GLsizei>(key.size()), key.data());
    const GLuint name = program.get();
    programs_.emplace(key, std::move(program));
    return name;
}

std::vector<std::string> ShaderLibrary::compiledPrograms() const {
    std::vector<std::string> keys;
    for (const auto& entry : programs_) keys.push_back(entry.first);
    return keys;
}

} // namespace obscura::detail
