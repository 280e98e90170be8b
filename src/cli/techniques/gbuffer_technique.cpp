// "gbuffer": the G-buffer's own buffers as a technique, so they can be rendered, written and
// timed like every other technique.
#include "obscura/gbuffer.hpp"
#include "obscura/error.hpp"
#include "lit_gbuffer.hpp"
#include "technique_registry.hpp"

#include <algorithm>
#include <cmath>

namespace obscura::cli {
namespace {

Image mapped(const Image& src, int channels, const std::function<float(const Image&, int, int, int)>& f) {
    Image out;
    out.width = src.width;
    out.height = src.height;
    out.channels = channels;
    out.pixels.resize(static_cast<std::size_t>(src.width) * static_cast<std::size_t>(src.height) *
                      static_cast<std::size_t>(channels));
    for (int y = 0; y < src.height; ++y)
        for (int x = 0; x < src.width; ++x)
            for (int c = 0; c < channels; ++c) out.at(x, y, c) = f(src, x, y, c);
    return out;
}

Image rgb(const Image& src) { return mapped(src, 3, [](const Image& s, int x, int y, int c) { return s.at(x, y, c); }); }

// The image size is --size's.
const std::vector<SettingInfo> kSettings =
    joinSettings(tableSettings(GBufferSettings{}, {"width", "height"}), LitGBuffer::settings());

class GBufferRun final : public TechniqueRun {
public:
    explicit GBufferRun(Context& ctx) : ctx_(ctx), lit_(ctx) {}

    void set(const std::string& key, const std::string& value) override {
        if (!setFromTable(settings_, key, value) && !lit_.set(key, value)) unknownSetting("gbuffer", key, kSettings);
    }

    void run(const FrameSetup& frame) override {
        settings_.width = frame.width;
        settings_.height = frame.height;
        view_ = lit_.render(frame, settings_);
    }

    std::vector<TechniqueOutput> outputs(const std::vector<std::string>& names) override {
        std::vector<TechniqueOutput> out;
        for (const auto& name : names) out.push_back(output(name));
        return out;
    }

    GBufferSamples samples() override {
        return readSamples(ctx_, gbuffer_, view_);
    }

    std::vector<std::pair<std::string, std::size_t>> memory() const override { return lit_.memory(); }

    std::string ignoredSetting(const std::string& key) const override {
        return lit_.ignoredSetting(key, settings_.directLighting);
    }
    std::string ignoredInScene(const std::string& key, const Scene& scene) const override {
        return LitGBuffer::ignoredInScene(key, scene);
    }

