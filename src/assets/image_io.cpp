#include "obscura/assets.hpp"
#include "obscura/error.hpp"

#ifdef OBSCURA_WITH_OPENIMAGEIO
#include <OpenImageIO/imageio.h>
#endif

#include <algorithm>
#include <cmath>

namespace obscura::assets {

std::string lowerExtension(const std::filesystem::path& path) {
    std::string e = path.extension().string();
    std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return e;
}

namespace {

float srgbEncode(float linear) {
    const float v = std::clamp(linear, 0.0f, 1.0f);
    return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
}

float srgbDecode(float encoded) {
    return encoded <= 0.04045f ? encoded / 12.92f : std::pow((encoded + 0.055f) / 1.055f, 2.4f);
}

} // namespace

#ifdef OBSCURA_WITH_OPENIMAGEIO
namespace {

// Where channel `name` stood when written with OpenImageIO's default names (R, G, B, A,
// channel4, channel5, ...), or -1 for any other name.
int defaultChannelIndex(const std::string& name) {
    static const char* const first[] = {"R", "G", "B", "A"};
    for (int i = 0; i < 4; ++i)
        if (name == first[i]) return i;
    if (name.size() > 7 && name.compare(0, 7, "channel") == 0 &&
        name.find_first_not_of("0123456789", 7) == std::string::npos)
        return std::stoi(name.substr(7));
    return -1;
}

// OpenEXR stores channels sorted by name, so a file written with the default names of more
// than 10 channels reads back as R, G, B, A, channel10, channel11, channel4, ...: put them
// back in the order they were written (the reference cache packs 12 for RGBA quantities).
void restoreDefaultChannelOrder(const OIIO::ImageSpec& spec, Image& img) {
    const int c = img.channels;
    if (c <= 4 || int(spec.channelnames.size()) != c) return;
    std::vector<int> from(std::size_t(c), -1);
    for (int k = 0; k < c; ++k) {
        const int at = defaultChannelIndex(spec.channelnames[std::size_t(k)]);
        if (at < 0 || at >= c || from[std::size_t(at)] != -1) return; // not the default names: leave as read
        from[std::size_t(at)] = k;
    }
    std::vector<float> row(static_cast<std::size_t>(c));
    for (std::size_t p = 0; p < img.pixels.size(); p += std::size_t(c)) {
        for (int k = 0; k < c; ++k) row[std::size_t(k)] = img.pixels[p + std::size_t(from[std::size_t(k)])];
        std::copy(row.begin(), row.end(), img.pixels.begin() + std::ptrdiff_t(p));
    }
}

} // namespace

Image readImage(const std::filesystem::path& path) {
    auto in = OIIO::ImageInput::open(path.string());
    if (!in) throw Error(ErrorCode::Io, "cannot read image " + path.string() + ": " + OIIO::geterror());
    const OIIO::ImageSpec& spec = in->spec();
    Image img;
    img.width = spec.width;
    img.height = spec.height;
    img.channels = spec.nchannels;
    img.pixels.resize(static_cast<std::size_t>(spec.width) * static_cast<std::size_t>(spec.height) *
                      static_cast<std::size_t>(spec.nchannels));
    if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, img.pixels.data()))
        throw Error(ErrorCode::Io, "cannot read image " + path.string() + ": " + in->geterror());
    restoreDefaultChannelOrder(spec, img);
    // 8- and 16-bit files are display-encoded (sRGB); float files are linear already.
    const bool linearize = spec.format.basetype == OIIO::TypeDesc::UINT8 || spec.format.basetype == OIIO::TypeDesc::UINT16;
    if (linearize)
        for (std::size_t i = 0; i < img.pixels.size(); ++i)
            if (static_cast<int>(i % static_cast<std::size_t>(img.channels)) != spec.alpha_channel)
                img.pixels[i] = srgbDecode(img.pixels[i]);
    return img;
}
#else
// Built without OpenImageIO (a machine that only runs the bench, whose references need no
// files): every file read or write says so.
Image readImage(const std::filesystem::path& path) {
    throw Error(ErrorCode::Io, "cannot read image " + path.string() + ": built without OpenImageIO");
}
#endif

