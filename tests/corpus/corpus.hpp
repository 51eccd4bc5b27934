// The real-material corpus: its truth.json, the matforge binary run on its sets, and the one
// table that maps each kind of true problem truth.json lists to the finding code that reports it.
#pragma once
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "material/roles.hpp"
#include "test_dirs.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include "test_env.hpp"

namespace corpus {
namespace fs = std::filesystem;

inline fs::path dir() { return mf::testenv::corpus_dir(); }

// truth.json, or nullptr after failing the calling test with what is missing (never a skip: a
// CI without the corpus must say so).
inline const nlohmann::json* truth() {
    static const std::optional<nlohmann::json> t = []() -> std::optional<nlohmann::json> {
        std::ifstream f(dir() / "truth.json");
        if (!f) return std::nullopt;
        auto j = nlohmann::json::parse(f, nullptr, false);
        if (j.is_discarded() || !j.contains("sets")) return std::nullopt;
        return j;
    }();
    if (!t) {
        ADD_FAILURE() << "the real-material corpus is missing: no readable " << (dir() / "truth.json")
                      << " (tests/data/corpus in the repository)";
        return nullptr;
    }
    return &*t;
}

struct RunResult {
    int code = -1;
    std::string output;  // stdout + stderr
};

inline RunResult run(const std::string& args) {
    RunResult r;
    const std::string cmd = mf::testenv::bin() + " " + args + " 2>&1";
    FILE* p = ::popen(cmd.c_str(), "r");
    if (!p) return r;
    std::array<char, 4096> buf{};
    while (size_t n = std::fread(buf.data(), 1, buf.size(), p)) r.output.append(buf.data(), n);
    const int status = ::pclose(p);
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return r;
}

inline std::string q(const fs::path& p) { return std::string("'").append(p.string()).append("'"); }

// A fresh, empty folder under the system's temporary folder (the corpus is read-only).
inline fs::path temp_dir(const std::string& name) { return mf::testdirs::fresh("matforge-corpus-", name); }

// truth.json's problem sentences (their opening words) → the code that reports that problem.
struct ProblemCode {
    std::string_view starts_with;
    std::string_view code;
};
inline const std::vector<ProblemCode>& problem_codes() {
    static const std::vector<ProblemCode> t{
        {"albedo very bright", "ALBEDO_TOO_BRIGHT"},
        {"albedo very dark", "ALBEDO_TOO_DARK"},
        {"albedo of metal pixels darker", "METAL_ALBEDO_TOO_DARK"},
        {"metalness not binary", "METALNESS_NOT_BINARY"},
        {"normal vectors not unit length", "NORMAL_NOT_UNIT_LENGTH"},
        {"normal map stored gamma/sRGB-encoded", "NORMAL_GAMMA_ENCODED"},
        {"data map PNG carries", "COLOR_SPACE_MISMATCH"},
        {"opacity map is constant 0", "OPACITY_ALL_TRANSPARENT"},
    };
    return t;
}
inline std::optional<std::string> code_of_problem(const std::string& problem) {
    for (const auto& p : problem_codes())
        if (problem.rfind(p.starts_with, 0) == 0) return std::string(p.code);
    return std::nullopt;
}

// truth roles → the input roles matforge names in manifests and findings.
inline bool role_matches(const std::string& truth_role, const std::string& role) {
    if (truth_role == "ao") return role == "occlusion";
    if (truth_role == "packed") {  // any packed input: orm, ort, Unity's mask_map, metallic_smoothness, ...
        const auto r = mf::role_from_name(role);
        return r && mf::traits(*r).packed;
    }
    return truth_role == role;
}

}  // namespace corpus
