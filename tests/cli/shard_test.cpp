// Sharded runs: `plan` (keys, shards), `ingest --shard I/N`, `merge` — the merged manifest of N
// shards is byte-identical to one unsharded run; merging parts of different runs is refused.
#include <fstream>
#include <map>
#include <sstream>

#include "cli_util.hpp"

using namespace mft;
using nlohmann::json;

namespace {

std::map<std::string, std::string> keys_of(const fs::path& plan) {
    std::map<std::string, std::string> k;
    const json p = read_json(plan);  // not `read_json(plan)["sets"]` in the for: the temporary would die first
    for (const auto& s : p["sets"]) k[s["name"]] = s["key"];
    return k;
}

}  // namespace

// `plan --commands`: one ingest command per shard on standard output, run as a farm runs a work
// list (here `xargs -P 2`, each line through sh -c), then merged: byte-identical to one run, with
// an output folder whose name needs quoting.
TEST(Shard, PlanCommandsRunAsAFarmRunsThem) {
    const fs::path work = temp_dir("commands");
    const fs::path out = work / "farm's out";
    const auto p = mf::testbin::spawn({mf::testenv::bin(), "plan", samples().string(), "-o",
                                       (work / "plan.json").string(), "--shards", "3", "--commands", "--out-dir",
                                       out.string()});
    ASSERT_EQ(p.code, 0) << p.output;
    std::vector<std::string> lines;
    std::istringstream text(p.output);
    for (std::string line; std::getline(text, line);)
        if (line.find(" ingest ") != std::string::npos) lines.push_back(line);
    ASSERT_EQ(lines.size(), 3u) << p.output;
    for (int i = 0; i < 3; ++i) {
        EXPECT_EQ(lines[i].substr(0, mf::testenv::bin().size()), mf::testenv::bin());
        EXPECT_TRUE(lines[i].ends_with("--preset gltf --shard " + std::to_string(i) + "/3")) << lines[i];
    }
    EXPECT_NE(p.output.find("merge "), std::string::npos) << "the merge step is said";
    std::ofstream(work / "list.txt") << lines[0] << "\n" << lines[1] << "\n" << lines[2] << "\n";
    const auto farm = mf::testbin::spawn({"/bin/sh", "-c", "xargs -P 2 -d '\\n' -n 1 sh -c < " + q(work / "list.txt")},
                                         600);
    ASSERT_EQ(farm.code, 0) << farm.output;
    const auto merged = mf::testbin::spawn({mf::testenv::bin(), "merge", (out / "manifest.shard-0-of-3.json").string(),
                                            (out / "manifest.shard-1-of-3.json").string(),
                                            (out / "manifest.shard-2-of-3.json").string(), "-o",
                                            (out / "manifest.json").string()});
    ASSERT_EQ(merged.code, 0) << merged.output;
    ASSERT_EQ(run("ingest " + q(samples()) + " -o " + q(work / "single") + " -q --no-cache").code, 0);
    EXPECT_EQ(bytes_of(out / "manifest.json"), bytes_of(work / "single/manifest.json"));
    // Without --out-dir there is no command to print.
    EXPECT_EQ(run("plan " + q(samples()) + " -o " + q(work / "p2.json") + " --commands").code, 2);
}

