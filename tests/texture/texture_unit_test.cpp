// Mip chains, block codecs, containers and preset fields of lib/texture, on images made here.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "base/srgb.hpp"
#include "core/json.hpp"
#include "engine/gltf.hpp"
#include "image/image.hpp"
#include "preset/preset.hpp"
#include "preset/texture_fields.hpp"
#include "test_env.hpp"
#include "texture/texture.hpp"

namespace mt = mf::texture;
using mf::Image8;

namespace {

Image8 make(int w, int h, int c, const std::function<std::array<uint8_t, 4>(int, int)>& f) {
    Image8 img(w, h, c);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const auto v = f(x, y);
            for (int k = 0; k < c; ++k) img.at(x, y, k) = v[static_cast<size_t>(k)];
        }
    return img;
}

uint8_t code(double v) { return static_cast<uint8_t>(std::lround(std::clamp(v, 0.0, 1.0) * 255.0)); }

const mf::BlockFormatInfo& block_format(const char* name) { return *mf::block_format_info(name); }

// A smooth, textured image: what block codecs meet in material maps.
Image8 smooth(int w, int h, int c) {
    return make(w, h, c, [&](int x, int y) {
        const double u = x / double(w), v = y / double(h);
        return std::array<uint8_t, 4>{code(0.5 + 0.4 * std::sin(6.0 * u + 2 * v)), code(0.3 + 0.5 * u * v),
                                      code(0.5 + 0.3 * std::cos(5.0 * v)), code(0.2 + 0.7 * u)};
    });
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Mips

TEST(Mips, ChainRunsToOnePixelAtEveryShape) {
    EXPECT_EQ(mt::mip_count(1024, 1024), 11);
    EXPECT_EQ(mt::mip_count(1024, 256), 11);
    EXPECT_EQ(mt::mip_count(6, 5), 3);
    EXPECT_EQ(mt::mip_count(1, 1), 1);
    const auto chain = mt::make_mips(smooth(12, 5, 1), {mt::ChannelKind::data}, {});
    ASSERT_EQ(chain.size(), 4u);
    const std::vector<std::pair<int, int>> sizes{{12, 5}, {6, 2}, {3, 1}, {1, 1}};
    for (size_t i = 0; i < chain.size(); ++i) {
        EXPECT_EQ(chain[i].width, sizes[i].first) << i;
        EXPECT_EQ(chain[i].height, sizes[i].second) << i;
    }
}

TEST(Mips, ColorIsFilteredInLinearLight) {
    // A 1-texel checker of sRGB black and white: its average light is 0.5 linear, sRGB code
    // 188; averaging the encoded values would give 128 (the gamma error).
    const Image8 checker = make(8, 8, 3, [](int x, int y) {
        const uint8_t v = (x + y) % 2 ? 255 : 0;
        return std::array<uint8_t, 4>{v, v, v, 0};
    });
    for (const auto filter : {mf::MipFilter::box, mf::MipFilter::kaiser}) {
        mt::MipOptions o;
        o.filter = filter;
        const auto srgb = mt::make_mips(checker, std::vector<mt::ChannelKind>(3, mt::ChannelKind::srgb_color), o);
        const auto data = mt::make_mips(checker, std::vector<mt::ChannelKind>(3, mt::ChannelKind::data), o);
        EXPECT_NEAR(srgb[1].at(1, 1, 0), 188, 1);
        EXPECT_NEAR(data[1].at(1, 1, 0), 128, 1);
        EXPECT_NEAR(srgb.back().at(0, 0, 2), 188, 1);
    }
}

TEST(Mips, ConstantsStayConstantAndBoxIsTheMean) {
    const Image8 flat = make(16, 16, 2, [](int, int) { return std::array<uint8_t, 4>{77, 200, 0, 0}; });
    for (const auto& level : mt::make_mips(flat, {mt::ChannelKind::data, mt::ChannelKind::data}, {}))
        for (int y = 0; y < level.height; ++y)
            for (int x = 0; x < level.width; ++x) {
                ASSERT_EQ(level.at(x, y, 0), 77);
                ASSERT_EQ(level.at(x, y, 1), 200);
            }
    const Image8 ramp = make(4, 2, 1, [](int x, int y) {
        return std::array<uint8_t, 4>{uint8_t(x * 40 + y * 20), 0, 0, 0};
    });
    mt::MipOptions box;
    box.filter = mf::MipFilter::box;
    const auto chain = mt::make_mips(ramp, {mt::ChannelKind::data}, box);
    EXPECT_EQ(chain[1].at(0, 0), 30);   // (0 + 40 + 20 + 60) / 4
    EXPECT_EQ(chain[1].at(1, 0), 110);  // (80 + 120 + 100 + 140) / 4
}

TEST(Mips, NormalsAreUnitAtEveryLevel) {
    std::mt19937 rng(7);
    std::normal_distribution<double> n(0.0, 0.6);
    const Image8 bumpy = make(64, 64, 3, [&](int, int) {
        double x = n(rng), y = n(rng), z = 1.0;
        const double len = std::sqrt(x * x + y * y + z * z);
        return std::array<uint8_t, 4>{code(x / len * 0.5 + 0.5), code(y / len * 0.5 + 0.5), code(z / len * 0.5 + 0.5),
                                      0};
    });
    const auto chain = mt::make_mips(bumpy, std::vector<mt::ChannelKind>(3, mt::ChannelKind::normal), {});
    for (size_t l = 1; l < chain.size(); ++l)
        for (int y = 0; y < chain[l].height; ++y)
            for (int x = 0; x < chain[l].width; ++x) {
                double len2 = 0;
                for (int k = 0; k < 3; ++k) len2 += std::pow(chain[l].at(x, y, k) / 127.5 - 1.0, 2);
                ASSERT_NEAR(std::sqrt(len2), 1.0, 0.012) << "level " << l;  // 8-bit quantization only
            }
}

TEST(Mips, AlphaTestCoverageIsKept) {
    // Foliage-like cutout: thin random strokes, 30 % covered. Plain filtering loses coverage
    // at the alpha test (averages of 0 and 1 fall under 0.5); the scaled levels keep it.
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    Image8 alpha(256, 256, 1);
    for (int s = 0; s < 260; ++s) {
        const double x0 = u(rng) * 256, y0 = u(rng) * 256, a = u(rng) * 6.3;
        for (int t = 0; t < 40; ++t) {
            const int x = static_cast<int>(x0 + t * std::cos(a)) & 255,
                      y = static_cast<int>(y0 + t * std::sin(a)) & 255;
            alpha.at(x, y) = 255;
        }
    }
    const double c0 = mt::alpha_coverage(alpha, 0, 0.5f);
    ASSERT_GT(c0, 0.1);
    const auto kept = mt::make_mips(alpha, {mt::ChannelKind::alpha_tested}, {});
    const auto plain = mt::make_mips(alpha, {mt::ChannelKind::data}, {});
    for (size_t l = 1; l + 3 < kept.size(); ++l) {  // down to 16x16
        EXPECT_NEAR(mt::alpha_coverage(kept[l], 0, 0.5f), c0, 0.02) << "level " << l;
    }
    EXPECT_LT(mt::alpha_coverage(plain[3], 0, 0.5f), 0.6 * c0);  // what the scaling fixes
}

TEST(Mips, HiddenTexelsTakeTheNearestShownColour) {
    using K = mt::ChannelKind;
    const std::vector<K> kinds{K::srgb_color, K::srgb_color, K::srgb_color, K::alpha_tested};
    // 16 x 4, wrapping: shown red at x = 2, shown blue at x = 12, the rest hidden and black.
    const Image8 src = make(16, 4, 4, [](int x, int) {
        return x == 2    ? std::array<uint8_t, 4>{255, 0, 0, 255}
               : x == 12 ? std::array<uint8_t, 4>{0, 0, 255, 200}
                         : std::array<uint8_t, 4>{0, 0, 0, 100};  // under a 0.5 cutoff: 128 is the first code shown
    });
    Image8 img = src;
    EXPECT_EQ(mt::dilate_under_alpha(img, kinds, 3, 128), 14u * 4);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 16; ++x) {
            SCOPED_TRACE("x " + std::to_string(x));
            EXPECT_EQ(img.at(x, y, 3), src.at(x, y, 3)) << "alpha is left as it is";
            const int to_red = std::min((x - 2 + 16) % 16, (2 - x + 16) % 16);
            const int to_blue = std::min((x - 12 + 16) % 16, (12 - x + 16) % 16);
            if (to_red < to_blue) {
                EXPECT_EQ(img.at(x, y, 0), 255);
                EXPECT_EQ(img.at(x, y, 2), 0);
            } else if (to_blue < to_red) {
                EXPECT_EQ(img.at(x, y, 0), 0);
                EXPECT_EQ(img.at(x, y, 2), 255);
            } else {  // x = 7 (and 15, across the wrap): halfway, the mean in linear light
                EXPECT_EQ(img.at(x, y, 0), 188) << "sRGB 188 is linear 0.5";
                EXPECT_EQ(img.at(x, y, 2), 188);
            }
        }
    // A blend shows every texel above alpha 0 (shown_from 1): nothing is hidden here.
    img = src;
    EXPECT_EQ(mt::dilate_under_alpha(img, kinds, 3, 1), 0u);
    EXPECT_EQ(img.pixels, src.pixels);
    // Nothing shown: nothing to take a colour from.
    Image8 hidden = src;
    for (size_t p = 3; p < hidden.pixels.size(); p += 4) hidden.pixels[p] = 0;
    img = hidden;
    EXPECT_EQ(mt::dilate_under_alpha(img, kinds, 3, 128), 0u);
    EXPECT_EQ(img.pixels, hidden.pixels);
    // Data channels (a linear packed map) are averaged as stored.
    const std::vector<K> data{K::data, K::data, K::data, K::alpha_tested};
    img = src;
    mt::dilate_under_alpha(img, data, 3, 128);
    EXPECT_EQ(img.at(7, 0, 0), 128);
    EXPECT_EQ(img.at(7, 0, 2), 128);
}

