// `ingest --tiers 128,256,4096` (or a preset's "max_size": [128, 256, 4096]): one pass writes each
// resolution tier into <out>/<tier> (<out>/<preset>/<tier> with several presets), each folder byte
// for byte what the preset with that max_size writes alone into it (a preset file from `matforge
// presets show`, its max_size edited); each source image is decoded once for every tier (counted
// under strace), and a tier above a set's size writes the set at its own size, never upsampled.
#include <map>
#include <set>

#include "cli_util.hpp"

using namespace mft;

namespace {

using mf::testfiles::files_under;

// `dir`'s files, names and bytes, against `want`: the same list, each file the same bytes.
void expect_same_files(const fs::path& dir, const std::map<std::string, std::string>& want, const std::string& what) {
    const auto got = files_under(dir);
    std::set<std::string> got_names, want_names;
    for (const auto& [rel, bytes] : got) got_names.insert(rel);
    for (const auto& [rel, bytes] : want) want_names.insert(rel);
    EXPECT_EQ(got_names, want_names) << what << ": not the same files";
    for (const auto& [rel, bytes] : want) {
        const auto it = got.find(rel);
        if (it != got.end()) {
            EXPECT_TRUE(it->second == bytes) << what << ": " << rel;
        }
    }
}

// The names in `dir` (not recursive), sorted.
std::set<std::string> names_in(const fs::path& dir) {
    std::set<std::string> names;
    for (const auto& e : fs::directory_iterator(dir)) names.insert(e.path().filename().string());
    return names;
}

// The shipped preset `name` as `matforge presets show` prints it, with `max_size` set, written to
// `file`: how a user runs a preset at another size.
fs::path sized_preset(const fs::path& file, const std::string& name, const nlohmann::json& max_size) {
    const auto shown = run("presets show " + name);
    EXPECT_EQ(shown.code, 0) << shown.output;
    nlohmann::json j = nlohmann::json::parse(shown.output);
    j["max_size"] = max_size;
    write_text(file, j.dump(2));
    return file;
}

std::string set_args(const std::vector<fs::path>& sets) {
    std::string s;
    for (const auto& p : sets) s += q(p) + " ";
    return s;
}

// Each tier's folder `out/<tier>` is what `preset` with that max_size writes alone into it (the
// folder an earlier run of ours: replaced in place, as MultiPreset does), every material's base
// colour at min(tier, its source's size): downsampled (RESIZED) below, never upsampled above.
void expect_tiers_as_alone(const std::string& sets, const fs::path& out, const std::string& preset,
                           const std::vector<int>& tiers, const fs::path& work) {
    for (const int tier : tiers) {
        const fs::path folder = out / std::to_string(tier);
        const auto together = files_under(folder);
        const nlohmann::json m = read_json(folder / "manifest.json");
        EXPECT_EQ(m["preset"], preset) << tier;
        ASSERT_FALSE(m["materials"].empty()) << tier;
        for (const auto& mat : m["materials"]) {
            const nlohmann::json* base = output_with(mat, "RGB", "albedo");
            ASSERT_NE(base, nullptr) << mat["name"];
            const int source = mat["inputs"]["albedo"]["width"];
            EXPECT_EQ((*base)["width"], std::min(tier, source)) << preset << " " << tier << " " << mat["name"];
            EXPECT_EQ(has_finding(mat, "RESIZED"), tier < source) << preset << " " << tier << " " << mat["name"];
        }
        const fs::path file = sized_preset(work / (preset + "-" + std::to_string(tier) + ".json"), preset, tier);
        const auto r = run("ingest " + sets + "-o " + q(folder) + " -q --no-cache --fail-on never --preset " + q(file));
        ASSERT_EQ(r.code, 0) << r.output;
        expect_same_files(folder, together, preset + " tier " + std::to_string(tier) + " alone vs together");
    }
}

}  // namespace

TEST(Tiers, EachTierFolderIsByteIdenticalToThePresetAloneWithThatMaxSize) {
    const fs::path work = temp_dir("tiers");
    const fs::path out = work / "out";
    const std::string sets = set_args({corpus_set("ambientcg_Net004A_1K-JPG"),
                                       corpus_set("polyhaven_rubberized_track_1k")});
    const std::string cache = " --cache " + q(work / "cache");
    auto r = run("ingest " + sets + "-o " + q(out) + " --fail-on never --tiers 256,4096,128" + cache);
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(names_in(out), (std::set<std::string>{"128", "256", "4096"})) << "one folder a tier, nothing beside";
    for (const char* tier : {"128", "256", "4096"})  // each tier's summary, named
        EXPECT_NE(r.output.find(std::string("matforge ingest [") + tier + "]: 2 materials"), std::string::npos)
            << r.output;
    // Restored from the cache into a fresh folder: the same bytes as computed.
    const fs::path again = work / "again";
    ASSERT_EQ(run("ingest " + sets + "-o " + q(again) + " -q --fail-on never --tiers 128,256,4096" + cache).code, 0);
    for (const char* tier : {"128", "256", "4096"})
        expect_same_files(again / tier, files_under(out / tier), std::string("restored tier ") + tier);
    expect_tiers_as_alone(sets, out, "gltf", {128, 256, 4096}, work);
}

