// Maps held as 8-bit codes (ingest hands the rules its decoded codes, validate.hpp's Samples)
// validate to exactly what their floats give (read_file_bands' unorm8 values): every finding,
// message and figure bit for bit, every fact of the set, and each map's statistics — over odd
// widths (the vector loops' tails), 1–4 channels, small bands, and maps that mix codes and floats.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <random>

#include "base/srgb.hpp"
#include "validate/map_stats.hpp"
#include "validate/validate.hpp"

namespace mv = mf::validate;
namespace md = mf::validate::detail;

namespace {

using mf::Image;
using mf::Image8;
using mf::Role;

uint8_t code_of(float v) { return static_cast<uint8_t>(std::lround(std::clamp(v, 0.f, 1.f) * 255.f)); }

// One map of a test set: its codes (8-bit) or floats (a 16-bit or float file).
struct TestMap {
    Role role;
    Image8 codes;
    Image floats;
    int bit_depth = 8;
    mf::NormalConvention convention = mf::NormalConvention::unknown;
};

using Maps = std::map<std::string, TestMap>;

// Serves every map band by band: an 8-bit map as its codes (`codes`) or as their floats.
mv::BandReader reader_of(const Maps& maps, bool codes) {
    return [&maps, codes](const mf::InputFile& in, int band_rows, mf::ImageInfo& info, std::string& error,
                          const std::function<void(int, int, mv::Samples)>& fn) {
        const auto it = maps.find(in.display);
        if (it == maps.end()) {
            error = in.display + ": not in the test set";
            return false;
        }
        const TestMap& m = it->second;
        const bool is8 = m.bit_depth == 8;
        const int w = is8 ? m.codes.width : m.floats.width, h = is8 ? m.codes.height : m.floats.height;
        const int ch = is8 ? m.codes.channels : m.floats.channels;
        info = {w, h, ch, m.bit_depth, m.bit_depth == 32, "memory", {}};
        std::vector<float> band;
        for (int y0 = 0; y0 < h; y0 += band_rows) {
            const int rows = std::min(band_rows, h - y0);
            if (!is8) {
                fn(y0, rows, {&m.floats.pixels[m.floats.index(0, y0)]});
            } else if (codes) {
                fn(y0, rows, {nullptr, &m.codes.pixels[m.codes.index(0, y0)]});
            } else {
                band.resize(static_cast<size_t>(w) * ch * rows);
                mf::to_float(&m.codes.pixels[m.codes.index(0, y0)], band.size(), band.data());
                fn(y0, rows, {band.data()});
            }
        }
        return true;
    };
}

mv::SetValidation validate(const Maps& maps, bool codes, int band_rows) {
    std::vector<mv::MapInput> inputs;
    for (const auto& [name, m] : maps) {
        mv::MapInput in;
        in.role = m.role;
        in.name = name;
        in.file.display = name;
        in.name_convention = m.convention;
        const bool is8 = m.bit_depth == 8;
        in.info = {is8 ? m.codes.width : m.floats.width,
                   is8 ? m.codes.height : m.floats.height,
                   is8 ? m.codes.channels : m.floats.channels,
                   m.bit_depth,
                   m.bit_depth == 32,
                   "memory",
                   {}};
        inputs.push_back(in);
    }
    mv::ValidateOptions opt;
    opt.reader = reader_of(maps, codes);
    opt.band_rows = band_rows;
    return mv::validate_set(inputs, {}, opt);
}

void expect_same(const mv::SetValidation& a, const mv::SetValidation& b) {
    ASSERT_EQ(a.findings.size(), b.findings.size());
    for (size_t i = 0; i < a.findings.size(); ++i)
        EXPECT_EQ(mf::to_json(a.findings[i]).dump(), mf::to_json(b.findings[i]).dump());
    EXPECT_EQ(a.albedo_alpha_min, b.albedo_alpha_min);
    EXPECT_EQ(a.opacity_invisible, b.opacity_invisible);
    EXPECT_EQ(a.normal_z_rebuilt, b.normal_z_rebuilt);
    EXPECT_EQ(a.unreadable, b.unreadable);
    ASSERT_EQ(a.normal.has_value(), b.normal.has_value());
    if (a.normal) {
        EXPECT_EQ(a.normal->resolved, b.normal->resolved);
        EXPECT_EQ(a.normal->source, b.normal->source);
        EXPECT_EQ(a.normal->content.confidence, b.normal->content.confidence);
        EXPECT_EQ(a.normal->content.method, b.normal->content.method);
        EXPECT_EQ(mf::to_json(a.normal->content.figures).dump(), mf::to_json(b.normal->content.figures).dump());
    }
}

std::vector<std::string> codes_of(const mv::SetValidation& v) {
    std::vector<std::string> c;
    for (const auto& f : v.findings) c.push_back(f.code);
    return c;
}

bool has(const mv::SetValidation& v, std::string_view code) {
    for (const auto& f : v.findings)
        if (f.code == code) return true;
    return false;
}

// A smooth height field in [0, 1] and its tangent-space normals (GL, n = 2c - 1 in codes).
struct Relief {
    Image height;
    Image normal;  // unit vectors
};

Relief relief(int w, int h, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.f, 6.2831853f);
    const float a = u(rng), b = u(rng);
    Relief r{Image(w, h, 1), Image(w, h, 3)};
    auto f = [&](float x, float y) {
        return 0.5f + 0.25f * std::sin(x * 0.31f + a) * std::cos(y * 0.23f + b) + 0.2f * std::sin((x + y) * 0.11f);
    };
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const auto fx = static_cast<float>(x), fy = static_cast<float>(y);
            r.height.at(x, y) = f(fx, fy);
            const float dx = 4.f * (f(fx + 0.5f, fy) - f(fx - 0.5f, fy));
            const float dy = 4.f * (f(fx, fy + 0.5f) - f(fx, fy - 0.5f));
            const float len = std::sqrt(dx * dx + dy * dy + 1.f);
            r.normal.at(x, y, 0) = -dx / len;
            r.normal.at(x, y, 1) = dy / len;  // GL: +Y up, rows go down
            r.normal.at(x, y, 2) = 1.f / len;
        }
    return r;
}

