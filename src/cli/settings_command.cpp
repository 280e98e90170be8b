// "obscura settings": every module's settings table as markdown, and the docs' copies of
// them checked or rewritten, so that docs/ cannot drift from the tables in the headers.
#include "commands.hpp"

#include "obscura/ambient_occlusion.hpp"
#include "obscura/compose.hpp"
#include "obscura/directional_occlusion.hpp"
#include "obscura/environment.hpp"
#include "obscura/error.hpp"
#include "obscura/gbuffer.hpp"
#include "obscura/indirect_light.hpp"
#include "obscura/media.hpp"
#include "obscura/screen_visibility.hpp"
#include "obscura/settings_table.hpp"
#include "obscura/shadow_maps.hpp"
#include "obscura/voxelizer.hpp"

#include <cstdio>
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

namespace obscura::cli {
namespace {

struct DocumentedTable {
    std::string name;     //!< the struct
    std::string markdown; //!< its table
};

std::string cell(std::string text) {
    std::string out;
    for (const char c : text) out += c == '|' ? std::string("\\|") : std::string(1, c);
    return out;
}

template <class S>
DocumentedTable documented(const std::string& name) {
    std::ostringstream md;
    md << "| key | field | unit | range | default | meaning |\n|---|---|---|---|---|---|\n";
    const S defaults{};
    for (const Setting<S>& row : S::table())
        md << "| `" << row.key << "` | `" << row.field << "` | " << cell(row.unit) << " | " << cell(row.range) << " | "
           << cell(row.format(row.values(defaults))) << " | " << cell(row.doc) << " |\n";
    return {name, md.str()};
}

std::vector<DocumentedTable> allTables() {
    return {documented<AmbientOcclusionSettings>("AmbientOcclusionSettings"),
            documented<IndirectLightSettings>("IndirectLightSettings"),
            documented<DirectionalOcclusionSettings>("DirectionalOcclusionSettings"),
            documented<EnvironmentSettings>("EnvironmentSettings"),
            documented<MediaSettings>("MediaSettings"),
            documented<ComposeSettings>("ComposeSettings"),
            documented<GBufferSettings>("GBufferSettings"),
            documented<ScreenTraceSettings>("ScreenTraceSettings"),
            documented<ShadowMapSettings>("ShadowMapSettings"),
            documented<ShadowMaskSettings>("ShadowMaskSettings"),
            documented<VoxelizerSettings>("VoxelizerSettings"),
            documented<TraversalSettings>("TraversalSettings")};
}

std::string readFile(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

// The docs' blocks "<!-- settings: Name -->\n...<!-- /settings -->" with each table in place
// of its block's body; `found` collects the names seen. Unknown names are an error.
std::string withTables(std::string text, const std::vector<DocumentedTable>& tables, std::vector<std::string>& found,
                       const std::string& file) {
    const std::string open = "<!-- settings: ", close = "<!-- /settings -->";
    std::size_t at = 0;
    while ((at = text.find(open, at)) != std::string::npos) {
        const std::size_t nameEnd = text.find(" -->\n", at);
        const std::size_t end = text.find(close, at);
        if (nameEnd == std::string::npos || end == std::string::npos || end < nameEnd)
            throw Error(ErrorCode::Parse, file + ": a settings block without its end");
        const std::string name = text.substr(at + open.size(), nameEnd - at - open.size());
        const DocumentedTable* table = nullptr;
        for (const DocumentedTable& t : tables)
            if (t.name == name) table = &t;
        if (!table) throw Error(ErrorCode::Parse, file + ": no settings table \"" + name + "\"");
        found.push_back(name);
        const std::size_t bodyStart = nameEnd + 5;
        text.replace(bodyStart, end - bodyStart, table->markdown);
        at = bodyStart + table->markdown.size() + close.size();
    }
    return text;
}

// Checks (or, with `update`, rewrites) every docs page's settings blocks; every table must
// appear once. Returns the exit status.
int syncDocs(const std::filesystem::path& dir, bool update) {
    const std::vector<DocumentedTable> tables = allTables();
    std::vector<std::string> found;
    int stale = 0;
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
        if (entry.path().extension() != ".md") continue;
        const std::string text = readFile(entry.path());
        const std::string current = withTables(text, tables, found, entry.path().string());
        if (current == text) continue;
        if (update) {
            std::ofstream(entry.path(), std::ios::binary) << current;
            std::printf("updated %s\n", entry.path().string().c_str());
        } else {
            std::fprintf(stderr, "%s: settings tables differ from the headers' (run obscura settings --update %s)\n",
                         entry.path().string().c_str(), dir.string().c_str());
            ++stale;
        }
    }
    for (const DocumentedTable& t : tables) {
        const auto n = std::count(found.begin(), found.end(), t.name);
        if (n != 1) {
            std::fprintf(stderr, "%s: %s appears in %d settings blocks, not 1\n", dir.string().c_str(), t.name.c_str(),
                         int(n));
            ++stale;
        }
    }
    return stale == 0 ? 0 : 1;
}

} // namespace

void addSettingsCommand(CLI::App& app) {
    CLI::App* cmd = app.add_subcommand("settings", "Print every module's settings table (markdown), or check or update docs/");
    auto check = std::make_shared<std::string>();
    auto update = std::make_shared<std::string>();
    cmd->add_option("--check", *check, "fail unless DIR's *.md settings blocks equal the tables")->type_name("DIR");
    cmd->add_option("--update", *update, "rewrite DIR's *.md settings blocks from the tables")->type_name("DIR");
    cmd->callback([check, update] {
        if (!check->empty()) {
            if (const int rc = syncDocs(*check, false); rc != 0) throw CLI::RuntimeError(rc);
            return;
        }
        if (!update->empty()) {
            // Rewrites what differs; still fails for a table missing from the docs or repeated.
            if (const int rc = syncDocs(*update, true); rc != 0) throw CLI::RuntimeError(rc);
            return;
        }
        for (const DocumentedTable& t : allTables()) std::printf("### `%s`\n\n%s\n", t.name.c_str(), t.markdown.c_str());
    });
}

} // namespace obscura::cli
