// core/spool (text kept in an unlinked temporary file), the streamed JSON writer and reader
// (core/json), streamed atomic writes and the incremental SHA-256 (core/files).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <thread>

#include <unistd.h>

#include "core/files.hpp"
#include "core/json.hpp"
#include "core/spool.hpp"
#include "core_util.hpp"

namespace fs = std::filesystem;
using nlohmann::json;

namespace {
using coretest::fresh_dir;
size_t entries_in(const fs::path& d) {
    return static_cast<size_t>(std::distance(fs::directory_iterator(d), fs::directory_iterator()));
}
std::string read_text(const fs::path& f) {
    std::ifstream in(f, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
}
}  // namespace

// Pieces come back as written, from several threads at once, and the spool leaves no file behind
// (O_TMPFILE: nothing is named in the folder while it is open, nothing after).
TEST(TextSpool, PiecesComeBackAndNoFileIsLeft) {
    const fs::path d = fresh_dir("spool");
    std::string error;
    auto spool = mf::TextSpool::open(d, error);
    ASSERT_TRUE(spool) << error;
    std::vector<std::thread> threads;
    std::vector<std::vector<uint32_t>> ids(4);
    for (int t = 0; t < 4; ++t)
        threads.emplace_back([&, t] {
            std::string e;
            for (int i = 0; i < 250; ++i) {
                const auto id = spool->append("t" + std::to_string(t) + "-" + std::to_string(i) +
                                                  std::string(size_t(i), 'x'),
                                              e);
                if (id) ids[size_t(t)].push_back(*id);
            }
        });
    for (auto& th : threads) th.join();
    EXPECT_EQ(spool->size(), 1000u);
    EXPECT_EQ(entries_in(d), 0u);
    for (int t = 0; t < 4; ++t) {
        ASSERT_EQ(ids[size_t(t)].size(), 250u);
        for (int i = 0; i < 250; ++i) {
            const auto text = spool->read(ids[size_t(t)][size_t(i)], error);
            ASSERT_TRUE(text) << error;
            EXPECT_EQ(*text, "t" + std::to_string(t) + "-" + std::to_string(i) + std::string(size_t(i), 'x'));
        }
    }
    EXPECT_FALSE(spool->read(1000, error));
    EXPECT_NE(error.find("no piece 1000"), std::string::npos) << error;
    spool.reset();
    EXPECT_EQ(entries_in(d), 0u);
    EXPECT_FALSE(mf::TextSpool::open(d / "missing", error));
    EXPECT_NE(error.find("missing"), std::string::npos) << error;
    fs::remove_all(d);
}

// write_json_text streams the bytes json_text writes for the whole tree, arrays filled in any
// key order, nested members and empty arrays left alone.
TEST(JsonStream, WritesTheBytesOfTheWholeDump) {
    json whole = {{"a", 1},
                  {"beta", json::array()},
                  {"materials", json::array()},
                  {"nested", {{"materials", json::array()}}},
                  {"zeta", "\xff name"}};
    json head = whole;
    for (int i = 0; i < 3; ++i) whole["materials"].push_back({{"name", "m" + std::to_string(i)}, {"v", {i, i + 0.5}}});
    whole["beta"].push_back("only");
    std::vector<json> mats(whole["materials"].begin(), whole["materials"].end());
    std::string text;
    const bool ok = mf::write_json_text(
        head,
        {{"materials", 3, [&](size_t i, const mf::ByteSink& s) { return s(mf::array_element_text(mats[i])); }},
         {"beta", 1, [&](size_t, const mf::ByteSink& s) { return s(mf::array_element_text("only")); }},
         {"absent", 2, [&](size_t, const mf::ByteSink&) { return false; }}},
        [&](std::string_view p) {
            text.append(p);
            return true;
        });
    EXPECT_TRUE(ok);
    EXPECT_EQ(text, mf::json_text(whole));
    // A sink that refuses stops the write.
    int calls = 0;
    EXPECT_FALSE(mf::write_json_text(
        head, {{"materials", 3, [&](size_t i, const mf::ByteSink& s) { return s(mf::array_element_text(mats[i])); }}},
        [&](std::string_view) { return ++calls < 3; }));
    EXPECT_EQ(calls, 3);
}

// The streamed reader hands over each element of the named array and returns the rest; a
// document too deep, bad JSON and a visitor's refusal are errors naming the file.
TEST(JsonStream, ReadsOneElementAtATime) {
    const fs::path d = fresh_dir("jsonread");
    json doc = {{"head", "h"}, {"materials", json::array()}, {"other", json::array({1, 2})}};
    for (int i = 0; i < 5; ++i) doc["materials"].push_back({{"i", i}, {"inner", json::array({{{"x", i}}})}});
    doc["materials"].push_back(7);  // not an object: handed over too
    std::ofstream(d / "doc.json") << mf::json_text(doc);
    std::vector<json> seen;
    std::string error;
    auto head = mf::read_json_file(
        d / "doc.json", "materials",
        [&](json& e, std::string&) {
            seen.push_back(e);
            return true;
        },
        error);
    ASSERT_TRUE(head) << error;
    EXPECT_EQ(seen.size(), 6u);
    for (int i = 0; i < 5; ++i) EXPECT_EQ(seen[size_t(i)], doc["materials"][size_t(i)]);
    EXPECT_EQ(seen[5], 7);
    EXPECT_EQ((*head)["materials"], json::array());
    EXPECT_EQ((*head)["other"], json::array({1, 2}));
    EXPECT_EQ((*head)["head"], "h");

    EXPECT_FALSE(mf::read_json_file(
        d / "doc.json", "materials",
        [&](json&, std::string& e) {
            e = "refused";
            return false;
        },
        error));
    EXPECT_EQ(error, (d / "doc.json").string() + ": refused");

    std::ofstream(d / "deep.json") << std::string(300, '[') + std::string(300, ']');
    EXPECT_FALSE(mf::read_json_file(
        d / "deep.json", "materials", [](json&, std::string&) { return true; }, error));
    EXPECT_NE(error.find("deeper than 256"), std::string::npos) << error;
    std::ofstream(d / "bad.json") << "{\"materials\": [1,";
    EXPECT_FALSE(mf::read_json_file(
        d / "bad.json", "materials", [](json&, std::string&) { return true; }, error));
    EXPECT_NE(error.find("bad.json: not valid JSON"), std::string::npos) << error;
    EXPECT_FALSE(mf::read_json_file(
        d, "materials", [](json&, std::string&) { return true; }, error));
    EXPECT_NE(error.find("a folder"), std::string::npos) << error;
    fs::remove_all(d);
}

// A streamed atomic write lands whole or not at all; Sha256 fed in pieces is the one-shot hash.
TEST(JsonStream, StreamedAtomicWriteAndIncrementalHash) {
    const fs::path d = fresh_dir("streamwrite");
    std::string error;
    const std::string big(3u << 20, 'q');  // past the writer's 1 MB buffer
    mf::Sha256 sha;
    ASSERT_TRUE(mf::write_file_atomic(
        d / "f.txt",
        [&](const mf::ByteSink& s) {
            for (const std::string_view p :
                 {std::string_view("head,"), std::string_view(big), std::string_view(",tail")})
                if (!(sha.update(p), s(p))) return false;
            return true;
        },
        error))
        << error;
    const std::string text = read_text(d / "f.txt");
    EXPECT_EQ(text, "head," + big + ",tail");
    EXPECT_EQ(sha.hex(), mf::sha256_hex({reinterpret_cast<const unsigned char*>(text.data()), text.size()}));
    // A producer that gives up leaves the old file and no temporary.
    error.clear();
    EXPECT_FALSE(mf::write_file_under(
        d, "f.txt", [](const mf::ByteSink& s) { return s("partial") && false; }, error));
    EXPECT_EQ(error, "f.txt: not written");
    EXPECT_EQ(read_text(d / "f.txt"), text);
    EXPECT_EQ(entries_in(d), 1u);
    fs::remove_all(d);
}
