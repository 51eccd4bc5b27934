// KTX 2.0 (Khronos KTX File Format Specification 2.0): identifier, header, level index, data
// format descriptor (Khronos Data Format 1.3 basic descriptor block), key/value data
// (KTXwriter), then the levels, smallest first, each aligned to lcm(block bytes, 4) when not
// supercompressed. Supercompression scheme 2 (Zstandard) compresses each level on its own.
#include <zstd.h>

#include <array>
#include <cstring>
#include <numeric>

#include "texture/bytes.hpp"
#include "texture/texture.hpp"

namespace mf::texture {
namespace {
using bytes::get32;
using bytes::get64;
using bytes::put32;
using bytes::set64;

constexpr std::array<uint8_t, 12> kIdentifier{0xAB, 'K', 'T', 'X', ' ', '2', '0', 0xBB, '\r', '\n', 0x1A, '\n'};
constexpr uint32_t kSchemeNone = 0, kSchemeZstd = 2;

// khr_df.h values.
constexpr uint32_t kModelBc1a = 128, kModelBc3 = 130, kModelBc4 = 131, kModelBc5 = 132, kModelBc7 = 134,
                   kModelAstc = 162;
constexpr uint32_t kPrimariesBt709 = 1;
constexpr uint32_t kTransferLinear = 1, kTransferSrgb = 2;
constexpr uint32_t kQualifierLinear = 0x10;  // a sample not sRGB-encoded in an sRGB format (alpha)

struct Vk {
    std::string_view block;
    uint32_t unorm, srgb;
    const char *unorm_name, *srgb_name;
};
// vulkan_core.h values. bc1 here is opaque BC1 (BC1_RGB: no punch-through alpha).
constexpr Vk kVk[] = {
    {"bc1", 131, 132, "VK_FORMAT_BC1_RGB_UNORM_BLOCK", "VK_FORMAT_BC1_RGB_SRGB_BLOCK"},
    {"bc3", 137, 138, "VK_FORMAT_BC3_UNORM_BLOCK", "VK_FORMAT_BC3_SRGB_BLOCK"},
    {"bc4", 139, 0, "VK_FORMAT_BC4_UNORM_BLOCK", ""},
    {"bc5", 141, 0, "VK_FORMAT_BC5_UNORM_BLOCK", ""},
    {"bc7", 145, 146, "VK_FORMAT_BC7_UNORM_BLOCK", "VK_FORMAT_BC7_SRGB_BLOCK"},
    {"astc-4x4", 157, 158, "VK_FORMAT_ASTC_4x4_UNORM_BLOCK", "VK_FORMAT_ASTC_4x4_SRGB_BLOCK"},
    {"astc-5x5", 161, 162, "VK_FORMAT_ASTC_5x5_UNORM_BLOCK", "VK_FORMAT_ASTC_5x5_SRGB_BLOCK"},
    {"astc-6x6", 165, 166, "VK_FORMAT_ASTC_6x6_UNORM_BLOCK", "VK_FORMAT_ASTC_6x6_SRGB_BLOCK"},
    {"astc-8x8", 171, 172, "VK_FORMAT_ASTC_8x8_UNORM_BLOCK", "VK_FORMAT_ASTC_8x8_SRGB_BLOCK"},
};

const Vk* vk_of(const BlockFormatInfo* f) {
    if (!f) return nullptr;
    for (const auto& v : kVk)
        if (v.block == f->name) return &v;
    return nullptr;
}

// The data format descriptor of a block-compressed format, as the Khronos dfdutils
// (createDFDCompressed) writes it: one or two 64/128-bit samples covering the block.
std::vector<uint8_t> make_dfd(const GpuTexture& t) {
    const BlockFormatInfo& f = *t.format;
    struct Sample {
        uint32_t channel, bit_offset, bits;
    };
    uint32_t model = kModelAstc;
    std::vector<Sample> samples;
    if (f.name == "bc1") model = kModelBc1a, samples = {{0, 0, 64}};                    // BC1A_COLOR
    else if (f.name == "bc3") model = kModelBc3, samples = {{15, 0, 64}, {0, 64, 64}};  // BC3_ALPHA, BC3_COLOR
    else if (f.name == "bc4") model = kModelBc4, samples = {{0, 0, 64}};                // BC4_DATA
    else if (f.name == "bc5") model = kModelBc5, samples = {{0, 0, 64}, {1, 64, 64}};   // BC5_RED, BC5_GREEN
    else if (f.name == "bc7") model = kModelBc7, samples = {{0, 0, 128}};               // BC7_COLOR
    else samples = {{0, 0, 128}};                                                       // ASTC_DATA
    std::vector<uint8_t> d;
    const auto block_size = static_cast<uint32_t>(24 + 16 * samples.size());
    put32(d, 4 + block_size);           // dfdTotalSize
    put32(d, 0);                        // vendorId KHRONOS (17 bits), descriptorType BASICFORMAT (15 bits)
    put32(d, 2u | (block_size << 16));  // versionNumber 2 (KDF 1.3), descriptorBlockSize
    put32(d, model | (kPrimariesBt709 << 8) | ((t.srgb ? kTransferSrgb : kTransferLinear) << 16) |
                 (0u << 24));  // flags: straight alpha
    put32(d, static_cast<uint32_t>(f.block_width - 1) | (static_cast<uint32_t>(f.block_height - 1) << 8));
    put32(d, static_cast<uint32_t>(f.block_bytes));  // bytesPlane0 (kept when supercompressed)
    put32(d, 0);                                     // bytesPlane4..7
    for (const Sample& s : samples) {
        const uint32_t channel = s.channel | (t.srgb && s.channel == 15 ? kQualifierLinear : 0u);
        put32(d, s.bit_offset | ((s.bits - 1) << 16) | (channel << 24));
        put32(d, 0);            // sample position
        put32(d, 0);            // sampleLower
        put32(d, 0xFFFFFFFFu);  // sampleUpper
    }
    return d;
}

void pad_to(std::vector<uint8_t>& out, size_t alignment) {
    while (out.size() % alignment) out.push_back(0);
}

}  // namespace

uint32_t vk_format(const GpuTexture& t) {
    const Vk* v = vk_of(t.format);
    return v ? (t.srgb ? v->srgb : v->unorm) : 0;
}

std::string vk_format_name(const GpuTexture& t) {
    const Vk* v = vk_of(t.format);
    return v ? (t.srgb ? v->srgb_name : v->unorm_name) : "";
}

bool write_ktx2(const GpuTexture& t, const Ktx2Options& opt, std::vector<uint8_t>& out, std::string& error) {
    if (!vk_of(t.format) || t.levels.empty()) {
        error = "no Vulkan format for this texture";
        return false;
    }
    const size_t levels = t.levels.size();
    const Level& top = t.levels[0];
    out.assign(kIdentifier.begin(), kIdentifier.end());
    put32(out, vk_format(t));
    put32(out, 1);  // typeSize: 1 for block-compressed formats
    put32(out, static_cast<uint32_t>(top.width));
    put32(out, static_cast<uint32_t>(top.height));
    put32(out, 0);  // pixelDepth
    put32(out, 0);  // layerCount: not an array
    put32(out, 1);  // faceCount
    put32(out, static_cast<uint32_t>(levels));
    put32(out, opt.zstd ? kSchemeZstd : kSchemeNone);
    const size_t index_at = out.size();  // dfd/kvd offsets and lengths, sgd offset and length
    out.resize(out.size() + 4 * 4 + 2 * 8, 0);
    const size_t level_index_at = out.size();
    out.resize(out.size() + levels * 24, 0);

    const std::vector<uint8_t> dfd = make_dfd(t);
    const auto dfd_at = static_cast<uint32_t>(out.size());
    out.insert(out.end(), dfd.begin(), dfd.end());
    const auto kvd_at = static_cast<uint32_t>(out.size());
    {
        const std::string key = "KTXwriter";
        const auto length = static_cast<uint32_t>(key.size() + 1 + opt.writer.size() + 1);
        put32(out, length);
        out.insert(out.end(), key.begin(), key.end());
        out.push_back(0);
        out.insert(out.end(), opt.writer.begin(), opt.writer.end());
        out.push_back(0);
        pad_to(out, 4);
    }
    const auto kvd_length = static_cast<uint32_t>(out.size() - kvd_at);
    auto index32 = [&](size_t field, uint32_t v) {
        for (size_t i = 0; i < 4; ++i) out[index_at + 4 * field + i] = static_cast<uint8_t>(v >> (8 * i));
    };
    index32(0, dfd_at);
    index32(1, static_cast<uint32_t>(dfd.size()));
    index32(2, kvd_at);
    index32(3, kvd_length);  // no supercompression global data: sgd offset and length stay 0

    // Levels smallest first (the specification's order: a streaming reader gets a usable texture
    // early); alignment lcm(block bytes, 4) without supercompression, none with it.
    const size_t alignment = opt.zstd ? 1 : std::lcm(static_cast<size_t>(t.format->block_bytes), size_t{4});
    for (size_t i = levels; i-- > 0;) {
        const Level& l = t.levels[i];
        pad_to(out, alignment);
        const size_t at = out.size();
        size_t length = l.data.size();
        if (opt.zstd) {
            std::vector<uint8_t> z(ZSTD_compressBound(l.data.size()));
            const size_t n = ZSTD_compress(z.data(), z.size(), l.data.data(), l.data.size(), opt.zstd_level);
            if (ZSTD_isError(n)) {
                error = std::string("zstd: ") + ZSTD_getErrorName(n);
                return false;
            }
            out.insert(out.end(), z.begin(), z.begin() + static_cast<std::ptrdiff_t>(n));
            length = n;
        } else {
            out.insert(out.end(), l.data.begin(), l.data.end());
        }
        set64(out, level_index_at + 24 * i, at);
        set64(out, level_index_at + 24 * i + 8, length);
        set64(out, level_index_at + 24 * i + 16, l.data.size());
    }
    return true;
}

bool read_ktx2(std::span<const uint8_t> b, GpuTexture& t, std::string& error) {
    if (b.size() < 80 || !std::equal(kIdentifier.begin(), kIdentifier.end(), b.begin())) {
        error = "not a KTX 2.0 file (no KTX 20 identifier)";
        return false;
    }
    const uint32_t format = get32(b, 12), width = get32(b, 20), height = get32(b, 24);
    const uint32_t depth = get32(b, 28), layers = get32(b, 32), faces = get32(b, 36),
                   levels = std::max(1u, get32(b, 40));
    const uint32_t scheme = get32(b, 44);
    t = GpuTexture{};
    for (const auto& v : kVk)
        if (format == v.unorm || (v.srgb && format == v.srgb)) {
            t.format = block_format_info(v.block);
            t.srgb = format == v.srgb;
        }
    if (!t.format) {
        error = "VkFormat " + std::to_string(format) + " is not one matforge reads (BC1, BC3, BC4, BC5, BC7, ASTC LDR)";
        return false;
    }
    if (depth != 0 || layers != 0 || faces != 1 || width == 0 || height == 0 || width > 65536 || height > 65536 ||
        levels > 17 || (scheme != kSchemeNone && scheme != kSchemeZstd)) {
        error =
            "KTX2 is not a single 2D texture matforge reads (depth, layers, faces, size, levels or supercompression)";
        return false;
    }
    if (b.size() < 80 + size_t{levels} * 24) {
        error = "KTX2 truncated in its level index";
        return false;
    }
    int w = static_cast<int>(width), h = static_cast<int>(height);
    for (uint32_t i = 0; i < levels; ++i) {
        const uint64_t at = get64(b, 80 + 24 * size_t{i}), length = get64(b, 80 + 24 * size_t{i} + 8);
        const uint64_t raw = get64(b, 80 + 24 * size_t{i} + 16);
        const size_t need = level_bytes(*t.format, w, h);
        if (at > b.size() || length > b.size() - at || raw != need) {
            error = "KTX2 level " + std::to_string(i) + " lies outside the file or has the wrong size";
            return false;
        }
        Level l{w, h, {}};
        const auto* p = b.data() + at;
        if (scheme == kSchemeZstd) {
            l.data.resize(need);
            const size_t n = ZSTD_decompress(l.data.data(), need, p, length);
            if (ZSTD_isError(n) || n != need) {
                error = "KTX2 level " + std::to_string(i) + ": zstd data does not inflate to " + std::to_string(need) +
                        " bytes";
                return false;
            }
        } else {
            l.data.assign(p, p + length);
        }
        t.levels.push_back(std::move(l));
        w = std::max(1, w / 2), h = std::max(1, h / 2);
    }
    // Straight alpha present: a BC3 texture (opaque BC1 carries none; a BC7 block says for itself).
    t.alpha = t.format->name == "bc3";
    return true;
}

}  // namespace mf::texture