TEST(Mips, ToksvigWidensRoughnessWhereNormalsSpread) {
    // Level-0 normals alternating between two tilted directions: the footprint's average is
    // short, so the level's roughness grows; flat normals leave it alone.
    const int w = 16;
    mf::Image tilted(w, w, 3), flat(w, w, 3);
    for (int y = 0; y < w; ++y)
        for (int x = 0; x < w; ++x) {
            const float s = (x + y) % 2 ? 0.6f : -0.6f;
            tilted.at(x, y, 0) = s, tilted.at(x, y, 1) = 0.f, tilted.at(x, y, 2) = 0.8f;
            flat.at(x, y, 2) = 1.f;
        }
    const Image8 rough = make(w, w, 1, [](int, int) { return std::array<uint8_t, 4>{code(0.3), 0, 0, 0}; });
    mt::MipOptions o;
    o.filter = mf::MipFilter::box;
    o.roughness_channel = 0;
    o.normals = &tilted;
    const auto widened = mt::make_mips(rough, {mt::ChannelKind::data}, o);
    // |n| = 0.8: alpha^2 = 0.3^4 + 2 * 0.2 / 0.8 = 0.5081 -> r = 0.8443
    EXPECT_NEAR(widened[1].at(0, 0) / 255.0, 0.8443, 0.003);
    o.normals = &flat;
    EXPECT_EQ(mt::make_mips(rough, {mt::ChannelKind::data}, o)[1].at(0, 0), code(0.3));
}

