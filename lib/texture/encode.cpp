// An output of a block-container preset: pack, mip chain, encode, decode back, measure, contain.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "base/parallel.hpp"
#include "core/text.hpp"
#include "findings/catalog.hpp"
#include "texture/texture.hpp"

namespace mf::texture {
namespace {

double round3(double v) { return std::round(v * 1000.0) / 1000.0; }

// Channel index (in file order) of the first channel holding `role` (smoothness counts as
// roughness), -1 when none; `smoothness` tells which.
int channel_of(const std::vector<ChannelSpec>& written, Role role, bool* smoothness = nullptr) {
    int at = 0;
    for (const auto& c : written) {
        if ((c.kind == ChannelSpec::Kind::role || c.kind == ChannelSpec::Kind::smoothness) && c.role == role) {
            if (smoothness) *smoothness = c.kind == ChannelSpec::Kind::smoothness;
            return at;
        }
        at += c.key == "RGB" ? 3 : 1;
    }
    return -1;
}

// The preset's output holding the normal map (RGB normal), nullptr when none.
const OutputSpec* normal_output(const Preset& preset) {
    for (const OutputSpec& o : preset.outputs)
        if (is_rgb_normal(o)) return &o;
    return nullptr;
}

Image8 quantized(const Image& img) {
    Image8 out(img.width, img.height, img.channels);
    for (size_t i = 0; i < img.pixels.size(); ++i) out.pixels[i] = quantize8(img.pixels[i]);
    return out;
}

Image channel_floats(const Image8& img, int channel) {
    Image out(img.width, img.height, 1);
    const auto c = static_cast<size_t>(img.channels);
    for (size_t p = 0; p < out.pixels.size(); ++p)
        out.pixels[p] = static_cast<float>(img.pixels[p * c + static_cast<size_t>(channel)]) / 255.f;
    return out;
}

// A cut-out's alpha test must keep level 0's coverage as the GPU decodes a level, not only as
// make_mips stores it: a block codec moves alpha near the cutoff, most where a block spans much of
// a small level (ASTC 6x6 kept 0.035 of Net004A's 16x16 level against 0.223 at level 0), and at the
// smallest levels coverage scaling leaves most alphas within a code or two of the cutoff (Net004A's
// 16x16 level: 22 % at 128, the rest at 127; BC7 moved it to 0.14). Where the decoded coverage strays
// more than half a point from `target`, the level's alpha is encoded again, pushed away from the
// cutoff by kStretch (each texel stays on its side of the test, so what the test keeps is what
// make_mips stored, and the codec's small errors no longer cross it), then, if still off, scaled
// as make_mips scales (bisection, with the encoder in the loop), and the closest is kept: `level`,
// `blocks` and `decoded` become that one's.
bool keep_decoded_coverage(Image8& level, int alpha_at, float cutoff, double target, const CodecOptions& codec,
                           std::vector<uint8_t>& blocks, Image8& decoded, std::string& error) {
    constexpr double kTolerance = 0.005;
    constexpr int kStretch = 8;
    double best_error = std::abs(alpha_coverage(decoded, alpha_at, cutoff) - target);
    if (best_error <= kTolerance) return true;
    const Image8 stored = level;
    const auto c = static_cast<size_t>(stored.channels), a = static_cast<size_t>(alpha_at);
    const int kept = std::clamp(first_kept_code(cutoff), 1, 255);
    Image8 trial;
    std::vector<uint8_t> trial_blocks;
    Image8 trial_decoded;
    // Scale 1 first (the stretch alone), then the bisection.
    float lo = 0.25f, hi = 4.f, scale = 1.f;
    for (int step = 0; step < 13 && best_error > kTolerance; ++step, scale = std::sqrt(lo * hi)) {
        trial = stored;
        for (size_t p = a; p < trial.pixels.size(); p += c) {
            const int v = quantize8(static_cast<float>(stored.pixels[p]) / 255.f * scale);
            trial.pixels[p] = static_cast<uint8_t>(v >= kept ? std::min(255, kept + (v - kept + 1) * kStretch - 1)
                                                             : std::max(0, kept - (kept - v) * kStretch));
        }
        if (!encode_level(trial, codec, trial_blocks, error) ||
            !decode_level(trial_blocks, trial.width, trial.height, codec, trial_decoded, error))
            return false;
        const double got = alpha_coverage(trial_decoded, alpha_at, cutoff);
        if (step > 0) (got < target ? lo : hi) = scale;
        if (std::abs(got - target) < best_error) {
            best_error = std::abs(got - target);
            level = trial;
            blocks = trial_blocks;
            decoded = trial_decoded;
        }
    }
    return true;
}

}  // namespace

double psnr(const Image8& ref, const Image8& decoded, int channels) {
    const auto rc = static_cast<size_t>(ref.channels), dc = static_cast<size_t>(decoded.channels);
    const size_t n = static_cast<size_t>(ref.width) * static_cast<size_t>(ref.height);
    double sum = 0.0;
    for (size_t p = 0; p < n; ++p)
        for (size_t k = 0; k < static_cast<size_t>(channels); ++k) {
            const double d = static_cast<double>(ref.pixels[p * rc + k]) -
                             static_cast<double>(decoded.pixels[p * dc + k]);
            sum += d * d;
        }
    const double mse = sum / static_cast<double>(std::max<size_t>(1, n * static_cast<size_t>(channels)));
    if (mse <= 0.0) return 100.0;
    return std::min(100.0, 10.0 * std::log10(255.0 * 255.0 / mse));
}

AngleError normal_angle_error(const Image8& ref, const Image8& decoded, bool xy_only) {
    const auto rc = static_cast<size_t>(ref.channels), dc = static_cast<size_t>(decoded.channels);
    const size_t n = static_cast<size_t>(ref.width) * static_cast<size_t>(ref.height);
    AngleError e;
    double sum = 0.0;
    auto unit = [](double& x, double& y, double& z) {
        const double len = std::sqrt(x * x + y * y + z * z);
        if (len > 1e-12) x /= len, y /= len, z /= len;
        else x = 0, y = 0, z = 1;
    };
    for (size_t p = 0; p < n; ++p) {
        const uint8_t* r = &ref.pixels[p * rc];
        const uint8_t* d = &decoded.pixels[p * dc];
        double ax = r[0] / 127.5 - 1.0, ay = r[1] / 127.5 - 1.0, az = r[2] / 127.5 - 1.0;
        double bx = d[0] / 127.5 - 1.0, by = d[1] / 127.5 - 1.0;
        double bz = xy_only ? z_from_xy(bx, by) : d[2] / 127.5 - 1.0;
        unit(ax, ay, az);
        unit(bx, by, bz);
        const double deg = std::acos(std::clamp(ax * bx + ay * by + az * bz, -1.0, 1.0)) * 180.0 / std::numbers::pi;
        sum += deg;
        e.max_deg = std::max(e.max_deg, deg);
    }
    e.mean_deg = n ? sum / static_cast<double>(n) : 0.0;
    return e;
}

bool encode_output(const OutputSpec& o, const Planes& planes, Size size, const EncodeContext& ctx, EncodedOutput& out,
                   std::string& error) {
    const Preset& preset = *ctx.preset;
    const std::vector<ChannelSpec> written = effective_channels(o, planes);
    int n = 0;
    for (const auto& c : written) n += c.key == "RGB" ? 3 : 1;
    const BlockFormatInfo* f = block_format_for(o, n);
    if (!f) {
        error = "output '" + o.suffix + "': no block format (the preset writes " + std::string(word(preset.format)) +
                ")";
        return false;
    }
    // Level 0: the codes a PNG of this output would hold.
    std::optional<Image8> packed8 = pack_output8(o, planes, preset, size, *ctx.color);
    Image8 level0 = packed8 ? std::move(*packed8) : quantized(pack_output(o, planes, preset, size, *ctx.color));
    packed8.reset();

    const int opacity_at = channel_of(written, Role::opacity);
    const AlphaUse alpha = opacity_at >= 0 ? classify_opacity(channel_floats(level0, opacity_at)) : AlphaUse::opaque;
    const bool cutout = alpha == AlphaUse::cutout;
    const std::vector<ChannelKind> kinds = channel_kinds(written, o.srgb, cutout);
    const bool normal = std::find(kinds.begin(), kinds.end(), ChannelKind::normal) != kinds.end();

    // Before any filtering or block fit, the colour of the texels never shown (under a cut-out's
    // alpha test, or alpha 0 in a blend) is the nearest shown colour, not what the source left
    // there (black, mostly): no dark fringe in any mip or block (dilate_under_alpha).
    if (preset.mips && alpha != AlphaUse::opaque) {
        const auto shown_from = static_cast<uint8_t>(cutout ? std::clamp(first_kept_code(preset.alpha_cutoff), 1, 255)
                                                            : 1);
        out.dilated_texels = static_cast<int64_t>(dilate_under_alpha(level0, kinds, opacity_at, shown_from));
    }

    // Direct3D 11 creates a BC texture only when its top level is a multiple of 4 wide and high.
    if (preset.format == FileFormat::dds && (level0.width % 4 || level0.height % 4)) {
        const int w4 = (level0.width + 3) / 4 * 4, h4 = (level0.height + 3) / 4 * 4;
        out.findings.push_back(finding(code::resized, "", "",
                                       "output '" + o.suffix + "': " + std::to_string(level0.width) + "x" +
                                           std::to_string(level0.height) + " resampled to " + std::to_string(w4) + "x" +
                                           std::to_string(h4) + " (Direct3D 11 BC textures are multiples of 4)",
                                       {{"from", {level0.width, level0.height}}, {"to", {w4, h4}}}));
        level0 = resize(level0, kinds, w4, h4);
    }

    std::vector<Image8> chain;
    if (preset.mips) {
        MipOptions mo;
        mo.filter = preset.mip_filter;
        mo.alpha_cutoff = preset.alpha_cutoff;
        Image normals;
        const OutputSpec* normal_map = preset.toksvig ? normal_output(preset) : nullptr;
        if (normal_map && planes.count(Role::normal)) {
            mo.roughness_channel = channel_of(written, Role::roughness, &mo.smoothness);
            if (mo.roughness_channel >= 0) {
                // The spread of the normals the engine samples: the normal map's 8-bit codes as its
                // own output's level 0 holds them, at this output's size.
                std::optional<Image8> codes = pack_output8(*normal_map, planes, preset, size, *ctx.color);
                Image8 n8 = codes ? std::move(*codes)
                                  : quantized(pack_output(*normal_map, planes, preset, size, *ctx.color));
                if (n8.width != level0.width || n8.height != level0.height)
                    n8 = resize(n8, std::vector<ChannelKind>(3, ChannelKind::normal), level0.width, level0.height);
                normals = normals_from_codes(n8);
                mo.normals = &normals;
            }
        }
        chain = make_mips(level0, kinds, mo);
    } else {
        chain.push_back(std::move(level0));
    }

    CodecOptions codec;
    codec.format = f;
    codec.srgb = o.srgb && f->has_srgb;
    codec.effort = o.effort.value_or(preset.effort);
    codec.normal_xy = normal && f->name == "bc5";
    codec.mask = !o.srgb && !normal && n > 1;
    // A cut-out's alpha is measured by what its test keeps (`coverage`), which keep_decoded_coverage
    // may buy with a rescaled alpha: its PSNR is the colour's.
    const int compared = cutout ? std::min({n, f->channels, opacity_at}) : std::min(n, f->channels);

    GpuTexture tex;
    tex.format = f;
    tex.srgb = codec.srgb;
    tex.alpha = n == 4 && f->channels == 4;
    tex.levels.resize(chain.size());
    out.levels.assign(chain.size(), {});
    std::vector<std::string> errors(chain.size());
    // Levels on `jobs` threads, largest first (level 0 is three quarters of the work).
    const double coverage0 = cutout ? alpha_coverage(chain[0], opacity_at, preset.alpha_cutoff) : 0.0;
    parallel_for(chain.size(), ctx.jobs, [&](size_t i) {
        Image8& level = chain[i];
        Level& l = tex.levels[i];
        l.width = level.width;
        l.height = level.height;
        Image8 decoded;
        if (!encode_level(level, codec, l.data, errors[i]) ||
            !decode_level(l.data, level.width, level.height, codec, decoded, errors[i]))
            return;
        if (cutout && i > 0 &&
            !keep_decoded_coverage(level, opacity_at, preset.alpha_cutoff, coverage0, codec, l.data, decoded,
                                   errors[i]))
            return;
        manifest::LevelError& e = out.levels[i];
        e.width = level.width;
        e.height = level.height;
        if (normal) {
            const AngleError a = normal_angle_error(level, decoded, codec.normal_xy);
            e.mean_angle_deg = round3(a.mean_deg);
            e.max_angle_deg = round3(a.max_deg);
        } else {
            e.psnr_db = round3(psnr(level, decoded, compared));
        }
        // What the alpha test keeps of the level as the GPU decodes it (RGBA codes).
        if (cutout) e.coverage = std::round(alpha_coverage(decoded, opacity_at, preset.alpha_cutoff) * 1e4) / 1e4;
    });
    for (const auto& e : errors)
        if (!e.empty()) {
            error = e;
            return false;
        }

    // The bound is level 0's, the level of the set's authored detail: one finding per output.
    // Each level below is recorded but not held to it: a 4x4 block of level n spans 4 * 2^n
    // texels of level 0, so on real maps its spread (and the error of any 8-value BC4/BC5 fit
    // of it) grows down the chain. On the samples an exhaustive, MSE-optimal BC4 fit of each
    // block still misses the shipped bounds there (Crystal_003's normal map 2.07 degrees at
    // level 3 and 2.95 at level 5 against 2; Metal_Damaged_001's metalness 33.9 dB at level 6
    // against 35), where level 0 meets them with 2x margin; a box filter instead of Kaiser
    // changes that by under 0.2 degrees. An encoder that is wrong is wrong at level 0.
    for (size_t i = 0; i < std::min<size_t>(1, out.levels.size()); ++i) {
        const auto& e = out.levels[i];
        const bool psnr_low = e.psnr_db && o.min_psnr_db && *e.psnr_db < *o.min_psnr_db;
        const bool angle_high = e.mean_angle_deg && o.max_mean_angle_deg && *e.mean_angle_deg > *o.max_mean_angle_deg;
        if (!psnr_low && !angle_high) continue;
        Figures figures = {{"block_format", std::string(f->name)},
                           {"level", static_cast<std::int64_t>(i)},
                           {"width", e.width},
                           {"height", e.height}};
        std::string what;
        if (psnr_low) {
            figures["psnr_db"] = *e.psnr_db;
            figures["min_psnr_db"] = *o.min_psnr_db;
            what = "PSNR " + fixed(*e.psnr_db, 2) + " dB is below the preset's " + fixed(*o.min_psnr_db, 1) + " dB";
        } else {
            figures["mean_angle_deg"] = *e.mean_angle_deg;
            figures["max_mean_angle_deg"] = *o.max_mean_angle_deg;
            what = "mean angular error " + fixed(*e.mean_angle_deg, 2) + " degrees is above the preset's " +
                   fixed(*o.max_mean_angle_deg, 1);
        }
        const std::string role = written.empty() || written[0].kind != ChannelSpec::Kind::role
                                     ? ""
                                     : std::string(role_name(written[0].role));
        out.findings.push_back(finding(code::encoding_error_exceeded, role, "",
                                       "output '" + o.suffix + "' level " + std::to_string(i) + " (" +
                                           std::to_string(e.width) + "x" + std::to_string(e.height) + ", " +
                                           std::string(f->name) + "): " + what,
                                       figures));
        break;
    }

    out.width = tex.levels[0].width;
    out.height = tex.levels[0].height;
    out.block_format = std::string(f->name);
    out.normal_xy = codec.normal_xy;
    if (preset.format == FileFormat::dds) {
        out.gpu_format = dxgi_format_name(tex);
        out.bytes = write_dds(tex);
    } else {
        out.gpu_format = vk_format_name(tex);
        Ktx2Options ko;
        ko.zstd = preset.supercompression == Supercompression::zstd;
        ko.zstd_level = preset.zstd_level;
        ko.writer = ctx.writer;
        if (ko.zstd) out.supercompression = std::string(word(Supercompression::zstd));
        if (!write_ktx2(tex, ko, out.bytes, error)) return false;
    }
    return true;
}

}  // namespace mf::texture
