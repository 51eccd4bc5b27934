// Image files through OpenImageIO. The renderer core never sees a file.
#include <OpenImageIO/imageio.h>

#include <cstring>
#include <system_error>

#include "preview/preview.hpp"

namespace mf::preview {

namespace {

// Opens with unassociated alpha: a 4th channel is data (smoothness, a mask) until a role says
// otherwise, and OpenImageIO would otherwise premultiply PNG colors by it.
std::unique_ptr<OIIO::ImageInput> open_input(const std::filesystem::path& file) {
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    auto in = OIIO::ImageInput::open(file.string(), &config);
    if (!in) throw std::runtime_error("cannot read " + file.string() + ": " + OIIO::geterror());
    return in;
}

void write_aside_and_rename(const std::filesystem::path& file, const char* format, const OIIO::ImageSpec& spec,
                            const OIIO::TypeDesc& type, const void* pixels) {
    std::filesystem::path tmp = file;
    tmp += ".tmp";
    {
        auto out = OIIO::ImageOutput::create(format);
        if (!out) throw std::runtime_error(std::string("no ") + format + " writer: " + OIIO::geterror());
        if (!out->open(tmp.string(), spec) || !out->write_image(type, pixels) || !out->close()) {
            const std::string err = out->geterror();
            std::error_code ec;
            std::filesystem::remove(tmp, ec);
            throw std::runtime_error("cannot write " + file.string() + ": " + err);
        }
    }
    std::error_code ec;
    std::filesystem::rename(tmp, file, ec);
    if (ec) throw std::runtime_error("cannot write " + file.string() + ": " + ec.message());
}

}  // namespace

render::Texture read_texture(const std::filesystem::path& file) {
    auto in = open_input(file);
    const OIIO::ImageSpec& spec = in->spec();
    if (spec.width <= 0 || spec.height <= 0 || int64_t{spec.width} * spec.height > int64_t{16384} * 16384)
        throw std::runtime_error(file.string() + ": unsupported size");
    render::Texture t;
    t.width = static_cast<uint32_t>(spec.width);
    t.height = static_cast<uint32_t>(spec.height);
    // Gray, gray+alpha, RGB, RGBA: anything past the 4th channel is not a texture channel.
    t.channels = static_cast<uint32_t>(std::min(spec.nchannels, 4));
    OIIO::TypeDesc type = OIIO::TypeDesc::FLOAT;
    t.type = render::TexelType::F32;
    if (spec.format == OIIO::TypeDesc::UINT8) {
        type = OIIO::TypeDesc::UINT8;
        t.type = render::TexelType::U8;
    } else if (spec.format == OIIO::TypeDesc::UINT16) {
        type = OIIO::TypeDesc::UINT16;
        t.type = render::TexelType::U16;
    }
    t.data.resize(size_t{t.width} * t.height * t.channels * type.size());
    if (!in->read_image(0, 0, 0, static_cast<int>(t.channels), type, t.data.data()))
        throw std::runtime_error("cannot read " + file.string() + ": " + in->geterror());
    return t;
}

render::Environment read_environment(const std::filesystem::path& file, float intensity) {
    auto in = open_input(file);
    const OIIO::ImageSpec& spec = in->spec();
    if (spec.width < 2 || spec.height < 1 || spec.nchannels < 1)
        throw std::runtime_error(file.string() + ": not an environment image");
    const int nch = std::min(spec.nchannels, 3);
    std::vector<float> src(size_t(spec.width) * size_t(spec.height) * size_t(nch));
    if (!in->read_image(0, 0, 0, nch, OIIO::TypeDesc::FLOAT, src.data()))
        throw std::runtime_error("cannot read " + file.string() + ": " + in->geterror());
    render::Environment env;
    env.width = static_cast<uint32_t>(spec.width);
    env.height = static_cast<uint32_t>(spec.height);
    env.intensity = intensity;
    env.rgba.resize(size_t{env.width} * env.height * 4);
    for (size_t p = 0; p < size_t{env.width} * env.height; ++p) {
        for (int c = 0; c < 3; ++c) {
            const float v = src[p * size_t(nch) + size_t(nch == 3 ? c : 0)];
            env.rgba[4 * p + size_t(c)] = std::isfinite(v) && v > 0.f ? v : 0.f;
        }
        env.rgba[4 * p + 3] = 1.f;
    }
    return env;
}

void write_png(const std::filesystem::path& file, uint32_t width, uint32_t height, const std::vector<uint8_t>& rgba8) {
    std::vector<uint8_t> rgb(size_t{width} * height * 3);
    for (size_t p = 0; p < size_t{width} * height; ++p) std::memcpy(&rgb[3 * p], &rgba8[4 * p], 3);
    OIIO::ImageSpec spec(static_cast<int>(width), static_cast<int>(height), 3, OIIO::TypeDesc::UINT8);
    spec.attribute("oiio:ColorSpace", "sRGB");
    write_aside_and_rename(file, "png", spec, OIIO::TypeDesc::UINT8, rgb.data());
}

void write_exr(const std::filesystem::path& file, uint32_t width, uint32_t height, const std::vector<float>& rgba32f) {
    std::vector<float> rgb(size_t{width} * height * 3);
    for (size_t p = 0; p < size_t{width} * height; ++p) std::memcpy(&rgb[3 * p], &rgba32f[4 * p], 12);
    OIIO::ImageSpec spec(static_cast<int>(width), static_cast<int>(height), 3, OIIO::TypeDesc::FLOAT);
    spec.attribute("oiio:ColorSpace", "linear");
    spec.attribute("compression", "zip");
    // The EXR writer stamps the time unless told one: a fixed stamp keeps reruns byte-identical.
    spec.attribute("DateTime", "2000:01:01 00:00:00");
    spec.attribute("Software", "matforge preview");
    write_aside_and_rename(file, "openexr", spec, OIIO::TypeDesc::FLOAT, rgb.data());
}

}  // namespace mf::preview