TEST(Mips, OpacityUseIsClassified) {
    mf::Image a(10, 10, 1, 1.f);
    EXPECT_EQ(mt::classify_opacity(a), mt::AlphaUse::opaque);
    for (int i = 0; i < 40; ++i) a.pixels[static_cast<size_t>(i)] = 0.f;
    EXPECT_EQ(mt::classify_opacity(a), mt::AlphaUse::cutout);
    for (int i = 0; i < 40; ++i) a.pixels[static_cast<size_t>(i)] = 0.5f;
    EXPECT_EQ(mt::classify_opacity(a), mt::AlphaUse::blend);
}

// ---------------------------------------------------------------------------------------------
// Codecs

struct CodecCase {
    const char* format;
    int channels;
    bool srgb;
    double min_psnr;
};

class Codec : public ::testing::TestWithParam<CodecCase> {};

TEST_P(Codec, RoundTripsSmoothContent) {
    const CodecCase c = GetParam();
    const Image8 img = smooth(64, 48, c.channels);
    for (const auto effort : {mf::Effort::fast, mf::Effort::normal}) {
        mt::CodecOptions o;
        o.format = &block_format(c.format);
        o.srgb = c.srgb;
        o.effort = effort;
        std::vector<uint8_t> blocks;
        std::string err;
        ASSERT_TRUE(mt::encode_level(img, o, blocks, err)) << err;
        EXPECT_EQ(blocks.size(), mt::level_bytes(*o.format, 64, 48));
        Image8 back;
        ASSERT_TRUE(mt::decode_level(blocks, 64, 48, o, back, err)) << err;
        EXPECT_GT(mt::psnr(img, back, std::min(c.channels, o.format->channels)), c.min_psnr) << c.format;
        // A wrong channel order or a decoder of another format is far off.
        EXPECT_LT(mt::psnr(img, back, std::min(c.channels, o.format->channels)), 100.0);
        // Threads share the work, never change the blocks.
        o.threads = 3;
        std::vector<uint8_t> threaded;
        ASSERT_TRUE(mt::encode_level(img, o, threaded, err)) << err;
        EXPECT_EQ(threaded, blocks) << c.format << " on 3 threads";
    }
}

INSTANTIATE_TEST_SUITE_P(Formats, Codec,
                         ::testing::Values(CodecCase{"bc1", 3, true, 36}, CodecCase{"bc3", 4, true, 36},
                                           CodecCase{"bc4", 1, false, 40}, CodecCase{"bc5", 2, false, 40},
                                           CodecCase{"astc-4x4", 4, false, 40}, CodecCase{"astc-6x6", 3, true, 36},
                                           CodecCase{"astc-8x8", 1, false, 34}),
                         [](const ::testing::TestParamInfo<CodecCase>& param_info) {
                             std::string n = param_info.param.format;
                             std::replace(n.begin(), n.end(), '-', '_');
                             return n;
                         });

// BC1's encoders by effort (lib/texture/codec.cpp's choice), on a crop of a real photograph,
// where libsquish's cluster fit is 50-100x slower than on smooth content: `normal` (stb_dxt,
// two refinements) is within 1 dB of `thorough` (squish's cluster fit) and above `fast`
// (one refinement); BC3's colour half is the same encoder's, its alpha squish's at every effort.
TEST(Codec, Bc1EffortsOnAPhotograph) {
    mf::InputFile in;
    in.path = mf::testenv::corpus_dir() / "real/polyhaven_brown_planks_09_1k_jpg+webp/brown_planks_09_diff_1k.jpg";
    mf::Decoded d;
    mf::ImageInfo info;
    std::string err;
    ASSERT_TRUE(mf::read_image(in, d, info, err)) << err;
    ASSERT_TRUE(d.is_codes());
    ASSERT_EQ(d.channels(), 3);
    // 256x256 from the middle, with an alpha ramp for BC3.
    const Image8 crop = make(256, 256, 4, [&](int x, int y) {
        const uint8_t* p = &d.codes.pixels[d.codes.index(384 + x, 384 + y)];
        return std::array<uint8_t, 4>{p[0], p[1], p[2], static_cast<uint8_t>(x)};
    });
    Image8 rgb(256, 256, 3);
    for (size_t p = 0; p < 256u * 256u; ++p) std::memcpy(&rgb.pixels[p * 3], &crop.pixels[p * 4], 3);
    auto encode = [&](const Image8& img, const char* format, mf::Effort effort, std::vector<uint8_t>& blocks) {
        mt::CodecOptions o;
        o.format = &block_format(format);
        o.srgb = true;
        o.effort = effort;
        EXPECT_TRUE(mt::encode_level(img, o, blocks, err)) << err;
        Image8 back;
        EXPECT_TRUE(mt::decode_level(blocks, img.width, img.height, o, back, err)) << err;
        return mt::psnr(img, back, 3);
    };
    std::vector<uint8_t> bc1_fast, bc1_normal, bc1_thorough, bc3_normal, bc3_thorough;
    const double fast = encode(rgb, "bc1", mf::Effort::fast, bc1_fast);
    const double normal = encode(rgb, "bc1", mf::Effort::normal, bc1_normal);
    const double thorough = encode(rgb, "bc1", mf::Effort::thorough, bc1_thorough);
    EXPECT_GT(fast, 38.0);  // measured 40.41 / 40.55 / 41.19 dB
    EXPECT_GT(normal, fast);
    EXPECT_GT(thorough, normal);
    EXPECT_LT(thorough - normal, 1.0);
    EXPECT_DOUBLE_EQ(encode(crop, "bc3", mf::Effort::normal, bc3_normal), normal);
    encode(crop, "bc3", mf::Effort::thorough, bc3_thorough);
    for (size_t b = 0; b < bc1_normal.size() / 8; ++b) {
        ASSERT_EQ(0, std::memcmp(&bc3_normal[b * 16 + 8], &bc1_normal[b * 8], 8)) << "colour half of block " << b;
        ASSERT_EQ(0, std::memcmp(&bc3_normal[b * 16], &bc3_thorough[b * 16], 8)) << "alpha half of block " << b;
    }
}

