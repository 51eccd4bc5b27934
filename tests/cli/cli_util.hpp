// Helpers for tests that run the matforge binary as a user would.
#pragma once
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include <unistd.h>

#include "core/files.hpp"
#include "image/image.hpp"
#include "test_files.hpp"

namespace mft {
namespace fs = std::filesystem;

struct RunResult {
    int code = -1;
    std::string output;  // stdout + stderr
};

inline RunResult run(const std::string& args) {
    RunResult r;
    const std::string cmd = std::string(MATFORGE_BIN) + " " + args + " 2>&1";
    FILE* p = ::popen(cmd.c_str(), "r");
    if (!p) return r;
    std::array<char, 4096> buf{};
    while (size_t n = std::fread(buf.data(), 1, buf.size(), p)) r.output.append(buf.data(), n);
    const int status = ::pclose(p);
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return r;
}

inline std::string q(const fs::path& p) { return "'" + p.string() + "'"; }

inline fs::path samples() { return fs::path(MATFORGE_SOURCE_DIR) / "sample_materials"; }

// A fresh, empty temporary folder per test.
inline fs::path temp_dir(const std::string& name) {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    fs::path d = fs::temp_directory_path() /
                 ("matforge-cli-" + std::string(info->test_suite_name()) + "-" + info->name() + "-" + name + "-" +
                  std::to_string(::getpid()));
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

using mf::testfiles::read_json;
using mf::testfiles::read_pixels;

inline int code8(float v) { return mf::quantize(v, 8); }

inline const nlohmann::json* material(const nlohmann::json& manifest, const std::string& name) {
    for (const auto& m : manifest["materials"])
        if (m["name"] == name) return &m;
    return nullptr;
}

inline const nlohmann::json* output_with(const nlohmann::json& mat, const std::string& key, const std::string& role) {
    for (const auto& o : mat["outputs"])
        if (o["channels"].contains(key) && o["channels"][key] == role) return &o;
    return nullptr;
}

inline bool has_finding(const nlohmann::json& mat, const std::string& code, const std::string& role = "") {
    for (const auto& f : mat["findings"])
        if (f["code"] == code && (role.empty() || f.value("role", "") == role)) return true;
    return false;
}

inline void write_text(const fs::path& p, const std::string& s) {
    fs::create_directories(p.parent_path());
    std::ofstream(p, std::ios::binary) << s;
}

// Writes an 8-bit image from float pixels (test fixtures).
inline void write_png(const fs::path& p, const mf::Image& img, int bits = 8) {
    std::vector<unsigned char> bytes;
    std::string err;
    ASSERT_TRUE(mf::encode_image(img, {p.extension() == ".exr" ? "exr" : p.extension().string().substr(1), bits}, bytes, err)) << err;
    ASSERT_TRUE(mf::write_file_atomic(p, bytes, err)) << err;
}

}  // namespace mft
