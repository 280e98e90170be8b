// obscura: command-line front end (render | info | voxelize | reference | bench | settings).
#include "commands.hpp"
#include "obscura/error.hpp"
#include "obscura/version.hpp"

#include <cstdio>

int main(int argc, char** argv) {
    CLI::App app{"Obscura " OBSCURA_VERSION_STRING ": real-time GI approximations and visibility queries, headless"};
    app.set_version_flag("--version", OBSCURA_VERSION_STRING);
    app.require_subcommand(1);
    obscura::cli::addRenderCommand(app);
    obscura::cli::addInfoCommand(app);
    obscura::cli::addVoxelizeCommand(app);
#ifdef OBSCURA_WITH_REFERENCE
    obscura::cli::addReferenceCommand(app);
    obscura::cli::addBenchCommand(app);
#endif
    obscura::cli::addSettingsCommand(app);
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e);
    } catch (const obscura::Error& e) {
        std::fprintf(stderr, "%s\n", e.what());
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "obscura: %s\n", e.what());
        return 1;
    }
    return 0;
}