TEST(Codec, Bc4AndBc5DecodeToTheRightChannels) {
    // Flat blocks: exact values, R from X and G from Y, as a GPU returns them (B 0, A 1).
    const Image8 xy = make(8, 4, 2, [](int, int) { return std::array<uint8_t, 4>{40, 210, 0, 0}; });
    mt::CodecOptions o;
    o.format = &block_format("bc5");
    std::vector<uint8_t> blocks;
    std::string err;
    ASSERT_TRUE(mt::encode_level(xy, o, blocks, err)) << err;
    Image8 back;
    ASSERT_TRUE(mt::decode_level(blocks, 8, 4, o, back, err)) << err;
    EXPECT_EQ(back.at(5, 2, 0), 40);
    EXPECT_EQ(back.at(5, 2, 1), 210);
    EXPECT_EQ(back.at(5, 2, 2), 0);
    EXPECT_EQ(back.at(5, 2, 3), 255);
    o.format = &block_format("bc4");
    const Image8 r = make(5, 3, 1, [](int, int) { return std::array<uint8_t, 4>{123, 0, 0, 0}; });
    ASSERT_TRUE(mt::encode_level(r, o, blocks, err)) << err;
    ASSERT_TRUE(mt::decode_level(blocks, 5, 3, o, back, err)) << err;
    EXPECT_EQ(back.width, 5);
    EXPECT_EQ(back.at(4, 2, 0), 123);
    EXPECT_EQ(back.at(4, 2, 1), 0);
}

TEST(Codec, BcDecodeRoundsAsTheSpecs) {
    // Endpoints are r / 31 and g / 63 rounded to 8 bits (r = 28: 230, not the bit-replicated
    // 231), interpolants rounded: 2/3 c0 + 1/3 c1 of g 69 and 8 is 49 (48.67), not 48.
    // c0 = (28, 17, 20), c1 = (1, 2, 1); texels 0..3 take indices 0..3.
    const std::array<uint8_t, 8> bc1{0x34, 0xE2, 0x41, 0x08, 0xE4, 0xE4, 0xE4, 0xE4};
    mt::CodecOptions o;
    o.format = &block_format("bc1");
    Image8 back;
    std::string err;
    ASSERT_TRUE(mt::decode_level(bc1, 4, 4, o, back, err)) << err;
    EXPECT_EQ(back.at(0, 0, 0), 230);
    EXPECT_EQ(back.at(0, 0, 1), 69);
    EXPECT_EQ(back.at(0, 0, 2), 165);
    EXPECT_EQ(back.at(1, 0, 0), 8);
    EXPECT_EQ(back.at(2, 0, 1), 49);   // (2 * 69 + 8 + 1) / 3
    EXPECT_EQ(back.at(3, 0, 1), 28);   // (69 + 2 * 8 + 1) / 3
    EXPECT_EQ(back.at(2, 0, 0), 156);  // (2 * 230 + 8 + 1) / 3 = 156.3
    // BC4 of a0 = 8, a1 = 0: 6/7 a0 + 1/7 a1 (index 2, texel 1) is 7 (6.86; truncated 6),
    // 1/7 a0 + 6/7 a1 (index 7, texel 15) is 1.
    const std::array<uint8_t, 8> bc4{8, 0, 0x10, 0, 0, 0, 0, 0xE0};
    o.format = &block_format("bc4");
    ASSERT_TRUE(mt::decode_level(bc4, 4, 4, o, back, err)) << err;
    EXPECT_EQ(back.at(0, 0, 0), 8);
    EXPECT_EQ(back.at(1, 0, 0), 7);
    EXPECT_EQ(back.at(2, 0, 0), 8);
    EXPECT_EQ(back.at(3, 3, 0), 1);
}

TEST(Codec, NormalXyRebuildsZForTheAngle) {
    // A tilted normal field in BC5 (X, Y only): the angle against the RGB source stays small;
    // read as RGB with Z = 0 (the decoded B) it would be about 60 degrees off.
    const Image8 n = make(16, 16, 3, [](int x, int) {
        const double a = 0.02 * x, nx = std::sin(a), nz = std::cos(a);
        return std::array<uint8_t, 4>{code(nx * 0.5 + 0.5), code(0.5), code(nz * 0.5 + 0.5), 0};
    });
    mt::CodecOptions o;
    o.format = &block_format("bc5");
    o.normal_xy = true;
    std::vector<uint8_t> blocks;
    std::string err;
    ASSERT_TRUE(mt::encode_level(n, o, blocks, err)) << err;
    Image8 back;
    ASSERT_TRUE(mt::decode_level(blocks, 16, 16, o, back, err)) << err;
    const auto a = mt::normal_angle_error(n, back, true);
    EXPECT_LT(a.mean_deg, 1.0);
    EXPECT_GT(mt::normal_angle_error(n, back, false).mean_deg, 40.0);
}

