// Internal: statistics of one map gathered band by band on its reader thread, and the rules
// that need nothing but that one map (values, channels, constants, metalness, normals, tags).
#pragma once
#include <array>
#include <string>
#include <vector>

#include "validate/validate.hpp"

namespace mf::validate::detail {

// a / b as a fraction (0 when b is 0).
inline double ratio(long long a, long long b) { return b > 0 ? static_cast<double>(a) / static_cast<double>(b) : 0.0; }

// mf::srgb_to_linear (base/srgb.hpp) of every 16-bit code k / 65535 (an 8-bit code k is the
// 16-bit code 257 k): exact for integer files, a lookup instead of a pow per sample.
const std::vector<float>& srgb_decode_table();

// What a normal map's statistics say (NORMAL_INVALID, NORMAL_GAMMA_ENCODED,
// NORMAL_NOT_UNIT_LENGTH); every figure is also in the findings' figures.
struct NormalSummary {
    double mean_x = 0, mean_y = 0, mean_z = 0, mean_length = 0, std_x = 0, std_y = 0;
    double bad_length_share = 0;  // |len − 1| > length_tolerance
    double negative_z_share = 0;  // z < −z_epsilon
    double upward_share = 0;      // within 45° of +Z: z ≥ |(x, y)|
    double gray_share = 0;        // R, G, B equal within the grayscale tolerance (≥ 3 channels)
    // The same pixels decoded as if the file were sRGB-encoded (8/16-bit files only).
    bool srgb_measured = false;
    double srgb_mean_x = 0, srgb_mean_y = 0, srgb_mean_length = 0, srgb_upward_share = 0;
    bool gamma_encoded = false;
    std::vector<std::string> invalid;  // why it is not a tangent-space normal map (empty: it is)
    bool not_unit_length = false;
    Figures figures() const;
};

struct MapStats {
    MapInput input;  // copy: the stats outlive no one, and this keeps the thread self-contained
    rules::Thresholds t;
    int width = 0, height = 0, channels = 0;
    bool is_jpeg = false;

    // Values.
    long long samples = 0, pixels = 0, nan = 0, inf = 0, out_of_range_pixels = 0;
    std::array<double, 4> min{}, max{}, sum{};
    std::array<long long, 4> finite{};
    // 8/16-bit files: every value is finite and a code / code_scale; the sums are kept exactly,
    // in codes (code_scale 0: a float file, summed in `sum`).
    float code_scale = 0.f;
    std::array<long long, 4> code_sum{};
    // NOT_GRAYSCALE (scalar roles with ≥ 3 channels) and PACKED_CHANNELS_IDENTICAL (packed
    // inputs whose layout gives R, G and B each a role): pixels whose R, G, B differ.
    long long gray_differing = 0;
    double gray_max_diff = 0, gray_sum_rg = 0, gray_sum_rb = 0;
    // METALNESS_NOT_BINARY (the channel holding metalness, if any).
    int metal_channel = -1;
    long long metal_dielectric = 0, metal_metal = 0, metal_between = 0;
    // Normal maps (the means of x and y come from the channel sums above).
    int normal_signed = -1;  // -1 undecided, 0 n = 2c − 1, 1 stored signed (float files)
    // Whether Z is rebuilt from X and Y: a two-channel map, or three channels whose blue holds
    // one value while X and Y vary (BC5 exports leave B empty). Decided on the first band (-1
    // undecided, 0 stored, 1 rebuilt); blue_min/blue_max over the whole map confirm it.
    int normal_z = -1;
    bool rebuilds_z() const { return channels == 2 || normal_z == 1; }
    long long normal_bad_length = 0, normal_negative_z = 0, normal_upward = 0, normal_gray = 0, normal_srgb_upward = 0;
    double normal_sum_length = 0, normal_sum_z = 0, normal_sum_xx = 0, normal_sum_yy = 0;
    double normal_srgb_sum_x = 0, normal_srgb_sum_y = 0, normal_srgb_sum_length = 0;
    // OPACITY_ALL_TRANSPARENT: the channel holding opacity (an opacity map's first, the albedo's
    // alpha when it is the set's opacity; the set-level caller decides, -1: none).
    int opacity_channel = -1;
    long long opacity_invisible = 0, opacity_below_cutoff = 0;

    MapStats(MapInput in, const ImageInfo& info, const rules::Thresholds& th);
    void add_band(int y0, int rows, const float* px);
    // An 8-bit file's band as its codes: the figures its floats (unorm8_values) would give, bit
    // for bit — every value is read through that table or one built from it, in the same order.
    void add_band(int y0, int rows, const uint8_t* codes);
    void add_band(int y0, int rows, Samples px) {
        px.codes ? add_band(y0, rows, px.codes) : add_band(y0, rows, px.floats);
    }

    // Findings that depend on this map alone, at their catalog severity: the rule groups below,
    // in order.
    void findings(std::vector<Finding>& out) const;
    struct Emit {  // adds a finding about this map's file
        std::string file, role;
        std::vector<Finding>& out;
        void operator()(std::string_view code, std::string r, std::string msg, Figures fig) const;
    };
    void value_findings(const Emit& add) const;
    void grayscale_findings(const Emit& add) const;
    void packed_findings(const Emit& add) const;
    void constant_findings(const Emit& add) const;
    void metalness_findings(const Emit& add) const;
    void opacity_findings(const Emit& add) const;
    void normal_findings(const Emit& add) const;
    void tag_findings(const Emit& add) const;

    bool is_normal() const { return input.role == Role::normal; }
    // The set's opacity held here (opacity_channel) hides the whole surface: OPACITY_ALL_TRANSPARENT,
    // and the plan leaves it out.
    bool all_transparent() const;
    NormalSummary normal_summary() const;  // meaningful for normal maps of ≥ 2 channels
    // A normal map that is not a tangent-space normal map: what raises NORMAL_INVALID.
    bool normal_invalid() const;
    double mean(int c) const {
        if (finite[c] == 0) return 0.0;
        const double total = code_scale > 0.f ? static_cast<double>(code_sum[c]) / code_scale : sum[c];
        return total / static_cast<double>(finite[c]);
    }
    bool scalar_role() const;
    // A packed input whose layout gives each of R, G and B a role (ORM, ARM, MRA, RMA), read
    // from ≥ 3 channels: one image in all three would be three roles at once.
    bool packed_rgb() const;

private:
    // add_band over a float pointer or a code reader (map_stats.cpp), and its parts.
    template <class P>
    void add_band_t(long long n, P px);
    template <class P>
    void normal_band(long long n, P px);  // the normal-map statistics
    // min, max and code sums of an integer file's band, its samples read as `lanes` says
    // (map_stats.cpp: floats, or 8-bit codes).
    template <class L>
    void codes_band(long long n, const typename L::T* px, const L& lanes);
};

// Which output role channel c of a map holds (packed inputs split; RGB roles whole).
std::optional<Role> channel_role(Role input_role, int channel);

}  // namespace mf::validate::detail
