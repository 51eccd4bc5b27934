// Through real encoded files (mf::encode_image → in-memory PNG/EXR → mf::read_bands): the path
// the CLI takes; color tags read from PNG chunks; an 8K set in bounded memory.
#include <gtest/gtest.h>
#include <sys/resource.h>

#include <OpenImageIO/imageio.h>

#include <chrono>
#include <filesystem>

#include "helpers.hpp"
#include "test_dirs.hpp"

using namespace mft;
namespace mv = mf::validate;

namespace {

mf::InputFile encode(const Image& img, const std::string& name, const std::string& format = "png", int bits = 8) {
    mf::EncodeOptions opt;
    opt.format = *mf::from_word<mf::FileFormat>(format);
    opt.bit_depth = bits;
    auto bytes = std::make_shared<std::vector<unsigned char>>();
    std::string err;
    EXPECT_TRUE(mf::encode_image(img, opt, *bytes, err)) << err;
    mf::InputFile f;
    f.display = name;
    f.bytes = bytes;
    return f;
}

long max_rss_kb() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return u.ru_maxrss;
}

}  // namespace

TEST(ValidateFiles, CleanAndBadSetsFromEncodedFiles) {
    const MemSet mem = clean_set(64);
    std::vector<mv::MapInput> maps;
    for (const auto& in : mem.inputs) {
        std::string err;
        auto m = mv::make_map_input(in.role, encode(*mem.images.at(in.name), in.name), in.name, in.name_convention,
                                    err);
        ASSERT_TRUE(m) << err;
        EXPECT_EQ(m->info.width, 64);
        maps.push_back(*m);
    }
    auto res = mv::validate_set(maps, {});
    EXPECT_TRUE(res.findings.empty()) << dump(res.findings);

    // A DX normal named GL, through PNG.
    const Image n = normal_from_height(*mem.images.at("T_height.png"), NormalConvention::dx);
    for (auto& m : maps)
        if (m.role == Role::normal) m.file = encode(n, m.name);
    res = mv::validate_set(maps, {});
    EXPECT_TRUE(has_code(res.findings, mf::code::normal_convention_mismatch)) << dump(res.findings);

    // A truncated file.
    auto cut = std::make_shared<std::vector<unsigned char>>(maps[2].file.bytes->begin(),
                                                            maps[2].file.bytes->begin() + 100);
    maps[2].file.bytes = cut;
    res = mv::validate_set(maps, {});
    EXPECT_TRUE(has_code(res.findings, mf::code::unreadable_file)) << dump(res.findings);
}

TEST(ValidateFiles, FloatExrWithNaN) {
    Image r(32, 32, 1, 0.5f);
    for (int x = 0; x < 32; ++x) r.at(x, 3) = static_cast<float>(x) / 31.f * 2.f;  // up to 2.0
    r.at(1, 1) = std::nanf("");
    std::string err;
    auto m = mv::make_map_input(Role::roughness, encode(r, "R.exr", "exr", 32), "R.exr", NormalConvention::unknown,
                                err);
    ASSERT_TRUE(m) << err;
    EXPECT_TRUE(m->info.is_float);
    const auto res = mv::validate_set({*m}, {});
    EXPECT_TRUE(has_code(res.findings, mf::code::nonfinite_values)) << dump(res.findings);
    EXPECT_TRUE(has_code(res.findings, mf::code::out_of_range_values)) << dump(res.findings);
}