namespace {

void requireConsistent(const Image& image, const std::string& who, int maxChannels = 4) {
    if (image.width < 1 || image.height < 1 || image.channels < 1 || image.channels > maxChannels ||
        image.pixels.size() != static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height) *
                                   static_cast<std::size_t>(image.channels))
        throw Error(ErrorCode::InvalidArgument, who + ": inconsistent image " + std::to_string(image.width) + "x" +
                                                    std::to_string(image.height) + "x" + std::to_string(image.channels));
}

#ifdef OBSCURA_WITH_OPENIMAGEIO
void writeWith(const std::filesystem::path& path, const OIIO::ImageSpec& spec, OIIO::TypeDesc type, const void* data) {
    if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
    auto out = OIIO::ImageOutput::create(path.string());
    if (!out) throw Error(ErrorCode::Io, "cannot write " + path.string() + ": " + OIIO::geterror());
    if (!out->open(path.string(), spec) || !out->write_image(type, data) || !out->close())
        throw Error(ErrorCode::Io, "cannot write " + path.string() + ": " + out->geterror());
}
#else
void writeWith(const std::filesystem::path& path) {
    throw Error(ErrorCode::Io, "cannot write " + path.string() + ": built without OpenImageIO");
}
#endif

} // namespace

TextureImage encodeDisplay(const Image& image, PngEncoding encoding) {
    requireConsistent(image, "encodeDisplay");
    TextureImage t;
    t.width = image.width;
    t.height = image.height;
    t.rgba.resize(static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height) * 4);
    const auto quantize = [](float v) {
        return static_cast<std::uint8_t>(std::lround(std::clamp(std::isfinite(v) ? v : 0.0f, 0.0f, 1.0f) * 255.0f));
    };
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            std::uint8_t* px = &t.rgba[(static_cast<std::size_t>(y) * static_cast<std::size_t>(image.width) +
                                        static_cast<std::size_t>(x)) * 4];
            for (int c = 0; c < 3; ++c) {
                const float v = image.at(x, y, image.channels >= 3 ? c : 0);
                px[c] = quantize(encoding == PngEncoding::Srgb ? srgbEncode(v) : v);
            }
            px[3] = image.channels == 4 ? quantize(image.at(x, y, 3)) : 255;
        }
    return t;
}

void writePng(const std::filesystem::path& path, const TextureImage& picture) {
    if (picture.width < 1 || picture.height < 1 ||
        picture.rgba.size() != static_cast<std::size_t>(picture.width) * static_cast<std::size_t>(picture.height) * 4)
        throw Error(ErrorCode::InvalidArgument, "writePng: inconsistent picture");
#ifdef OBSCURA_WITH_OPENIMAGEIO
    OIIO::ImageSpec spec(picture.width, picture.height, 4, OIIO::TypeDesc::UINT8);
    spec.alpha_channel = 3;
    writeWith(path, spec, OIIO::TypeDesc::UINT8, picture.rgba.data());
#else
    writeWith(path);
#endif
}

void writeImage(const std::filesystem::path& path, const Image& image, PngEncoding encoding) {
    const std::string ext = lowerExtension(path);
    if (ext != ".exr" && ext != ".png")
        throw Error(ErrorCode::InvalidArgument, "writeImage: " + path.string() + " must end in .exr or .png");
    // PNG pictures have up to 4 channels; EXR files any number (references store value and halves).
    requireConsistent(image, "writeImage", ext == ".png" ? 4 : 1024);
    if (ext == ".png") return writePng(path, encodeDisplay(image, encoding));
#ifdef OBSCURA_WITH_OPENIMAGEIO
    OIIO::ImageSpec spec(image.width, image.height, image.channels, OIIO::TypeDesc::FLOAT);
    if (image.channels == 4) spec.alpha_channel = 3;
    spec.attribute("compression", "zip");
    writeWith(path, spec, OIIO::TypeDesc::FLOAT, image.pixels.data());
#else
    writeWith(path);
#endif
}

TextureImage readTextureImage(const std::filesystem::path& path) {
    return encodeDisplay(readImage(path), PngEncoding::Srgb);
}

} // namespace obscura::assets