Image8 to_codes(
    const Image& img, const std::function<float(float)>& f = [](float v) { return v; }) {
    Image8 c(img.width, img.height, img.channels);
    for (size_t i = 0; i < img.pixels.size(); ++i) c.pixels[i] = code_of(f(img.pixels[i]));
    return c;
}

Image8 encode_normals(
    const Image& n, int channels, const std::function<float(float)>& f = [](float v) { return v; }) {
    Image8 c(n.width, n.height, channels);
    for (int y = 0; y < n.height; ++y)
        for (int x = 0; x < n.width; ++x)
            for (int k = 0; k < channels; ++k) c.at(x, y, k) = k < 3 ? code_of(f(0.5f * n.at(x, y, k) + 0.5f)) : 255;
    return c;
}

// A set with something for every rule that reads pixels: RGBA albedo (dark patches, a hidden
// part), non-binary metalness, a grey roughness map with coloured pixels, a GL normal map with
// its height map, and AO.
Maps rich_set(int w, int h, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> code(0, 255);
    Maps m;
    Image8 albedo(w, h, 4), metal(w, h, 1), rough(w, h, 3), ao(w, h, 1);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const bool dark = (x / 7 + y / 5) % 3 == 0;
            for (int k = 0; k < 3; ++k)
                albedo.at(x, y, k) = static_cast<uint8_t>(dark ? code(rng) % 25 : 60 + code(rng) % 180);
            albedo.at(x, y, 3) = static_cast<uint8_t>(x < w / 5 ? 0 : (x < w / 4 ? 128 : 255));
            const int mk = (x * 3 + y) % 10;
            metal.at(x, y) = static_cast<uint8_t>(mk < 4 ? 0 : mk < 6 ? 255 : code(rng));
            const auto g = static_cast<uint8_t>(code(rng));
            rough.at(x, y, 0) = rough.at(x, y, 1) = rough.at(x, y, 2) = g;
            if ((x + y) % 4 == 0) rough.at(x, y, 2) = static_cast<uint8_t>(std::min(255, g + 40));
            ao.at(x, y) = static_cast<uint8_t>(200 + code(rng) % 56);
        }
    const Relief r = relief(w, h, seed);
    m["albedo.png"] = {Role::albedo, std::move(albedo), {}};
    m["metal.png"] = {Role::metalness, std::move(metal), {}};
    m["rough.jpg"] = {Role::roughness, std::move(rough), {}};
    m["ao.png"] = {Role::occlusion, std::move(ao), {}};
    m["normal.png"] = {Role::normal, encode_normals(r.normal, 3), {}};
    m["height.png"] = {Role::height, to_codes(r.height), {}};
    return m;
}

}  // namespace

