// Reading back what the container writers wrote: one entry for both containers and one decode of
// the top level, shared by `matforge preview` (devices that cannot sample a format) and
// `matforge report` (thumbnails of the outputs), so both show the blocks an engine samples.
#include <algorithm>
#include <cmath>

#include "texture/texture.hpp"

namespace mf::texture {

double z_from_xy(double x, double y) { return std::sqrt(std::max(0.0, 1.0 - x * x - y * y)); }

bool is_gpu_texture_name(const std::filesystem::path& file) {
    std::string ext = file.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext == ".dds" || ext == ".ktx2";
}

bool read_gpu_texture(std::span<const uint8_t> bytes, GpuTexture& t, std::string& error) {
    // "DDS " and the KTX 2.0 identifier's first bytes (0xAB 'K' 'T' 'X'): the readers check the rest.
    const bool dds = bytes.size() >= 4 && std::equal(bytes.begin(), bytes.begin() + 4, "DDS ");
    const bool ktx2 = bytes.size() >= 4 && bytes[0] == 0xAB && bytes[1] == 'K' && bytes[2] == 'T' && bytes[3] == 'X';
    if (!dds && !ktx2) {
        error = "neither a DDS nor a KTX2 file (no \"DDS \" or KTX identifier)";
        return false;
    }
    if (!(dds ? read_dds(bytes, t, error) : read_ktx2(bytes, t, error))) return false;
    if (t.levels.empty() || !t.format) {
        error = "no texture levels";
        return false;
    }
    return true;
}

bool decode_top_level(const GpuTexture& t, int channels, bool rebuild_z, Image8& codes, std::string& error) {
    if (t.levels.empty() || !t.format || channels < 1 || channels > 4) {
        error = "no texture level to decode";
        return false;
    }
    const Level& top = t.levels[0];
    CodecOptions co;
    co.format = t.format;
    co.srgb = t.srgb;
    Image8 rgba;
    if (!decode_level(top.data, top.width, top.height, co, rgba, error)) return false;
    if (channels == 4 && !rebuild_z) {
        codes = std::move(rgba);
        return true;
    }
    codes = Image8(top.width, top.height, channels);
    const size_t n = static_cast<size_t>(top.width) * static_cast<size_t>(top.height);
    const auto c = static_cast<size_t>(channels);
    for (size_t p = 0; p < n; ++p) {
        for (size_t k = 0; k < c; ++k) codes.pixels[p * c + k] = rgba.pixels[p * 4 + k];
        if (rebuild_z && c >= 3) {
            const double x = rgba.pixels[p * 4] / 127.5 - 1.0, y = rgba.pixels[p * 4 + 1] / 127.5 - 1.0;
            const double z = z_from_xy(x, y);
            codes.pixels[p * c + 2] = static_cast<uint8_t>(std::lround((z + 1.0) * 127.5));
        }
    }
    return true;
}

}  // namespace mf::texture
