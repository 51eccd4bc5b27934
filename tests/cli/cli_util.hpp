// Helpers for tests that run the matforge binary as a user would.
#pragma once
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include <unistd.h>

#include "core/files.hpp"
#include "image/image.hpp"
#include "run_binary.hpp"
#include "test_files.hpp"

namespace mft {
namespace fs = std::filesystem;

struct RunResult {
    int code = -1;
    std::string output;  // stdout + stderr
};

// Runs `matforge ARGS` through the shell (ARGS quoted with q()), with `env` (VAR=value ...)
// prepended. A JSON report printed to stdout goes to the schema spool like the files.
inline RunResult run_env(const std::string& env, const std::string& args) {
    const auto p = mf::testbin::spawn({"/bin/sh", "-c", env + " exec " + mf::testenv::bin() + " " + args});
    if (args.find("--report json") != std::string::npos && args.find("--report-file") == std::string::npos)
        mf::testbin::spool_text(p.output, "stdout");
    return {p.signal ? -1 : p.code, p.output};
}

inline RunResult run(const std::string& args) { return run_env("", args); }

inline std::string q(const fs::path& p) { return std::string("'").append(p.string()).append("'"); }

// A set of the real corpus (tests/data/corpus/real/<name>), read in place: never written to.
inline fs::path corpus_set(const std::string& name) { return mf::testenv::corpus_dir() / "real" / name; }

inline fs::path samples() { return mf::testenv::source_dir() / "sample_materials"; }

// A fresh, empty temporary folder per test.
inline fs::path temp_dir(const std::string& name) { return mf::testdirs::fresh_for_test("matforge-cli-", name); }

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

// The output folder of a manifest read by an `ingested()` helper (stored under "__out").
inline fs::path out_of(const nlohmann::json& m) { return m["__out"].get<std::string>(); }

inline mf::Image output_pixels(const nlohmann::json& m, const nlohmann::json& o) {
    return read_pixels(out_of(m) / o["file"].get<std::string>());
}

// Every material of `m` is ok with outputs, and every output is on disk with the recorded
// sha256 and size.
inline void expect_outputs_as_recorded(const nlohmann::json& m) {
    EXPECT_TRUE(m["failures"].empty()) << m["failures"].dump(1);
    for (const auto& mat : m["materials"]) {
        EXPECT_EQ(mat["status"], "ok") << mat["name"];
        EXPECT_FALSE(mat["outputs"].empty());
        for (const auto& o : mat["outputs"]) {
            std::vector<unsigned char> bytes;
            std::string err;
            ASSERT_TRUE(mf::read_file(out_of(m) / o["file"].get<std::string>(), bytes, err)) << err;
            EXPECT_EQ(mf::sha256_hex(bytes), o["sha256"]) << o["file"];
            const auto img = output_pixels(m, o);
            EXPECT_EQ(img.width, o["width"]);
            EXPECT_EQ(img.height, o["height"]);
        }
    }
}

// `dx` is `gl` with green mirrored (255 - g) and red kept, within the one code renormalization
// may move.
inline void expect_green_mirrored(const mf::Image& gl, const mf::Image& dx) {
    ASSERT_EQ(gl.pixels.size(), dx.pixels.size());
    int worst = 0;
    for (int y = 0; y < gl.height; ++y)
        for (int x = 0; x < gl.width; ++x) {
            worst = std::max(worst, std::abs(code8(gl.at(x, y, 1)) - (255 - code8(dx.at(x, y, 1)))));
            ASSERT_NEAR(code8(gl.at(x, y, 0)), code8(dx.at(x, y, 0)), 1);
        }
    EXPECT_LE(worst, 1) << "green flipped (255 - g, renormalization may move one code)";
}

// The bytes of a file ("" when it cannot be read): byte-identity checks.
inline std::string bytes_of(const fs::path& p) {
    std::ifstream f(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(f), {}};
}

inline void write_text(const fs::path& p, const std::string& s) {
    fs::create_directories(p.parent_path());
    std::ofstream(p, std::ios::binary) << s;
}

// Writes an 8-bit image from float pixels (test fixtures).
inline void write_png(const fs::path& p, const mf::Image& img, int bits = 8) {
    std::vector<unsigned char> bytes;
    std::string err;
    const auto format = mf::from_word<mf::FileFormat>(p.extension().string().substr(1));
    ASSERT_TRUE(format) << p << ": not a format encode_image writes";
    ASSERT_TRUE(mf::encode_image(img, {*format, bits}, bytes, err)) << err;
    ASSERT_TRUE(mf::write_file_atomic(p, bytes, err)) << err;
}

}  // namespace mft
