#include "integrator_controls.hpp"

#include "obscura/error.hpp"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <stdexcept>
#include <string>

namespace obscura::examples {
namespace {

const char* const kResolutions[] = {"full", "half", "quarter"};
const char* const kThicknessModes[] = {"constant", "depth_peeling", "peeling_or_constant"}; // ScreenThickness's order

int indexOf(const std::vector<std::string>& names, const std::string& name) {
    const auto it = std::find(names.begin(), names.end(), name);
    return it == names.end() ? -1 : static_cast<int>(it - names.begin());
}

// A CLI11 check with a short message (CLI::NonNegativeNumber prints DBL_MAX in full).
std::string finiteNonNegative(const std::string& value) {
    try {
        const float v = std::stof(value);
        return v >= 0.0f && std::isfinite(v) ? std::string() : "world units, finite and >= 0";
    } catch (const std::exception&) {
        return "not a number";
    }
}

} // namespace

void IntegratorControls::addOptions(CLI::App& cli) {
    std::string known;
    for (const auto& m : methods) known += (known.empty() ? "" : "|") + m;
    cli.add_option_function<std::string>("--method", [this](const std::string& v) {
        method = indexOf(methods, v);
        if (method < 0) throw CLI::ValidationError("--method", v + " is not one of the methods");
    }, known + " (default " + methods.front() + ")");
    cli.add_option("--rays", rays, "Directions per pixel [1, 1024] (horizon: even, rays / 2 slices)")
        ->check(CLI::Range(1, 1024))
        ->capture_default_str();
    cli.add_option("--steps", steps, "Samples per ray [1, 256]")->check(CLI::Range(1, 256))->capture_default_str();
    cli.add_option("--radius", radius, "World units, >= 0 (0: a tenth of the scene's diagonal)")
        ->check(finiteNonNegative)
        ->capture_default_str();
    cli.add_option_function<std::string>("--resolution", [this](const std::string& v) {
        resolution = indexOf({std::begin(kResolutions), std::end(kResolutions)}, v);
        if (resolution < 0) throw CLI::ValidationError("--resolution", v + ": expected full, half or quarter");
    }, "full|half|quarter (default full)");
    cli.add_option("--blur", blur, "Geometry-aware blur taps each side [0, 16]")->check(CLI::Range(0, 16))->capture_default_str();
    cli.add_option_function<std::string>("--thickness-mode", [this](const std::string& v) {
        thicknessMode = indexOf({std::begin(kThicknessModes), std::end(kThicknessModes)}, v);
        if (thicknessMode < 0)
            throw CLI::ValidationError("--thickness-mode",
                                       v + ": expected constant, depth_peeling or peeling_or_constant");
    }, "Screen-space methods: constant (--thickness behind each depth sample), depth_peeling (down to the second "
       "depth layer) or peeling_or_constant (the deeper of both) (default constant)");
    cli.add_option("--thickness", thickness, thicknessHelp)->capture_default_str();
}

void IntegratorControls::check() const {
    // The flags' own checks ran while parsing; these depend on two flags.
    if (methods[std::size_t(method)] == "horizon" && rays % 2 != 0)
        throw Error(ErrorCode::Parse, "--rays: the horizon method takes an even count (rays / 2 slices), got " +
                                          std::to_string(rays));
    if (!(thickness >= 0.0f) || std::isinf(thickness))
        throw Error(ErrorCode::Parse, "--thickness: world units, finite and >= 0");
}

AoResolution IntegratorControls::aoResolution() const {
    return resolution == 2 ? AoResolution::Quarter : resolution == 1 ? AoResolution::Half : AoResolution::Full;
}

void IntegratorControls::drawPanel(const char* title) {
    ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_FirstUseEver);
    ImGui::Begin(title, nullptr, ImGuiWindowFlags_AlwaysAutoResize);
    std::vector<const char*> names;
    for (const auto& m : methods) names.push_back(m.c_str());
    changed |= ImGui::Combo("method", &method, names.data(), static_cast<int>(names.size()));
    // The flags' full ranges, on a log scale so that the small counts stay easy to pick: a
    // narrower slider would clamp a value given by flag as soon as it is touched.
    changed |= ImGui::SliderInt("rays", &rays, 1, 1024, "%d", ImGuiSliderFlags_Logarithmic);
    changed |= ImGui::SliderInt("steps", &steps, 1, 256, "%d", ImGuiSliderFlags_Logarithmic);
    changed |= ImGui::DragFloat("radius", &radius, std::max(radius, 1.0f) * 0.01f, 0.0f, 1e6f);
    changed |= ImGui::Combo("resolution", &resolution, kResolutions, 3);
    changed |= ImGui::SliderInt("blur", &blur, 0, 16);
    changed |= ImGui::Combo("thickness", &thicknessMode, kThicknessModes, 3);
    // Clamped also when typed (Ctrl+click): a negative thickness is refused by the integrators.
    changed |= ImGui::DragFloat("slab", &thickness, std::max(thickness, 1.0f) * 0.01f, 0.0f, 1e6f, "%.3f",
                                ImGuiSliderFlags_AlwaysClamp);
    ImGui::End();
}

} // namespace obscura::examples
