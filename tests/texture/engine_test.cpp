// The engines' material files (presets godot, unity-hdrp, unity-urp, unreal, d3d11) on
// sample_materials and the real-material corpus, read back by readers that are not matforge's
// writers (tests/texture/checkers: Godot 4.6 itself, its web export template in headless
// Chromium, which loads each .tres and renders it; PyYAML for Unity's YAML, a recording stand-in
// of Unreal's `unreal` module limited to the documented API, glslang's HLSL front end) and cross-checked
// against the manifest: each slot holds the texture whose channels the engine reads there, data
// maps are never sRGB, normal maps are imported as normal maps, every path and guid resolves,
// every written texture is used, every file is listed with its hash.
#include <iostream>
#include <set>

#include "engine/engine.hpp"
#include "engine/mtlx.hpp"
#include "manifest/attribution.hpp"
#include "manifest/manifest.hpp"
#include "texture_cli.hpp"

using namespace mtt;

namespace {

struct Ingested {
    fs::path out;
    json manifest;
};
const Ingested& ingested(const std::string& preset, const std::string& what) {
    static std::map<std::string, Ingested> cache;
    const std::string key = preset + "-" + what;
    if (auto it = cache.find(key); it != cache.end()) return it->second;
    Ingested r;
    r.out = fs::temp_directory_path() / ("matforge-texture-engine-" + key + "-" + std::to_string(::getpid()));
    fs::remove_all(r.out);
    mf::testbin::register_test_dir(r.out);
    r.manifest = ingest({what == "corpus" ? corpus() : samples()}, r.out, preset, {"--fail-on", "never"});
    return cache[key] = r;
}

// The corpus ingested for every engine preset in one run (`--preset a,b,...`: each preset's
// folder is what its own run writes, MultiPreset.EachFolderIsByteIdenticalToItsOwnRun), so
// the engines' readers below also read what a multi-preset run writes.
std::map<std::string, Ingested> corpus_for_every_engine() {
    const std::vector<std::string> presets{"godot", "unity-hdrp", "unity-urp", "unreal"};
    const fs::path out = fs::temp_directory_path() / ("matforge-texture-engine-corpus-" + std::to_string(::getpid()));
    fs::remove_all(out);
    mf::testbin::register_test_dir(out);
    std::vector<std::string> args{"ingest",     corpus().string(), "-o",
                                  out.string(), "--quiet",         "--fail-on",
                                  "never",      "--preset",        "godot,unity-hdrp,unity-urp,unreal"};
    const auto r = matforge(args);
    EXPECT_EQ(r.code, 0) << r.output;
    std::map<std::string, Ingested> each;
    for (const auto& p : presets) each[p] = {out / p, mf::testfiles::read_json(out / p / "manifest.json")};
    return each;
}

// "KEY:role" -> the file (relative to the manifest's folder) holding it, for one material.
std::map<std::string, std::string> channels_of(const json& m) {
    std::map<std::string, std::string> at;
    for (const auto& o : m["outputs"])
        for (const auto& [key, v] : o["channels"].items())
            if (v.is_string()) at[key + ":" + v.get<std::string>()] = o["file"];
    return at;
}
const json* output_named(const json& m, const std::string& file) {
    for (const auto& o : m["outputs"])
        if (o["file"] == file) return &o;
    return nullptr;
}
bool holds(const json& o, const std::string& key, const std::string& role) {
    return o["channels"].contains(key) && o["channels"][key] == role;
}

// Every material file listed exists and hashes to its sha256; the formats listed, in a set.
std::multiset<std::string> listed_formats(const Ingested& r, const json& m) {
    std::multiset<std::string> formats;
    for (const auto& f : m["material_files"]) {
        EXPECT_EQ(mf::sha256_hex(read_bytes(r.out / f["file"].get<std::string>())), f["sha256"]) << f["file"];
        formats.insert(f["format"].get<std::string>());
    }
    return formats;
}

std::vector<json> python_checker(const std::string& script, const std::vector<std::string>& args, const fs::path& cwd) {
    std::vector<std::string> argv{"python3", (mf::testenv::source_dir() / "tests/texture/checkers" / script).string()};
    argv.insert(argv.end(), args.begin(), args.end());
    const fs::path old = fs::current_path();
    fs::current_path(cwd);
    const auto p = mf::testbin::spawn(argv, 300);
    fs::current_path(old);
    EXPECT_EQ(p.code, 0) << p.output;
    std::vector<json> out;
    std::istringstream lines(p.output);
    for (std::string line; std::getline(lines, line);)
        if (!line.empty()) out.push_back(json::parse(line));
    return out;
}

// ---- Godot 4

// Godot 4.6 itself (its web export template in headless Chromium: checkers/godot_load.mjs)
// loads each .tres under ROOT (paths relative to it, which is res://) and renders it on a
// sphere into OUT_DIR; one JSON line per file.
std::vector<json> godot_load(const fs::path& root, const std::vector<std::string>& tres, const fs::path& out) {
    if (!npm_checkers_installed()) return {};
    fs::create_directories(out);
    std::vector<std::string> argv{"node",
                                  (mf::testenv::source_dir() / "tests/texture/checkers/godot_load.mjs").string(),
                                  mf::testenv::npm_dir().string(), root.string(), out.string()};
    argv.insert(argv.end(), tres.begin(), tres.end());
    auto reports = json_lines(argv);
    EXPECT_EQ(reports.size(), tres.size());
    for (const auto& rep : reports) EXPECT_EQ(rep["engine_errors"], json::array()) << rep["file"];
    return reports;
}

// Each ORMMaterial3D slot and the channels Godot reads there (Godot's class reference).
const std::map<std::string, std::vector<std::string>> kGodotSlots{
    {"albedo_texture", {"RGB:albedo"}},  {"orm_texture", {"G:roughness", "B:metalness"}},
    {"normal_texture", {"RGB:normal"}},  {"emission_texture", {"RGB:emissive"}},
    {"heightmap_texture", {"R:height"}},
};

// Godot's pictures (checkers/godot_load.mjs: the preview's reference scene, its sphere, light
// and camera, 4x4 samples a pixel averaged in linear) against `matforge preview --scene reference
// --aa 4` of the same manifest, over the pixels lit in both away from the silhouette. The two
// agree at 26.6-42.5 dB on the samples and the corpus (docs/engines.md); most of the gap is
// Godot's default Burley diffuse, brighter than the preview's Lambert toward the terminator (with
// Lambert's they agree at 35-44 dB). A normal map's green read upside down takes Rocks004 from
// 35.9 to 18.3 dB (WoodFloor040 barely moves), an albedo mirrored broken_wall from 26.6 to 19.3.
// The lit share catches a cut-out drawn solid; Godot's is lower where a near-black material's
// samples round to code 0 before they are averaged (Obsidian_001: 0.79).
void expect_godot_renders_as_the_preview(const Ingested& r, const fs::path& renders) {
    const fs::path preview = renders / "preview";
    preview_reference(r.out / "manifest.json", preview, 192);  // godot_load.mjs's size
    for (const auto& m : r.manifest["materials"]) {
        const std::string name = m["name"];
        expect_agrees_with_preview(preview / (name + ".png"), renders / (name + ".godot.png"), 25.0, {0.75, 1.1},
                                   "godot " + name);
    }
}

void expect_godot(const Ingested& r) {
    std::vector<std::string> tres;
    for (const auto& m : r.manifest["materials"]) {
        const auto formats = listed_formats(r, m);
        EXPECT_EQ(formats.count("tres"), 1u) << m["name"];
        EXPECT_EQ(formats.count("import"), m["outputs"].size()) << m["name"] << ": an .import beside each texture";
        tres.push_back(m["name"].get<std::string>() + "/" + m["name"].get<std::string>() + ".tres");
    }
    // The renders beside the output folder, not in it: other tests list what the ingest wrote.
    const fs::path renders = r.out.string() + "-godot";
    mf::testbin::register_test_dir(renders);
    const auto reports = godot_load(r.out, tres, renders);
    ASSERT_EQ(reports.size(), r.manifest["materials"].size());
    size_t credited = 0;
    for (size_t i = 0; i < reports.size(); ++i) {
        const json& rep = reports[i];
        const json& m = r.manifest["materials"][i];
        SCOPED_TRACE(rep["file"].get<std::string>());
        ASSERT_TRUE(rep["ok"].get<bool>()) << rep["error"];
        EXPECT_EQ(rep["class"], "ORMMaterial3D");
        const json& props = rep["props"];
        const auto at = channels_of(m);
        std::set<std::string> used;
        for (const auto& [slot, needs] : kGodotSlots) {
            // A misspelled slot would be silently absent: every slot is asked for by name.
            ASSERT_TRUE(props.contains(slot)) << slot;
            const bool present = at.count(needs[0]) > 0;
            ASSERT_EQ(!props[slot].is_null(), present) << slot;
            if (!present) continue;
            const json& tex = props[slot];
            const std::string file = tex["file"];
            for (const auto& n : needs) EXPECT_EQ(at.at(n), file) << slot << " reads " << n;
            used.insert(file);
            const json* o = output_named(m, file);
            ASSERT_TRUE(o) << file;
            EXPECT_EQ(tex["width"], (*o)["width"]) << file;
            EXPECT_EQ(tex["height"], (*o)["height"]) << file;
            // The import settings Godot applies to it, as Godot's ConfigFile reads them.
            ASSERT_TRUE(rep["imports"].contains(file) && rep["imports"][file].is_object()) << file << ".import";
            const json& imp = rep["imports"][file];
            EXPECT_EQ(imp["remap"]["importer"], "texture");
            EXPECT_EQ(imp["remap"]["type"], "CompressedTexture2D");
            const json& params = imp["params"];
            EXPECT_EQ(params["compress/normal_map"], slot == "normal_texture" ? 1 : 2) << slot;
            EXPECT_EQ(params["compress/mode"], 2) << slot;
            EXPECT_EQ(params["mipmaps/generate"], true);
            EXPECT_EQ(params["detect_3d/compress_to"], 0);
        }
        // The text resource's heading (Godot reads format 3; load_steps counts the ext_resources).
        const auto bytes = read_bytes(r.out / rep["file"].get<std::string>());
        const std::string text(bytes.begin(), bytes.end());
        EXPECT_EQ(text.substr(0, text.find('\n')),
                  "[gd_resource type=\"ORMMaterial3D\" load_steps=" + std::to_string(used.size() + 1) + " format=3]");
        // ORM: occlusion in R when the set has one; AO read only with ao_enabled.
        if (at.count("R:occlusion")) {
            EXPECT_EQ(at.at("R:occlusion"), at.at("G:roughness"));
        }
        EXPECT_EQ(props["ao_enabled"], true);
        EXPECT_EQ(props["normal_enabled"], at.count("RGB:normal") > 0);
        EXPECT_EQ(props["emission_enabled"], at.count("RGB:emissive") > 0);
        EXPECT_EQ(props["heightmap_enabled"], at.count("R:height") > 0);
        EXPECT_EQ(props["emission"], json::array({0, 0, 0, 1}))
            << "Godot adds the emission colour to the texture: left black";
        // The material's credit as Godot reads it back: its metadata `copyright` (a stored
        // property "metadata/copyright"), none where the licence is unknown.
        std::string error;
        const auto entry = mf::manifest::material_from_json(m, m["name"], error);
        ASSERT_TRUE(entry) << error;
        const auto credit = entry->provenance ? mf::manifest::material_credit(*entry->provenance) : std::nullopt;
        EXPECT_EQ(props.contains("metadata/copyright"), credit.has_value());
        if (credit) {
            EXPECT_EQ(props["metadata/copyright"], credit->line);
        }
        credited += credit.has_value();
        for (const auto& o : m["outputs"])
            EXPECT_TRUE(used.count(o["file"])) << o["file"] << " is written but not used";
        // Alpha as the manifest decided it (the glTF's alphaMode): scissor at the cutoff, or blend.
        const std::string alpha = m.value("alpha_mode", "none");
        EXPECT_EQ(props["transparency"], alpha == "mask" ? 2 : alpha == "blend" ? 1 : 0) << alpha;
        if (alpha == "mask") {
            EXPECT_NEAR(props["alpha_scissor_threshold"].get<double>(), m["alpha_cutoff"].get<double>(), 1e-6);
        }
        // Godot draws it: the sphere covers part of the frame, in a colour that is not black.
        ASSERT_TRUE(rep.contains("render")) << "not rendered";
        const json& render = rep["render"];
        EXPECT_GT(render["lit"].get<double>(), 0.05) << "share of the frame drawn";
        const double mean = render["mean"][0].get<double>() + render["mean"][1].get<double>() +
                            render["mean"][2].get<double>();
        EXPECT_GT(mean, 0.03) << render.dump();
        EXPECT_TRUE(fs::is_regular_file(renders / (m["name"].get<std::string>() + ".godot.png")));
    }
    EXPECT_GE(credited, 3u) << "the samples' ambientCG, Poly Haven and 3dtextures.me sets";
    expect_godot_renders_as_the_preview(r, renders);
}

TEST(EngineFiles, GodotSamples) {
    const auto& r = ingested("godot", "samples");
    ASSERT_EQ(r.manifest["materials"].size(), 4u);
    expect_godot(r);
    // Net004A's net is cut out.
    EXPECT_EQ(r.manifest["materials"][2]["name"], "Net004A");
    EXPECT_EQ(r.manifest["materials"][2]["alpha_mode"], "mask");
}

// ---- Unity HDRP and URP

struct UnitySlot {
    std::string slot;
    std::vector<std::string> reads;  // "KEY:role" the shader reads there
    std::string keyword;             // the keyword that turns the map on ("" = none needed)
};
// HDRP Lit and URP Lit (Unity's shader documentation; the shaders' guids from their packages).
const std::vector<UnitySlot> kHdrp{{"_BaseColorMap", {"RGB:albedo"}, ""},
                                   {"_MaskMap", {"R:metalness", "A:smoothness"}, "_MASKMAP"},
                                   {"_NormalMap", {"RGB:normal"}, "_NORMALMAP"},
                                   {"_HeightMap", {"R:height"}, "_HEIGHTMAP"},
                                   {"_EmissiveColorMap", {"RGB:emissive"}, "_EMISSIVE_COLOR_MAP"}};
const std::vector<UnitySlot> kUrp{{"_BaseMap", {"RGB:albedo"}, ""},
                                  {"_MetallicGlossMap", {"R:metalness", "A:smoothness"}, "_METALLICSPECGLOSSMAP"},
                                  {"_BumpMap", {"RGB:normal"}, "_NORMALMAP"},
                                  {"_OcclusionMap", {"R:occlusion"}, "_OCCLUSIONMAP"},
                                  {"_ParallaxMap", {"R:height"}, "_PARALLAXMAP"},
                                  {"_EmissionMap", {"RGB:emissive"}, "_EMISSION"}};

void expect_unity(const Ingested& r, bool hdrp) {
    std::vector<std::string> args{"."};
    for (const auto& m : r.manifest["materials"]) {
        const auto formats = listed_formats(r, m);
        EXPECT_EQ(formats.count("mat"), 1u) << m["name"];
        EXPECT_EQ(formats.count("meta"), m["outputs"].size() + 1)
            << m["name"] << ": a .meta per texture and the .mat's";
        args.push_back(m["name"].get<std::string>() + "/" + m["name"].get<std::string>() + ".mat");
    }
    const auto reports = python_checker("unity_check.py", args, r.out);
    ASSERT_EQ(reports.size(), r.manifest["materials"].size());
    for (size_t i = 0; i < reports.size(); ++i) {
        const json& rep = reports[i];
        const json& m = r.manifest["materials"][i];
        SCOPED_TRACE(rep["file"].get<std::string>());
        ASSERT_TRUE(rep["ok"].get<bool>()) << rep["error"];
        EXPECT_TRUE(rep["guids_unique"].get<bool>());
        EXPECT_EQ(rep["name"], m["name"]);
        EXPECT_EQ(rep["shader_file_id"], 4800000);
        EXPECT_EQ(rep["shader_guid"], hdrp ? "6e4ae4064600d784cac1e41a9e6f2e59" : "933532a4fcc9baf4fa0491de14d08ed7");
        EXPECT_EQ(rep["mat_meta"]["importer"], json::array({"NativeFormatImporter"}));
        // HDRP's material version beside the Material (else HDRP upgrades and rewrites it on import).
        EXPECT_EQ(rep["asset_versions"],
                  hdrp ? json::array({{{"script_guid", "da692e001514ec24dbc4cca1949ff7e8"}, {"version", 13}}})
                       : json::array());
        const auto at = channels_of(m);
        const std::set<std::string> keywords(rep["keywords"].begin(), rep["keywords"].end());
        std::set<std::string> used;
        for (const UnitySlot& s : hdrp ? kHdrp : kUrp) {
            const bool present = at.count(s.reads[0]) > 0;
            ASSERT_TRUE(rep["textures"].contains(s.slot)) << s.slot;
            const json& t = rep["textures"][s.slot];
            ASSERT_EQ(!t.is_null(), present) << s.slot;
            if (!s.keyword.empty()) {
                EXPECT_EQ(keywords.count(s.keyword), present ? 1u : 0u) << s.keyword;
            }
            if (!present) continue;
            ASSERT_FALSE(t["file"].is_null()) << s.slot << ": guid " << t["guid"] << " names no .meta";
            const std::string file = t["file"];
            for (const auto& n : s.reads) EXPECT_EQ(at.at(n), file) << s.slot << " reads " << n;
            used.insert(file);
            const json* o = output_named(m, file);
            ASSERT_TRUE(o);
            const json& imp = t["importer"];
            EXPECT_EQ(imp["mipmaps"]["sRGBTexture"], (*o)["color_space"] == "sRGB" ? 1 : 0) << file;
            EXPECT_EQ(imp["textureType"], holds(*o, "RGB", "normal") ? 1 : 0) << file;
            EXPECT_EQ(imp["alphaIsTransparency"], holds(*o, "A", "opacity") ? 1 : 0) << file;
            // A kept wherever it holds anything (the mask map's smoothness too): 0 drops it.
            EXPECT_EQ(imp["alphaUsage"], (*o)["channels"].contains("A") ? 1 : 0) << file;
            EXPECT_GE(imp["maxTextureSize"].get<int>(), std::max((*o)["width"].get<int>(), (*o)["height"].get<int>()));
        }
        if (hdrp && at.count("RGB:normal")) {
            EXPECT_TRUE(keywords.count("_NORMALMAP_TANGENT_SPACE"));
        }
        if (hdrp && at.count("G:occlusion")) {
            EXPECT_EQ(at.at("G:occlusion"), at.at("R:metalness"));
        }
        for (const auto& o : m["outputs"])
            EXPECT_TRUE(used.count(o["file"])) << o["file"] << " is written but not used";
        // The maps carry the values: every multiplier at 1.
        EXPECT_EQ(rep["floats"]["_Metallic"], 1);
        EXPECT_EQ(rep["floats"]["_Smoothness"], 1);
        const std::string alpha = m.value("alpha_mode", "none");
        EXPECT_EQ(keywords.count("_ALPHATEST_ON"), alpha == "mask" ? 1u : 0u);
        EXPECT_EQ(rep["floats"][hdrp ? "_AlphaCutoffEnable" : "_AlphaClip"], alpha == "mask" ? 1 : 0);
    }
}

TEST(EngineFiles, UnityHdrpSamples) { expect_unity(ingested("unity-hdrp", "samples"), true); }
TEST(EngineFiles, UnityUrpSamples) { expect_unity(ingested("unity-urp", "samples"), false); }

// A re-ingest into another folder: the same guids, so references in a user's project hold.
TEST(EngineFiles, UnityGuidsAreStableAcrossRuns) {
    const auto& a = ingested("unity-hdrp", "samples");
    const fs::path b = temp_dir("again");
    ingest({samples()}, b, "unity-hdrp", {"--fail-on", "never"});
    size_t metas = 0;
    for (const auto& e : fs::recursive_directory_iterator(a.out))
        if (e.path().extension() == ".meta") {
            ++metas;
            EXPECT_EQ(read_bytes(e.path()), read_bytes(b / fs::relative(e.path(), a.out))) << e.path();
        }
    EXPECT_GE(metas, 16u);
}

// ---- Unreal

void expect_unreal(const Ingested& r) {
    std::vector<std::string> scripts;
    for (const auto& m : r.manifest["materials"]) {
        const auto formats = listed_formats(r, m);
        EXPECT_EQ(formats, std::multiset<std::string>{"py"}) << m["name"];
        scripts.push_back(m["name"].get<std::string>() + "/import_" + m["name"].get<std::string>() + ".py");
    }
    const auto reports = python_checker("unreal_check.py", scripts, r.out);
    ASSERT_EQ(reports.size(), r.manifest["materials"].size());
    for (size_t i = 0; i < reports.size(); ++i) {
        const json& rep = reports[i];
        const json& m = r.manifest["materials"][i];
        SCOPED_TRACE(rep["file"].get<std::string>());
        ASSERT_TRUE(rep["parses"].get<bool>()) << rep["error"];
        ASSERT_TRUE(rep["ok"].get<bool>()) << rep["error"];
        ASSERT_EQ(rep["imports"].size(), m["outputs"].size()) << "every written texture imported";
        std::map<std::string, std::string> asset_of;  // output file -> imported asset
        for (const auto& imp : rep["imports"]) {
            EXPECT_TRUE(imp["exists"].get<bool>()) << imp["filename"];
            EXPECT_TRUE(imp["automated"].get<bool>());
            const fs::path f = fs::relative(imp["filename"].get<std::string>(), fs::canonical(r.out));
            asset_of[f.generic_string()] = imp["destination_path"].get<std::string>() + "/" + f.stem().string();
        }
        std::map<std::string, std::string> param_of;  // imported asset -> the instance parameter
        for (const auto& [param, asset] : rep["instance"]["textures"].items()) param_of[asset] = param;
        for (const auto& o : m["outputs"]) {
            const std::string file = o["file"];
            ASSERT_TRUE(asset_of.count(file)) << file << " is written but not imported";
            const json& tex = rep["textures"][asset_of[file]];
            EXPECT_EQ(tex["srgb"], o["color_space"] == "sRGB") << file;
            const std::string want = holds(o, "RGB", "normal")                                  ? "TC_NORMALMAP"
                                     : holds(o, "G", "roughness") && holds(o, "B", "metalness") ? "TC_MASKS"
                                     : holds(o, "R", "height")                                  ? "TC_GRAYSCALE"
                                                                                                : "TC_DEFAULT";
            EXPECT_EQ(tex["compression_settings"], "TextureCompressionSettings." + want) << file;
            const std::string param = holds(o, "RGB", "albedo")     ? "BaseColor"
                                      : holds(o, "RGB", "normal")   ? "Normal"
                                      : holds(o, "G", "roughness")  ? "ORM"
                                      : holds(o, "RGB", "emissive") ? "Emissive"
                                                                    : "";
            if (!param.empty()) {
                EXPECT_EQ(param_of[asset_of[file]], param) << file;
            }
        }
        EXPECT_EQ(rep["instance"]["parent"], "/Game/Matforge/M_MatforgeORM");
        EXPECT_TRUE(rep["parent"]["created"].get<bool>()) << "a project without the parent gets it";
        const std::set<std::vector<std::string>> wired{{"BaseColor", "RGB", "MP_BASE_COLOR"},
                                                       {"ORM", "R", "MP_AMBIENT_OCCLUSION"},
                                                       {"ORM", "G", "MP_ROUGHNESS"},
                                                       {"ORM", "B", "MP_METALLIC"},
                                                       {"Normal", "RGB", "MP_NORMAL"},
                                                       {"BaseColor", "A", "MP_OPACITY_MASK"}};
        std::set<std::vector<std::string>> got;
        for (const auto& c : rep["parent"]["connections"]) got.insert(c.get<std::vector<std::string>>());
        for (const auto& w : wired) EXPECT_TRUE(got.count(w)) << w[0] << "." << w[1] << " -> " << w[2];
        const std::string alpha = m.value("alpha_mode", "opaque");
        EXPECT_EQ(rep["instance"]["overrides"]["blend_mode"],
                  std::string("BlendMode.") + (alpha == "mask"    ? "BLEND_MASKED"
                                               : alpha == "blend" ? "BLEND_TRANSLUCENT"
                                                                  : "BLEND_OPAQUE"));
    }
}

TEST(EngineFiles, UnrealSamples) { expect_unreal(ingested("unreal", "samples")); }

// Each Unreal instance is complete on its own (issue 45): run one after the other in one project,
// in either order, the parent made by the first compiles (a default texture on every parameter,
// the engine's neutral ones where that set has none) and every instance sets every parameter —
// a set without an emission map gets black and strength 0, never another set's glow. The
// folder's import_all.py runs every script.
TEST(EngineFiles, UnrealInstancesAreCompleteInAnyOrder) {
    const Ingested& r = ingested("unreal", "corpus");
    const std::string lit = "OfficeCeiling005", dark = "WoodFloor040";  // with and without an emission map
    auto script = [](const std::string& m) { return m + "/import_" + m + ".py"; };
    for (const auto& order : {std::vector<std::string>{lit, dark}, std::vector<std::string>{dark, lit}}) {
        SCOPED_TRACE(order[0] + " first");
        const auto reports = python_checker("unreal_check.py", {"--session", script(order[0]), script(order[1])},
                                            r.out);
        ASSERT_EQ(reports.size(), 2u);
        ASSERT_TRUE(reports[0]["ok"].get<bool>()) << reports[0]["error"];
        ASSERT_TRUE(reports[1]["ok"].get<bool>()) << reports[1]["error"];
        EXPECT_TRUE(reports[0]["parent"]["created"].get<bool>());
        EXPECT_FALSE(reports[1]["parent"]["created"].get<bool>()) << "the second reuses the first's parent";
        const json& defaults = reports[1]["parent"]["defaults"];
        for (const char* p : {"BaseColor", "ORM", "Normal", "Emissive"})
            EXPECT_TRUE(defaults.contains(p)) << p << " has no default texture: the parent would not compile";
        for (size_t i = 0; i < 2; ++i) {
            const json& inst = reports[i]["instance"];
            for (const char* p : {"BaseColor", "ORM", "Normal", "Emissive"})
                EXPECT_TRUE(inst["textures"].contains(p)) << order[i] << " leaves " << p << " to the parent";
            const bool has_emission = order[i] == lit;
            EXPECT_EQ(inst["textures"]["Emissive"] == "/Engine/EngineResources/Black", !has_emission) << order[i];
            EXPECT_EQ(inst["scalars"]["EmissiveStrength"].get<double>() > 0, has_emission) << order[i];
        }
    }
    ASSERT_TRUE(fs::exists(r.out / "import_all.py"));
    const auto all = python_checker("unreal_check.py", {"import_all.py"}, r.out);
    ASSERT_EQ(all.size(), 1u);
    ASSERT_TRUE(all[0]["ok"].get<bool>()) << all[0]["error"];
    size_t outputs = 0;
    for (const auto& m : r.manifest["materials"]) outputs += m["outputs"].size();
    EXPECT_EQ(all[0]["imports"].size(), outputs) << "every material's textures imported";
}

// Every engine's files for the real corpus, from one run of the four presets: Godot's, Unity's
// (HDRP and URP) and Unreal's readers as on the samples.
TEST(EngineFiles, EveryEngineOnTheCorpusInOneRun) {
    const auto each = corpus_for_every_engine();
    ASSERT_GE(each.at("godot").manifest["materials"].size(), 15u);
    for (const auto& [preset, r] : each) EXPECT_EQ(r.manifest["preset"], preset);
    expect_godot(each.at("godot"));
    expect_unity(each.at("unity-hdrp"), true);
    expect_unity(each.at("unity-urp"), false);
    expect_unreal(each.at("unreal"));
}

// ---- A preset whose layout an engine cannot read is refused before any set is read.

TEST(EngineFiles, APresetTheEngineCannotReadIsRefused) {
    const fs::path dir = temp_dir("preset");
    const auto shown = matforge({"presets", "show", "godot"});
    ASSERT_EQ(shown.code, 0) << shown.output;
    json p = json::parse(shown.output.substr(shown.output.find('{')));
    p["name"] = "godot-swapped";
    for (auto& o : p["outputs"])
        if (o["suffix"] == "orm") o["channels"] = {{"R", "roughness"}, {"G", "occlusion"}, {"B", "metalness"}};
    write_text(dir / "p.json", p.dump(2));
    const auto r = matforge({"ingest", samples().string(), "-o", (dir / "out").string(), "--preset",
                             (dir / "p.json").string()});
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("'orm' holds occlusion in G; orm_texture reads it from R"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir / "out" / "manifest.json"));
}

}  // namespace