TEST(Metrics, PsnrAndAngles) {
    const Image8 a = make(4, 4, 1, [](int, int) { return std::array<uint8_t, 4>{100, 0, 0, 0}; });
    Image8 b = a;
    EXPECT_EQ(mt::psnr(a, b, 1), 100.0);
    b.at(0, 0) = 116;  // MSE 256/16 = 16: 10 log10(65025 / 16) = 36.09 dB
    EXPECT_NEAR(mt::psnr(a, b, 1), 36.0896, 1e-3);
    const Image8 up = make(2, 1, 3, [](int, int) { return std::array<uint8_t, 4>{128, 128, 255, 0}; });
    const Image8 side = make(2, 1, 4, [](int, int) { return std::array<uint8_t, 4>{255, 128, 128, 255}; });
    EXPECT_NEAR(mt::normal_angle_error(up, side, false).max_deg, 90.0, 0.5);
}

// ---------------------------------------------------------------------------------------------
// Containers

namespace {

mt::GpuTexture texture_of(const char* format, bool srgb, int w, int h) {
    mt::GpuTexture t;
    t.format = &block_format(format);
    t.srgb = srgb;
    for (int i = 0; i < mt::mip_count(w, h); ++i) {
        const int lw = std::max(1, w >> i), lh = std::max(1, h >> i);
        mt::Level l{lw, lh, std::vector<uint8_t>(mt::level_bytes(*t.format, lw, lh))};
        for (size_t k = 0; k < l.data.size(); ++k) l.data[k] = static_cast<uint8_t>(k * 7 + static_cast<size_t>(i));
        t.levels.push_back(std::move(l));
    }
    return t;
}

uint32_t u32(const std::vector<uint8_t>& b, size_t at) {
    uint32_t v;
    std::memcpy(&v, b.data() + at, 4);
    return v;
}
uint64_t u64(const std::vector<uint8_t>& b, size_t at) {
    uint64_t v;
    std::memcpy(&v, b.data() + at, 8);
    return v;
}

}  // namespace

TEST(Dds, HeaderFollowsTheProgrammingGuide) {
    const mt::GpuTexture t = texture_of("bc1", true, 64, 32);
    const auto b = mt::write_dds(t);
    EXPECT_EQ(u32(b, 0), 0x20534444u);  // "DDS "
    EXPECT_EQ(u32(b, 4), 124u);         // dwSize
    EXPECT_EQ(u32(b, 8),
              0x1u | 0x2 | 0x4 | 0x1000 | 0x20000 | 0x80000);  // caps height width pixelformat mipmapcount linearsize
    EXPECT_EQ(u32(b, 12), 32u);                                // height
    EXPECT_EQ(u32(b, 16), 64u);                                // width
    EXPECT_EQ(u32(b, 20), 64u / 4 * 32 / 4 * 8);               // linear size of level 0
    EXPECT_EQ(u32(b, 28), 7u);                                 // mip count
    EXPECT_EQ(u32(b, 76), 32u);                                // pixel format size
    EXPECT_EQ(u32(b, 80), 0x4u);                               // DDPF_FOURCC
    EXPECT_EQ(u32(b, 84), 0x30315844u);                        // "DX10"
    EXPECT_EQ(u32(b, 108), 0x1000u | 0x8 | 0x400000);          // texture complex mipmap
    EXPECT_EQ(u32(b, 128), 72u);                               // DXGI_FORMAT_BC1_UNORM_SRGB
    EXPECT_EQ(u32(b, 132), 3u);                                // TEXTURE2D
    EXPECT_EQ(u32(b, 140), 1u);                                // arraySize
    size_t data = 0;
    for (const auto& l : t.levels) data += l.data.size();
    EXPECT_EQ(b.size(), 148 + data);
    mt::GpuTexture back;
    std::string err;
    ASSERT_TRUE(mt::read_dds(b, back, err)) << err;
    EXPECT_EQ(back.format->name, "bc1");
    EXPECT_TRUE(back.srgb);
    ASSERT_EQ(back.levels.size(), t.levels.size());
    for (size_t i = 0; i < t.levels.size(); ++i) EXPECT_EQ(back.levels[i].data, t.levels[i].data) << i;
    EXPECT_EQ(mt::dxgi_format_name(texture_of("bc5", false, 4, 4)), "DXGI_FORMAT_BC5_UNORM");
    EXPECT_EQ(mt::dxgi_format(texture_of("bc4", false, 4, 4)), 80u);
    EXPECT_EQ(mt::dxgi_format(texture_of("bc3", true, 4, 4)), 78u);
}

