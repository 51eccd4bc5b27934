// Helpers of the tests that run matforge with the GPU-texture and glTF presets and read what it
// wrote with independent readers: OpenImageIO (DDS), ktx-parse and glTF-Validator (npm, run by
// node from the build tree; scripts/npm-checkers.sh installs them on first use).
#pragma once
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include <unistd.h>

#include "core/files.hpp"
#include "image/image.hpp"
#include "preset/texture_fields.hpp"
#include "run_binary.hpp"
#include "test_files.hpp"
#include "texture/texture.hpp"

namespace mtt {
namespace fs = std::filesystem;
using nlohmann::json;

inline fs::path samples() { return mf::testenv::source_dir() / "sample_materials"; }
inline fs::path corpus() { return mf::testenv::corpus_dir() / "real"; }

struct Run {
    int code = -1;
    std::string output;
};
inline Run matforge(const std::vector<std::string>& args) {
    std::vector<std::string> argv{mf::testenv::bin()};
    argv.insert(argv.end(), args.begin(), args.end());
    const auto p = mf::testbin::spawn(argv, 600);
    return {p.signal ? -1 : p.code, p.output};
}

// A fresh folder per test (the schema spool copies the manifests left in it).
inline fs::path temp_dir(const std::string& name) { return mf::testdirs::fresh_for_test("matforge-texture-", name); }

inline void write_text(const fs::path& p, const std::string& s) {
    fs::create_directories(p.parent_path());
    std::ofstream(p, std::ios::binary) << s;
}

inline std::vector<uint8_t> read_bytes(const fs::path& p) {
    std::vector<uint8_t> b;
    std::string err;
    EXPECT_TRUE(mf::read_file(p, b, err)) << err;
    return b;
}

// Whether scripts/SCRIPT has installed its checkers into `dir` (run once per process and script:
// npm-checkers.sh, py-checkers.sh).
inline bool checkers_installed(const std::string& script, const fs::path& dir) {
    static std::map<std::string, bool> done;  // a test program runs its tests on one thread
    if (const auto it = done.find(script); it != done.end()) return it->second;
    const auto p = mf::testbin::spawn({mf::testenv::source_dir().string() + "/scripts/" + script, dir.string()}, 600);
    EXPECT_EQ(p.code, 0) << "scripts/" << script << ": " << p.output;
    return done[script] = p.code == 0;
}
inline bool npm_checkers_installed() { return checkers_installed("npm-checkers.sh", mf::testenv::npm_dir()); }

// Runs a checker (argv) and parses its JSON lines, one per file it was given.
inline std::vector<json> json_lines(const std::vector<std::string>& argv) {
    const auto p = mf::testbin::spawn(argv, 300);
    EXPECT_EQ(p.code, 0) << p.output;
    std::vector<json> out;
    std::istringstream lines(p.output);
    for (std::string line; std::getline(lines, line);)
        if (!line.empty() && line[0] == '{') out.push_back(json::parse(line));
    return out;
}

// Runs `PY_DIR/bin/python SCRIPT ARGS...` (tests/texture/checkers, on the real implementations
// from PyPI: scripts/py-checkers.sh).
inline std::vector<json> py_checker(const std::string& script, const std::vector<std::string>& args) {
    if (!checkers_installed("py-checkers.sh", mf::testenv::py_dir())) return {};
    std::vector<std::string> argv{(mf::testenv::py_dir() / "bin" / "python").string(),
                                  mf::testenv::source_dir().string() + "/tests/texture/checkers/" + script};
    argv.insert(argv.end(), args.begin(), args.end());
    return json_lines(argv);
}

// Runs libktx's loader on `files` (tests/texture/checkers/ktx_open, built by
// scripts/ktx-checker.sh): one JSON line per file.
inline std::vector<json> ktx_checker(const std::vector<fs::path>& files) {
    if (!checkers_installed("ktx-checker.sh", mf::testenv::ktx_dir())) return {};
    std::vector<std::string> argv{(mf::testenv::ktx_dir() / "release" / "ktx_open").string()};
    for (const auto& f : files) argv.push_back(f.string());
    std::vector<json> out = json_lines(argv);
    EXPECT_EQ(out.size(), files.size());
    return out;
}

// Runs `node SCRIPT NPM_DIR ARGS...` (tests/texture/checkers).
inline std::vector<json> node_checker(const std::string& script, const std::vector<fs::path>& files) {
    if (!npm_checkers_installed()) return {};
    std::vector<std::string> argv{"node", mf::testenv::source_dir().string() + "/tests/texture/checkers/" + script,
                                  mf::testenv::npm_dir().string()};
    for (const auto& f : files) argv.push_back(f.string());
    std::vector<json> out = json_lines(argv);
    EXPECT_EQ(out.size(), files.size());
    return out;
}

// An ingest of `inputs` with `preset` into `out` (must succeed), and its manifest.
inline json ingest(const std::vector<fs::path>& inputs, const fs::path& out, const std::string& preset,
                   const std::vector<std::string>& extra = {}) {
    std::vector<std::string> args{"ingest"};
    for (const auto& i : inputs) args.push_back(i.string());
    args.insert(args.end(), {"-o", out.string(), "--preset", preset, "--quiet"});
    args.insert(args.end(), extra.begin(), extra.end());
    const auto r = matforge(args);
    EXPECT_EQ(r.code, 0) << r.output;
    return mf::testfiles::read_json(out / "manifest.json");
}

// The same outputs as a shipped GPU preset, as 8-bit PNGs without mips: what each texture's
// level 0 encodes (ingest makes level 0 from exactly these codes).
inline fs::path png_twin(const std::string& preset, const fs::path& dir) {
    const auto r = matforge({"presets", "show", preset});
    EXPECT_EQ(r.code, 0) << r.output;
    json p = json::parse(r.output.substr(r.output.find('{')));
    p["name"] = preset + "-png";
    p["format"] = "png";
    for (const char* k : {"mips", "mip_filter", "effort", "supercompression", "zstd_level", "toksvig", "material_file"})
        p.erase(k);
    for (auto& o : p["outputs"])
        for (const char* k : {"block_format", "block_format_alpha", "effort", "min_psnr_db", "max_mean_angle_deg"})
            o.erase(k);
    const fs::path file = dir / (preset + "-png.json");
    write_text(file, p.dump(2));
    return file;
}

inline mf::Image8 read_codes(const fs::path& png) {
    mf::Decoded d;
    mf::ImageInfo info;
    std::string err;
    mf::InputFile in;
    in.path = png;
    in.display = png.string();
    EXPECT_TRUE(mf::read_image(in, d, info, err)) << err;
    EXPECT_TRUE(d.is_codes()) << png;
    return d.codes;
}

// The mip chain a GPU output encodes, rebuilt from its PNG twin's level 0 and the manifest
// entry's channels (as ingest builds it: texture/mips); `normal_codes`: the set's normal map as
// its PNG twin holds it, whose spread widens a roughness channel's mips (the presets' default
// specular anti-aliasing; nullptr for a set without one).
inline std::vector<mf::Image8> reference_chain(const json& output, const mf::Image8& level0, const std::string& filter,
                                               const mf::Image8* normal_codes = nullptr) {
    std::vector<mf::ChannelSpec> written;
    for (const char* key : {"RGB", "R", "G", "B", "A"}) {
        if (!output["channels"].contains(key)) continue;
        mf::ChannelSpec c;
        c.key = key;
        const auto& v = output["channels"][key];
        if (v.is_number()) {
            c.kind = mf::ChannelSpec::Kind::constant;
        } else {
            c.kind = mf::ChannelSpec::Kind::role;
            c.role = *mf::role_from_name(v.get<std::string>());
        }
        written.push_back(c);
    }
    auto use = mf::texture::AlphaUse::opaque;
    if (output["channels"].contains("A") && output["channels"]["A"] == "opacity") {
        mf::Image a(level0.width, level0.height, 1);
        for (size_t p = 0; p < a.pixels.size(); ++p) a.pixels[p] = level0.pixels[p * 4 + 3] / 255.f;
        use = mf::texture::classify_opacity(a);
    }
    const bool cutout = use == mf::texture::AlphaUse::cutout;
    const auto kinds = mf::texture::channel_kinds(written, output["color_space"] == "sRGB", cutout);
    mf::texture::MipOptions o;
    o.filter = filter == "box" ? mf::MipFilter::box : mf::MipFilter::kaiser;
    mf::Image normals;
    int at = 0;
    for (const auto& c : written) {
        if (normal_codes && c.kind == mf::ChannelSpec::Kind::role && c.role == mf::Role::roughness) {
            normals = mf::texture::normals_from_codes(*normal_codes);
            o.normals = &normals;
            o.roughness_channel = at;
        }
        at += c.key == "RGB" ? 3 : 1;
    }
    // The colour under the alpha (a cut-out's test at the presets' 0.5: codes from 128; a blend's
    // 0) filled before the mips, as ingest does.
    mf::Image8 filled = level0;
    if (use != mf::texture::AlphaUse::opaque) mf::texture::dilate_under_alpha(filled, kinds, 3, cutout ? 128 : 1);
    return mf::texture::make_mips(filled, kinds, o);
}

// Every mip level of a DDS through OpenImageIO. OpenImageIO 2.4 reads the DX10 header for BC4
// to BC7 only; for BC1/BC3 it is handed the same blocks under the legacy FourCC header
// (DXT1/DXT5), which carries everything but the sRGB flag (checked on our header separately).
inline std::vector<mf::Image8> oiio_levels(const fs::path& dds, const fs::path& scratch) {
    std::vector<uint8_t> b = read_bytes(dds);
    fs::path path = dds;
    uint32_t dxgi = 0;
    std::memcpy(&dxgi, b.data() + 128, 4);
    if (dxgi == 71 || dxgi == 72 || dxgi == 77 || dxgi == 78) {
        const uint32_t fourcc = dxgi <= 72 ? 0x31545844u : 0x35545844u;  // "DXT1" / "DXT5"
        std::memcpy(b.data() + 84, &fourcc, 4);
        b.erase(b.begin() + 128, b.begin() + 148);
        path = scratch / (dds.stem().string() + ".legacy.dds");
        std::string err;
        EXPECT_TRUE(mf::write_file_atomic(path, b, err)) << err;
    }
    std::vector<mf::Image8> levels;
    auto in = OIIO::ImageInput::open(path.string());
    EXPECT_TRUE(in) << OIIO::geterror();
    if (!in) return levels;
    for (int m = 0; in->seek_subimage(0, m); ++m) {
        const OIIO::ImageSpec& s = in->spec();
        mf::Image8 img(s.width, s.height, s.nchannels);
        EXPECT_TRUE(in->read_image(0, m, 0, s.nchannels, OIIO::TypeDesc::UINT8, img.pixels.data())) << in->geterror();
        levels.push_back(std::move(img));
    }
    return levels;
}

// Every mip level of a DDS decoded by PyPI's texture2ddecoder (tests/texture/checkers/bc_decode.py,
// which parses the DDS itself): RGBA codes, largest first.
inline std::vector<mf::Image8> texture2d_levels(const fs::path& dds, const fs::path& scratch) {
    std::vector<mf::Image8> levels;
    if (!checkers_installed("py-checkers.sh", mf::testenv::py_dir())) return levels;
    const fs::path out = scratch / (dds.stem().string() + ".texture2d");
    const auto p = mf::testbin::spawn({(mf::testenv::py_dir() / "bin" / "python").string(),
                                       mf::testenv::source_dir().string() + "/tests/texture/checkers/bc_decode.py",
                                       dds.string(), out.string()},
                                      300);
    EXPECT_EQ(p.code, 0) << p.output;
    if (p.code != 0) return levels;
    for (const auto& l : mf::testfiles::read_json(out / "levels.json")) {
        mf::Image8 img(l["width"].get<int>(), l["height"].get<int>(), 4);
        const auto bytes = read_bytes(out / l["file"].get<std::string>());
        EXPECT_EQ(bytes.size(), img.pixels.size()) << dds;
        if (bytes.size() == img.pixels.size()) std::memcpy(img.pixels.data(), bytes.data(), bytes.size());
        levels.push_back(std::move(img));
    }
    return levels;
}

// Every mip level of a DDS through a decoder other than matforge's: OpenImageIO's (BC1-BC5; its
// 2.4 reads no BC7), texture2ddecoder's (BC7).
inline std::vector<mf::Image8> independent_levels(const fs::path& dds, const fs::path& scratch) {
    const std::vector<uint8_t> b = read_bytes(dds);
    uint32_t dxgi = 0;
    if (b.size() >= 132) std::memcpy(&dxgi, b.data() + 128, 4);
    return dxgi == 98 || dxgi == 99 ? texture2d_levels(dds, scratch) : oiio_levels(dds, scratch);
}

inline bool xy_only(const json& output) { return output.value("normal_z", "") == "reconstructed"; }
inline bool is_normal(const json& output) {
    return output["channels"].contains("RGB") && output["channels"]["RGB"] == "normal";
}

// Checks a decoded level against its reference and the manifest's recorded error.
inline void expect_recorded_error(const json& output, size_t level, const mf::Image8& ref, const mf::Image8& decoded,
                                  const std::string& who) {
    const json& rec = output["levels"][level];
    ASSERT_EQ(decoded.width, rec["width"].get<int>()) << who;
    ASSERT_EQ(decoded.height, rec["height"].get<int>()) << who;
    ASSERT_EQ(ref.width, decoded.width) << who;
    if (is_normal(output)) {
        const auto a = mf::texture::normal_angle_error(ref, decoded, xy_only(output));
        EXPECT_NEAR(a.mean_deg, rec["mean_angle_deg"].get<double>(), 0.002) << who;
        EXPECT_NEAR(a.max_deg, rec["max_angle_deg"].get<double>(), 0.002) << who;
    } else {
        const auto* f = mf::block_format_info(output["block_format"].get<std::string>());
        // A cut-out's (its levels record coverage): the colour's PSNR; its alpha is the coverage's.
        const int channels = rec.contains("coverage") ? 3 : std::min(ref.channels, f->channels);
        EXPECT_NEAR(mf::texture::psnr(ref, decoded, channels), rec["psnr_db"].get<double>(), 0.002) << who;
    }
}

// Two renders of one material (8-bit sRGB PNGs of one size, RGB read) compared where both drew
// it: the PSNR (peak 255) over the pixels lit (any channel above 0) in both pictures whose four
// neighbours are lit in both too, so a silhouette's partly covered pixels, which each renderer
// filters its own way, stay out. `lit_a`, `lit_b`: each picture's lit pixels.
struct Compared {
    double psnr_db = 0;
    size_t interior = 0, lit_a = 0, lit_b = 0;
};
inline Compared interior_psnr(const fs::path& a, const fs::path& b) {
    const mf::Image8 pa = read_codes(a), pb = read_codes(b);
    Compared c;
    EXPECT_TRUE(pa.width == pb.width && pa.height == pb.height && pa.channels >= 3 && pb.channels >= 3)
        << a << " and " << b << " differ in size or are not colour";
    if (pa.width != pb.width || pa.height != pb.height || pa.channels < 3 || pb.channels < 3) return c;
    const auto lit = [&](const mf::Image8& p, int x, int y) {
        if (x < 0 || y < 0 || x >= p.width || y >= p.height) return false;
        return p.at(x, y, 0) > 0 || p.at(x, y, 1) > 0 || p.at(x, y, 2) > 0;
    };
    double sum = 0;
    for (int y = 0; y < pa.height; ++y)
        for (int x = 0; x < pa.width; ++x) {
            c.lit_a += lit(pa, x, y);
            c.lit_b += lit(pb, x, y);
            bool inside = true;
            for (const auto& [dx, dy] : {std::pair{0, 0}, {1, 0}, {-1, 0}, {0, 1}, {0, -1}})
                inside = inside && lit(pa, x + dx, y + dy) && lit(pb, x + dx, y + dy);
            if (!inside) continue;
            for (int k = 0; k < 3; ++k) {
                const double d = double(pa.at(x, y, k)) - double(pb.at(x, y, k));
                sum += d * d;
            }
            ++c.interior;
        }
    const double mse = c.interior ? sum / (3.0 * static_cast<double>(c.interior)) : 0.0;
    c.psnr_db = mse > 0 ? 10.0 * std::log10(255.0 * 255.0 / mse) : 99.0;
    return c;
}

// A copy of `file` at `copy` with the first `from` replaced by `to` (which must be there): what
// the checkers' own tests hand them to show that they refuse a broken file.
inline fs::path damaged_copy(const fs::path& file, const std::string& from, const std::string& to,
                             const fs::path& copy) {
    const auto raw = read_bytes(file);
    std::string text(raw.begin(), raw.end());
    const size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from << " is not in " << file;
    if (at != std::string::npos) text.replace(at, from.size(), to);
    write_text(copy, text);
    return copy;
}

// `matforge preview MANIFEST --scene reference --aa 4` at `size` into `dir`: the picture another
// renderer's (Blender's, Godot's) is held against, in the same scene (docs/preview.md).
inline void preview_reference(const fs::path& manifest, const fs::path& dir, int size) {
    const auto p = matforge({"preview", manifest.string(), "-o", dir.string(), "--scene", "reference", "--size",
                             std::to_string(size), "--aa", "4"});
    EXPECT_EQ(p.code, 0) << p.output;
}

// Another renderer's picture of a material against the preview's: at least `min_db` over the
// pixels both drew, away from the silhouette, on more than 1000 of them; its lit pixels within
// `lit` (low, high) times the preview's (a cut-out drawn solid, or half the sphere missing, is
// far outside). Prints the figures (ctest --verbose) for docs/engines.md.
inline void expect_agrees_with_preview(const fs::path& preview_png, const fs::path& other_png, double min_db,
                                       std::pair<double, double> lit, const std::string& who) {
    const Compared c = interior_psnr(preview_png, other_png);
    EXPECT_GE(c.psnr_db, min_db) << who;
    EXPECT_GT(c.interior, 1000u) << who;
    ASSERT_GT(c.lit_a, 0u) << who;
    const double ratio = static_cast<double>(c.lit_b) / static_cast<double>(c.lit_a);
    EXPECT_GT(ratio, lit.first) << who;
    EXPECT_LT(ratio, lit.second) << who;
    std::cout << who << ": " << c.psnr_db << " dB over " << c.interior << " px, lit ratio " << ratio << "\n";
}

}  // namespace mtt