namespace {

// ---- Direct3D 11: the include, once per folder (every shard alike), compiled as HLSL.

TEST(EngineFiles, D3d11FolderGetsTheHlslIncludeThatCompiles) {
    const fs::path dir = temp_dir("d3d11");
    const json m = ingest({samples() / "Net004A_1K-JPG"}, dir / "out", "d3d11", {"--fail-on", "never"});
    ASSERT_EQ(m["library"].size(), 2u) << m["library"].dump();  // and ATTRIBUTION.md (every preset)
    EXPECT_EQ(m["library"][1]["file"], "ATTRIBUTION.md");
    EXPECT_EQ(m["library"][0]["file"], "matforge_material.hlsli");
    EXPECT_EQ(m["library"][0]["format"], "hlsli");
    const fs::path include = dir / "out" / "matforge_material.hlsli";
    EXPECT_EQ(m["library"][0]["sha256"], mf::sha256_hex(read_bytes(include)));
    EXPECT_EQ(read_bytes(include), read_bytes(mf::testenv::source_dir() / "lib/engine/matforge_material.hlsli"));
    for (const auto& mat : m["materials"]) EXPECT_FALSE(mat.contains("material_files")) << "the include is per folder";
    // glslang's HLSL front end compiles a pixel shader built on it (no fxc or dxc in Debian).
    const auto p =
        mf::testbin::spawn({"glslangValidator", "-D", "-V", "-S", "frag", "-e", "main", "--target-env", "vulkan1.2",
                            "-I" + (dir / "out").string(), "-o", (dir / "ps.spv").string(),
                            (mf::testenv::source_dir() / "tests/texture/checkers/d3d11_material.hlsl").string()},
                           120);
    ASSERT_EQ(p.code, 0) << p.output;
    EXPECT_GT(fs::file_size(dir / "ps.spv"), 1000u);
    // A shard writes it too (each part is a complete folder of its own), and merge keeps it;
    // ATTRIBUTION.md lists the run's materials: merge writes it, no shard.
    const auto part = matforge({"ingest", (samples() / "Net004A_1K-JPG").string(), "-o", (dir / "shard").string(),
                                "--preset", "d3d11", "--quiet", "--fail-on", "never", "--shard", "0/1"});
    ASSERT_EQ(part.code, 0) << part.output;
    const json shard = mf::testfiles::read_json(dir / "shard" / "manifest.shard-0-of-1.json");
    EXPECT_EQ(shard["library"], json::array({m["library"][0]}));
    const auto merged = matforge({"merge", (dir / "shard" / "manifest.shard-0-of-1.json").string(), "-o",
                                  (dir / "shard" / "manifest.json").string()});
    ASSERT_EQ(merged.code, 0) << merged.output;
    EXPECT_EQ(mf::testfiles::read_json(dir / "shard" / "manifest.json")["library"], m["library"]);
}

}  // namespace