TEST(Ktx2, LevelsSmallestFirstAlignedAndZstdRoundTrips) {
    for (const bool zstd : {false, true}) {
        const mt::GpuTexture t = texture_of("bc3", true, 40, 24);
        std::vector<uint8_t> b;
        std::string err;
        ASSERT_TRUE(mt::write_ktx2(t, {zstd, 19, "matforge test"}, b, err)) << err;
        const uint8_t id[12] = {0xAB, 'K', 'T', 'X', ' ', '2', '0', 0xBB, '\r', '\n', 0x1A, '\n'};
        EXPECT_EQ(std::memcmp(b.data(), id, 12), 0);
        EXPECT_EQ(u32(b, 12), 138u);  // VK_FORMAT_BC3_SRGB_BLOCK
        EXPECT_EQ(u32(b, 16), 1u);    // typeSize
        EXPECT_EQ(u32(b, 40), 6u);    // levelCount: 40x24 .. 1x1
        EXPECT_EQ(u32(b, 44), zstd ? 2u : 0u);
        uint64_t previous_offset = ~uint64_t{0};
        for (size_t i = 0; i < 6; ++i) {
            const uint64_t off = u64(b, 80 + 24 * i), len = u64(b, 88 + 24 * i), raw = u64(b, 96 + 24 * i);
            EXPECT_EQ(raw, t.levels[i].data.size());
            if (!zstd) {
                EXPECT_EQ(off % 16, 0u) << "level " << i << ": lcm(16, 4) alignment";
                EXPECT_EQ(len, raw);
            }
            EXPECT_LT(off, previous_offset) << "level " << i << " is stored after level " << i + 1;
            previous_offset = off;
        }
        mt::GpuTexture back;
        ASSERT_TRUE(mt::read_ktx2(b, back, err)) << err;
        ASSERT_EQ(back.levels.size(), 6u);
        for (size_t i = 0; i < 6; ++i) EXPECT_EQ(back.levels[i].data, t.levels[i].data) << i;
        EXPECT_TRUE(back.srgb);
    }
}

TEST(Ktx2, ReadRefusesDamage) {
    const mt::GpuTexture t = texture_of("bc4", false, 16, 16);
    std::vector<uint8_t> b;
    std::string err;
    ASSERT_TRUE(mt::write_ktx2(t, {true, 3, "x"}, b, err)) << err;
    mt::GpuTexture back;
    std::vector<uint8_t> cut(b.begin(), b.begin() + static_cast<std::ptrdiff_t>(b.size() - 3));
    EXPECT_FALSE(mt::read_ktx2(cut, back, err));
    std::vector<uint8_t> bad = b;
    bad[0] = 'X';
    EXPECT_FALSE(mt::read_ktx2(bad, back, err));
    EXPECT_NE(err.find("KTX"), std::string::npos);
}

// ---------------------------------------------------------------------------------------------
// Preset fields: impossible requests are errors naming the field

namespace {

std::string preset_error(const std::string& format, const std::string& outputs, const std::string& extra = "") {
    const std::string text = R"({"name": "t", "format": ")" + format + "\", " + extra + R"( "outputs": [)" + outputs +
                             "]}";
    std::string error;
    const auto j = mf::parse_json(text, "preset", error);
    EXPECT_TRUE(j) << error;
    mf::Preset p;
    return mf::parse_preset(*j, p, error) ? "" : error;
}

const std::string kAlbedo = R"({"suffix": "c", "color_space": "srgb", "channels": {"RGB": "albedo"})";

}  // namespace

TEST(PresetFields, ImpossibleFormatsNameTheField) {
    EXPECT_EQ(preset_error("dds", kAlbedo + R"(, "block_format": "bc1"})", R"("mips": true,)"), "");
    auto has = [](const std::string& error, const std::string& what) {
        EXPECT_NE(error.find(what), std::string::npos) << error;
    };
    has(preset_error("dds", kAlbedo + R"(, "block_format": "bc5"})"),
        "outputs[0] ('c'): block_format: bc5 has no sRGB variant");
    has(preset_error("ktx2", R"({"suffix": "c", "channels": {"RGB": "albedo"}, "block_format": "bc5"})"),
        "outputs[0] ('c'): block_format: bc5 stores 2 channels; this output writes 3 (RGB albedo)");
    has(preset_error("ktx2", kAlbedo + R"(, "block_format": "astc-hdr-6x6"})"),
        "outputs[0] ('c'): block_format: astc-hdr-6x6 encodes float (HDR) samples; this output is 8-bit");
    has(preset_error("dds", kAlbedo + R"(, "block_format": "astc-6x6"})"), "block_format: astc-6x6 has no DXGI format");
    has(preset_error("dds", kAlbedo + R"(, "block_format": "bc9"})"), "block_format: unknown block format 'bc9'");
    has(preset_error("dds", kAlbedo + "}"), "outputs[0] ('c'): block_format: required with format dds");
    has(preset_error("png", kAlbedo + R"(, "block_format": "bc1"})"), "block_format: needs format dds or ktx2");
    has(preset_error("png", kAlbedo + "}", R"("mips": true,)"), "mips: needs format dds or ktx2");
    has(preset_error("ktx2",
                     R"({"suffix": "r", "channels": {"R": "roughness", "G": "metalness"}, "block_format": "bc4"})"),
        "block_format: bc4 stores 1 channel; this output writes 2 (R roughness, G metalness)");
    has(preset_error(
            "ktx2",
            R"({"suffix": "c", "color_space": "srgb", "channels": {"RGB": "albedo", "A": "opacity"}, "block_format": "bc1"})"),
        "bc1 stores 3 channels; this output writes 4 (RGB albedo, A opacity): set block_format_alpha");
    has(preset_error("dds", kAlbedo + R"(, "block_format": "bc1"})", R"("supercompression": "zstd",)"),
        "supercompression: zstd is a KTX2 scheme");
    has(preset_error("dds", kAlbedo + R"(, "block_format": "bc1"})", R"("constant_size": 2,)"), "constant_size");
    has(preset_error("png", kAlbedo + "}", R"("material_file": "gltf",)"),
        "metallicRoughnessTexture needs an output with roughness in G, metalness in B (linear)");
}

