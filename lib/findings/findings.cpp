#include "findings/findings.hpp"

#include <algorithm>
#include <limits>
#include <nlohmann/json.hpp>

namespace mf {

std::string_view severity_name(Severity s) {
    switch (s) {
        case Severity::info: return "info";
        case Severity::warning: return "warning";
        case Severity::error: return "error";
    }
    return "error";
}

std::optional<Severity> severity_from_name(std::string_view name) {
    if (name == "info") return Severity::info;
    if (name == "warning") return Severity::warning;
    if (name == "error") return Severity::error;
    return std::nullopt;
}

std::optional<double> figure_number(const Figures& figures, std::string_view name) {
    const auto it = figures.find(name);
    if (it == figures.end()) return std::nullopt;
    if (const auto* i = std::get_if<std::int64_t>(&it->second)) return static_cast<double>(*i);
    if (const auto* d = std::get_if<double>(&it->second)) return *d;
    return std::nullopt;
}

std::optional<std::string> figure_string(const Figures& figures, std::string_view name) {
    const auto it = figures.find(name);
    if (it == figures.end()) return std::nullopt;
    if (const auto* s = std::get_if<std::string>(&it->second)) return *s;
    return std::nullopt;
}

namespace {
nlohmann::json value_json(const FigureValue& v) {
    return std::visit([](const auto& x) { return nlohmann::json(x); }, v);
}
}  // namespace

std::string figure_text(const FigureValue& v) {
    return value_json(v).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

nlohmann::json to_json(const Figures& figures) {
    nlohmann::json j = nlohmann::json::object();
    for (const auto& [name, v] : figures) j[name] = value_json(v);
    return j;
}

nlohmann::json to_json(const Finding& f) {
    nlohmann::json j;
    j["code"] = f.code;
    j["severity"] = severity_name(f.severity);
    if (!f.role.empty()) j["role"] = f.role;
    if (!f.file.empty()) j["file"] = f.file;
    j["message"] = f.message;
    if (!f.figures.empty()) j["figures"] = to_json(f.figures);
    return j;
}

namespace {
// A string member: `fallback` when absent, nullopt (and `error`) when of another type.
std::optional<std::string> string_member(const nlohmann::json& j, const char* key, std::string& error, bool required) {
    const auto it = j.find(key);
    if (it == j.end()) {
        if (required) error = std::string("no \"") + key + "\"";
        return required ? std::nullopt : std::optional<std::string>(std::string());
    }
    if (!it->is_string()) {
        error = std::string("\"") + key + "\" is not a string";
        return std::nullopt;
    }
    return it->get<std::string>();
}
// A figure as written by to_json: a flag, a number, a text, or a list of numbers or of texts.
std::optional<FigureValue> figure_from_json(const nlohmann::json& v) {
    if (v.is_boolean()) return v.get<bool>();
    if (v.is_number_unsigned()) {
        const auto u = v.get<std::uint64_t>();
        if (u > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max())) return static_cast<double>(u);
        return static_cast<std::int64_t>(u);
    }
    if (v.is_number_integer()) return v.get<std::int64_t>();
    if (v.is_number_float()) return v.get<double>();
    if (v.is_string()) return v.get<std::string>();
    if (!v.is_array()) return std::nullopt;
    if (std::all_of(v.begin(), v.end(), [](const nlohmann::json& e) { return e.is_number_integer(); })) {
        std::vector<std::int64_t> counts;
        for (const auto& e : v) counts.push_back(e.get<std::int64_t>());
        return counts;
    }
    if (std::all_of(v.begin(), v.end(), [](const nlohmann::json& e) { return e.is_number(); })) {
        std::vector<double> numbers;
        for (const auto& e : v) numbers.push_back(e.get<double>());
        return numbers;
    }
    if (std::all_of(v.begin(), v.end(), [](const nlohmann::json& e) { return e.is_string(); }))
        return v.get<std::vector<std::string>>();
    return std::nullopt;
}
}  // namespace

std::optional<Finding> finding_from_json(const nlohmann::json& j, std::string& error) {
    if (!j.is_object()) {
        error = "a finding is not an object";
        return std::nullopt;
    }
    Finding f;
    auto code = string_member(j, "code", error, true);
    auto severity = string_member(j, "severity", error, true);
    auto role = string_member(j, "role", error, false);
    auto file = string_member(j, "file", error, false);
    auto message = string_member(j, "message", error, false);
    if (!code || !severity || !role || !file || !message) return std::nullopt;
    const auto s = severity_from_name(*severity);
    if (!s) {
        error = "unknown severity \"" + *severity + "\"";
        return std::nullopt;
    }
    f.code = std::move(*code);
    f.severity = *s;
    f.role = std::move(*role);
    f.file = std::move(*file);
    f.message = std::move(*message);
    if (const auto fig = j.find("figures"); fig != j.end()) {
        if (!fig->is_object()) {
            error = "\"figures\" is not an object";
            return std::nullopt;
        }
        for (const auto& [name, v] : fig->items()) {
            auto value = figure_from_json(v);
            if (!value) {
                error = "figure \"" + name + "\" is not a flag, a number, a text or a list of numbers or texts";
                return std::nullopt;
            }
            static_cast<FigureValue&>(f.figures[name]) = std::move(*value);
        }
    }
    return f;
}

nlohmann::json to_json(const InputFailure& f) {
    return {{"source", f.source}, {"code", f.code}, {"message", f.message}};
}

std::optional<InputFailure> input_failure_from_json(const nlohmann::json& j, std::string& error) {
    if (!j.is_object()) {
        error = "a failure is not an object";
        return std::nullopt;
    }
    auto source = string_member(j, "source", error, true);
    auto code = string_member(j, "code", error, true);
    auto message = string_member(j, "message", error, false);
    if (!source || !code || !message) return std::nullopt;
    return InputFailure{std::move(*source), std::move(*code), std::move(*message)};
}

std::optional<Severity> worst(const std::vector<Finding>& findings) {
    std::optional<Severity> w;
    for (const auto& f : findings)
        if (!w || f.severity > *w) w = f.severity;
    return w;
}

}  // namespace mf