    // Positions and face normals against primary-ray hits (the reconstruction and
    // rasterization error); the direct radiance (shadowed through shadow maps unless
    // shadows=0) against direct light with visibility (what the shadow maps and the
    // area-light approximations cost).
    std::vector<Measurement> measurements() override {
        const GBufferSamples s = samples();
        const glm::dmat4 toWorld = glm::inverse(glm::dmat4(view_.camera.view));
        Image position = rgb(s.viewPositions), normal = rgb(s.viewNormals);
        for (int y = 0; y < position.height; ++y)
            for (int x = 0; x < position.width; ++x) {
                const glm::dvec3 p(position.at(x, y, 0), position.at(x, y, 1), position.at(x, y, 2));
                const glm::dvec3 n(normal.at(x, y, 0), normal.at(x, y, 1), normal.at(x, y, 2));
                const glm::dvec3 pw = glm::dvec3(toWorld * glm::dvec4(p, 1.0)), nw = glm::dmat3(toWorld) * n;
                for (int c = 0; c < 3; ++c) {
                    position.at(x, y, c) = static_cast<float>(pw[c]);
                    normal.at(x, y, c) = static_cast<float>(nw[c]);
                }
            }
        return {
            {"position", position, std::nullopt, Measurement::Geometry::Position},
            {"normal", normal, std::nullopt, Measurement::Geometry::Normal},
            {"direct", rgb(readTexture(ctx_, view_.directRadiance)), reference::DirectLight{true}, Measurement::Geometry::None},
        };
    }

private:
    TechniqueOutput output(const std::string& name) {
        TechniqueOutput o;
        o.name = name;
        if (name == "direct") {
            o.image = rgb(readTexture(ctx_, view_.directRadiance));
            o.display = o.image;
        } else if (name == "albedo") {
            o.image = rgb(readTexture(ctx_, view_.albedo));
            o.display = o.image;
        } else if (name == "normal") {
            o.image = rgb(readTexture(ctx_, view_.normal));
            o.display = mapped(o.image, 3, [](const Image& s, int x, int y, int c) { return s.at(x, y, c) * 0.5f + 0.5f; });
            o.encoding = assets::PngEncoding::Linear;
        } else if (name == "depth") {
            o.image = readTexture(ctx_, view_.depth);
            o.display = o.image;
            o.encoding = assets::PngEncoding::Linear;
        } else if (name == "position" || name == "distance") {
            const Image p = readTexture(ctx_, gbuffer_.positions(view_));
            if (name == "position") {
                o.image = rgb(p);
            } else {
                o.image = mapped(p, 1, [](const Image& s, int x, int y, int) {
                    return s.at(x, y, 3) > 0.0f ? std::sqrt(s.at(x, y, 0) * s.at(x, y, 0) + s.at(x, y, 1) * s.at(x, y, 1) +
                                                            s.at(x, y, 2) * s.at(x, y, 2))
                                                : 0.0f;
                });
            }
            // Display: distance scaled to the farthest visible point.
            float far = 0.0f;
            for (int y = 0; y < p.height; ++y)
                for (int x = 0; x < p.width; ++x)
                    far = std::max(far, std::sqrt(p.at(x, y, 0) * p.at(x, y, 0) + p.at(x, y, 1) * p.at(x, y, 1) +
                                                  p.at(x, y, 2) * p.at(x, y, 2)));
            o.display = mapped(o.image, o.image.channels, [far](const Image& s, int x, int y, int c) {
                return far > 0.0f ? std::abs(s.at(x, y, c)) / far : 0.0f;
            });
            o.encoding = assets::PngEncoding::Linear;
        } else if (name == "layer_gap") {
            o.image = layerGap();
            o.display = o.image;
            o.encoding = assets::PngEncoding::Linear;
        } else {
            throw Error(ErrorCode::InvalidArgument, "gbuffer has no output \"" + name +
                                                        "\" (outputs: direct, albedo, normal, depth, position, distance, layer_gap)");
        }
        return o;
    }

    std::string missingOutput(const std::string& name) const override {
        return name == "layer_gap" && settings_.depthLayers != 2 ? "needs --set depth_layers=2" : "";
    }

    // World units between the first and the second depth layer's points along each pixel's
    // ray (what depth-peeled thickness takes as solid), 0 where either layer is missing.
    Image layerGap() {
        if (const std::string why = missingOutput("layer_gap"); !why.empty())
            throw Error(ErrorCode::InvalidArgument, "gbuffer output \"layer_gap\" " + why);
        const Image front = readTexture(ctx_, gbuffer_.positions(view_));
        GBufferView back = view_;
        back.depth = view_.backDepth;
        const Image behind = readTexture(ctx_, gbuffer_.positions(back));
        return mapped(front, 1, [&behind](const Image& f, int x, int y, int) {
            if (f.at(x, y, 3) == 0.0f || behind.at(x, y, 3) == 0.0f) return 0.0f;
            const glm::vec3 a(f.at(x, y, 0), f.at(x, y, 1), f.at(x, y, 2));
            const glm::vec3 b(behind.at(x, y, 0), behind.at(x, y, 1), behind.at(x, y, 2));
            return glm::length(b - a);
        });
    }

    Context& ctx_;
    LitGBuffer lit_;
    GBuffer& gbuffer_ = lit_.gbuffer();
    GBufferSettings settings_;
    GBufferView view_;
};

const TechniqueRegistrar registrar({
    "gbuffer",
    "G-buffer: hardware depth, view-space face normal, albedo, direct radiance (shadow-mapped)",
    {"direct", "albedo", "normal", "depth", "position", "distance", "layer_gap"},
    kSettings,
    {{"default", {}}},
    [](Context& ctx) { return std::make_unique<GBufferRun>(ctx); },
});

} // namespace
} // namespace obscura::cli