// A path cannot hijack a command list (issue 45): every runner of one command a line splits
// lines before a shell sees the quotes, so `plan --commands` refuses a path with a newline (or
// any control character), names it and prints no command; a path with quotes, $(), backticks and
// `;` is quoted and runs as itself through the documented `while read` loop. A file named like a
// shipped preset in the working folder does not turn `--preset gltf` into that file's path.
TEST(Shard, PlanCommandsCannotBeSplitByAPath) {
    const fs::path work = temp_dir("hijack");
    const fs::path set = samples() / "Net004A_1K-JPG";
    const fs::path evil = work / "lib\ntouch X\nx";
    fs::create_directories(evil);
    fs::copy(set, evil / "Net004A_1K-JPG", fs::copy_options::recursive);
    // In `work`, with the arguments as they are (no shell quoting of them).
    const std::vector<std::string> in_work{"/bin/sh", "-c", "cd \"$0\" && exec \"$@\"", work.string(),
                                           mf::testenv::bin()};
    auto args = [&](std::vector<std::string> more) {
        std::vector<std::string> v = in_work;
        v.insert(v.end(), more.begin(), more.end());
        return v;
    };
    const auto p = mf::testbin::spawn(args({"plan", evil.string(), "-o", "plan.json", "--shards", "2", "--commands",
                                            "--out-dir", "out"}));
    EXPECT_EQ(p.code, 2) << p.output;
    EXPECT_EQ(p.output.find(mf::testenv::bin() + " ingest"), std::string::npos) << p.output;
    EXPECT_NE(p.output.find("newline"), std::string::npos) << p.output;
    EXPECT_NE(p.output.find("lib\\x0atouch X\\x0ax"), std::string::npos) << "the path is named, escaped: " << p.output;
    EXPECT_FALSE(fs::exists(work / "X"));
    for (const std::string out : {"out\tdir", "out\x7f"}) {
        const auto t = mf::testbin::spawn(args({"plan", set.string(), "-o", "p.json", "--commands", "--out-dir",
                                                (work / out).string()}));
        EXPECT_EQ(t.code, 2) << out << ": " << t.output;
    }
    // Quotes and shell syntax are quoted, and run as the path they are.
    const fs::path odd = work / "it's $(touch Y) `touch Z`; x";
    fs::create_directories(odd);
    fs::copy(set, odd / "Net004A_1K-JPG", fs::copy_options::recursive);
    std::ofstream(work / "gltf") << "{\"not\": \"a preset\"}";  // a file named like the shipped preset
    const auto c = mf::testbin::spawn(args({"plan", odd.string(), "-o", "plan.json", "--commands", "--out-dir",
                                            (odd / "out").string(), "--preset", "gltf"}));
    ASSERT_EQ(c.code, 0) << c.output;
    std::string line;
    std::istringstream text(c.output);
    for (std::string l; std::getline(text, l);)
        if (l.find(" ingest ") != std::string::npos) line = l;
    EXPECT_TRUE(line.ends_with("--preset gltf --shard 0/1")) << line;
    std::ofstream(work / "list.txt") << line << "\n";
    const auto farm = mf::testbin::spawn(
        {"/bin/sh", "-c", "cd " + q(work) + " && while IFS= read -r cmd; do sh -c \"$cmd\" || exit 1; done < list.txt"},
        600);
    ASSERT_EQ(farm.code, 0) << farm.output;
    EXPECT_TRUE(fs::exists(odd / "out/manifest.shard-0-of-1.json"));
    EXPECT_FALSE(fs::exists(work / "Y"));
    EXPECT_FALSE(fs::exists(work / "Z"));
}

// Each material of a manifest records its set's action key, the plan's; `plan --changed-since`
// lists only the sets whose key differs from (or is absent in) that manifest, each with its shard
// in the whole library's split, and --commands prints only the shards holding one.
TEST(Shard, PlanChangedSinceListsOnlyTheChangedSets) {
    const fs::path work = temp_dir("changed");
    fs::copy(samples(), work / "lib", fs::copy_options::recursive);
    ASSERT_EQ(run("ingest " + q(work / "lib") + " -o " + q(work / "out") + " -q --no-cache").code, 0);
    ASSERT_EQ(run("plan " + q(work / "lib") + " -o " + q(work / "all.json") + " --shards 3").code, 0);
    const auto keys = keys_of(work / "all.json");
    const json m = read_json(work / "out/manifest.json");
    ASSERT_EQ(m["materials"].size(), 4u);
    for (const auto& mat : m["materials"]) EXPECT_EQ(mat["key"], keys.at(mat["name"])) << mat["name"];
    const std::string since = " --changed-since " + q(work / "out/manifest.json");
    ASSERT_EQ(run("plan " + q(work / "lib") + " -o " + q(work / "none.json") + " --shards 3" + since).code, 0);
    EXPECT_TRUE(read_json(work / "none.json")["sets"].empty());
    EXPECT_EQ(read_json(work / "none.json")["unchanged"], 4);
    // One file of one set changed (bytes after the JPEG's end: the same picture, another file).
    fs::path changed;
    for (const auto& e : fs::directory_iterator(work / "lib/Net004A_1K-JPG"))
        if (e.path().extension() == ".jpg" && (changed.empty() || e.path() < changed)) changed = e.path();
    ASSERT_FALSE(changed.empty());
    std::ofstream(changed, std::ios::binary | std::ios::app) << '\0';
    const auto p = mf::testbin::spawn({mf::testenv::bin(), "plan", (work / "lib").string(), "-o",
                                       (work / "one.json").string(), "--shards", "3", "--changed-since",
                                       (work / "out/manifest.json").string(), "--commands", "--out-dir",
                                       (work / "out").string()});
    ASSERT_EQ(p.code, 0) << p.output;
    const json one = read_json(work / "one.json");
    ASSERT_EQ(one["sets"].size(), 1u) << one.dump(1);
    EXPECT_EQ(one["sets"][0]["name"], "Net004A");
    EXPECT_NE(one["sets"][0]["key"], keys.at("Net004A"));
    EXPECT_EQ(one["unchanged"], 3);
    size_t commands = 0;
    std::istringstream text(p.output);
    for (std::string line; std::getline(text, line);)
        if (line.find(" ingest ") != std::string::npos) {
            ++commands;
            EXPECT_TRUE(line.ends_with("--shard " + std::to_string(one["sets"][0]["shard"].get<int>()) + "/3")) << line;
        }
    EXPECT_EQ(commands, 1u) << p.output;
}

