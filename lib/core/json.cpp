#include "core/json.hpp"

#include <set>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>

#include "core/files.hpp"

namespace mf {

std::string json_text(const nlohmann::json& j) {
    return j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

std::string array_element_text(const nlohmann::json& element) {
    // json_text indents 2 spaces a level: a top-level array's elements sit at 4. JSON strings hold
    // no raw newline, so every line of an element's dump is a line of the file.
    const std::string one = element.dump(2, ' ', false, nlohmann::json::error_handler_t::replace);
    std::string out;
    out.reserve(one.size() + one.size() / 8);
    for (size_t start = 0; start <= one.size();) {
        const size_t end = std::min(one.find('\n', start), one.size());
        out.append("    ").append(one, start, end - start);
        if (end < one.size()) out += '\n';
        start = end + 1;
    }
    return out;
}

bool write_json_text(const nlohmann::json& head, const std::vector<StreamedArray>& arrays, const ByteSink& sink) {
    const std::string text = json_text(head);
    // Where each array's empty "[]" is in the head's text, in text order.
    std::vector<std::pair<size_t, const StreamedArray*>> at;
    for (const StreamedArray& a : arrays) {
        const std::string empty = "\n  " + nlohmann::json(a.key).dump() + ": []";
        const size_t pos = text.find(empty);
        if (pos == std::string::npos || a.count == 0) continue;  // not an empty top-level array: left as it is
        at.emplace_back(pos + empty.size() - 2, &a);             // at its "[]"
    }
    std::sort(at.begin(), at.end());
    size_t written = 0;
    for (const auto& [pos, a] : at) {
        if (!sink(std::string_view(text).substr(written, pos - written)) || !sink("[\n")) return false;
        for (size_t i = 0; i < a->count; ++i)
            if (!a->element(i, sink) || !sink(i + 1 < a->count ? ",\n" : "\n  ]")) return false;
        written = pos + 2;
    }
    return sink(std::string_view(text).substr(written));
}

std::string json_text_with_array(const nlohmann::json& head, const std::string& key, size_t count,
                                 const std::function<nlohmann::json(size_t)>& element) {
    std::string text;
    write_json_text(head,
                    {{key, count,
                      [&](size_t i, const ByteSink& sink) { return sink(array_element_text(element(i))); }}},
                    [&](std::string_view piece) {
                        text.append(piece);
                        return true;
                    });
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
// What no document of ours holds, found before a DOM is built: nesting past the limit, a member
// named twice in one object (a parser keeps one of them silently: which one the user meant is
// unknowable), a NUL character in a string (a path holding one is cut there by the system, and
// another file is read).
struct DocumentCheck : nlohmann::json_sax<nlohmann::json> {
    std::vector<std::set<std::string>> keys;  // the members seen, per open object
    int depth = 0;
    std::string message;  // set when the document is refused for one of the reasons above
    std::string parse_message;
    bool open() {
        if (++depth > kMaxJsonDepth) message = "JSON nested deeper than " + std::to_string(kMaxJsonDepth) + " levels";
        return message.empty();
    }
    bool text(const string_t& s) {
        if (s.find('\0') != string_t::npos)
            message = "the string \"" + s.substr(0, s.find('\0')) + "\\u0000…\" holds a NUL character";
        return message.empty();
    }
    bool null() override { return true; }
    bool boolean(bool) override { return true; }
    bool number_integer(number_integer_t) override { return true; }
    bool number_unsigned(number_unsigned_t) override { return true; }
    bool number_float(number_float_t, const string_t&) override { return true; }
    bool string(string_t& s) override { return text(s); }
    bool binary(binary_t&) override { return true; }
    bool start_object(std::size_t) override {
        keys.emplace_back();
        return open();
    }
    bool key(string_t& k) override {
        if (!text(k)) return false;
        if (!keys.back().insert(k).second) message = "the member \"" + k + "\" is given twice in one object";
        return message.empty();
    }
    bool end_object() override {
        keys.pop_back();
        return --depth, true;
    }
    bool start_array(std::size_t) override { return open(); }
    bool end_array() override { return --depth, true; }
    bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception& e) override {
        parse_message = e.what();
        return false;
    }
};
}  // namespace

std::optional<nlohmann::json> parse_json(std::string_view text, const std::string& what, std::string& error) {
    DocumentCheck check;
    if (!nlohmann::json::sax_parse(text, &check)) {
        error = what +
                (!check.message.empty() ? ": " + check.message : ": not valid JSON (" + check.parse_message + ")");
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

std::optional<nlohmann::json> read_json_file(
    const std::filesystem::path& file, const std::string& key,
    const std::function<bool(nlohmann::json& element, std::string& error)>& each, std::string& error) {
    if (const auto why = not_a_regular_file(file)) {  // a FIFO would block the read forever
        error = file.string() + ": " + *why;
        return std::nullopt;
    }
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> in(std::fopen(file.c_str(), "rb"), &std::fclose);
    if (!in) {
        error = file.string() + ": cannot open (" + std::strerror(errno) + ")";
        return std::nullopt;
    }
    struct Stop {  // thrown from the parser's callback: too deep, or `each` said stop
        std::string message;
    };
    std::string top_key;
    try {
        // The callback sees every value as it completes (depth 1: the document's members, 2: an
        // element of one of its arrays); returning false drops the value from the tree. The
        // parser itself is iterative: depth only matters to whoever walks the tree later.
        auto j = nlohmann::json::parse(in.get(), [&](int depth, nlohmann::json::parse_event_t event,
                                                     nlohmann::json& parsed) {
            if (depth > kMaxJsonDepth) throw Stop{"nested deeper than " + std::to_string(kMaxJsonDepth) + " levels"};
            if ((event == nlohmann::json::parse_event_t::value || event == nlohmann::json::parse_event_t::key) &&
                parsed.is_string() && parsed.get_ref<const std::string&>().find('\0') != std::string::npos)
                throw Stop{"a string holds a NUL character"};
            if (event == nlohmann::json::parse_event_t::key && depth == 1) top_key = parsed.get<std::string>();
            const bool element_done = event == nlohmann::json::parse_event_t::object_end ||
                                      event == nlohmann::json::parse_event_t::array_end ||
                                      event == nlohmann::json::parse_event_t::value;
            if (depth != 2 || top_key != key || !element_done) return true;
            std::string e;
            if (!each(parsed, e)) throw Stop{e};
            return false;
        });
        return j;
    } catch (const Stop& s) {
        error = file.string() + ": " + s.message;
    } catch (const nlohmann::json::exception& e) {
        error = file.string() + ": not valid JSON (" + e.what() + ")";
    }
    return std::nullopt;
}

}  // namespace mf
