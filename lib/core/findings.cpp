#include "core/findings.hpp"

#include <algorithm>

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

nlohmann::json to_json(const Finding& f) {
    nlohmann::json j;
    j["code"] = f.code;
    j["severity"] = severity_name(f.severity);
    if (!f.role.empty()) j["role"] = f.role;
    if (!f.file.empty()) j["file"] = f.file;
    j["message"] = f.message;
    if (!f.figures.empty()) j["figures"] = f.figures;
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
        f.figures = *fig;
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
