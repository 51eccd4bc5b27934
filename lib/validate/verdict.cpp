#include "validate/verdict.hpp"

namespace mf::validate {

std::optional<FailOn> fail_on_from_name(std::string_view n) {
    if (n == "error") return FailOn::error;
    if (n == "warning") return FailOn::warning;
    if (n == "info") return FailOn::info;
    if (n == "never") return FailOn::never;
    return std::nullopt;
}

std::string_view fail_on_name(FailOn f) {
    switch (f) {
        case FailOn::info: return "info";
        case FailOn::warning: return "warning";
        case FailOn::error: return "error";
        case FailOn::never: break;
    }
    return "never";
}

bool fails(Severity s, FailOn f) {
    switch (f) {
        case FailOn::never: return false;
        case FailOn::info: return true;
        case FailOn::warning: return s >= Severity::warning;
        case FailOn::error: return s >= Severity::error;
    }
    return false;
}

void add_material(Summary& s, const std::vector<Finding>& findings) {
    bool incomplete = false;
    for (const auto& f : findings) {
        if (f.severity == Severity::error) ++s.error;
        else if (f.severity == Severity::warning) ++s.warning;
        else ++s.info;
        incomplete = incomplete || f.code == code::unreadable_file || f.code == code::output_write_failed;
    }
    s.incomplete += incomplete ? 1 : 0;
}

Summary summarize(const manifest::Manifest& m) {
    Summary s;
    for (const auto& mm : m.materials) add_material(s, mm.findings);
    s.failures = static_cast<int>(m.failures.size());
    return s;
}

bool run_fails(const Summary& s, FailOn f) {
    if (s.failures > 0 || s.incomplete > 0) return true;
    return (s.error > 0 && fails(Severity::error, f)) || (s.warning > 0 && fails(Severity::warning, f)) ||
           (s.info > 0 && fails(Severity::info, f));
}

}  // namespace mf::validate
