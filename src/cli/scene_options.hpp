#pragma once
// Options every subcommand shares: which scene, from where, at which size.
#include "obscura/assets.hpp"

#include <CLI/CLI.hpp>

#include <string>

namespace obscura::cli {

struct SceneOptions {
    std::string scene = "cornell";
    std::string camera;            //!< ex,ey,ez,tx,ty,tz,ux,uy,uz,fovy_deg[,near,far]; empty = the scene's own
    std::string size = "256x256";
    std::string depth = "standard"; //!< standard | zero_to_one | reversed
    std::string environment;        //!< FILE[,intensity[,rotation_deg]]; empty = the scene's own
};

void addSceneOptions(CLI::App& cmd, SceneOptions& options);

struct ResolvedScene {
    assets::LoadedScene scene;
    Camera camera;
    int width = 0, height = 0;
};

//! Parses --environment's "FILE[,intensity[,rotation_deg]]"; throws Error{Parse}.
Environment parseEnvironment(const std::string& text);

//! Loads the scene and builds the camera; throws obscura::Error naming the bad option.
ResolvedScene resolveScene(const SceneOptions& options);

} // namespace obscura::cli
