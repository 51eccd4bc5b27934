#include "core/json.hpp"

#include <cstdint>

namespace mf {

std::string json_text(const nlohmann::json& j) {
    return j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

std::optional<int> json_int(const nlohmann::json& v, int lo, int hi) {
    if (!v.is_number_integer()) return std::nullopt;
    if (v.is_number_unsigned()) {
        const auto u = v.get<std::uint64_t>();
        if (hi < 0 || u > static_cast<std::uint64_t>(hi) || static_cast<std::int64_t>(u) < lo) return std::nullopt;
        return static_cast<int>(u);
    }
    const auto i = v.get<std::int64_t>();
    if (i < lo || i > hi) return std::nullopt;
    return static_cast<int>(i);
}

std::optional<float> json_float(const nlohmann::json& v, double lo, double hi) {
    if (!v.is_number()) return std::nullopt;
    const double d = v.get<double>();
    if (!(d >= lo && d <= hi)) return std::nullopt;  // also NaN
    return static_cast<float>(d);
}

}  // namespace mf
