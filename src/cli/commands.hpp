#pragma once
#include <CLI/CLI.hpp>

namespace obscura::cli {

//! Adds `obscura render` to the app.
void addRenderCommand(CLI::App& app);
//! Adds `obscura voxelize` (grid.json + grid.u8, optional PLY of cubes).
void addVoxelizeCommand(CLI::App& app);
//! Adds `obscura info` (GL context, techniques, scenes).
void addInfoCommand(CLI::App& app);
//! Adds `obscura reference` and `obscura bench` (need obscura::reference).
void addReferenceCommand(CLI::App& app);
void addBenchCommand(CLI::App& app);
void addSettingsCommand(CLI::App& app);

} // namespace obscura::cli
