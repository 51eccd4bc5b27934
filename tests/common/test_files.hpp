// Reading what a run wrote, for the tests that drive the matforge binary (tests/cli,
// tests/hostile): one definition, so both judge outputs the same way.
#pragma once
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "image/image.hpp"

namespace mf::testfiles {

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

}  // namespace mf::testfiles