TEST(Shard, MergedShardsAreByteIdenticalToOneRun) {
    const fs::path work = temp_dir("merge");
    ASSERT_EQ(run("plan " + q(samples()) + " -o " + q(work / "plan.json") + " --shards 3").code, 0);
    const json plan = read_json(work / "plan.json");
    std::map<int, int> per_shard;
    for (const auto& s : plan["sets"]) ++per_shard[s["shard"].get<int>()];
    EXPECT_EQ(per_shard.size(), 3u) << plan.dump(2);
    for (int i = 0; i < 3; ++i) {
        const auto r = run("ingest " + q(samples()) + " -o " + q(work / "out") + " -q --shard " + std::to_string(i) +
                           "/3");
        ASSERT_EQ(r.code, 0) << r.output;
        // Each shard processed exactly the sets the plan gave it.
        const json part = read_json(work / "out" / ("manifest.shard-" + std::to_string(i) + "-of-3.json"));
        EXPECT_EQ(static_cast<int>(part["materials"].size()), per_shard[i]);
        for (const auto& m : part["materials"])
            for (const auto& s : plan["sets"]) {
                if (s["name"] == m["name"]) {
                    EXPECT_EQ(s["shard"], i) << m["name"];
                }
            }
    }
    ASSERT_EQ(run("merge " + q(work / "out/manifest.shard-0-of-3.json") + " " +
                  q(work / "out/manifest.shard-1-of-3.json") + " " + q(work / "out/manifest.shard-2-of-3.json") +
                  " -o " + q(work / "out/manifest.json"))
                  .code,
              0);
    ASSERT_EQ(run("ingest " + q(samples()) + " -o " + q(work / "single") + " -q --no-cache").code, 0);
    EXPECT_EQ(bytes_of(work / "out/manifest.json"), bytes_of(work / "single/manifest.json"));
    // The run's library.gltf, which no shard writes (each sees its part), comes from the merge;
    // so does ATTRIBUTION.md, every material of the run.
    EXPECT_EQ(bytes_of(work / "out/library.gltf"), bytes_of(work / "single/library.gltf"));
    EXPECT_EQ(bytes_of(work / "out/ATTRIBUTION.md"), bytes_of(work / "single/ATTRIBUTION.md"));
    EXPECT_NE(bytes_of(work / "single/ATTRIBUTION.md").find("| Net004A | ambientCG | Net004A | CC0-1.0 |"),
              std::string::npos);
    fs::remove(work / "out/manifest.json");
    fs::remove(work / "out/library.gltf");
    // A killed shard re-run completes its part: the same bytes again.
    fs::remove(work / "out/manifest.shard-1-of-3.json");
    ASSERT_EQ(run("ingest " + q(samples()) + " -o " + q(work / "out") + " -q --shard 1/3").code, 0);
    ASSERT_EQ(run("merge " + q(work / "out/manifest.shard-0-of-3.json") + " " +
                  q(work / "out/manifest.shard-1-of-3.json") + " " + q(work / "out/manifest.shard-2-of-3.json") +
                  " -o " + q(work / "out/manifest.json"))
                  .code,
              0);
    EXPECT_EQ(bytes_of(work / "out/manifest.json"), bytes_of(work / "single/manifest.json"));
    EXPECT_EQ(bytes_of(work / "out/library.gltf"), bytes_of(work / "single/library.gltf"));
}