TEST(ValidateCodes, SetsValidateAsTheirFloatsDo) {
    struct Case {
        std::string what;
        Maps maps;
    };
    std::vector<Case> cases;
    for (auto [w, h] : {std::pair{67, 45}, {130, 33}, {16, 16}, {1, 9}})
        cases.push_back({"rich " + std::to_string(w) + "x" + std::to_string(h), rich_set(w, h, 7u + w)});
    {
        // Packed ORM, a separate opacity hiding everything, a two-channel normal map (Z rebuilt).
        Maps m = rich_set(51, 29, 3);
        Image8 orm(51, 29, 3), opacity(51, 29, 1);
        for (size_t i = 0; i < orm.pixels.size(); ++i) orm.pixels[i] = static_cast<uint8_t>((i * 37) % 256);
        std::fill(opacity.pixels.begin(), opacity.pixels.end(), uint8_t{0});
        m.erase("metal.png");
        m.erase("ao.png");
        m.erase("rough.jpg");
        m["orm.png"] = {Role::orm, std::move(orm), {}};
        m["opacity.png"] = {Role::opacity, std::move(opacity), {}};
        m["normal.png"] = {Role::normal, encode_normals(relief(51, 29, 3).normal, 2), {}};
        cases.push_back({"orm, invisible opacity, two-channel normal", std::move(m)});
    }
    {
        // A normal map stored sRGB-encoded, an empty-blue normal beside it (alternate roles are
        // not read jointly), a bright albedo; the height as 16-bit floats (mixed with codes).
        Maps m;
        const Relief r = relief(73, 41, 11);
        Image8 albedo(73, 41, 3);
        std::fill(albedo.pixels.begin(), albedo.pixels.end(), uint8_t{250});
        m["albedo.png"] = {Role::albedo, std::move(albedo), {}};
        m["normal.png"] = {Role::normal,
                           encode_normals(r.normal, 3, [](float v) { return mf::linear_to_srgb(v); }),
                           {}};
        Image h16 = r.height;
        for (auto& v : h16.pixels) v = std::round(v * 65535.f) / 65535.f;
        m["height.png"] = {Role::height, {}, std::move(h16), 16};
        cases.push_back({"gamma-encoded normal, 16-bit height", std::move(m)});
    }
    {
        // Blue held at one value while X and Y vary: Z is rebuilt (NORMAL_Z_RECONSTRUCTED), the
        // name says DX against GL content.
        Maps m;
        Image8 n = encode_normals(relief(90, 20, 5).normal, 3);
        for (int y = 0; y < n.height; ++y)
            for (int x = 0; x < n.width; ++x) n.at(x, y, 2) = 0;
        m["normal_dx.png"] = {Role::normal, std::move(n), {}, 8, mf::NormalConvention::dx};
        cases.push_back({"empty blue", std::move(m)});
    }
    size_t findings = 0;
    for (const Case& c : cases)
        for (int band_rows : {1, 7, 64}) {
            SCOPED_TRACE(c.what + ", bands of " + std::to_string(band_rows));
            const mv::SetValidation floats = validate(c.maps, false, band_rows);
            const mv::SetValidation codes = validate(c.maps, true, band_rows);
            expect_same(floats, codes);
            findings += codes.findings.size();
        }
    // The cases do reach the rules whose figures come from the codes loops.
    const mv::SetValidation rich = validate(cases[0].maps, true, 16);
    for (std::string_view code : {mf::code::albedo_too_dark, mf::code::metalness_not_binary, mf::code::not_grayscale})
        EXPECT_TRUE(has(rich, code)) << code << " not among " << ::testing::PrintToString(codes_of(rich));
    EXPECT_TRUE(has(validate(cases[5].maps, true, 16), mf::code::normal_gamma_encoded));
    EXPECT_TRUE(validate(cases[4].maps, true, 16).opacity_invisible);
    EXPECT_TRUE(validate(cases[6].maps, true, 16).normal_z_rebuilt);
    EXPECT_GT(findings, 30u);
}