namespace {

// A material name is any bytes (a file's name): with a quote, a backslash, a newline and a byte
// that is not UTF-8, each engine file still parses, by the same independent readers, and gives
// the name back (the bad byte as U+FFFD).
TEST(EngineFiles, AnyNameMakesFilesTheReadersParse) {
    const fs::path dir = temp_dir("names");
    mf::manifest::Material m;
    m.name = "Net\"004A\\\nx\xff";
    const std::string want = "Net\"004A\\\nx\xef\xbf\xbd";
    EXPECT_EQ(json::parse(mf::engine::string_literal(m.name)).get<std::string>(), want);
    const auto write_all = [&](const std::vector<mf::engine::File>& files) {
        std::vector<std::string> paths;
        for (const auto& f : files) {  // at paths without the name (the checkers print the paths)
            std::string rel = f.file;
            for (size_t at; (at = rel.find(m.name)) != std::string::npos;) rel.replace(at, m.name.size(), "M");
            write_text(dir / "lib" / rel, f.text);
            paths.push_back(rel);
        }
        return paths;
    };
    const auto tres = write_all(mf::engine::godot_files(*mf::engine_material(mf::MaterialFileKind::godot), m, {}));
    const auto godot = godot_load(dir / "lib", {tres.back()}, dir / "godot");
    ASSERT_EQ(godot.size(), 1u);
    ASSERT_TRUE(godot[0]["ok"].get<bool>()) << godot[0]["error"];
    EXPECT_EQ(godot[0]["class"], "ORMMaterial3D");
    EXPECT_EQ(godot[0]["props"]["resource_name"], want);
    const auto* hdrp = mf::engine_material(mf::MaterialFileKind::unity_hdrp);
    ASSERT_TRUE(hdrp);
    const auto mat = write_all(mf::engine::unity_files(*hdrp, m, {}));
    const auto unity = python_checker("unity_check.py", {".", mat[0]}, dir / "lib");
    ASSERT_EQ(unity.size(), 1u);
    ASSERT_TRUE(unity[0]["ok"].get<bool>()) << unity[0]["error"];
    EXPECT_EQ(unity[0]["name"], want);
    const auto py = write_all(mf::engine::unreal_files(*mf::engine_material(mf::MaterialFileKind::unreal), m, {}));
    const auto unreal = python_checker("unreal_check.py", {py[0]}, dir / "lib");
    ASSERT_EQ(unreal.size(), 1u);
    ASSERT_TRUE(unreal[0]["parses"].get<bool>()) << unreal[0]["error"];
    // The MaterialX document names the material in its first comment, where XML forbids "--":
    // Python's expat, a strict XML parser, reads it.
    mf::manifest::Material dashes;
    dashes.name = "Oak--Floor---";
    write_text(dir / "lib/dashes.mtlx", mf::mtlx::material_mtlx(dashes, "dashes.mtlx"));
    const auto p = mf::testbin::spawn({"python3", "-c",
                                       "import sys, xml.etree.ElementTree as E; E.parse(sys.argv[1]); print('ok')",
                                       (dir / "lib/dashes.mtlx").string()});
    EXPECT_EQ(p.code, 0) << p.output;
    EXPECT_NE(p.output.find("ok"), std::string::npos) << p.output;
}

}  // namespace
