#include "preset/texture_fields.hpp"

#include <algorithm>
#include <array>
#include <optional>

#include "core/error.hpp"
#include "core/json.hpp"

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

bool one_of(const std::string& v, std::initializer_list<const char*> allowed) {
    return std::any_of(allowed.begin(), allowed.end(), [&](const char* a) { return v == a; });
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

bool is_rgb_normal(const OutputSpec& o) {
    return !o.channels.empty() && o.channels[0].key == "RGB" && o.channels[0].kind == ChannelSpec::Kind::role &&
           o.channels[0].role == Role::normal;
}

// The channel counts an output can be written with: with and without a dropped last channel.
std::vector<int> written_counts(const OutputSpec& o) {
    const int n = o.channel_count();
    if (!o.channels.empty() && o.channels.back().optional) return {n - 1, n};
    return {n};
}

bool check_block_format(const Preset& p, const OutputSpec& o, const std::string& where, std::string& error) {
    for (const std::string* name : {&o.block_format, &o.block_format_alpha}) {
        if (name->empty()) continue;
        const std::string field = where + (name == &o.block_format ? "block_format" : "block_format_alpha");
        const BlockFormatInfo* f = block_format_info(*name);
        if (!f) return fail(error, field + ": unknown block format '" + *name + "' (" + block_format_names() + ")");
        if (p.format == "dds" && !f->in_dds)
            return fail(error, field + ": " + *name +
                                   " has no DXGI format; DDS carries bc1, bc3, bc4 and bc5 (ASTC goes in ktx2)");
        if (f->hdr && o.bit_depth == 8)
            return fail(error,
                        field + ": " + *name + " encodes float (HDR) samples; this output is 8-bit (bit_depth 8)");
        if (f->hdr)
            return fail(error,
                        field + ": " + *name + ": ASTC HDR outputs are not supported (8-bit LDR block formats only)");
        if (o.bit_depth != 8)
            return fail(error, field + ": block formats store 8-bit samples; bit_depth must be 8, not " +
                                   std::to_string(o.bit_depth));
        if (o.srgb && !f->has_srgb)
            return fail(error, field + ": " + *name +
                                   " has no sRGB variant; use it for linear data (color_space linear) or pick bc1/bc3");
    }
    for (int n : written_counts(o)) {
        const std::string& name = block_format_for(o, n);
        const std::string field = where + (&name == &o.block_format ? "block_format" : "block_format_alpha");
        const BlockFormatInfo* f = block_format_info(name);
        // BC5 stores a normal's X and Y; the engine rebuilds Z (the only 3-channel output it takes).
        const bool xy_normal = f->name == "bc5" && n == 3 && is_rgb_normal(o);
        const bool fits = xy_normal ||
                          (n <= f->channels && (f->name != "bc4" || n == 1) && (f->name != "bc5" || n == 2));
        if (!fits)
            return fail(error,
                        field + ": " + name + " stores " + std::to_string(f->channels) + " channel" +
                            (f->channels == 1 ? "" : "s") + "; this output writes " + std::to_string(n) + " (" +
                            layout(o, n) + ")" +
                            (n == 4 && o.block_format_alpha.empty() ? ": set block_format_alpha (bc3) for it" : ""));
    }
    if (!o.block_format_alpha.empty() && written_counts(o).back() != 4)
        return fail(error, where + "block_format_alpha: this output never writes 4 channels");
    return true;
}

// The glTF material model (glTF 2.0 section 3.9): baseColorTexture (sRGB RGB, A = alpha),
// normalTexture (linear RGB, +Y), metallicRoughnessTexture (G roughness, B metalness, linear),
// occlusionTexture (R, linear), emissiveTexture (sRGB RGB). A preset whose layout the
// material's slots cannot reference cannot get a .gltf.
bool check_gltf_layout(const Preset& p, std::string& error) {
    const std::string where = "material_file gltf: ";
    if (p.format != "png")
        return fail(error, where + "glTF 2.0 textures are PNG or JPEG (core); this preset writes " + p.format);
    auto find = [&](Role r) -> std::pair<const OutputSpec*, const ChannelSpec*> {
        for (const auto& o : p.outputs)
            for (const auto& c : o.channels)
                if ((c.kind == ChannelSpec::Kind::role || c.kind == ChannelSpec::Kind::smoothness) && c.role == r)
                    return {&o, &c};
        return {nullptr, nullptr};
    };
    const auto [albedo_o, albedo_c] = find(Role::albedo);
    if (!albedo_o || albedo_c->key != "RGB" || !albedo_o->srgb)
        return fail(error, where + "baseColorTexture needs an sRGB output with albedo in RGB");
    if (const auto [o, c] = find(Role::opacity); o && (o != albedo_o || c->key != "A"))
        return fail(error, where + "glTF reads opacity from the base color's alpha; this preset writes it elsewhere");
    if (const auto [o, c] = find(Role::normal); o && (o->srgb || c->key != "RGB"))
        return fail(error, where + "normalTexture needs a linear output with the normal in RGB");
    const auto [rough_o, rough_c] = find(Role::roughness);
    const auto [metal_o, metal_c] = find(Role::metalness);
    if (!rough_o || !metal_o || rough_o != metal_o || rough_c->key != "G" || metal_c->key != "B" ||
        rough_c->kind != ChannelSpec::Kind::role || rough_o->srgb)
        return fail(error, where + "metallicRoughnessTexture reads roughness from G and metalness from B of one linear "
                                   "output; no output of this preset has that layout");
    if (const auto [o, c] = find(Role::occlusion); o && (o->srgb || c->key != "R"))
        return fail(error, where + "occlusionTexture reads occlusion from R of a linear output");
    if (const auto [o, c] = find(Role::emissive); o && (!o->srgb || c->key != "RGB"))
        return fail(error, where + "emissiveTexture needs an sRGB output with emissive in RGB");
    if (p.normal_convention != NormalConvention::gl)
        return fail(error, where + "glTF normal textures are +Y (normal_convention gl)");
    return true;
}

}  // namespace