TEST(Shard, MergeRefusesPartsOfDifferentRuns) {
    const fs::path work = temp_dir("refuse");
    const std::string in = q(samples());
    // Parts of other runs are copied into run a's folder (merge takes parts from one folder).
    int copies = 0;
    auto shard = [&](const std::string& out, const std::string& which, const std::string& extra = "") {
        const auto r = run("ingest " + in + " -o " + q(work / out) + " -q --shard " + which + extra);
        EXPECT_EQ(r.code, 0) << r.output;
        const fs::path part = work / out /
                              ("manifest.shard-" + which.substr(0, which.find('/')) + "-of-" +
                               which.substr(which.find('/') + 1) + ".json");
        if (out == "a") return q(part);
        const fs::path copy = work / "a" / ("other-" + std::to_string(++copies) + ".json");
        fs::copy_file(part, copy);
        return q(copy);
    };
    auto refused = [&](const std::string& parts, const std::string& says) {
        const auto r = run("merge " + parts + " -o " + q(work / "a/m.json"));
        EXPECT_EQ(r.code, 2) << r.output;
        EXPECT_NE(r.output.find(says), std::string::npos) << r.output;
        EXPECT_FALSE(fs::exists(work / "a/m.json"));
    };
    const std::string a0 = shard("a", "0/2"), a1 = shard("a", "1/2");
    // Another preset by name.
    refused(a0 + " " + shard("b", "1/2", " --preset unreal"), "preset \"gltf\" vs \"unreal\"");
    // The same preset name, other content (a preset file edited between shards).
    const fs::path preset = work / "gltf.json";
    { std::ofstream(preset) << run("presets show gltf").output; }
    auto edited = read_json(preset);
    edited["max_size"] = 1024;
    std::ofstream(preset) << edited.dump();
    refused(a0 + " " + shard("c", "1/2", " --preset " + q(preset)), "other preset content");
    // A missing shard, a shard twice, a shard of another split, a manifest that is no shard.
    refused(a0, "shard(s) 1 of 2 missing");
    refused(a0 + " " + a0, "shard 0 of 2 is given twice");
    refused(a0 + " " + shard("d", "1/3"), "shard count \"2\" vs \"3\"");
    ASSERT_EQ(run("ingest " + q(samples() / "Metal_Damaged_001_SD") + " -o " + q(work / "e") + " -q").code, 0);
    fs::copy_file(work / "e/manifest.json", work / "a/e.json");
    refused(a0 + " " + q(work / "a/e.json"), "is not the manifest of a shard");
    // The shard of another library: the same preset and split, other sets.
    const fs::path lib = work / "lib";
    fs::copy(samples(), lib, fs::copy_options::recursive);
    fs::remove_all(lib / "flat_two_sets");  // another library: two sets fewer
    EXPECT_EQ(run("ingest " + q(lib) + " -o " + q(work / "f") + " -q --shard 1/2").code, 0);
    fs::copy_file(work / "f/manifest.shard-1-of-2.json", work / "a/f.json");
    refused(a0 + " " + q(work / "a/f.json"), "made from other libraries, or from one that changed");
    // Where the merged manifest goes: never over a part, always beside the parts.
    {
        const std::string before = bytes_of(work / "a/manifest.shard-1-of-2.json");
        const auto r = run("merge " + a0 + " " + a1 + " -o " + a1);
        EXPECT_EQ(r.code, 2) << r.output;
        EXPECT_NE(r.output.find("is one of the parts"), std::string::npos) << r.output;
        EXPECT_EQ(bytes_of(work / "a/manifest.shard-1-of-2.json"), before);
    }
    {
        const auto r = run("merge " + a0 + " " + a1 + " -o " + q(work / "elsewhere/manifest.json"));
        EXPECT_EQ(r.code, 2) << r.output;
        EXPECT_NE(r.output.find("is not in the folder of the part"), std::string::npos) << r.output;
        EXPECT_FALSE(fs::exists(work / "elsewhere"));
    }
    // The right parts, in any order: merged.
    EXPECT_EQ(run("merge " + a1 + " " + a0 + " -o " + q(work / "a/manifest.json")).code, 0);
    EXPECT_EQ(run("ingest " + in + " -o " + q(work / "x") + " --shard 3/3").code, 2);
}