TEST(ColorTag, PngChunks) {
    // Written by OpenImageIO with explicit color spaces, read back by our chunk parser.
    const auto dir = mf::testdirs::fresh("matforge-colortag-", "png");
    auto write = [&](const std::string& name, const char* cs) {
        const auto path = (dir / name).string();
        auto out = OIIO::ImageOutput::create(path);
        OIIO::ImageSpec spec(4, 4, 3, OIIO::TypeDesc::UINT8);
        if (cs) spec.attribute("oiio:ColorSpace", cs);
        std::vector<unsigned char> px(48, 128);
        EXPECT_TRUE(out->open(path, spec));
        EXPECT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, px.data()));
        out->close();
        mf::InputFile f;
        f.display = name;
        f.path = path;
        return mv::read_color_tag(f);
    };
    EXPECT_EQ(write("plain.png", nullptr).tag, mv::ColorTag::none);
    const auto lin = write("lin.png", "linear");
    EXPECT_EQ(lin.tag, mv::ColorTag::linear);
    EXPECT_EQ(lin.source, "png:gAMA");
    EXPECT_EQ(write("srgb.png", "sRGB").tag, mv::ColorTag::srgb);
    EXPECT_EQ(write("plain.exr", nullptr).tag, mv::ColorTag::none) << "EXR's default is not a statement";
    EXPECT_EQ(write("plain.jpg", nullptr).tag, mv::ColorTag::none) << "JPEG's default is not a statement";
    std::filesystem::remove_all(dir);

    // Hand-made chunk list: cICP wins over sRGB (PNG 3rd edition precedence).
    std::vector<unsigned char> png{0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    auto chunk = [&](const char* type, std::vector<unsigned char> data) {
        const uint32_t n = static_cast<uint32_t>(data.size());
        for (int s = 24; s >= 0; s -= 8) png.push_back(static_cast<unsigned char>(n >> s));
        png.insert(png.end(), type, type + 4);
        png.insert(png.end(), data.begin(), data.end());
        png.insert(png.end(), 4, 0);  // CRC (not checked)
    };
    chunk("IHDR", std::vector<unsigned char>(13, 0));
    chunk("sRGB", {0});
    chunk("cICP", {1, 8, 0, 1});
    chunk("IDAT", {});
    const auto t = mv::png_color_tag(png.data(), png.size());
    EXPECT_EQ(t.tag, mv::ColorTag::linear);
    EXPECT_EQ(t.source, "png:cICP");
    EXPECT_EQ(mv::png_color_tag(png.data(), 20).tag, mv::ColorTag::none) << "truncated";
}

TEST(ValidateFiles, EightKSetInBoundedMemory) {
    // 8192² albedo + metalness + normal + height generated band by band by the reader itself:
    // nothing holds a whole map, so the peak memory measures the validator alone.
    constexpr int W = 8192, H = 8192;
    auto gen = [](const mf::InputFile& in, int band_rows, mf::ImageInfo& info, std::string&,
                  const std::function<void(int, int, mv::Samples)>& fn) {
        const bool normal = in.display == "N.png";
        const int c = normal || in.display == "A.png" ? 3 : 1;
        info = {W, H, c, 8, false, "memory", {}};
        std::vector<float> band(static_cast<size_t>(W) * c * band_rows);
        for (int y0 = 0; y0 < H; y0 += band_rows) {
            const int rows = std::min(band_rows, H - y0);
            for (int y = 0; y < rows; ++y)
                for (int x = 0; x < W; ++x) {
                    float* p = &band[(static_cast<size_t>(y) * W + x) * c];
                    const float t = static_cast<float>((x + y0 + y) % 64) / 64.f;
                    if (normal) {
                        p[0] = 0.5f + 0.2f * (t - 0.5f);
                        p[1] = 0.5f;
                        p[2] = 0.97f;
                    } else if (c == 3) {
                        p[0] = p[1] = p[2] = 0.4f + 0.2f * t;
                    } else if (in.display == "M.png") p[0] = x < W / 2 ? 0.f : 1.f;
                    else p[0] = t;
                }
            fn(y0, rows, {band.data()});
        }
        return true;
    };
    std::vector<mv::MapInput> maps;
    for (auto [role, name] : {std::pair{Role::albedo, "A.png"},
                              {Role::metalness, "M.png"},
                              {Role::normal, "N.png"},
                              {Role::height, "H.png"}}) {
        mv::MapInput m;
        m.role = role;
        m.name = name;
        m.file.display = name;
        m.info = {W, H, (role == Role::albedo || role == Role::normal) ? 3 : 1, 8, false, "memory", {}};
        maps.push_back(m);
    }
    mv::ValidateOptions opt;
    opt.reader = gen;
    const long before = max_rss_kb();
    const auto t0 = std::chrono::steady_clock::now();
    const auto res = mv::validate_set(maps, {}, opt);
    const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const long grown_mb = (max_rss_kb() - before) / 1024;
    std::printf("[ 8K set ] 4 maps of 8192x8192 in %.1f s, peak memory grew by %ld MB "
                "(one 8K RGB float map would be 768 MB)\n",
                secs, grown_mb);
    EXPECT_LT(grown_mb, 200);
    EXPECT_TRUE(has_code(res.findings, mf::code::metal_albedo_too_dark)) << dump(res.findings);
}
