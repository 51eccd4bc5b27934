// DDS with the DX10 header (Microsoft's "Programming Guide for DDS"): "DDS ", DDS_HEADER
// (124 bytes, pixel format FourCC "DX10"), DDS_HEADER_DXT10 (20 bytes: DXGI format, 2D
// texture, one array element, alpha mode), then every mip level, largest first.
#include <cstring>

#include "texture/bytes.hpp"
#include "texture/texture.hpp"

namespace mf::texture {
namespace {
using bytes::get32;
using bytes::put32;

constexpr uint32_t kMagic = 0x20534444;       // "DDS "
constexpr uint32_t kFourccDx10 = 0x30315844;  // "DX10"
constexpr uint32_t kCaps = 0x1, kHeight = 0x2, kWidth = 0x4, kPixelFormat = 0x1000, kMipCount = 0x20000,
                   kLinearSize = 0x80000;
constexpr uint32_t kFourcc = 0x4;
constexpr uint32_t kCapsComplex = 0x8, kCapsTexture = 0x1000, kCapsMipmap = 0x400000;
constexpr uint32_t kDimensionTexture2d = 3;
constexpr uint32_t kAlphaUnknown = 0, kAlphaStraight = 1;

struct Dxgi {
    std::string_view block;
    uint32_t unorm, srgb;
    const char *unorm_name, *srgb_name;
};
// dxgiformat.h values.
constexpr Dxgi kDxgi[] = {
    {"bc1", 71, 72, "DXGI_FORMAT_BC1_UNORM", "DXGI_FORMAT_BC1_UNORM_SRGB"},
    {"bc3", 77, 78, "DXGI_FORMAT_BC3_UNORM", "DXGI_FORMAT_BC3_UNORM_SRGB"},
    {"bc4", 80, 0, "DXGI_FORMAT_BC4_UNORM", ""},
    {"bc5", 83, 0, "DXGI_FORMAT_BC5_UNORM", ""},
    {"bc7", 98, 99, "DXGI_FORMAT_BC7_UNORM", "DXGI_FORMAT_BC7_UNORM_SRGB"},
};

const Dxgi* dxgi_of(const BlockFormatInfo* f) {
    if (!f) return nullptr;
    for (const auto& d : kDxgi)
        if (d.block == f->name) return &d;
    return nullptr;
}

}  // namespace

uint32_t dxgi_format(const GpuTexture& t) {
    const Dxgi* d = dxgi_of(t.format);
    return d ? (t.srgb ? d->srgb : d->unorm) : 0;
}

std::string dxgi_format_name(const GpuTexture& t) {
    const Dxgi* d = dxgi_of(t.format);
    return d ? (t.srgb ? d->srgb_name : d->unorm_name) : "";
}

std::vector<uint8_t> write_dds(const GpuTexture& t) {
    std::vector<uint8_t> out;
    const Level& top = t.levels.at(0);
    const auto mips = static_cast<uint32_t>(t.levels.size());
    put32(out, kMagic);
    put32(out, 124);
    put32(out, kCaps | kHeight | kWidth | kPixelFormat | kLinearSize | (mips > 1 ? kMipCount : 0));
    put32(out, static_cast<uint32_t>(top.height));
    put32(out, static_cast<uint32_t>(top.width));
    put32(out, static_cast<uint32_t>(top.data.size()));  // linear size of the top level
    put32(out, 0);                                       // depth
    put32(out, mips);
    for (int i = 0; i < 11; ++i) put32(out, 0);  // reserved
    // DDS_PIXELFORMAT: FourCC "DX10", the format is in the extended header.
    put32(out, 32);
    put32(out, kFourcc);
    put32(out, kFourccDx10);
    for (int i = 0; i < 5; ++i) put32(out, 0);
    put32(out, kCapsTexture | (mips > 1 ? kCapsComplex | kCapsMipmap : 0));
    for (int i = 0; i < 4; ++i) put32(out, 0);  // caps2, caps3, caps4, reserved2
    // DDS_HEADER_DXT10
    put32(out, dxgi_format(t));
    put32(out, kDimensionTexture2d);
    put32(out, 0);  // misc flags (not a cube)
    put32(out, 1);  // array size
    put32(out, t.alpha ? kAlphaStraight : kAlphaUnknown);
    for (const Level& l : t.levels) out.insert(out.end(), l.data.begin(), l.data.end());
    return out;
}

bool read_dds(std::span<const uint8_t> b, GpuTexture& t, std::string& error) {
    constexpr size_t kHeaderBytes = 4 + 124 + 20;
    if (b.size() < kHeaderBytes || get32(b, 0) != kMagic || get32(b, 4) != 124) {
        error = "not a DDS file (no \"DDS \" header)";
        return false;
    }
    if (get32(b, 84) != kFourccDx10) {
        error = "DDS without the DX10 header (only DX10 block-compressed files are read)";
        return false;
    }
    const uint32_t height = get32(b, 12), width = get32(b, 16);
    const uint32_t mips = (get32(b, 8) & kMipCount) ? std::max(1u, get32(b, 28)) : 1u;
    const uint32_t format = get32(b, 128);
    t = GpuTexture{};
    for (const auto& d : kDxgi)
        if (format == d.unorm || (d.srgb && format == d.srgb)) {
            t.format = block_format_info(d.block);
            t.srgb = format == d.srgb;
        }
    if (!t.format) {
        error = "DXGI format " + std::to_string(format) + " is not one matforge reads (BC1, BC3, BC4, BC5, BC7)";
        return false;
    }
    if (get32(b, 132) != kDimensionTexture2d || get32(b, 140) != 1) {
        error = "DDS is not a single 2D texture";
        return false;
    }
    if (width == 0 || height == 0 || width > 65536 || height > 65536 || mips > 17) {
        error = "DDS size " + std::to_string(width) + "x" + std::to_string(height) + " with " + std::to_string(mips) +
                " levels is out of range";
        return false;
    }
    t.alpha = get32(b, 144) == kAlphaStraight;
    size_t at = kHeaderBytes;
    int w = static_cast<int>(width), h = static_cast<int>(height);
    for (uint32_t i = 0; i < mips; ++i) {
        const size_t n = level_bytes(*t.format, w, h);
        if (b.size() - at < n) {
            error = "DDS truncated in level " + std::to_string(i);
            return false;
        }
        t.levels.push_back({w, h,
                            std::vector<uint8_t>(b.begin() + static_cast<std::ptrdiff_t>(at),
                                                 b.begin() + static_cast<std::ptrdiff_t>(at + n))});
        at += n;
        w = std::max(1, w / 2), h = std::max(1, h / 2);
    }
    return true;
}

}  // namespace mf::texture