// A set added to the library after shard 1 ran and before shard 0 (the new split moves sets
// between shards): merge refuses instead of writing a manifest that silently lacks sets.
TEST(Shard, LibraryChangedBetweenShardsIsRefused) {
    const fs::path work = temp_dir("changed");
    const fs::path lib = work / "lib";
    fs::copy(samples(), lib, fs::copy_options::recursive);
    const fs::path later = work / "later";
    fs::rename(lib / "Metal_Damaged_001_SD", later);
    ASSERT_EQ(run("ingest " + q(lib) + " -o " + q(work / "out") + " -q --shard 1/2").code, 0);
    fs::rename(later, lib / "Metal_Damaged_001_SD");
    ASSERT_EQ(run("ingest " + q(lib) + " -o " + q(work / "out") + " -q --shard 0/2").code, 0);
    const auto r = run("merge " + q(work / "out/manifest.shard-0-of-2.json") + " " +
                       q(work / "out/manifest.shard-1-of-2.json") + " -o " + q(work / "out/manifest.json"));
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("changed between the shards' runs"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(work / "out/manifest.json"));
    // Shard 1 run again on the library as it is now: merged, and complete.
    ASSERT_EQ(run("ingest " + q(lib) + " -o " + q(work / "out") + " -q --shard 1/2").code, 0);
    ASSERT_EQ(run("merge " + q(work / "out/manifest.shard-0-of-2.json") + " " +
                  q(work / "out/manifest.shard-1-of-2.json") + " -o " + q(work / "out/manifest.json"))
                  .code,
              0);
    EXPECT_EQ(read_json(work / "out/manifest.json")["materials"].size(), 4u);
}

// A hand-edited part: an output listed outside the folder, or with bytes it does not have.
TEST(Shard, MergeChecksEveryListedFile) {
    const fs::path work = temp_dir("listed");
    for (const char* s : {"0/2", "1/2"})
        ASSERT_EQ(run("ingest " + q(samples()) + " -o " + q(work / "out") + " -q --shard " + s).code, 0);
    const fs::path p0 = work / "out/manifest.shard-0-of-2.json", p1 = work / "out/manifest.shard-1-of-2.json";
    const std::string original = bytes_of(p0);
    auto merge = [&] { return run("merge " + q(p0) + " " + q(p1) + " -o " + q(work / "out/manifest.json")); };
    json j = json::parse(original);
    const std::string file = j["materials"][0]["outputs"][0]["file"];
    j["materials"][0]["outputs"][0]["file"] = "../../escaped.png";
    std::ofstream(p0) << j.dump(2);
    auto r = merge();
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("is not a path inside the output folder"), std::string::npos) << r.output;
    j = json::parse(original);
    j["materials"][0]["outputs"][0]["sha256"] = std::string(64, '0');
    std::ofstream(p0) << j.dump(2);
    r = merge();
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find(file + ": its bytes do not hash"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(work / "out/manifest.json"));
    std::ofstream(p0) << original;
    r = merge();
    EXPECT_EQ(r.code, 0) << r.output;
}