// A GPU preset's tiers, with another preset in the same pass: <out>/<preset>/<tier>. Two tiers
// above the sources' size write the same textures (encoded once, process/share.hpp); each is still
// exactly its own run's.
TEST(Tiers, GpuPresetsTogetherWriteEachPresetsTiersAsAlone) {
    const fs::path work = temp_dir("gpu");
    const fs::path out = work / "out";
    const std::string sets = set_args({corpus_set("3dtextures_Metal_Damaged_001_SD"),
                                       corpus_set("ambientcg_Net004A_1K-JPG")});
    auto r = run("ingest " + sets + "-o " + q(out) + " --no-cache --fail-on never --preset vulkan-ktx2,d3d11 --tiers " +
                 "128,2048,4096");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(names_in(out), (std::set<std::string>{"d3d11", "vulkan-ktx2"}));
    for (const char* p : {"d3d11", "vulkan-ktx2"}) {
        EXPECT_EQ(names_in(out / p), (std::set<std::string>{"128", "2048", "4096"})) << p;
        EXPECT_NE(r.output.find(std::string("matforge ingest [") + p + "/2048]: 2 materials"), std::string::npos)
            << r.output;
    }
    // The tiers above the sources hold the same textures, manifests aside.
    for (const char* p : {"d3d11", "vulkan-ktx2"}) {
        auto big = files_under(out / p / "4096"), less = files_under(out / p / "2048");
        big.erase("manifest.json");
        less.erase("manifest.json");
        EXPECT_TRUE(big == less) << p;
    }
    expect_tiers_as_alone(sets, out / "vulkan-ktx2", "vulkan-ktx2", {128, 2048, 4096}, work);
    expect_tiers_as_alone(sets, out / "d3d11", "d3d11", {128, 4096}, work);
}

// A preset's max_size given as a list is its tiers: the same folders, the same bytes as --tiers;
// --tiers replaces the list.
TEST(Tiers, PresetListMaxSizeIsTiersAndTiersOptionReplacesIt) {
    const fs::path work = temp_dir("list");
    const std::string sets = q(samples() / "Metal_Damaged_001_SD") + " ";
    const fs::path listed = sized_preset(work / "tiered.json", "gltf", nlohmann::json::array({256, 128}));
    const fs::path out = work / "out";
    auto r = run("ingest " + sets + "-o " + q(out) + " -q --no-cache --fail-on never --preset " + q(listed));
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(names_in(out), (std::set<std::string>{"128", "256"}));
    const auto by_list_128 = files_under(out / "128"), by_list_256 = files_under(out / "256");
    // The same folders from the shipped preset and --tiers (a tier's preset is the file's with its
    // max_size: the same text, so the same action keys in the manifests).
    r = run("ingest " + sets + "-o " + q(out) + " -q --no-cache --fail-on never --preset gltf --tiers 128,256");
    ASSERT_EQ(r.code, 0) << r.output;
    expect_same_files(out / "128", by_list_128, "128: --tiers vs the list");
    expect_same_files(out / "256", by_list_256, "256: --tiers vs the list");
    // --tiers replaces the preset's list.
    const fs::path only = work / "only";
    r = run("ingest " + sets + "-o " + q(only) + " -q --no-cache --fail-on never --preset " + q(listed) +
            " --tiers 128");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(names_in(only), (std::set<std::string>{"128"}));
    expect_tiers_as_alone(sets, out, "gltf", {128}, work);
    // validate takes the list's largest tier; plan refuses it (its keys are one max_size's).
    r = run("validate " + sets + "--preset " + q(listed) + " --fail-on never");
    EXPECT_EQ(r.code, 0) << r.output;
    r = run("plan " + sets + "-o " + q(work / "plan.json") + " --preset " + q(listed));
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("max_size is a list of tiers"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(work / "plan.json"));
}

