#include "core/json.hpp"

#include <cstdint>

#include "core/files.hpp"

namespace mf {

std::string json_text(const nlohmann::json& j) {
    return j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

std::string json_text_with_array(const nlohmann::json& head, const std::string& key, size_t count,
                                 const std::function<nlohmann::json(size_t)>& element) {
    std::string text = json_text(head);
    if (count == 0) return text;
    // json_text indents 2 spaces a level: the array's key at 2, its elements at 4. JSON strings
    // hold no raw newline, so every line of an element's dump is a line of the file.
    const std::string empty = "\n  " + nlohmann::json(key).dump() + ": []";
    const size_t at = text.find(empty);
    if (at == std::string::npos) return text;  // `key` is not an empty top-level array: the caller's mistake
    std::string items = "\n  " + nlohmann::json(key).dump() + ": [\n";
    for (size_t i = 0; i < count; ++i) {
        const std::string one = element(i).dump(2, ' ', false, nlohmann::json::error_handler_t::replace);
        for (size_t start = 0; start <= one.size();) {
            const size_t end = std::min(one.find('\n', start), one.size());
            items.append("    ").append(one, start, end - start);
            if (end < one.size()) items += '\n';
            start = end + 1;
        }
        items += i + 1 < count ? ",\n" : "\n  ]";
    }
    text.replace(at, empty.size(), items);
    return text;
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

namespace {
// Counts nesting; stops the parse at the first container past the limit.
struct DepthCheck : nlohmann::json_sax<nlohmann::json> {
    int depth = 0;
    bool too_deep = false;
    std::string message;
    bool open() {
        too_deep = ++depth > kMaxJsonDepth;
        return !too_deep;
    }
    bool null() override { return true; }
    bool boolean(bool) override { return true; }
    bool number_integer(number_integer_t) override { return true; }
    bool number_unsigned(number_unsigned_t) override { return true; }
    bool number_float(number_float_t, const string_t&) override { return true; }
    bool string(string_t&) override { return true; }
    bool binary(binary_t&) override { return true; }
    bool start_object(std::size_t) override { return open(); }
    bool key(string_t&) override { return true; }
    bool end_object() override { return --depth, true; }
    bool start_array(std::size_t) override { return open(); }
    bool end_array() override { return --depth, true; }
    bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception& e) override {
        message = e.what();
        return false;
    }
};
}  // namespace

std::optional<nlohmann::json> parse_json(std::string_view text, const std::string& what, std::string& error) {
    DepthCheck check;
    if (!nlohmann::json::sax_parse(text, &check)) {
        error = what + (check.too_deep ? ": JSON nested deeper than " + std::to_string(kMaxJsonDepth) + " levels"
                                       : ": not valid JSON (" + check.message + ")");
        return std::nullopt;
    }
    return nlohmann::json::parse(text, nullptr, false);
}

std::optional<nlohmann::json> read_json_file(const std::filesystem::path& file, std::string& error) {
    std::vector<unsigned char> bytes;
    if (!read_file(file, bytes, error)) return std::nullopt;
    return parse_json(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), file.string(),
                      error);
}

}  // namespace mf