// The glTF's slots are checked at load from the same table its writer iterates
// (preset/engine_slots.cpp): one ORM may serve occlusionTexture and metallicRoughnessTexture, an
// output no slot reads is written beside the material, and everything the material cannot read
// as the preset writes it is refused, naming the slot.
TEST(PresetFields, GltfLayoutIsCheckedFromTheSlotTable) {
    const std::string gltf = R"("material_file": "gltf",)";
    const std::string orm = R"({"suffix": "orm", "channels": {"R": "occlusion", "G": "roughness", "B": "metalness"}})";
    const std::string height = R"({"suffix": "h", "channels": {"R": "height"}})";
    EXPECT_EQ(preset_error("png", kAlbedo + "}," + orm, gltf), "");
    EXPECT_EQ(preset_error("png", kAlbedo + "}," + orm + "," + height, gltf), "");
    auto has = [](const std::string& error, const std::string& what) {
        EXPECT_NE(error.find(what), std::string::npos) << error;
    };
    has(preset_error("tga", kAlbedo + "}," + orm, gltf), "it imports png; this preset writes tga");
    has(preset_error("png", kAlbedo + "}," + orm, gltf + R"("normal_convention": "dx",)"),
        "its normal slot reads gl normals; this preset's normal_convention is dx");
    // Smoothness is not roughness: metallicRoughnessTexture has nothing to read.
    has(preset_error("png",
                     kAlbedo + R"(}, {"suffix": "m", "channels": {"R": 1.0, "G": "smoothness", "B": "metalness"}})",
                     gltf),
        "metallicRoughnessTexture needs an output with roughness in G, metalness in B");
    // Roughness and metalness in two textures: the slot reads one.
    has(preset_error("png", kAlbedo + R"(}, {"suffix": "r", "channels": {"R": 1.0, "G": "roughness"}},
                     {"suffix": "m", "channels": {"R": 1.0, "G": 1.0, "B": "metalness"}})",
                     gltf),
        "metallicRoughnessTexture reads one texture; 'r' and 'm' both go there");
    has(preset_error("png", kAlbedo + R"(}, {"suffix": "o", "channels": {"R": "opacity"}},)" + orm, gltf),
        "'o' holds opacity in R; baseColorTexture reads it from A as sRGB");
    has(preset_error("png",
                     kAlbedo + "}," + orm +
                         R"(, {"suffix": "n", "color_space": "srgb", "channels": {"RGB": "normal"}})",
                     gltf),
        "'n' holds normal in RGB; normalTexture reads it from RGB as linear data");
    has(preset_error("png", R"({"suffix": "c", "channels": {"RGB": "albedo"}},)" + orm, gltf),
        "'c' holds albedo in RGB; baseColorTexture reads it from RGB as sRGB");
    // BC5 takes the RGB normal (X, Y stored).
    EXPECT_EQ(preset_error("ktx2", R"({"suffix": "n", "channels": {"RGB": "normal"}, "block_format": "bc5"})"), "");
}

// The vocabulary is typed once at load: each word reads back as its enumerator, anything else
// is refused naming the field and every word, and the typed fields reach the preset.
TEST(PresetFields, VocabularyIsTypedOnceAtLoad) {
    auto round_trip = [](auto e) { EXPECT_EQ(mf::from_word<decltype(e)>(mf::word(e)), e) << mf::word(e); };
    for (auto f : {mf::FileFormat::png, mf::FileFormat::exr, mf::FileFormat::tif, mf::FileFormat::tga,
                   mf::FileFormat::dds, mf::FileFormat::ktx2})
        round_trip(f);
    for (auto e : {mf::Effort::fast, mf::Effort::normal, mf::Effort::thorough}) round_trip(e);
    round_trip(mf::MipFilter::box), round_trip(mf::MipFilter::kaiser);
    round_trip(mf::Supercompression::zstd), round_trip(mf::MaterialFileKind::gltf);
    round_trip(mf::MaterialFileKind::unity_hdrp), round_trip(mf::MaterialFileKind::d3d11);
    EXPECT_FALSE(mf::from_word<mf::FileFormat>("PNG"));
    EXPECT_FALSE(mf::from_word<mf::Effort>(""));
    EXPECT_EQ(mf::word_list<mf::FileFormat>(), "png, exr, tif, tga, dds or ktx2");
    EXPECT_EQ(mf::word_list<mf::MipFilter>(), "box or kaiser");
    auto has = [](const std::string& error, const std::string& what) {
        EXPECT_NE(error.find(what), std::string::npos) << error;
    };
    has(preset_error("webp", kAlbedo + "}"), "format must be png, exr, tif, tga, dds or ktx2");
    const std::string bc1 = kAlbedo + R"(, "block_format": "bc1")";
    has(preset_error("dds", bc1 + "}", R"("mips": true, "mip_filter": "lanczos",)"),
        "mip_filter must be box or kaiser");
    has(preset_error("dds", bc1 + "}", R"("effort": 3,)"), "effort must be fast, normal or thorough");
    has(preset_error("dds", bc1 + R"(, "effort": "max"})"),
        "outputs[0] ('c'): effort must be fast, normal or thorough");
    has(preset_error("ktx2", bc1 + "}", R"("supercompression": "lz4",)"), "supercompression must be none or zstd");
    has(preset_error("png", kAlbedo + "}", R"("material_file": "usd",)"),
        "material_file must be none, gltf, godot, unity-hdrp, unity-urp, unreal or d3d11");
    has(preset_error("dds", kAlbedo + R"(, "block_format": 1})"), "unknown block format 1");
    const std::string text = R"({"name": "t", "format": "ktx2", "mips": true, "mip_filter": "box", "effort": "fast",
        "supercompression": "zstd", "outputs": [)" +
                             kAlbedo + R"(, "block_format": "bc1", "effort": "thorough"},
        {"suffix": "o", "color_space": "srgb", "channels": {"RGB": "albedo", "A": "opacity"}, "block_format": "bc1",
         "block_format_alpha": "bc3"}]})";
    std::string error;
    const auto j = mf::parse_json(text, "preset", error);
    ASSERT_TRUE(j) << error;
    mf::Preset p;
    ASSERT_TRUE(mf::parse_preset(*j, p, error)) << error;
    EXPECT_EQ(p.format, mf::FileFormat::ktx2);
    EXPECT_EQ(p.mip_filter, mf::MipFilter::box);
    EXPECT_EQ(p.effort, mf::Effort::fast);
    EXPECT_EQ(p.supercompression, mf::Supercompression::zstd);
    EXPECT_EQ(p.material_file, mf::MaterialFileKind::none);
    ASSERT_EQ(p.outputs.size(), 2u);
    EXPECT_EQ(p.outputs[0].effort, mf::Effort::thorough);
    EXPECT_FALSE(p.outputs[1].effort);
    EXPECT_EQ(mf::block_format_for(p.outputs[1], 3)->name, "bc1");
    EXPECT_EQ(mf::block_format_for(p.outputs[1], 4)->name, "bc3");
    EXPECT_EQ(p.output_path("M", p.outputs[0]), "M/M_c.ktx2");
}

