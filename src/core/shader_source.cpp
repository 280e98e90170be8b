#include "core/shader_source.hpp"

#include <regex>
#include <set>
#include <sstream>
#include <stdexcept>

namespace obscura::detail {
namespace {

bool endsWith(std::string_view s, std::string_view suffix) {
    return s.size() >= suffix.size() && s.substr(s.size() - suffix.size()) == suffix;
}

std::string dirName(const std::string& path) {
    const auto slash = path.find_last_of('/');
    return slash == std::string::npos ? std::string{} : path.substr(0, slash + 1);
}

std::string_view trimLeft(std::string_view s) {
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
    return s;
}

// Parses `#include "x"` (any blanks after '#'). Returns nullopt when the line is not an
// include; throws for an include with a malformed argument.
std::optional<std::string> includeTarget(std::string_view line, const std::string& where) {
    line = trimLeft(line);
    if (line.empty() || line.front() != '#') return std::nullopt;
    line = trimLeft(line.substr(1));
    if (line.substr(0, 7) != "include") return std::nullopt;
    line = trimLeft(line.substr(7));
    // <...> includes belong to C++-only sections of shared headers (#ifdef __cplusplus) and
    // are left for the GLSL preprocessor to skip.
    if (!line.empty() && line.front() == '<') return std::nullopt;
    const auto close = line.size() > 1 ? line.find('"', 1) : std::string_view::npos;
    if (line.empty() || line.front() != '"' || close == std::string_view::npos)
        throw std::runtime_error(where + ": #include expects a quoted path, got: " + std::string(line));
    return std::string(line.substr(1, close - 1));
}

struct Resolver {
    const ShaderFileLookup& lookup;
    ResolvedSource out;
    std::set<std::string> included;

    void file(const std::string& path) {
        const auto text = lookup(path);
        if (!text) throw std::runtime_error(path + ": shader file not found");
        included.insert(path);
        const auto index = out.files.size();
        out.files.push_back(path);
        out.text += "#line 1 " + std::to_string(index) + "\n";

        std::istringstream lines(*text);
        std::string line;
        int lineNo = 0;
        while (std::getline(lines, line)) {
            ++lineNo;
            const std::string where = path + ":" + std::to_string(lineNo);
            if (auto target = includeTarget(line, where)) {
                const auto found = locate(*target, path, where);
                if (!included.count(found)) {
                    file(found);
                    out.text += "#line " + std::to_string(lineNo + 1) + " " + std::to_string(index) + "\n";
                } else {
                    out.text += "\n"; // keeps the line count of this file intact
                }
                continue;
            }
            if (index == 0) collectVariant(line);
            out.text += line;
            out.text += '\n';
        }
    }

    std::string locate(const std::string& target, const std::string& from, const std::string& where) {
        const std::string sibling = normalizeShaderPath(dirName(from) + target);
        if (included.count(sibling) || lookup(sibling)) return sibling;
        const std::string rooted = normalizeShaderPath(target);
        if (included.count(rooted) || lookup(rooted)) return rooted;
        throw std::runtime_error(where + ": cannot find #include \"" + target + "\" (looked for " + sibling +
                                 " and " + rooted + ")");
    }

    void collectVariant(std::string_view line) {
        line = trimLeft(line);
        constexpr std::string_view tag = "//! variant:";
        if (line.substr(0, tag.size()) == tag) out.variants.emplace_back(trimLeft(line.substr(tag.size())));
    }
};

} // namespace

std::optional<ShaderStage> stageFromPath(std::string_view path) {
    static constexpr std::pair<std::string_view, ShaderStage> suffixes[] = {
        {".vert.glsl", ShaderStage::Vertex},     {".tesc.glsl", ShaderStage::TessControl},
        {".tese.glsl", ShaderStage::TessEvaluation}, {".geom.glsl", ShaderStage::Geometry},
        {".frag.glsl", ShaderStage::Fragment},   {".comp.glsl", ShaderStage::Compute},
    };
    for (const auto& [suffix, stage] : suffixes)
        if (endsWith(path, suffix)) return stage;
    return std::nullopt;
}

const char* stageShortName(ShaderStage stage) {
    switch (stage) {
    case ShaderStage::Vertex: return "vert";
    case ShaderStage::TessControl: return "tesc";
    case ShaderStage::TessEvaluation: return "tese";
    case ShaderStage::Geometry: return "geom";
    case ShaderStage::Fragment: return "frag";
    case ShaderStage::Compute: return "comp";
    }
    return "?";
}

std::string normalizeShaderPath(std::string_view path) {
    std::vector<std::string> parts;
    std::string part;
    std::istringstream in{std::string(path)};
    while (std::getline(in, part, '/')) {
        if (part.empty() || part == ".") continue;
        if (part == "..") {
            if (!parts.empty()) parts.pop_back();
            continue;
        }
        parts.push_back(part);
    }
    std::string out;
    for (const auto& p : parts) out += (out.empty() ? "" : "/") + p;
    return out;
}

ResolvedSource resolveIncludes(const std::string& path, const ShaderFileLookup& lookup) {
    Resolver r{lookup, {}, {}};
    r.file(normalizeShaderPath(path));
    return std::move(r.out);
}

std::string mapShaderLog(std::string_view log, const std::vector<std::string>& files) {
    // Order matters: the Mesa form "S:L(C)" must be tried before the NVIDIA form "S(L)".
    static const std::regex pattern(R"((\d+):(\d+)\((\d+)\)|\b(\d+)\((\d+)\)|\b(\d+):(\d+):)");
    const auto fileName = [&](const std::string& index) {
        const auto i = std::stoul(index);
        return i < files.size() ? files[i] : "<source " + index + ">";
    };
    std::string out;
    std::string text(log);
    auto it = std::sregex_iterator(text.begin(), text.end(), pattern);
    std::size_t last = 0;
    for (; it != std::sregex_iterator(); ++it) {
        const auto& m = *it;
        out.append(text, last, static_cast<std::size_t>(m.position()) - last);
        if (m[1].matched) out += fileName(m[1]) + ":" + m[2].str() + ":" + m[3].str();
        else if (m[4].matched) out += fileName(m[4]) + ":" + m[5].str();
        else out += fileName(m[6]) + ":" + m[7].str() + ":";
        last = static_cast<std::size_t>(m.position() + m.length());
    }
    out.append(text, last);
    return out;
}

} // namespace obscura::detail