// Decoded once a run: every image of the set is opened (header, digest, pixels) as often by a run
// of three tiers, or of two presets in two tiers each, as by one preset's run alone. Counted under
// strace, as Hostile.ZipOfManyEntriesIsOpenedOnce counts an archive's opens: a decode per tier
// would open each map once more per tier.
TEST(Tiers, EachSourceImageIsDecodedOnceForEveryTier) {
    const fs::path work = temp_dir("decoded");
    const std::vector<fs::path> sets{corpus_set("polyhaven_rubberized_track_1k"),
                                     corpus_set("ambientcg_Net004A_1K-JPG")};
    int run_no = 0;
    auto opens = [&](const std::vector<std::string>& args) {
        const fs::path trace = work / ("open" + std::to_string(run_no) + ".trace");
        std::vector<std::string> argv{
            "strace",           "-f",    "-qq", "-e", "trace=open,openat,openat2", "-o", trace.string(),
            mf::testenv::bin(), "ingest"};
        for (const auto& s : sets) argv.push_back(s.string());
        const std::vector<std::string> common{"-o",        (work / ("out" + std::to_string(run_no++))).string(),
                                              "-q",        "--no-cache",
                                              "--fail-on", "never"};
        argv.insert(argv.end(), common.begin(), common.end());
        argv.insert(argv.end(), args.begin(), args.end());
        const auto p = mf::testbin::spawn(argv);
        EXPECT_EQ(p.code, 0) << p.output;
        std::map<std::string, int> count;  // image file -> successful opens
        std::ifstream f(trace);
        EXPECT_TRUE(f) << "strace wrote no trace";
        for (std::string line; std::getline(f, line);) {
            if (line.find("= -1") != std::string::npos) continue;
            for (const auto& s : sets) {
                const std::string prefix = s.string() + "/";
                const size_t at = line.find(prefix);
                if (at == std::string::npos) continue;
                const size_t end = line.find('"', at);
                const std::string file = line.substr(at + prefix.size(), end - at - prefix.size());
                const std::string ext = fs::path(file).extension().string();
                if (ext == ".jpg" || ext == ".png" || ext == ".webp") ++count[s.filename().string() + "/" + file];
            }
        }
        return count;
    };
    const auto alone = opens({"--preset", "gltf"});
    EXPECT_GE(alone.size(), 10u) << "the trace holds the sets' images";
    for (const auto& [file, n] : alone) EXPECT_GE(n, 1) << file;
    EXPECT_EQ(opens({"--preset", "gltf", "--tiers", "128,256,4096"}), alone) << "three tiers of one preset";
    // Two presets of one normal convention (they choose the same maps), two tiers each.
    EXPECT_EQ(opens({"--preset", "gltf,vulkan-ktx2", "--tiers", "128,256"}), alone) << "two presets, two tiers each";
}

// Tiers that name no size, or one twice, are usage errors (exit 2) naming the entry, before
// anything is created; so are the same in a preset's list.
TEST(Tiers, UnclearTiersAreRefusedBeforeAnythingIsWritten) {
    const fs::path work = temp_dir("refused");
    const std::string sets = q(samples() / "Metal_Damaged_001_SD") + " ";
    auto refused = [&](const std::string& args, const std::string& says) {
        const auto r = run("ingest " + sets + "-o " + q(work / "out") + " " + args);
        EXPECT_EQ(r.code, 2) << args << "\n" << r.output;
        EXPECT_NE(r.output.find(says), std::string::npos) << args << "\n" << r.output;
        EXPECT_EQ(r.output.rfind("matforge ingest: ", 0), 0u) << r.output;
        EXPECT_FALSE(fs::exists(work / "out")) << args;
    };
    refused("--tiers 0", "--tiers: 0 is no tier");
    refused("--tiers=-512", "--tiers: -512 is no tier");
    refused("--tiers 512,70000", "--tiers: 70000 is no tier");
    refused("--tiers 99999999999999999999", "is no tier");
    refused("--tiers 512,1024,512", "--tiers: 512 is given twice");
    refused("--tiers 1k", "\"1k\" is not a whole number of pixels");
    refused("--tiers 512.5", "\"512.5\" is not a whole number of pixels");
    refused("--tiers 512,,1024", "an empty tier");
    refused("--tiers ''", "an empty tier");
    refused("--tiers 128,256 --report json", "--report takes one run's findings; with several tiers");
    auto listed = [&](const std::string& name, const nlohmann::json& max_size, const std::string& says) {
        refused("--preset " + q(sized_preset(work / name, "gltf", max_size)), says);
    };
    listed("zero.json", nlohmann::json::array({0, 512}), "max_size: 0 is no tier");
    listed("twice.json", nlohmann::json::array({512, 512}), "max_size: 512 is given twice");
    listed("word.json", nlohmann::json::array({512, "big"}), "max_size: \"big\" is not a whole number of pixels");
    listed("empty.json", nlohmann::json::array(), "max_size: no tier given");
    listed("over.json", nlohmann::json::array({65537}), "max_size: 65537 is no tier");
    // One tier is one run: --report works, on <out>/<tier>.
    const auto r = run("ingest " + sets + "-o " + q(work / "one") +
                       " --no-cache --fail-on never --tiers 128 --report json" + " --report-file " +
                       q(work / "report.json"));
    EXPECT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(names_in(work / "one"), (std::set<std::string>{"128"}));
    EXPECT_EQ(read_json(work / "report.json")["materials"].size(), 1u);
}