TEST(PresetFields, ShippedGpuPresetsParse) {
    for (const char* name : {"d3d11", "vulkan-ktx2", "vulkan-ktx2-astc", "gltf"}) {
        std::string error;
        const auto p = mf::load_preset(name, error);
        ASSERT_TRUE(p) << error;
        if (std::string(name) == "gltf") {
            EXPECT_EQ(p->material_file, mf::MaterialFileKind::gltf);
            continue;
        }
        EXPECT_TRUE(p->mips) << name;
        for (const auto& o : p->outputs) EXPECT_TRUE(o.block_format) << name << " " << o.suffix;
    }
}

// ---------------------------------------------------------------------------------------------
// The glTF sphere

TEST(GltfSphere, FacesOutwardWithUnitNormalsAndTangents) {
    const auto& b = mf::gltf::sphere_buffer();
    constexpr size_t kVertices = 65 * 33, kIndices = 3 * (2 * 64 * 32 - 2 * 64);
    ASSERT_GE(b.size(), kVertices * 48 + kIndices * 2);
    auto f = [&](size_t at) {
        float v;
        std::memcpy(&v, b.data() + at, 4);
        return v;
    };
    const size_t pos = 0, nrm = kVertices * 12, tan = kVertices * 24, uv = kVertices * 40, idx = kVertices * 48;
    for (size_t v = 0; v < kVertices; ++v) {
        const float nx = f(nrm + v * 12), ny = f(nrm + v * 12 + 4), nz = f(nrm + v * 12 + 8);
        const float tx = f(tan + v * 16), ty = f(tan + v * 16 + 4), tz = f(tan + v * 16 + 8);
        ASSERT_NEAR(nx * nx + ny * ny + nz * nz, 1.f, 1e-5f);
        ASSERT_NEAR(tx * tx + ty * ty + tz * tz, 1.f, 1e-5f);
        ASSERT_NEAR(nx * tx + ny * ty + nz * tz, 0.f, 1e-5f);
        ASSERT_EQ(f(tan + v * 16 + 12), 1.f);
        ASSERT_NEAR(f(pos + v * 12 + 4), 0.5f * ny, 1e-6f);
        ASSERT_GE(f(uv + v * 8), 0.f);
    }
    // Every triangle counter-clockwise seen from outside, none degenerate.
    for (size_t t = 0; t < kIndices / 3; ++t) {
        std::array<std::array<float, 3>, 3> p{};
        for (size_t k = 0; k < 3; ++k) {
            uint16_t i;
            std::memcpy(&i, b.data() + idx + (3 * t + k) * 2, 2);
            ASSERT_LT(i, kVertices);
            for (size_t c = 0; c < 3; ++c) p[k][c] = f(pos + i * 12u + c * 4);
        }
        const std::array<float, 3> e1{p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]};
        const std::array<float, 3> e2{p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]};
        const std::array<float, 3> n{e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                                     e1[0] * e2[1] - e1[1] * e2[0]};
        const float out = n[0] * (p[0][0] + p[1][0] + p[2][0]) + n[1] * (p[0][1] + p[1][1] + p[2][1]) +
                          n[2] * (p[0][2] + p[1][2] + p[2][2]);
        ASSERT_GT(out, 0.f) << "triangle " << t;
    }
    // The front (+Z) texel to the right has larger u: the texture is not mirrored.
    const size_t front = 16 * 65 + 0, right = 16 * 65 + 1;
    EXPECT_NEAR(f(pos + front * 12 + 8), 0.5f, 1e-6f);
    EXPECT_GT(f(pos + right * 12), f(pos + front * 12));
    EXPECT_GT(f(uv + right * 8), f(uv + front * 8));
}

TEST(GltfUri, PercentEncodesAllButUnreservedAndSlash) {
    EXPECT_EQ(mf::gltf::uri_of("a b/c%d_é.png"), "a%20b/c%25d_%C3%A9.png");
}
