// Reading what a run wrote, for the tests that drive the matforge binary (tests/cli,
// tests/hostile): one definition, so both judge outputs the same way.
#pragma once
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "image/image.hpp"

namespace mf::testfiles {

// `bytes` as an in-memory input named `name` (as an entry of a .zip is read).
inline mf::InputFile in_memory(const std::vector<unsigned char>& bytes, const std::string& name) {
    mf::InputFile in;
    in.display = name;
    in.bytes = std::make_shared<const std::vector<unsigned char>>(bytes);
    return in;
}

// A file's bytes (empty when it cannot be read).
inline std::vector<unsigned char> file_bytes(const std::filesystem::path& p) {
    std::ifstream f(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

inline nlohmann::json read_json(const std::filesystem::path& p) {
    std::ifstream f(p);
    return nlohmann::json::parse(f);  // throws (the test fails) when not valid JSON / UTF-8
}

// Decodes an output image as ingest reads images (float, unassociated alpha); a failed read
// fails the calling test and returns an empty image.
inline mf::Image read_pixels(const std::filesystem::path& p) {
    mf::Image img;
    mf::ImageInfo info;
    std::string err;
    mf::InputFile in;
    in.path = p;
    in.display = p.string();
    EXPECT_TRUE(mf::read_image(in, img, info, err)) << err;
    return img;
}

// Every regular file under `dir` (relative path, '/'-separated) with its bytes: a folder's
// state before and after a command, compared whole.
inline std::map<std::string, std::string> files_under(const std::filesystem::path& dir) {
    std::map<std::string, std::string> files;
    for (const auto& e : std::filesystem::recursive_directory_iterator(dir))
        if (e.is_regular_file()) {
            std::ifstream f(e.path(), std::ios::binary);
            files[std::filesystem::relative(e.path(), dir).generic_string()] = {std::istreambuf_iterator<char>(f), {}};
        }
    return files;
}

}  // namespace mf::testfiles
