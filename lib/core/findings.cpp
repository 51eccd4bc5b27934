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

Finding finding_from_json(const nlohmann::json& j) {
    Finding f;
    f.code = j.at("code").get<std::string>();
    f.severity = severity_from_name(j.at("severity").get<std::string>()).value_or(Severity::error);
    f.role = j.value("role", "");
    f.file = j.value("file", "");
    f.message = j.value("message", "");
    if (j.contains("figures")) f.figures = j.at("figures");
    return f;
}

std::optional<Severity> worst(const std::vector<Finding>& findings) {
    std::optional<Severity> w;
    for (const auto& f : findings)
        if (!w || f.severity > *w) w = f.severity;
    return w;
}

}  // namespace mf
