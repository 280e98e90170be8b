#pragma once
// The controls the AO and GI examples share: command-line flags and, in a window, an ImGui
// panel over the same values (method, rays, steps, radius, resolution, blur, and the
// thickness and the screen-space thickness mode).
#include "obscura/ambient_occlusion.hpp"

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

namespace obscura::examples {

struct IntegratorControls {
    std::vector<std::string> methods; //!< names of the methods, the order of their enum
    int method = 0;
    int rays = 16;
    int steps = 8;
    float radius = 0.0f; //!< world units; 0 = a tenth of the scene's diagonal
    int resolution = 0;  //!< 0 full, 1 half, 2 quarter
    int blur = 0;        //!< taps each side
    int thicknessMode = 0;  //!< ScreenThickness's order: constant, depth_peeling, peeling_or_constant
    float thickness = 0.0f; //!< world units, >= 0; what it bounds (and 0's meaning) per method: thicknessHelp
    //! --thickness's help: the example's methods read `thickness` differently (the hybrid GI's
    //! is a voxel hit's distance from the tangent plane, not a depth sample's slab).
    std::string thicknessHelp = "World units behind each depth sample (raymarch, points), >= 0 (0: the radius)";
    bool changed = true; //!< set when a widget moved; the example re-renders

    void addOptions(CLI::App& cli);
    //! Validates the parsed flags (after CLI11_PARSE), with what is accepted.
    void check() const;
    AoResolution aoResolution() const;
    ScreenThickness screenThickness() const { return static_cast<ScreenThickness>(thicknessMode); }
    //! The ImGui widgets; sets `changed` when a value moves.
    void drawPanel(const char* title);
};

} // namespace obscura::examples
