#include "preset/texture_fields.hpp"

#include <algorithm>
#include <array>
#include <optional>

#include "base/error.hpp"
#include "core/json.hpp"
#include "preset/engine_slots.hpp"

namespace mf {
namespace {

// Block sizes and bytes from the formats' definitions (DXGI BC1-BC5: 4x4 texels in 8 or 16
// bytes; ASTC: 128 bits per block of any listed footprint). ASTC has no DXGI format DirectX
// loads, so it is KTX2-only.
constexpr std::array kFormats{
    BlockFormatInfo{"bc1", 4, 4, 8, 3, true, true, false},
    BlockFormatInfo{"bc3", 4, 4, 16, 4, true, true, false},
    BlockFormatInfo{"bc4", 4, 4, 8, 1, false, true, false},
    BlockFormatInfo{"bc5", 4, 4, 16, 2, false, true, false},
    BlockFormatInfo{"bc7", 4, 4, 16, 4, true, true, false},
    BlockFormatInfo{"astc-4x4", 4, 4, 16, 4, true, false, false},
    BlockFormatInfo{"astc-5x5", 5, 5, 16, 4, true, false, false},
    BlockFormatInfo{"astc-6x6", 6, 6, 16, 4, true, false, false},
    BlockFormatInfo{"astc-8x8", 8, 8, 16, 4, true, false, false},
    BlockFormatInfo{"astc-hdr-4x4", 4, 4, 16, 4, false, false, true},
    BlockFormatInfo{"astc-hdr-6x6", 6, 6, 16, 4, false, false, true},
};

std::optional<bool> bool_field(const nlohmann::json& j, const char* key, bool def) {
    if (!j.contains(key)) return def;
    if (!j.at(key).is_boolean()) return std::nullopt;
    return j.at(key).get<bool>();
}

// Field `key` of `j`, when present, as a word of E into `out` (left as it is when absent);
// false + `error` naming the field.
template <class E>
bool word_field(const nlohmann::json& j, const char* key, E& out, const std::string& where, std::string& error) {
    if (!j.contains(key)) return true;
    const auto& v = j.at(key);
    const auto e = v.is_string() ? from_word<E>(v.get<std::string>()) : std::nullopt;
    if (!e) return fail(error, where + key + " must be " + word_list<E>());
    out = *e;
    return true;
}

// "RGB albedo", "R roughness, G metalness": what an output writes, for messages.
std::string layout(const OutputSpec& o, int channels) {
    std::string s;
    int n = 0;
    for (const auto& c : o.channels) {
        if (n >= channels) break;
        n += c.key == "RGB" ? 3 : 1;
        std::string what = c.kind == ChannelSpec::Kind::role         ? std::string(role_name(c.role))
                           : c.kind == ChannelSpec::Kind::smoothness ? "smoothness"
                           : c.kind == ChannelSpec::Kind::constant   ? "a constant"
                                                                     : "unused";
        s += (s.empty() ? "" : ", ") + c.key + " " + what;
    }
    return s;
}

// The channel counts an output can be written with: with and without a dropped last channel.
std::vector<int> written_counts(const OutputSpec& o) {
    const int n = o.channel_count();
    if (!o.channels.empty() && o.channels.back().optional) return {n - 1, n};
    return {n};
}

bool check_block_format(const Preset& p, const OutputSpec& o, const std::string& where, std::string& error) {
    for (const BlockFormatInfo* f : {o.block_format, o.block_format_alpha}) {
        if (!f) continue;
        const std::string field = where + (f == o.block_format ? "block_format" : "block_format_alpha");
        const std::string name(f->name);
        if (p.format == FileFormat::dds && !f->in_dds)
            return fail(error, field + ": " + name +
                                   " has no DXGI format; DDS carries bc1, bc3, bc4, bc5 and bc7 (ASTC goes in ktx2)");
        if (f->hdr && o.bit_depth == 8)
            return fail(error,
                        field + ": " + name + " encodes float (HDR) samples; this output is 8-bit (bit_depth 8)");
        if (f->hdr)
            return fail(error,
                        field + ": " + name + ": ASTC HDR outputs are not supported (8-bit LDR block formats only)");
        if (o.bit_depth != 8)
            return fail(error, field + ": block formats store 8-bit samples; bit_depth must be 8, not " +
                                   std::to_string(o.bit_depth));
        if (o.srgb && !f->has_srgb)
            return fail(
                error, field + ": " + name +
                           " has no sRGB variant; use it for linear data (color_space linear) or pick bc1, bc3 or bc7");
    }
    for (int n : written_counts(o)) {
        const BlockFormatInfo* f = block_format_for(o, n);
        const std::string field = where + (f == o.block_format ? "block_format" : "block_format_alpha");
        const std::string name(f->name);
        // BC5 stores a normal's X and Y; the engine rebuilds Z (the only 3-channel output it takes).
        const bool xy_normal = f->name == "bc5" && n == 3 && is_rgb_normal(o);
        const bool fits = xy_normal ||
                          (n <= f->channels && (f->name != "bc4" || n == 1) && (f->name != "bc5" || n == 2));
        if (!fits)
            return fail(error,
                        field + ": " + name + " stores " + std::to_string(f->channels) + " channel" +
                            (f->channels == 1 ? "" : "s") + "; this output writes " + std::to_string(n) + " (" +
                            layout(o, n) + ")" +
                            (n == 4 && !o.block_format_alpha ? ": set block_format_alpha (bc3 or bc7) for it" : ""));
    }
    if (o.block_format_alpha && written_counts(o).back() != 4)
        return fail(error, where + "block_format_alpha: this output never writes 4 channels");
    return true;
}

}  // namespace

bool is_rgb_normal(const OutputSpec& o) {
    return !o.channels.empty() && o.channels[0].key == "RGB" && o.channels[0].kind == ChannelSpec::Kind::role &&
           o.channels[0].role == Role::normal;
}

const BlockFormatInfo* block_format_info(std::string_view name) {
    for (const auto& f : kFormats)
        if (f.name == name) return &f;
    return nullptr;
}

std::string block_format_names() {
    std::string s;
    for (const auto& f : kFormats) s += (s.empty() ? "" : ", ") + std::string(f.name);
    return s;
}

const BlockFormatInfo* block_format_for(const OutputSpec& o, int written_channels) {
    return written_channels == 4 && o.block_format_alpha ? o.block_format_alpha : o.block_format;
}

bool parse_texture_fields(const nlohmann::json& j, Preset& p, std::string& error) {
    const bool container = is_block_container(p.format);
    const auto mips = bool_field(j, "mips", false);
    // Specular anti-aliasing is on wherever there are mips (issue 48: glTF-Transform's, three.js's
    // and Bevy's users ask for it because their engines no longer do it at run time); it acts on
    // outputs with roughness, in sets with a normal map (encode_output).
    const auto toksvig = mips ? bool_field(j, "toksvig", *mips) : std::nullopt;
    if (!mips || !toksvig) return fail(error, "mips and toksvig must be true or false");
    p.mips = *mips;
    p.toksvig = *toksvig;
    const std::string format(word(p.format));
    if (p.mips && !container) return fail(error, "mips: needs format dds or ktx2 (" + format + " holds one level)");
    if (p.toksvig && !p.mips) return fail(error, "toksvig: adjusts the roughness of mip levels; set mips true");
    if (!word_field(j, "mip_filter", p.mip_filter, "", error) || !word_field(j, "effort", p.effort, "", error) ||
        !word_field(j, "supercompression", p.supercompression, "", error))
        return false;
    if (p.supercompression == Supercompression::zstd && p.format != FileFormat::ktx2)
        return fail(error, "supercompression: zstd is a KTX2 scheme; this preset writes " + format);
    if (j.contains("zstd_level")) {
        const auto level = json_int(j.at("zstd_level"), 1, 22);
        if (!level) return fail(error, "zstd_level must be an integer within 1..22");
        p.zstd_level = *level;
    }
    if (j.contains("alpha_cutoff")) {
        const auto cut = json_float(j.at("alpha_cutoff"), 0.0, 1.0);
        if (!cut || *cut <= 0.f || *cut >= 1.f)
            return fail(error, "alpha_cutoff must be a number between 0 and 1 (exclusive)");
        p.alpha_cutoff = *cut;
    }
    if (!word_field(j, "material_file", p.material_file, "", error)) return false;
    if (p.format == FileFormat::dds && !j.contains("constant_size"))
        p.constant_size = 4;  // the smallest BC texture D3D11 creates
    if (container && p.constant_size % 4 != 0 && p.format == FileFormat::dds)
        return fail(error, "constant_size: Direct3D 11 creates BC textures whose top level is a multiple of 4; use 4");

    const nlohmann::json& outs = j.at("outputs");
    for (size_t i = 0; i < p.outputs.size() && i < outs.size(); ++i) {
        OutputSpec& o = p.outputs[i];
        const nlohmann::json& oj = outs[i];
        const std::string where = "outputs[" + std::to_string(i) + "] ('" + o.suffix + "'): ";
        for (const char* key : {"block_format", "block_format_alpha"}) {
            if (!oj.contains(key)) continue;
            const auto& v = oj.at(key);
            const BlockFormatInfo* f = v.is_string() ? block_format_info(v.get<std::string>()) : nullptr;
            if (!f)
                return fail(error, where + key + ": unknown block format " +
                                       (v.is_string() ? "'" + v.get<std::string>() + "'" : v.dump()) + " (" +
                                       block_format_names() + ")");
            (std::string_view(key) == "block_format" ? o.block_format : o.block_format_alpha) = f;
        }
        Effort effort{};
        if (oj.contains("effort")) {
            if (!word_field(oj, "effort", effort, where, error)) return false;
            o.effort = effort;
        }
        for (const char* key : {"min_psnr_db", "max_mean_angle_deg"}) {
            if (!oj.contains(key)) continue;
            const bool psnr = std::string_view(key) == "min_psnr_db";
            const auto v = json_float(oj.at(key), 0.0, psnr ? 100.0 : 90.0);
            if (!v)
                return fail(error,
                            where + key +
                                (psnr ? " must be a number of dB within 0..100" : " must be degrees within 0..90"));
            (psnr ? o.min_psnr_db : o.max_mean_angle_deg) = *v;
            if (!container)
                return fail(error, where + key + ": error bounds apply to block-compressed outputs (dds, ktx2)");
        }
        if (!container) {
            if (o.block_format || o.block_format_alpha)
                return fail(error,
                            where + "block_format: needs format dds or ktx2 (this preset writes " + format + ")");
            continue;
        }
        if (!o.block_format)
            return fail(error,
                        where + "block_format: required with format " + format + " (" + block_format_names() + ")");
        if (!check_block_format(p, o, where, error)) return false;
    }
    const EngineMaterial* e = engine_material(p.material_file);
    return !e || check_engine_layout(p, *e, error);
}

}  // namespace mf
