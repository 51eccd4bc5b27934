// Image files through lib/image (reading: guarded, unassociated alpha, bomb guard; encoding:
// deterministic) and lib/core (atomic writes). The renderer core never sees a file.
#include <cmath>
#include <cstring>

#include "core/files.hpp"
#include "image/image.hpp"
#include "preview/preview.hpp"

namespace mf::preview {
namespace {

InputFile input(const std::filesystem::path& file) {
    InputFile in;
    in.path = file;
    in.display = file.string();
    return in;
}

template <class T>
void copy_samples(const std::vector<T>& src, render::Texture& t) {
    t.data.resize(src.size() * sizeof(T));
    std::memcpy(t.data.data(), src.data(), t.data.size());
}

bool write_encoded(const std::filesystem::path& file, bool ok, const std::vector<unsigned char>& bytes,
                   std::string& error) {
    if (!ok) {
        error = file.string() + ": " + error;
        return false;
    }
    return write_file_atomic(file, bytes, error);
}

}  // namespace

std::optional<render::Texture> read_texture(const std::filesystem::path& file, std::string& error) {
    Decoded d;
    ImageInfo info;
    if (!read_image(input(file), d, info, error)) return std::nullopt;
    render::Texture t;
    t.width = static_cast<uint32_t>(d.width());
    t.height = static_cast<uint32_t>(d.height());
    // Gray, gray+alpha, RGB, RGBA: anything past the 4th channel is not a texture channel.
    const int nch = d.channels();
    t.channels = static_cast<uint32_t>(std::min(nch, 4));
    const size_t texels = size_t{t.width} * t.height;
    if (d.is_codes()) {
        t.type = render::TexelType::u8;
        if (nch <= 4) {
            t.data = std::move(d.codes.pixels);  // the codes as decoded, not copied
        } else {
            t.data.resize(texels * 4);
            for (size_t p = 0; p < texels; ++p) std::memcpy(&t.data[4 * p], &d.codes.pixels[p * size_t(nch)], 4);
        }
        return t;
    }
    auto each_sample = [&](auto&& put) {
        for (size_t p = 0; p < texels; ++p)
            for (uint32_t c = 0; c < t.channels; ++c) put(p * t.channels + c, d.floats.pixels[p * size_t(nch) + c]);
    };
    if (info.bit_depth == 16 && !info.is_float) {
        // 16-bit integer files stay 16-bit: OpenImageIO's float is k / 65535, so rounding gives k
        // back exactly, and the renderer uploads them as UNORM16 as stored.
        t.type = render::TexelType::u16;
        std::vector<uint16_t> px(texels * t.channels);
        each_sample([&](size_t i, float v) { px[i] = quantize_unorm(v, 65535.f); });
        copy_samples(px, t);
        return t;
    }
    t.type = render::TexelType::f32;
    std::vector<float> px(texels * t.channels);
    each_sample([&](size_t i, float v) { px[i] = v; });
    copy_samples(px, t);
    return t;
}

std::optional<render::Environment> read_environment(const std::filesystem::path& file, float intensity,
                                                    std::string& error) {
    Image img;
    ImageInfo info;
    if (!read_image(input(file), img, info, error)) return std::nullopt;
    if (img.width < 2 || img.height < 1 || img.channels < 1) {
        error = file.string() + ": not an environment image (at least 2x1 pixels)";
        return std::nullopt;
    }
    const int nch = img.channels;
    render::Environment env;
    env.width = static_cast<uint32_t>(img.width);
    env.height = static_cast<uint32_t>(img.height);
    env.intensity = intensity;
    env.rgba.resize(size_t{env.width} * env.height * 4);
    for (size_t p = 0; p < size_t{env.width} * env.height; ++p) {
        for (int c = 0; c < 3; ++c) {
            const float v = img.pixels[p * size_t(nch) + size_t(nch >= 3 ? c : 0)];
            env.rgba[4 * p + size_t(c)] = std::isfinite(v) && v > 0.f ? v : 0.f;  // radiance is never negative
        }
        env.rgba[4 * p + 3] = 1.f;
    }
    return env;
}

bool write_png(const std::filesystem::path& file, uint32_t width, uint32_t height, const std::vector<uint8_t>& rgba8,
               std::string& error) {
    Image8 rgb(static_cast<int>(width), static_cast<int>(height), 3);
    for (size_t p = 0; p < size_t{width} * height; ++p) std::memcpy(&rgb.pixels[3 * p], &rgba8[4 * p], 3);
    std::vector<unsigned char> bytes;
    const bool ok = encode_image(rgb, EncodeOptions{FileFormat::png, 8}, bytes, error);
    return write_encoded(file, ok, bytes, error);
}

bool write_exr(const std::filesystem::path& file, uint32_t width, uint32_t height, const std::vector<float>& rgba32f,
               std::string& error) {
    Image rgb(static_cast<int>(width), static_cast<int>(height), 3);
    for (size_t p = 0; p < size_t{width} * height; ++p) std::memcpy(&rgb.pixels[3 * p], &rgba32f[4 * p], 12);
    std::vector<unsigned char> bytes;
    const bool ok = encode_image(rgb, EncodeOptions{FileFormat::exr, 32}, bytes, error);
    return write_encoded(file, ok, bytes, error);
}

}  // namespace mf::preview
