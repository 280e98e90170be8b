// The examples' ImGui panel (IntegratorControls::drawPanel) sets the values the flags set:
// Dear ImGui driven with mouse input and no window or renderer (it needs neither to lay out
// and handle widgets), clicked along the panel's frames to find each widget, as a user would.
// Written against Debian 12's Dear ImGui 1.86 and three of its internals (imgui_internal.h):
// a combo's popup window is named ##Combo_00, ImGuiWindow::Active says it is open, and
// ImGuiWindow::ItemWidthDefault is the frames' width. Another ImGui may need them updated.
#include "integrator_controls.hpp"

#include <catch2/catch.hpp>
#include <imgui.h>
#include <imgui_internal.h>

#include <functional>
#include <map>
#include <string>

using obscura::examples::IntegratorControls;

namespace {

constexpr const char* kTitle = "controls";

IntegratorControls defaults() {
    IntegratorControls c;
    c.methods = {"raymarch", "points", "horizon"};
    c.rays = 16;
    c.steps = 8;
    c.radius = 5.0f;
    c.blur = 5;
    return c;
}

// One ImGui context for one trial; frames run with the mouse where the trial puts it.
struct Panel {
    ImGuiContext* context;
    IntegratorControls controls = defaults();

    Panel() : context(ImGui::CreateContext()) {
        ImGui::SetCurrentContext(context);
        ImGuiIO& io = ImGui::GetIO();
        io.IniFilename = nullptr;
        io.DisplaySize = ImVec2(640, 480);
        io.DeltaTime = 1.0f / 60.0f;
        unsigned char* pixels = nullptr;
        int w = 0, h = 0;
        io.Fonts->GetTexDataAsRGBA32(&pixels, &w, &h); // builds the font atlas NewFrame needs
        for (int i = 0; i < 3; ++i) frame(ImVec2(-1, -1), false); // the auto-resized window settles
        controls.changed = false;
    }
    ~Panel() { ImGui::DestroyContext(context); }

    void frame(ImVec2 mouse, bool down) {
        ImGuiIO& io = ImGui::GetIO();
        io.MousePos = mouse;
        io.MouseDown[0] = down;
        ImGui::NewFrame();
        controls.drawPanel(kTitle);
        ImGui::Render();
    }
    void click(ImVec2 at) {
        frame(at, false);
        frame(at, true);
        frame(at, false);
    }
    void drag(ImVec2 from, float dx) {
        frame(from, false);
        frame(from, true);
        for (int i = 1; i <= 4; ++i) frame(ImVec2(from.x + dx * float(i) / 4.0f, from.y), true);
        frame(ImVec2(from.x + dx, from.y), false);
    }
    ImGuiWindow* window(const char* name) const { return ImGui::FindWindowByName(name); }
};

// The panel's rectangle and its frames' extent: items are ItemWidthDefault wide from the
// window's padding (an auto-resized window's default, 16 font heights).
struct Layout {
    float top, bottom, frameLeft, frameRight;
};

Layout layoutOf(const Panel& p) {
    const ImGuiWindow* w = p.window(kTitle);
    REQUIRE(w != nullptr);
    const float left = w->Pos.x + ImGui::GetStyle().WindowPadding.x;
    return {w->Pos.y, w->Pos.y + w->Size.y, left, left + w->ItemWidthDefault};
}

// What a trial changed, by field name.
std::map<std::string, float> changes(const IntegratorControls& c) {
    const IntegratorControls d = defaults();
    std::map<std::string, float> out;
    if (c.method != d.method) out["method"] = float(c.method);
    if (c.rays != d.rays) out["rays"] = float(c.rays);
    if (c.steps != d.steps) out["steps"] = float(c.steps);
    if (c.radius != d.radius) out["radius"] = c.radius;
    if (c.resolution != d.resolution) out["resolution"] = float(c.resolution);
    if (c.blur != d.blur) out["blur"] = float(c.blur);
    if (c.thicknessMode != d.thicknessMode) out["thickness mode"] = float(c.thicknessMode);
    if (c.thickness != d.thickness) out["thickness"] = c.thickness;
    return out;
}

// Runs `trial` on a fresh panel at every height of the panel (2 pixels apart) and gathers
// every value each field took; each trial changes `changed` exactly when it changes a value.
std::map<std::string, std::vector<float>> scan(const std::function<void(Panel&, const Layout&, float y)>& trial) {
    std::map<std::string, std::vector<float>> seen;
    Layout layout;
    {
        Panel p;
        layout = layoutOf(p);
    }
    for (float y = layout.top + 1.0f; y < layout.bottom; y += 2.0f) {
        Panel p;
        trial(p, layout, y);
        const auto changed = changes(p.controls);
        CAPTURE(y);
        CHECK(p.controls.changed == !changed.empty());
        for (const auto& [name, value] : changed) seen[name].push_back(value);
    }
    return seen;
}

bool took(const std::map<std::string, std::vector<float>>& seen, const std::string& name, float value) {
    const auto it = seen.find(name);
    if (it == seen.end()) return false;
    for (float v : it->second)
        if (v == value) return true;
    return false;
}

} // namespace

TEST_CASE("The examples' ImGui panel switches method, rays, steps, radius, resolution, blur and thickness",
          "[examples]") {
    // Clicking a slider's frame at its right end sets its maximum, at its left end its minimum.
    const auto right = scan([](Panel& p, const Layout& l, float y) { p.click(ImVec2(l.frameRight - 2.0f, y)); });
    CHECK(took(right, "rays", 1024.0f));
    CHECK(took(right, "steps", 256.0f));
    CHECK(took(right, "blur", 16.0f));
    const auto left = scan([](Panel& p, const Layout& l, float y) { p.click(ImVec2(l.frameLeft + 2.0f, y)); });
    CHECK(took(left, "rays", 1.0f));
    CHECK(took(left, "steps", 1.0f));
    CHECK(took(left, "blur", 0.0f));
    // Dragging the radius to the right makes it larger (its speed: 1 % of it a pixel).
    const auto dragged = scan([](Panel& p, const Layout& l, float y) { p.drag(ImVec2(l.frameLeft + 60.0f, y), 40.0f); });
    REQUIRE(dragged.count("radius") == 1);
    for (float r : dragged.at("radius")) CHECK(r > defaults().radius);
    REQUIRE(dragged.count("thickness") == 1); // the slab's drag
    for (float t : dragged.at("thickness")) CHECK(t > defaults().thickness);
    // A combo opens a list below it; clicking its second entry picks it (ImGui names a
    // combo's popup ##Combo_00).
    const auto picked = scan([](Panel& p, const Layout& l, float y) {
        const ImVec2 at(l.frameLeft + 20.0f, y);
        p.click(at);
        p.frame(at, false); // a popup is placed and sized in the frame after it opens
        const ImGuiWindow* list = p.window("##Combo_00");
        if (!list || !list->Active) return;
        // The second entry of the list (each a font height plus the item spacing).
        const float entry = ImGui::GetFontSize() + ImGui::GetStyle().ItemSpacing.y;
        p.click(ImVec2(list->Pos.x + 10.0f, list->Pos.y + ImGui::GetStyle().WindowPadding.y + 1.5f * entry));
    });
    CHECK(took(picked, "method", 1.0f));
    CHECK(took(picked, "resolution", 1.0f));
    CHECK(took(picked, "thickness mode", 1.0f));
}
