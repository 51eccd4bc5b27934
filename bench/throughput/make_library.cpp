// make_library: writes the throughput benchmark's material library, deterministically.
//
//   make_library <out-dir> [--1k N] [--2k N] [--4k N] [--jobs N]
//
// Writes the sets under <out-dir>/sets/ (the folder to ingest) and <out-dir>/library.tsv.
// Sets follow real vendor naming (mostly ambientCG "<Name>_1K-JPG/<Name>_1K-JPG_Color.jpg",
// some ambientCG PNG-only sets, a few Poly Haven "_arm_" sets) with mixed PNG/JPEG/EXR inputs.
// Content is smooth tileable value noise (fBm): white noise would make the PNG/JPEG codecs
// unrealistically slow and skew every timing. Normals come from the same height by central
// differences, so the content agrees with the name's GL/DX convention (matforge checks it).
//
// Besides the images, library.tsv lists each set's material name and the file of each
// role. The oiiotool peer and the floor read it, as a studio script would read its asset
// database, instead of re-implementing vendor naming in bash.
//
// Uses OpenImageIO directly (not matforge's image code, which the benchmark measures).

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace fs = std::filesystem;

namespace {

// ---------------------------------------------------------------- noise

uint32_t hash32(uint32_t x) {  // lowbias32: good avalanche, no tables
    x ^= x >> 16;
    x *= 0x7feb352dU;
    x ^= x >> 15;
    x *= 0x846ca68bU;
    x ^= x >> 16;
    return x;
}

float lattice(uint32_t seed, int x, int y) {
    const uint32_t h = hash32(seed ^ hash32(static_cast<uint32_t>(x) * 0x9e3779b9U ^ hash32(static_cast<uint32_t>(y))));
    return static_cast<float>(h >> 8) * (1.f / 16777216.f);
}

// Tileable value noise: `cells` lattice cells across the unit square, smoothstep blend.
float value_noise(uint32_t seed, float u, float v, int cells) {
    const float x = u * static_cast<float>(cells), y = v * static_cast<float>(cells);
    const int x0 = static_cast<int>(std::floor(x)), y0 = static_cast<int>(std::floor(y));
    const float fx = x - static_cast<float>(x0), fy = y - static_cast<float>(y0);
    const float sx = fx * fx * (3.f - 2.f * fx), sy = fy * fy * (3.f - 2.f * fy);
    auto w = [cells](int i) { return ((i % cells) + cells) % cells; };
    const float a = lattice(seed, w(x0), w(y0)), b = lattice(seed, w(x0 + 1), w(y0));
    const float c = lattice(seed, w(x0), w(y0 + 1)), d = lattice(seed, w(x0 + 1), w(y0 + 1));
    return (a + (b - a) * sx) + ((c + (d - c) * sx) - (a + (b - a) * sx)) * sy;
}

// fBm in texture space (cells 8..256 across the image whatever its size), so a 4K set is the
// same material as its 1K version with finer detail, as vendors' resolutions are.
float fbm(uint32_t seed, float u, float v) {
    float sum = 0.f, amp = 0.5f, norm = 0.f;
    for (int o = 0, cells = 8; o < 6; ++o, cells *= 2, amp *= 0.5f) {
        sum += amp * value_noise(seed + static_cast<uint32_t>(o) * 101U, u, v, cells);
        norm += amp;
    }
    return sum / norm;
}

float clamp01(float x) { return std::clamp(x, 0.f, 1.f); }
float smoothstep(float e0, float e1, float x) {
    const float t = clamp01((x - e0) / (e1 - e0));
    return t * t * (3.f - 2.f * t);
}
float linear_to_srgb(float l) {
    const double d = std::clamp(static_cast<double>(l), 0.0, 1.0);
    return static_cast<float>(d <= 0.0031308 ? d * 12.92 : 1.055 * std::pow(d, 1.0 / 2.4) - 0.055);
}

// ---------------------------------------------------------------- set recipes

enum class Family { ambientcg_jpg, ambientcg_png, polyhaven };

struct Recipe {
    Family family;
    bool normal_dx;     // _NormalDX instead of _NormalGL (Poly Haven: _nor_dx_)
    bool metalness;     // a metalness map (ambientCG) / metal areas in ARM's B (Poly Haven)
    bool occlusion;     // an AO map (ARM always has one)
    bool displacement;  // ambientCG JPG: half EXR; PNG-only: 16-bit PNG; Poly Haven: half EXR
};

// Cycled by a global set index, so every size gets a mix and the 1K sets hold every recipe.
constexpr Recipe kRecipes[] = {
    {Family::ambientcg_jpg, false, true, true, true},  // the full ambientCG download
    {Family::ambientcg_jpg, false, false, true, true},
    {Family::ambientcg_png, false, false, true, true},  // PNG-only, 16-bit displacement
    {Family::ambientcg_jpg, true, false, true, false},  // DX normal: flipped for glTF
    {Family::ambientcg_jpg, false, true, false, true},  // no AO: occlusion 1
    {Family::polyhaven, false, false, true, true},      // _arm_ packed input
    {Family::ambientcg_jpg, false, false, true, false},
    {Family::ambientcg_png, true, true, true, false},
    {Family::ambientcg_jpg, true, false, false, true},
    {Family::polyhaven, true, true, true, false},
};
constexpr size_t kRecipeCount = std::size(kRecipes);

constexpr const char* kWords[] = {"Bricks", "Concrete", "Ground",  "Metal",  "Planks",  "Rock",
                                  "Tiles",  "Fabric",   "Leather", "Marble", "Asphalt", "Gravel"};
constexpr const char* kPhWords[] = {"rock_wall",   "brick_floor", "forest_ground",   "rusty_metal",
                                    "wood_planks", "cobblestone", "painted_plaster", "sandstone"};

struct SetJob {
    int index;  // global, decides recipe, name and seed
    int size;   // 1024, 2048, 4096
};

// What library.tsv says about one set ("-" where a role has no file).
struct Row {
    std::string name, dir, albedo, normal, normal_conv = "gl", ao = "-", roughness = "-", metalness = "-", arm = "-",
                                           height = "-";
    int size = 0;
};

std::string pad3(int i) {
    char b[8];
    std::snprintf(b, sizeof b, "%03d", i);
    return b;
}

bool write_image(const fs::path& p, int w, int h, int ch, OIIO::TypeDesc file_type, OIIO::TypeDesc mem_type,
                 const void* data, std::string& err) {
    OIIO::ImageSpec spec(w, h, ch, file_type);
    if (ch == 1) spec.channelnames = {"Y"};
    // Fixed metadata: byte-identical libraries across runs (EXR would stamp the time).
    spec.attribute("DateTime", "2000:01:01 00:00:00");
    spec.attribute("Software", "matforge make_library");
    const std::string ext = p.extension().string();
    if (ext == ".jpg") spec.attribute("Compression", "jpeg:90");
    if (ext == ".exr") spec.attribute("compression", "zip");
    auto out = OIIO::ImageOutput::create(p.string());
    if (!out || !out->open(p.string(), spec) || !out->write_image(mem_type, data) || !out->close()) {
        err = p.string() + ": " + (out ? out->geterror() : OIIO::geterror());
        return false;
    }
    return true;
}

bool make_set(const fs::path& root, const SetJob& job, Row& row, std::string& err) {
    const Recipe& r = kRecipes[static_cast<size_t>(job.index) % kRecipeCount];
    const int n = job.size;
    const uint32_t seed = hash32(static_cast<uint32_t>(job.index) * 7919U + 17U);
    const std::string res = std::to_string(n / 1024) + "K";  // "1K"
    const std::string ph_res = std::to_string(n / 1024) + "k";

    // Names and files by family.
    std::string base, dir;
    auto file = [&](const char* ambient_tag, const char* ph_tag, const char* ext) {
        if (r.family == Family::polyhaven) return base + "_" + ph_tag + "_" + ph_res + ext;
        return dir + "_" + ambient_tag + ext;
    };
    if (r.family == Family::polyhaven) {
        base = std::string(kPhWords[static_cast<size_t>(job.index) % std::size(kPhWords)]) + "_" + pad3(job.index);
        dir = base + "_" + ph_res;
        row.name = base;
    } else {
        base = std::string(kWords[static_cast<size_t>(job.index) % std::size(kWords)]) + pad3(job.index);
        dir = base + "_" + res + (r.family == Family::ambientcg_jpg ? "-JPG" : "-PNG");
        row.name = base;
    }
    row.dir = dir;
    row.size = n;
    const bool jpg = r.family == Family::ambientcg_jpg;
    const char* scalar_ext = jpg ? ".jpg" : ".png";
    row.albedo = file("Color", "diff", jpg ? ".jpg" : ".png");
    row.normal = file(r.normal_dx ? "NormalDX" : "NormalGL", r.normal_dx ? "nor_dx" : "nor_gl", ".png");
    row.normal_conv = r.normal_dx ? "dx" : "gl";
    if (r.family == Family::polyhaven) {
        row.arm = file("", "arm", ".png");
    } else {
        row.roughness = file("Roughness", "", scalar_ext);
        if (r.occlusion) row.ao = file("AmbientOcclusion", "", scalar_ext);
        if (r.metalness) row.metalness = file("Metalness", "", scalar_ext);
    }
    if (r.displacement)
        row.height = r.family == Family::ambientcg_png ? file("Displacement", "", ".png")
                                                       : file("Displacement", "disp", ".exr");

    // Planes, in [0,1]. Height first: the normal needs its neighbours.
    const size_t px = static_cast<size_t>(n) * static_cast<size_t>(n);
    std::vector<float> height(px), rough(px), metal(px), ao(px);
    std::vector<uint8_t> albedo(px * 3);
    const float hue = static_cast<float>(hash32(seed ^ 0xabcU) >> 8) * (1.f / 16777216.f);
    const std::array<float, 3> tint{0.35f + 0.4f * hue, 0.3f + 0.25f * (1.f - hue), 0.2f + 0.3f * hue};
    const std::array<float, 3> metal_tint{0.91f, 0.78f - 0.2f * hue, 0.55f};
    const float inv = 1.f / static_cast<float>(n);
    for (int y = 0; y < n; ++y) {
        const float v = (static_cast<float>(y) + 0.5f) * inv;
        for (int x = 0; x < n; ++x) {
            const float u = (static_cast<float>(x) + 0.5f) * inv;
            const size_t i = static_cast<size_t>(y) * static_cast<size_t>(n) + static_cast<size_t>(x);
            const float h = fbm(seed, u, v);
            const float c = fbm(seed + 1000U, u, v);
            height[i] = h;
            rough[i] = clamp01(0.25f + 0.6f * c);
            metal[i] = r.metalness ? smoothstep(0.56f, 0.6f, fbm(seed + 2000U, u, v)) : 0.f;
            ao[i] = r.occlusion || r.family == Family::polyhaven ? 0.35f + 0.65f * smoothstep(0.15f, 0.65f, h) : 1.f;
            for (int k = 0; k < 3; ++k) {
                const float lin = (tint[static_cast<size_t>(k)] * (0.55f + 0.6f * c)) * (1.f - metal[i]) +
                                  metal_tint[static_cast<size_t>(k)] * metal[i];
                albedo[i * 3 + static_cast<size_t>(k)] =
                    static_cast<uint8_t>(std::lround(linear_to_srgb(lin * (0.7f + 0.3f * h)) * 255.f));
            }
        }
    }
    // Normals by central differences (wrapping: tileable). GL: n = (-s dh/dx, +s dh/drow, 1) with
    // rows going down (+Y up); DX negates green. s in pixels scales with the size so every
    // resolution shows the same relief.
    std::vector<uint8_t> normal(px * 3);
    const float s = 0.04f * static_cast<float>(n);
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            auto at = [&](int xx, int yy) {
                return height[static_cast<size_t>((yy + n) % n) * static_cast<size_t>(n) +
                              static_cast<size_t>((xx + n) % n)];
            };
            const float dx = (at(x + 1, y) - at(x - 1, y)) * 0.5f, drow = (at(x, y + 1) - at(x, y - 1)) * 0.5f;
            float nx = -s * dx, ny = s * drow, nz = 1.f;
            const float len = std::sqrt(nx * nx + ny * ny + nz * nz);
            nx /= len, ny /= len, nz /= len;
            if (r.normal_dx) ny = -ny;
            const size_t i = (static_cast<size_t>(y) * static_cast<size_t>(n) + static_cast<size_t>(x)) * 3;
            normal[i] = static_cast<uint8_t>(std::lround((nx * 0.5f + 0.5f) * 255.f));
            normal[i + 1] = static_cast<uint8_t>(std::lround((ny * 0.5f + 0.5f) * 255.f));
            normal[i + 2] = static_cast<uint8_t>(std::lround((nz * 0.5f + 0.5f) * 255.f));
        }

