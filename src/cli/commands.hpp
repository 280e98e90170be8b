#pragma once
#include <CLI/CLI.hpp>

namespace obscura::cli {

//! Adds `obscura render` to the app.
void addRenderCommand(CLI::App& app);
//! Adds `obscura info` (GL context, techniques, scenes).
void addInfoCommand(CLI::App& app);

} // namespace obscura::cli