// MapStats over codes against the same band as floats: every counter and sum, for 1–4 channels
// and pixel counts around the 16-code vector blocks (48 codes for three channels).
TEST(ValidateCodes, MapStatisticsOfCodesEqualThoseOfTheirFloats) {
    std::mt19937 rng(42);
    std::uniform_int_distribution<int> code(0, 255);
    for (Role role : {Role::roughness, Role::metalness, Role::normal, Role::albedo, Role::opacity})
        for (int channels = 1; channels <= 4; ++channels)
            for (int width : {1, 5, 15, 16, 17, 47, 48, 49, 200}) {
                if (role == Role::normal && channels < 2) continue;
                SCOPED_TRACE(std::string(mf::role_name(role)) + " " + std::to_string(channels) + " channels, width " +
                             std::to_string(width));
                mv::MapInput in;
                in.role = role;
                in.info = {width, 3, channels, 8, false, "png", {}};
                md::MapStats a(in, in.info, mf::rules::Thresholds{}), b(in, in.info, mf::rules::Thresholds{});
                for (int y0 = 0; y0 < 3; ++y0) {
                    // Half the pixels grey (every channel one code), the rest any codes.
                    std::vector<uint8_t> band(static_cast<size_t>(width) * channels);
                    for (size_t p = 0; p < band.size(); p += static_cast<size_t>(channels)) {
                        const bool grey = code(rng) % 2 == 0;
                        const auto g = static_cast<uint8_t>(code(rng));
                        for (size_t k = 0; k < static_cast<size_t>(channels); ++k)
                            band[p + k] = grey ? g : static_cast<uint8_t>(code(rng));
                    }
                    std::vector<float> floats(band.size());
                    mf::to_float(band.data(), band.size(), floats.data());
                    a.add_band(y0, 1, floats.data());
                    b.add_band(y0, 1, band.data());
                }
                EXPECT_EQ(a.min, b.min);
                EXPECT_EQ(a.max, b.max);
                EXPECT_EQ(a.code_sum, b.code_sum);
                EXPECT_EQ(a.finite, b.finite);
                EXPECT_EQ(a.pixels, b.pixels);
                EXPECT_EQ(a.gray_differing, b.gray_differing);
                EXPECT_EQ(a.gray_max_diff, b.gray_max_diff);
                EXPECT_EQ(a.gray_sum_rg, b.gray_sum_rg);
                EXPECT_EQ(a.gray_sum_rb, b.gray_sum_rb);
                EXPECT_EQ(a.metal_dielectric, b.metal_dielectric);
                EXPECT_EQ(a.metal_between, b.metal_between);
                EXPECT_EQ(a.opacity_invisible, b.opacity_invisible);
                EXPECT_EQ(a.opacity_below_cutoff, b.opacity_below_cutoff);
                EXPECT_EQ(a.normal_z, b.normal_z);
                EXPECT_EQ(a.normal_bad_length, b.normal_bad_length);
                EXPECT_EQ(a.normal_upward, b.normal_upward);
                EXPECT_EQ(a.normal_gray, b.normal_gray);
                EXPECT_EQ(a.normal_sum_length, b.normal_sum_length);
                EXPECT_EQ(a.normal_sum_z, b.normal_sum_z);
                EXPECT_EQ(a.normal_sum_xx, b.normal_sum_xx);
                EXPECT_EQ(a.normal_srgb_sum_x, b.normal_srgb_sum_x);
                EXPECT_EQ(a.normal_srgb_sum_length, b.normal_srgb_sum_length);
                EXPECT_EQ(a.normal_srgb_upward, b.normal_srgb_upward);
                // The sums are real: a wrong loop would not pass by accident.
                EXPECT_GT(b.code_sum[0], 0);
            }
}
