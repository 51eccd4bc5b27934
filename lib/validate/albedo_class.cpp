#include "validate/albedo_class.hpp"

#include <algorithm>
#include <array>
#include <limits>

#include "base/srgb.hpp"
#include "image/image.hpp"
#include "validate/map_stats.hpp"

namespace mf::validate {

AlbedoClassifier::AlbedoClassifier(const rules::Thresholds& t, bool linear_input)
    : linear_input_(linear_input), dielectric_max_(t.dielectric_max), metal_min_(t.metal_min) {
    auto lin = [](double srgb255) { return mf::srgb_to_linear(static_cast<float>(srgb255 / 255.0)); };
    dark_lin_ = lin(t.albedo_min_srgb);
    bright_lin_ = lin(t.albedo_max_srgb);
    metal_dark_lin_ = lin(t.metal_albedo_min_srgb);
    std::array<float, 257> edges{};
    for (int k = 0; k < 256; ++k) edges[static_cast<size_t>(k)] = lin(k + 0.5);
    edges[256] = std::numeric_limits<float>::infinity();
    for (size_t b = 0; b <= kBuckets; ++b) {
        const float lo = static_cast<float>(b) / static_cast<float>(kBuckets);
        const auto k = static_cast<size_t>(std::lower_bound(edges.begin(), edges.end(), lo) - edges.begin());
        first_code_[b] = static_cast<uint8_t>(k);  // at most 255 (edge 255 lies above 1)
        next_edge_[b] = edges[k];
    }
    decode_ = detail::srgb_decode_table().data();
    linear8_ = unorm8_table([this](float v) { return linear(v); });
}

}  // namespace mf::validate