TEST(Shard, ActionKeysFollowContentAndConfigurationOnly) {
    const fs::path work = temp_dir("keys");
    fs::copy(samples(), work / "in", fs::copy_options::recursive);
    ASSERT_EQ(run("plan " + q(work / "in") + " -o " + q(work / "p1.json")).code, 0);
    const auto k1 = keys_of(work / "p1.json");
    // A time stamp is not content: the same keys.
    fs::last_write_time(work / "in/Metal_Damaged_001_SD/Metal_Damaged_001_basecolor.jpg",
                        fs::file_time_type::clock::now());
    ASSERT_EQ(run("plan " + q(work / "in") + " -o " + q(work / "p2.json")).code, 0);
    EXPECT_EQ(keys_of(work / "p2.json"), k1);
    // One byte of one file: that set's key only.
    {
        std::fstream f(work / "in/Metal_Damaged_001_SD/Metal_Damaged_001_basecolor.jpg",
                       std::ios::in | std::ios::out | std::ios::binary);
        f.seekp(-1, std::ios::end);
        f.put('\x7f');
    }
    ASSERT_EQ(run("plan " + q(work / "in") + " -o " + q(work / "p3.json")).code, 0);
    const auto k3 = keys_of(work / "p3.json");
    ASSERT_EQ(k3.size(), k1.size());
    for (const auto& [name, key] : k1) EXPECT_EQ(key != k3.at(name), name == "Metal_Damaged_001") << name;
    // Another preset: every key.
    ASSERT_EQ(run("plan " + q(work / "in") + " -o " + q(work / "p4.json") + " --preset unreal").code, 0);
    const auto k4 = keys_of(work / "p4.json");
    for (const auto& [name, key] : k3) EXPECT_NE(key, k4.at(name)) << name;
}

// A shard whose own run failed (a map of one of its sets unreadable): merge refuses, exit 1,
// naming that shard and the set, and writes nothing; --keep-errors writes what one run of the
// same library writes (and exits 1 as it does); the map restored, that shard alone run again,
// the merge completes, byte-identical to one run.
TEST(Shard, MergeRefusesAFailedShardNamingIt) {
    const fs::path work = temp_dir("failed");
    const fs::path lib = work / "lib";
    fs::copy(samples(), lib, fs::copy_options::recursive);
    ASSERT_EQ(run("plan " + q(lib) + " -o " + q(work / "plan.json") + " --shards 2").code, 0);
    int shard = -1;
    const json plan = read_json(work / "plan.json");
    for (const auto& s : plan["sets"])
        if (s["name"] == "Metal_Damaged_001") shard = s["shard"].get<int>();
    ASSERT_GE(shard, 0);
    fs::path map;
    for (const auto& e : fs::directory_iterator(lib / "Metal_Damaged_001_SD"))
        if (e.path().filename().string().find("basecolor") != std::string::npos) map = e.path();
    ASSERT_FALSE(map.empty());
    const std::string kept = bytes_of(map);
    {  // its first bytes overwritten, its size kept: the split stays the same
        std::fstream f(map, std::ios::in | std::ios::out | std::ios::binary);
        f << "not an image";
    }
    const std::string parts = q(work / "out/manifest.shard-0-of-2.json") + " " +
                              q(work / "out/manifest.shard-1-of-2.json");
    const std::string merged = q(work / "out/manifest.json");
    for (int i = 0; i < 2; ++i)
        EXPECT_EQ(run("ingest " + q(lib) + " -o " + q(work / "out") + " -q --shard " + std::to_string(i) + "/2").code,
                  i == shard ? 1 : 0);
    auto r = run("merge " + parts + " -o " + merged);
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_NE(r.output.find("shard " + std::to_string(shard) + " of 2 ("), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("1 set failed, first Metal_Damaged_001: UNREADABLE_FILE"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("shard " + std::to_string(1 - shard) + " of 2"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(work / "out/manifest.json"));
    // --keep-errors: what one run of this library writes, and its exit code.
    EXPECT_EQ(run("merge " + parts + " -o " + merged + " --keep-errors").code, 1);
    EXPECT_EQ(run("ingest " + q(lib) + " -o " + q(work / "single-bad") + " -q --no-cache").code, 1);
    EXPECT_EQ(bytes_of(work / "out/manifest.json"), bytes_of(work / "single-bad/manifest.json"));
    // The map restored, that shard alone again: merged.
    std::ofstream(map, std::ios::binary | std::ios::trunc) << kept;
    ASSERT_EQ(run("ingest " + q(lib) + " -o " + q(work / "out") + " -q --shard " + std::to_string(shard) + "/2").code,
              0);
    r = run("merge " + parts + " -o " + merged);
    EXPECT_EQ(r.code, 0) << r.output;
    ASSERT_EQ(run("ingest " + q(lib) + " -o " + q(work / "single") + " -q --no-cache").code, 0);
    EXPECT_EQ(bytes_of(work / "out/manifest.json"), bytes_of(work / "single/manifest.json"));
}