bool is_block_container(const std::string& format) { return format == "dds" || format == "ktx2"; }

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

const std::string& block_format_for(const OutputSpec& o, int written_channels) {
    return written_channels == 4 && !o.block_format_alpha.empty() ? o.block_format_alpha : o.block_format;
}

bool parse_texture_fields(const nlohmann::json& j, Preset& p, std::string& error) {
    const bool container = is_block_container(p.format);
    const auto mips = bool_field(j, "mips", false);
    const auto toksvig = bool_field(j, "toksvig", false);
    if (!mips || !toksvig) return fail(error, "mips and toksvig must be true or false");
    p.mips = *mips;
    p.toksvig = *toksvig;
    if (p.mips && !container) return fail(error, "mips: needs format dds or ktx2 (" + p.format + " holds one level)");
    if (p.toksvig && !p.mips) return fail(error, "toksvig: adjusts the roughness of mip levels; set mips true");
    p.mip_filter = j.value("mip_filter", p.mip_filter);
    if (!one_of(p.mip_filter, {"box", "kaiser"})) return fail(error, "mip_filter must be box or kaiser");
    p.effort = j.value("effort", p.effort);
    if (!one_of(p.effort, {"fast", "normal", "thorough"}))
        return fail(error, "effort must be fast, normal or thorough");
    p.supercompression = j.value("supercompression", p.supercompression);
    if (!one_of(p.supercompression, {"none", "zstd"})) return fail(error, "supercompression must be none or zstd");
    if (p.supercompression == "zstd" && p.format != "ktx2")
        return fail(error, "supercompression: zstd is a KTX2 scheme; this preset writes " + p.format);
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
    p.material_file = j.value("material_file", std::string());
    if (p.material_file == "none") p.material_file.clear();
    if (!p.material_file.empty() && p.material_file != "gltf") return fail(error, "material_file must be gltf or none");
    if (p.format == "dds" && !j.contains("constant_size"))
        p.constant_size = 4;  // the smallest BC texture D3D11 creates
    if (container && p.constant_size % 4 != 0 && p.format == "dds")
        return fail(error, "constant_size: Direct3D 11 creates BC textures whose top level is a multiple of 4; use 4");

    const nlohmann::json& outs = j.at("outputs");
    for (size_t i = 0; i < p.outputs.size() && i < outs.size(); ++i) {
        OutputSpec& o = p.outputs[i];
        const nlohmann::json& oj = outs[i];
        const std::string where = "outputs[" + std::to_string(i) + "] ('" + o.suffix + "'): ";
        o.block_format = oj.value("block_format", std::string());
        o.block_format_alpha = oj.value("block_format_alpha", std::string());
        o.effort = oj.value("effort", std::string());
        if (!o.effort.empty() && !one_of(o.effort, {"fast", "normal", "thorough"}))
            return fail(error, where + "effort must be fast, normal or thorough");
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
            if (!o.block_format.empty() || !o.block_format_alpha.empty())
                return fail(error,
                            where + "block_format: needs format dds or ktx2 (this preset writes " + p.format + ")");
            continue;
        }
        if (o.block_format.empty())
            return fail(error,
                        where + "block_format: required with format " + p.format + " (" + block_format_names() + ")");
        if (!check_block_format(p, o, where, error)) return false;
    }
    return p.material_file != "gltf" || check_gltf_layout(p, error);
}

}  // namespace mf