    const fs::path d = root / dir;
    fs::create_directories(d);
    using OIIO::TypeDesc;
    auto q8 = [](const std::vector<float>& f) {
        std::vector<uint8_t> b(f.size());
        for (size_t i = 0; i < f.size(); ++i) b[i] = static_cast<uint8_t>(std::lround(clamp01(f[i]) * 255.f));
        return b;
    };
    if (!write_image(d / row.albedo, n, n, 3, TypeDesc::UINT8, TypeDesc::UINT8, albedo.data(), err)) return false;
    if (!write_image(d / row.normal, n, n, 3, TypeDesc::UINT8, TypeDesc::UINT8, normal.data(), err)) return false;
    if (r.family == Family::polyhaven) {
        std::vector<uint8_t> arm(px * 3);
        for (size_t i = 0; i < px; ++i) {
            arm[i * 3] = static_cast<uint8_t>(std::lround(ao[i] * 255.f));
            arm[i * 3 + 1] = static_cast<uint8_t>(std::lround(rough[i] * 255.f));
            arm[i * 3 + 2] = static_cast<uint8_t>(std::lround(metal[i] * 255.f));
        }
        if (!write_image(d / row.arm, n, n, 3, TypeDesc::UINT8, TypeDesc::UINT8, arm.data(), err)) return false;
    } else {
        if (!write_image(d / row.roughness, n, n, 1, TypeDesc::UINT8, TypeDesc::UINT8, q8(rough).data(), err))
            return false;
        if (row.ao != "-" && !write_image(d / row.ao, n, n, 1, TypeDesc::UINT8, TypeDesc::UINT8, q8(ao).data(), err))
            return false;
        if (row.metalness != "-" &&
            !write_image(d / row.metalness, n, n, 1, TypeDesc::UINT8, TypeDesc::UINT8, q8(metal).data(), err))
            return false;
    }
    if (row.height != "-") {
        if (row.height.ends_with(".exr")) {
            if (!write_image(d / row.height, n, n, 1, TypeDesc::HALF, TypeDesc::FLOAT, height.data(), err))
                return false;
        } else {
            std::vector<uint16_t> h16(px);
            for (size_t i = 0; i < px; ++i) h16[i] = static_cast<uint16_t>(std::lround(height[i] * 65535.f));
            if (!write_image(d / row.height, n, n, 1, TypeDesc::UINT16, TypeDesc::UINT16, h16.data(), err))
                return false;
        }
    }
    return true;
}

bool parse_int(const std::string& s, int& v) {
    const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
    return r.ec == std::errc() && r.ptr == s.data() + s.size() && v >= 0;
}

int usage() {
    std::cerr << "usage: make_library <out-dir> [--1k N (40)] [--2k N (8)] [--4k N (2)] [--jobs N (2)]\n";
    return 2;
}

}  // namespace

int main(int argc, char** argv) {
    std::vector<std::string> args(argv + 1, argv + argc);
    std::string out;
    int n1 = 40, n2 = 8, n4 = 2, jobs = 2;
    for (size_t i = 0; i < args.size(); ++i) {
        auto value = [&](int& v) { return i + 1 < args.size() && parse_int(args[++i], v); };
        if (args[i] == "--1k") {
            if (!value(n1)) return usage();
        } else if (args[i] == "--2k") {
            if (!value(n2)) return usage();
        } else if (args[i] == "--4k") {
            if (!value(n4)) return usage();
        } else if (args[i] == "--jobs") {
            if (!value(jobs) || jobs < 1) return usage();
        } else if (!args[i].starts_with("-") && out.empty()) {
            out = args[i];
        } else {
            return usage();
        }
    }
    if (out.empty()) return usage();

    // One global index across sizes: names stay unique and recipes keep cycling.
    std::vector<SetJob> sets;
    int g = 0;
    for (int i = 0; i < n1; ++i) sets.push_back({g++, 1024});
    for (int i = 0; i < n2; ++i) sets.push_back({g++, 2048});
    for (int i = 0; i < n4; ++i) sets.push_back({g++, 4096});

    // The sets get a folder of their own: the listing beside them must not be ingested.
    const fs::path root = fs::path(out) / "sets";
    std::error_code ec;
    fs::create_directories(root, ec);
    std::vector<Row> rows(sets.size());
    std::vector<std::string> errors(sets.size());
    std::atomic<size_t> next{0};
    auto worker = [&] {
        for (size_t i = next++; i < sets.size(); i = next++)
            if (!make_set(root, sets[i], rows[i], errors[i]) && errors[i].empty()) errors[i] = "failed";
    };
    std::vector<std::thread> pool;
    for (int t = 1; t < std::min<int>(jobs, static_cast<int>(sets.size())); ++t) pool.emplace_back(worker);
    worker();
    for (auto& t : pool) t.join();
    for (const auto& e : errors)
        if (!e.empty()) {
            std::cerr << "make_library: " << e << "\n";
            return 1;
        }

    const fs::path tsv_path = fs::path(out) / "library.tsv";
    std::ofstream tsv(tsv_path);
    tsv << "name\tdir\tsize\talbedo\tnormal\tnormal_convention\tocclusion\troughness\tmetalness\tarm\theight\n";
    for (const auto& r : rows)
        tsv << r.name << '\t' << r.dir << '\t' << r.size << '\t' << r.albedo << '\t' << r.normal << '\t'
            << r.normal_conv << '\t' << r.ao << '\t' << r.roughness << '\t' << r.metalness << '\t' << r.arm << '\t'
            << r.height << '\n';
    if (!tsv) {
        std::cerr << "make_library: cannot write " << tsv_path.string() << "\n";
        return 1;
    }
    std::cout << "make_library: " << sets.size() << " sets (" << n1 << " x 1K, " << n2 << " x 2K, " << n4
              << " x 4K) in " << root.string() << "\n";
    return 0;
}
