// `matforge ingest --preset gltf`: a .gltf per set and library.gltf, checked by the Khronos
// glTF-Validator (0 errors, 0 warnings) on sample_materials/ and the real-material corpus, and
// their materials checked against the manifest (slots, alpha mode, URIs, hashes).
#include <cmath>
#include <fstream>
#include <set>

#include "base/srgb.hpp"
#include "core/text.hpp"
#include "manifest/attribution.hpp"
#include "manifest/manifest.hpp"
#include "material/provenance.hpp"
#include "texture_cli.hpp"

using namespace mtt;

namespace gltf_credit {

// The credit matforge gives a manifest entry (manifest/attribution.hpp material_credit, whose
// text Credit.* in tests/material pins), nullopt where its licence is unknown: what the material
// files must carry, read back here by the real implementations.
std::optional<mf::manifest::Credit> of(const json& m) {
    std::string error;
    const auto entry = mf::manifest::material_from_json(m, m.value("name", ""), error);
    EXPECT_TRUE(entry) << error;
    return entry && entry->provenance ? mf::manifest::material_credit(*entry->provenance) : std::nullopt;
}

// The licences `text` names as matforge's provenance reads a sidecar's (SPDX ids, else names).
std::vector<std::string> licences_in(const std::string& text) {
    std::vector<std::string> out;
    for (const auto& n : mf::licences_named(text))
        out.emplace_back(n.licence->spdx.empty() ? n.licence->name : n.licence->spdx);
    return out;
}

// The entry's provenance, {} where it has none (nothing known).
const json& provenance(const json& m) {
    static const json none = json::object();
    return m.contains("provenance") ? m["provenance"] : none;
}
bool licence_known(const json& m) { return provenance(m).contains("licence"); }

// The manifest entry's licence as the same list: the one licence a credit must name.
std::vector<std::string> manifest_licence(const json& m) {
    const json& l = m["provenance"]["licence"];
    return {l.contains("spdx") ? l["spdx"].get<std::string>() : l["name"].get<std::string>()};
}

}  // namespace gltf_credit

namespace {

struct Run {
    fs::path out;
    json manifest;
};
const Run& ingested(const std::string& what) {
    static std::map<std::string, Run> cache;
    if (auto it = cache.find(what); it != cache.end()) return it->second;
    Run r;
    r.out = fs::temp_directory_path() / ("matforge-texture-gltf-" + what + "-" + std::to_string(::getpid()));
    fs::remove_all(r.out);
    mf::testbin::register_test_dir(r.out);
    EXPECT_TRUE(what != "corpus" || fs::is_directory(corpus())) << corpus() << ": the real-material corpus is missing";
    r.manifest = ingest({what == "corpus" ? corpus() : samples()}, r.out, "gltf", {"--fail-on", "never"});
    return cache[what] = r;
}

std::vector<fs::path> gltf_files(const fs::path& out) {
    std::vector<fs::path> files;
    for (const auto& e : fs::recursive_directory_iterator(out))
        if (e.path().extension() == ".gltf") files.push_back(e.path());
    std::sort(files.begin(), files.end());
    return files;
}

void expect_valid(const Run& r, size_t materials) {
    const auto files = gltf_files(r.out);
    ASSERT_EQ(files.size(), materials + 1) << "one per set and library.gltf";
    const auto reports = node_checker("gltf_validate.mjs", files);
    ASSERT_EQ(reports.size(), files.size());
    for (const auto& rep : reports) {
        EXPECT_EQ(rep["validator"], "2.0.0-dev.3.10");
        EXPECT_EQ(rep["errors"], 0) << rep.dump(1);
        EXPECT_EQ(rep["warnings"], 0) << rep.dump(1);
        EXPECT_EQ(rep["infos"], 0) << rep.dump(1);
        // The validator opened the buffer and every image (a missing one is an error).
        size_t images = 0;
        for (const auto& res : rep["resources"]) images += !res["image"].is_null();
        EXPECT_GE(images, 2u) << rep["file"];
    }
}

}  // namespace

TEST(Gltf, SampleMaterialsPassTheValidator) {
    const auto& r = ingested("samples");
    ASSERT_EQ(r.manifest["materials"].size(), 4u);
    expect_valid(r, 4);
}

TEST(Gltf, CorpusPassesTheValidator) {
    const auto& r = ingested("corpus");
    ASSERT_GE(r.manifest["materials"].size(), 15u);
    expect_valid(r, r.manifest["materials"].size());
}

// Each .gltf's asset.copyright (glTF 2.0: "a copyright message suitable for display to credit the
// content creator") is the material's credit, naming the manifest's licence, the asset and its
// page, and is absent where the licence is unknown (Crystal_003 of the samples); library.gltf,
// of several sources, points to ATTRIBUTION.md. The glTF-Validator passes them (expect_valid) and
// does read the field: a copyright that is not a string is its TYPE_MISMATCH at /asset/copyright.
TEST(Gltf, CopyrightIsTheCreditReadByTheValidator) {
    const auto& r = ingested("samples");
    size_t credited = 0, unknown = 0;
    for (const auto& m : r.manifest["materials"]) {
        const std::string name = m["name"];
        SCOPED_TRACE(name);
        const json g = mf::testfiles::read_json(r.out / name / (name + ".gltf"));
        const auto credit = gltf_credit::of(m);
        if (!gltf_credit::licence_known(m)) {
            EXPECT_FALSE(credit);
            EXPECT_FALSE(g["asset"].contains("copyright")) << g["asset"];
            ++unknown;
            continue;
        }
        ASSERT_TRUE(credit);
        ASSERT_TRUE(g["asset"].contains("copyright")) << g["asset"];
        const std::string c = g["asset"]["copyright"];
        EXPECT_EQ(c, credit->line);
        EXPECT_EQ(gltf_credit::licences_in(c), gltf_credit::manifest_licence(m)) << c;
        EXPECT_NE(c.find(m["provenance"]["licence"]["url"].get<std::string>()), std::string::npos) << c;
        EXPECT_NE(c.find(m["provenance"]["asset_id"].get<std::string>()), std::string::npos) << c;
        if (m["provenance"].contains("url")) {
            EXPECT_NE(c.find(m["provenance"]["url"].get<std::string>()), std::string::npos) << c;
        }
        ++credited;
    }
    EXPECT_EQ(credited, 3u) << "ambientCG, Poly Haven, 3dtextures.me";
    EXPECT_EQ(unknown, 1u) << "Crystal_003";
    const json lib = mf::testfiles::read_json(r.out / "library.gltf");
    EXPECT_EQ(lib["asset"]["copyright"],
              "Materials of several sources or licences: each one's source, licence and credit in ATTRIBUTION.md "
              "beside this file");
    // A library of one material carries that material's credit.
    const fs::path alone = temp_dir("credit-alone");
    const json one = ingest({samples() / "Net004A_1K-JPG"}, alone, "gltf", {"--fail-on", "never"});
    ASSERT_EQ(one["materials"].size(), 1u);
    const auto credit = gltf_credit::of(one["materials"][0]);
    ASSERT_TRUE(credit);
    EXPECT_EQ(mf::testfiles::read_json(alone / "library.gltf")["asset"]["copyright"], credit->line);
    const std::string net = (r.out / "Net004A" / "Net004A.gltf").string();
    const auto reports = node_checker("gltf_validate.mjs",
                                      {damaged_copy(net, "\"copyright\": \"", "\"copyright\": 5, \"was\": \"",
                                                    r.out / "Net004A" / "copyright_number.gltf")});
    ASSERT_EQ(reports.size(), 1u);
    EXPECT_GE(reports[0]["errors"].get<int>(), 1) << reports[0].dump(1);
    bool mismatch = false;
    for (const auto& msg : reports[0]["messages"])
        mismatch |= msg["code"] == "TYPE_MISMATCH" && msg["pointer"] == "/asset/copyright";
    EXPECT_TRUE(mismatch) << reports[0]["messages"].dump(1);
    fs::remove(r.out / "Net004A" / "copyright_number.gltf");
}

TEST(Gltf, MaterialsReferenceTheWrittenTexturesInTheirSlots) {
    const auto& r = ingested("samples");
    for (const auto& m : r.manifest["materials"]) {
        const std::string name = m["name"];
        ASSERT_EQ(m["material_files"].size(), 4u) << name;
        EXPECT_EQ(m["material_files"][0]["file"], name + "/" + name + ".gltf");
        EXPECT_EQ(m["material_files"][1]["file"], name + "/" + name + ".bin");
        EXPECT_EQ(m["material_files"][2]["file"], name + "/" + name + ".mtlx");
        EXPECT_EQ(m["material_files"][3]["file"], name + "/" + name + ".usda");
        for (const auto& f : m["material_files"])
            EXPECT_EQ(mf::sha256_hex(read_bytes(r.out / f["file"].get<std::string>())), f["sha256"]) << f["file"];
        const json g = mf::testfiles::read_json(r.out / name / (name + ".gltf"));
        EXPECT_EQ(g["asset"]["version"], "2.0");
        EXPECT_EQ(g["buffers"][0]["uri"], name + ".bin");
        const json& mat = g["materials"][0];
        EXPECT_EQ(mat["name"], name);
        auto uri_of_slot = [&](const json& slot) {
            const size_t t = slot["index"];
            return g["images"][g["textures"][t]["source"].get<size_t>()]["uri"].get<std::string>();
        };
        // Each slot names the file the manifest says holds that role, relative to the .gltf.
        std::map<std::string, std::string> file_of;
        for (const auto& o : m["outputs"]) {
            const std::string f = fs::path(o["file"].get<std::string>()).filename().string();
            for (const auto& [key, v] : o["channels"].items())
                if (v.is_string()) file_of[key + ":" + v.get<std::string>()] = f;
        }
        EXPECT_EQ(uri_of_slot(mat["pbrMetallicRoughness"]["baseColorTexture"]), file_of["RGB:albedo"]) << name;
        EXPECT_EQ(uri_of_slot(mat["pbrMetallicRoughness"]["metallicRoughnessTexture"]), file_of["G:roughness"]) << name;
        EXPECT_EQ(file_of["G:roughness"], file_of["B:metalness"]);
        EXPECT_EQ(uri_of_slot(mat["normalTexture"]), file_of["RGB:normal"]) << name;
        // Factors stay at their defaults of 1: the textures carry the values.
        EXPECT_FALSE(mat["pbrMetallicRoughness"].contains("metallicFactor"));
        EXPECT_FALSE(mat["pbrMetallicRoughness"].contains("roughnessFactor"));
        // Occlusion only where the set has an occlusion (AO map or packed ARM).
        const bool occlusion = m["inputs"].contains("occlusion") || m["inputs"].contains("orm");
        EXPECT_EQ(mat.contains("occlusionTexture"), occlusion) << name;
        if (occlusion) {
            EXPECT_EQ(uri_of_slot(mat["occlusionTexture"]), file_of["R:occlusion"]);
        }
        // Net004A's cut-out net is alpha-tested; the others are opaque.
        if (name == "Net004A") {
            EXPECT_EQ(mat["alphaMode"], "MASK");
            EXPECT_EQ(mat["alphaCutoff"], 0.5);
            EXPECT_EQ(mat["doubleSided"], true);
        } else {
            EXPECT_FALSE(mat.contains("alphaMode")) << name;
        }
        EXPECT_FALSE(mat.contains("emissiveTexture")) << name << ": no emissive map in the samples";
        EXPECT_FALSE(g.contains("extensionsUsed")) << name << ": KHR_materials_emissive_strength only when needed";
        EXPECT_EQ(g["meshes"][0]["primitives"][0]["attributes"].size(), 4u) << "POSITION NORMAL TANGENT TEXCOORD_0";
    }
}

TEST(Gltf, LibraryHoldsEveryMaterialOnItsOwnNode) {
    const auto& r = ingested("samples");
    ASSERT_EQ(r.manifest["library"].size(), 5u);  // ATTRIBUTION.md, library.gltf, .bin, .usda, .mtlx
    EXPECT_EQ(r.manifest["library"][0]["file"], "ATTRIBUTION.md");
    EXPECT_EQ(r.manifest["library"][1]["file"], "library.gltf");
    const json g = mf::testfiles::read_json(r.out / "library.gltf");
    ASSERT_EQ(g["nodes"].size(), r.manifest["materials"].size());
    ASSERT_EQ(g["materials"].size(), r.manifest["materials"].size());
    std::set<std::pair<double, double>> places;
    for (size_t i = 0; i < g["nodes"].size(); ++i) {
        const json& n = g["nodes"][i];
        EXPECT_EQ(n["name"], r.manifest["materials"][i]["name"]);
        EXPECT_EQ(
            g["materials"][g["meshes"][n["mesh"].get<size_t>()]["primitives"][0]["material"].get<size_t>()]["name"],
            n["name"]);
        places.insert({n["translation"][0].get<double>(), n["translation"][1].get<double>()});
    }
    EXPECT_EQ(places.size(), g["nodes"].size()) << "a grid: every node in its own place";
    // URIs from the root: the material's folder, then the file.
    for (const auto& img : g["images"]) EXPECT_TRUE(fs::exists(r.out / img["uri"].get<std::string>())) << img["uri"];
    EXPECT_EQ(mf::sha256_hex(read_bytes(r.out / "library.gltf")), r.manifest["library"][1]["sha256"]);
}

TEST(Gltf, DxNormalsSkipTheGltfWithAFinding) {
    const fs::path out = temp_dir("dx");
    const json m = ingest({samples() / "Net004A_1K-JPG"}, out, "gltf", {"--normal-convention", "dx"});
    EXPECT_FALSE(fs::exists(out / "Net004A" / "Net004A.gltf"));
    EXPECT_FALSE(fs::exists(out / "library.gltf"));
    bool skipped = false;
    for (const auto& f : m["materials"][0]["findings"]) skipped |= f["code"] == "MATERIAL_FILE_SKIPPED";
    EXPECT_TRUE(skipped);
    EXPECT_FALSE(m["materials"][0].contains("material_files"));
}

// An HDR emissive (an EXR of radiance up to 4) written to an 8-bit file: stored as emissive / 4
// (the hue kept, not clipped to white), emissive_strength 4 in the manifest, the glTF carrying
// KHR_materials_emissive_strength (glTF-Validator clean), and the preview's radiance back at 4.
TEST(Gltf, HdrEmissiveKeepsItsHueAndStrength) {
    const fs::path dir = temp_dir("hdr");
    const fs::path set = dir / "in" / "Lamp";
    fs::create_directories(set);
    auto write = [](const mf::Image& img, const fs::path& file, const std::string& format, int bits) {
        std::vector<unsigned char> bytes;
        std::string err;
        ASSERT_TRUE(mf::encode_image(img, {*mf::from_word<mf::FileFormat>(format), bits}, bytes, err)) << err;
        ASSERT_TRUE(mf::write_file_atomic(file, bytes, err)) << err;
    };
    write(mf::Image(16, 16, 3, 0.02f), set / "Lamp_Color.png", "png", 8);
    mf::Image emissive(16, 16, 3);
    for (size_t p = 0; p < 256; ++p) {
        emissive.pixels[3 * p] = 4.f;
        emissive.pixels[3 * p + 1] = 3.f;
        emissive.pixels[3 * p + 2] = 2.f;
    }
    write(emissive, set / "Lamp_Emissive.exr", "exr", 32);
    const fs::path out = dir / "out";
    const json m = ingest({dir / "in"}, out, "gltf");
    ASSERT_EQ(m["materials"].size(), 1u);
    const json& mat = m["materials"][0];
    ASSERT_TRUE(mat.contains("emissive_strength")) << mat.dump(1);
    EXPECT_FLOAT_EQ(mat["emissive_strength"].get<float>(), 4.f);
    const mf::Image png = mf::testfiles::read_pixels(out / "Lamp" / "Lamp_emissive.png");
    auto code = [](double linear) { return static_cast<int>(std::lround(mf::linear_to_srgb(linear) * 255.0)); };
    EXPECT_EQ(static_cast<int>(std::lround(png.at(5, 5, 0) * 255.f)), 255);
    EXPECT_EQ(static_cast<int>(std::lround(png.at(5, 5, 1) * 255.f)), code(0.75));
    EXPECT_EQ(static_cast<int>(std::lround(png.at(5, 5, 2) * 255.f)), code(0.5));
    const json doc = mf::testfiles::read_json(out / "Lamp" / "Lamp.gltf");
    EXPECT_EQ(doc["materials"][0]["extensions"]["KHR_materials_emissive_strength"]["emissiveStrength"], 4.0);
    EXPECT_EQ(doc["extensionsUsed"], json::array({"KHR_materials_emissive_strength"}));
    const auto reports = node_checker("gltf_validate.mjs", {out / "Lamp" / "Lamp.gltf", out / "library.gltf"});
    ASSERT_EQ(reports.size(), 2u);
    for (const auto& rep : reports) {
        EXPECT_EQ(rep["errors"], 0) << rep.dump(1);
        EXPECT_EQ(rep["warnings"], 0) << rep.dump(1);
    }
    // The preview multiplies back: the sphere's centre emits (4, 3, 2) (plus a dim reflection).
    const auto r = matforge({"preview", (out / "manifest.json").string(), "-o", (dir / "prev").string(), "--device",
                             "cpu", "--size", "32", "--scene", "reference", "--format", "exr"});
    ASSERT_EQ(r.code, 0) << r.output;
    const mf::Image frame = mf::testfiles::read_pixels(dir / "prev" / "Lamp.exr");
    EXPECT_NEAR(frame.at(16, 16, 0), 4.f, 0.25f);
    EXPECT_NEAR(frame.at(16, 16, 1), 3.f, 0.2f);
    EXPECT_NEAR(frame.at(16, 16, 2), 2.f, 0.15f);
}

namespace {

// The MaterialX document beside each .gltf: MaterialX's own validation with its standard
// libraries passes it; its gltf_pbr reads every written texture, colour maps (and only they)
// as srgb_texture, each packed channel through an extract of the channel the manifest names,
// the normal through a normalmap node; it is listed in the manifest with its hash.
// The runs' documents go to one checker process: MaterialX's WebAssembly build and its standard
// libraries take seconds to load, each document a fraction of that.
void expect_mtlx(const std::vector<const Run*>& runs) {
    std::vector<fs::path> files;
    std::vector<const json*> mats;
    for (const Run* r : runs) {
        size_t mine = 0;
        for (const auto& m : r->manifest["materials"])
            for (const auto& f : m["material_files"])
                if (f["format"] == "mtlx") {
                    files.push_back(r->out / f["file"].get<std::string>());
                    mats.push_back(&m);
                    ++mine;
                    EXPECT_EQ(f["sha256"], mf::sha256_hex(read_bytes(files.back()))) << files.back();
                }
        ASSERT_EQ(mine, r->manifest["materials"].size()) << "one .mtlx per material";
    }
    const auto reports = node_checker("mtlx_validate.cjs", files);
    ASSERT_EQ(reports.size(), files.size());
    static const std::map<std::string, std::string> kInput{{"albedo", "base_color"},   {"opacity", "alpha"},
                                                           {"metalness", "metallic"},  {"roughness", "roughness"},
                                                           {"occlusion", "occlusion"}, {"normal", "normal"},
                                                           {"emissive", "emissive"}};
    for (size_t i = 0; i < files.size(); ++i) {
        const json& rep = reports[i];
        const json& m = *mats[i];
        SCOPED_TRACE(files[i].string());
        EXPECT_EQ(rep["version"], "1.39.4");
        EXPECT_TRUE(rep["valid"].get<bool>()) << rep["message"];
        ASSERT_EQ(rep["shaders"].size(), 1u);
        const json& sh = rep["shaders"][0];
        EXPECT_EQ(sh["category"], "gltf_pbr");
        EXPECT_TRUE(sh["nodedef"].get<bool>());
        // file -> the colour space its colour image nodes read it in; the files read as data
        // (vector images: never a colour space).
        std::map<std::string, std::string> colorspace;
        std::set<std::string> as_data;
        for (const auto& img : rep["images"]) {
            const std::string f = img["file"], type = img["type"];
            if (type.starts_with("color")) {
                colorspace[f] = img["colorspace"];
            } else {
                as_data.insert(f);
                EXPECT_EQ(img["colorspace"], "") << f << " read as " << type;
            }
        }
        for (const auto& o : m["outputs"]) {
            const std::string file = fs::path(o["file"].get<std::string>()).filename().string();
            ASSERT_TRUE(colorspace.count(file) || as_data.count(file)) << file << " is written but not used";
            if (colorspace.count(file))
                EXPECT_EQ(colorspace[file], o["color_space"] == "sRGB" ? "srgb_texture" : "") << file;
            else EXPECT_NE(o["color_space"], "sRGB") << file << ": a colour map read only as data";
            for (const auto& [key, role] : o["channels"].items()) {
                const auto input = kInput.find(role.get<std::string>());
                if (input == kInput.end()) continue;
                ASSERT_TRUE(sh["inputs"].contains(input->second)) << role;
                const std::string node = sh["inputs"][input->second];
                if (key.size() == 1) {  // one channel: an extract of that channel
                    EXPECT_EQ(rep["extracts"].value(node, std::string("?")),
                              std::to_string(std::string("RGBA").find(key)))
                        << role << " from " << key;
                } else if (role == "normal") {
                    EXPECT_TRUE(node.ends_with("_normalmap")) << node;
                }
            }
        }
    }
}

// The run's USD layers (their paths) and the manifest entry each belongs to; `check_digest`:
// each file's SHA-256 is the one its material_files entry records.
void usda_layers(const Run& r, std::vector<std::string>& files, std::vector<const json*>& mats, bool check_digest) {
    for (const auto& m : r.manifest["materials"])
        for (const auto& f : m["material_files"])
            if (f["format"] == "usda") {
                files.push_back((r.out / f["file"].get<std::string>()).string());
                mats.push_back(&m);
                if (check_digest) {
                    EXPECT_EQ(f["sha256"], mf::sha256_hex(read_bytes(files.back()))) << files.back();
                }
            }
}

// The USD layer beside each .gltf, opened by OpenUSD itself (checkers/usd_open.py: PyPI
// usd-core's Usd.Stage.Open, UsdShade and UsdValidation): it composes without an error and every
// validator usdchecker runs passes (the UsdPreviewSurface rules: a normal map's scale and bias,
// each input's type as the shader's Sdr definition declares it; missing references; metadata);
// its defaultPrim is a Material whose surface is a UsdPreviewSurface; every connection resolves;
// every written texture is read by a UsdUVTexture whose file USD's asset resolver finds at the
// output's path, whose st comes from a UsdPrimvarReader_float2 of "st", in sRGB for colour maps and
// raw for data; each role's input reads the channel the manifest names; the normal is rescaled
// to [-1, 1].
void expect_usda(const Run& r) {
    std::vector<std::string> files;
    std::vector<const json*> mats;
    usda_layers(r, files, mats, true);
    ASSERT_EQ(mats.size(), r.manifest["materials"].size()) << "one .usda per material";
    const std::vector<json> reps = py_checker("usd_open.py", files);
    ASSERT_EQ(reps.size(), mats.size());
    static const std::map<std::string, std::string> kInput{
        {"albedo", "inputs:diffuseColor"},   {"opacity", "inputs:opacity"},     {"metalness", "inputs:metallic"},
        {"roughness", "inputs:roughness"},   {"occlusion", "inputs:occlusion"}, {"normal", "inputs:normal"},
        {"emissive", "inputs:emissiveColor"}};
    for (size_t i = 0; i < reps.size(); ++i) {
        const json& rep = reps[i];
        const json& m = *mats[i];
        SCOPED_TRACE(rep["file"].get<std::string>());
        ASSERT_TRUE(rep["ok"].get<bool>()) << rep["error"];
        EXPECT_TRUE(rep["validation"].empty()) << rep["validation"].dump(1);
        EXPECT_TRUE(rep["unresolved"].empty()) << rep["unresolved"];
        EXPECT_EQ(rep["metadata"]["upAxis"], "Y");
        const std::string root = "/" + rep["metadata"]["defaultPrim"].get<std::string>();
        const json& prims = rep["prims"];
        ASSERT_EQ(prims[root]["type"], "Material");
        const std::string surface = prims[root]["attributes"]["outputs:surface"]["connect"]["path"];
        const std::string shader = surface.substr(0, surface.find('.'));
        EXPECT_EQ(prims[shader]["attributes"]["info:id"]["value"], "UsdPreviewSurface");
        const json& in = prims[shader]["attributes"];
        for (const auto& o : m["outputs"]) {
            const fs::path written = fs::weakly_canonical(r.out / o["file"].get<std::string>());
            std::string reader;  // the UsdUVTexture whose file USD resolves to this output
            for (const auto& [attr, asset] : rep["assets"].items())
                if (fs::path(asset["resolved"].get<std::string>()) == written) reader = attr.substr(0, attr.find('.'));
            ASSERT_FALSE(reader.empty()) << written << " is written but no texture resolves to it";
            const json& ra = prims[reader]["attributes"];
            EXPECT_EQ(ra["info:id"]["value"], "UsdUVTexture");
            EXPECT_EQ(ra["inputs:sourceColorSpace"]["value"], o["color_space"] == "sRGB" ? "sRGB" : "raw") << written;
            const std::string st = ra["inputs:st"]["connect"]["path"];
            const json& st_prim = prims[st.substr(0, st.find('.'))]["attributes"];
            EXPECT_EQ(st_prim["info:id"]["value"], "UsdPrimvarReader_float2");
            EXPECT_EQ(st_prim["inputs:varname"]["value"], "st");
            for (const auto& [key, role] : o["channels"].items()) {
                const auto input = kInput.find(role.get<std::string>());
                if (input == kInput.end()) continue;
                ASSERT_TRUE(in.contains(input->second)) << role;
                const std::string want = reader +
                                         ".outputs:" + (key == "RGB" ? std::string("rgb") : mf::ascii_lower(key));
                EXPECT_EQ(in[input->second]["connect"]["path"], want) << role;
                if (role == "normal") {
                    EXPECT_EQ(ra["inputs:scale"]["value"], json::array({2.0, 2.0, 2.0, 1.0}));
                    EXPECT_EQ(ra["inputs:bias"]["value"], json::array({-1.0, -1.0, -1.0, 0.0}));
                }
            }
        }
    }
    // OpenUSD is no rubber stamp here: a layer whose texture prims were renamed has connections to
    // nothing, an 8-bit normal map without its scale fails UsdPreviewSurface's normal-map rule, a texture
    // that is not there is unresolved, and text that is not USD does not open.
    const auto raw = read_bytes(files.front());
    const std::string text(raw.begin(), raw.end());
    auto variant = [&](const std::string& name, std::string t, const std::string& from, const std::string& to) {
        for (size_t at = 0; !from.empty() && (at = t.find(from, at)) != std::string::npos; at += to.size())
            t.replace(at, from.size(), to);
        write_text(fs::path(files.front()).parent_path() / name, t);
        return (fs::path(files.front()).parent_path() / name).string();
    };
    const std::vector<std::string> bad{variant("broken.usda", text, "def Shader \"Tex_", "def Shader \"Gone_"),
                                       variant("scale.usda", text, "float4 inputs:scale = (2, 2, 2, 1)", ""),
                                       variant("gone.usda", text, ".png@", "_gone.png@"),
                                       variant("not.usda", "#usda 1.0\ndef Material \"M\" {\n  float x = @\n}\n", "",
                                               "")};
    const std::vector<json> b = py_checker("usd_open.py", bad);
    ASSERT_EQ(b.size(), 4u);
    EXPECT_FALSE(b[0]["unresolved"].empty()) << b[0].dump();
    if (text.find("inputs:scale") != std::string::npos) {
        EXPECT_NE(b[1]["validation"].dump().find("NormalMapTextureValidator"), std::string::npos) << b[1].dump();
    }
    EXPECT_NE(b[2]["validation"].dump().find("MissingReferenceValidator"), std::string::npos) << b[2].dump();
    EXPECT_FALSE(b[3]["ok"].get<bool>()) << b[3].dump();
    for (const auto& f : bad) fs::remove(f);
}

}  // namespace

TEST(Gltf, UsdLayerBesideEachGltfReadsEveryTexture) {
    expect_usda(ingested("samples"));
    expect_usda(ingested("corpus"));
}

// Each material's USD layer carries its credit in customLayerData, as ambientCG's own USD files
// carry theirs, read back by OpenUSD itself (Sdf.Layer.customLayerData): `copyright` is the
// manifest's licence (its name, SPDX id and address), `author` the attribution where the
// licence asks for one (the Godot demo's CC BY) else the vendor, `url` the asset's page; a layer
// whose licence is unknown has none. For ambientCG's sets, OpenUSD reads the vendor's own
// .usdc of the download beside ours: both state the licence the manifest records.
TEST(Gltf, UsdLayerCarriesTheLicenceAsAmbientCgsOwnDoes) {
    const auto& r = ingested("corpus");
    std::vector<std::string> files;
    std::vector<const json*> mats;
    usda_layers(r, files, mats, false);
    ASSERT_EQ(mats.size(), r.manifest["materials"].size());
    // The vendor's own layers: the corpus sets ambientCG ships a .usdc with.
    std::vector<std::pair<const json*, std::string>> theirs;
    for (const auto& m : r.manifest["materials"]) {
        if (gltf_credit::provenance(m).value("vendor", "") != "ambientcg") continue;
        const fs::path dir = fs::path(m["source"].get<std::string>()).is_absolute()
                                 ? fs::path(m["source"].get<std::string>())
                                 : r.out / m["source"].get<std::string>();
        for (const auto& e : fs::directory_iterator(dir))
            if (e.path().extension() == ".usdc") theirs.emplace_back(&m, e.path().string());
    }
    std::vector<std::string> all = files;
    for (const auto& [m, f] : theirs) all.push_back(f);
    const std::vector<json> reps = py_checker("usd_open.py", all);
    ASSERT_EQ(reps.size(), all.size());
    size_t credited = 0, cc_by = 0, ambientcg = 0;
    for (size_t i = 0; i < files.size(); ++i) {
        const json& rep = reps[i];
        const json& m = *mats[i];
        SCOPED_TRACE(rep["file"].get<std::string>());
        ASSERT_TRUE(rep["ok"].get<bool>()) << rep["error"];
        const json& data = rep["customLayerData"];
        const auto credit = gltf_credit::of(m);
        if (!gltf_credit::licence_known(m)) {
            EXPECT_FALSE(credit);
            EXPECT_TRUE(data.empty()) << data;
            continue;
        }
        ASSERT_TRUE(credit);
        ++credited;
        const json& p = m["provenance"];
        const json& l = p["licence"];
        // The manifest's licence, as its name, SPDX id and address say it.
        const std::string copyright = data.value("copyright", "");
        EXPECT_EQ(copyright, l["name"].get<std::string>() + " (" + l["spdx"].get<std::string>() + ", " +
                                 l["url"].get<std::string>() + ")");
        EXPECT_EQ(gltf_credit::licences_in(copyright), gltf_credit::manifest_licence(m)) << copyright;
        EXPECT_EQ(copyright, credit->licence);
        if (l["attribution_required"].get<bool>()) {
            ++cc_by;
            EXPECT_EQ(data.value("author", ""), p["attribution"]) << data;
        } else {
            EXPECT_EQ(data.value("author", ""), p.value("vendor_name", "")) << data;
        }
        EXPECT_EQ(data.value("url", ""), p.value("url", "")) << data;
        if (p.value("vendor", "") == "ambientcg") {
            ++ambientcg;
            EXPECT_EQ(data["url"], "https://ambientcg.com/view?id=" + p["asset_id"].get<std::string>());
        }
    }
    EXPECT_EQ(credited, 10u) << "docs/provenance.md's corpus table: 10 sets of a known licence";
    EXPECT_EQ(cc_by, 1u) << "godot_tps-demo_container1";
    EXPECT_EQ(ambientcg, 4u) << "three ambientCG folders and Rocks004 of the flat folder";
    ASSERT_EQ(theirs.size(), 3u) << "the ambientCG folders ship a .usdc; the flat folder does not";
    for (size_t k = 0; k < theirs.size(); ++k) {
        const json& rep = reps[files.size() + k];
        SCOPED_TRACE(theirs[k].second);
        ASSERT_TRUE(rep["ok"].get<bool>()) << rep["error"];
        const std::string copyright = rep["customLayerData"].value("copyright", "");
        EXPECT_EQ(gltf_credit::licences_in(copyright), gltf_credit::manifest_licence(*theirs[k].first)) << copyright;
        EXPECT_EQ(rep["customLayerData"].value("author", ""), "ambientCG (ambientCG.com)");
    }
}

// library.usda references every material's layer under /Materials (the manifest lists it with
// its hash); OpenUSD composes it, finding each referenced layer, and validates it.
TEST(Gltf, UsdLibraryReferencesEveryMaterialLayer) {
    const auto& r = ingested("samples");
    bool listed = false;
    for (const auto& f : r.manifest["library"])
        if (f["file"] == "library.usda") {
            listed = true;
            EXPECT_EQ(f["format"], "usda");
            EXPECT_EQ(f["sha256"], mf::sha256_hex(read_bytes(r.out / "library.usda")));
        }
    ASSERT_TRUE(listed) << r.manifest["library"].dump();
    const std::vector<json> reps = py_checker("usd_open.py", {(r.out / "library.usda").string()});
    ASSERT_EQ(reps.size(), 1u);
    const json& rep = reps[0];
    ASSERT_TRUE(rep["ok"].get<bool>()) << rep["error"];
    EXPECT_TRUE(rep["validation"].empty()) << rep["validation"].dump(1);
    EXPECT_TRUE(rep["unresolved"].empty()) << rep["unresolved"];
    EXPECT_EQ(rep["metadata"]["defaultPrim"], "Materials");
    EXPECT_EQ(rep["prims"]["/Materials"]["type"], "Scope");
    std::set<std::string> referenced;
    size_t shaders = 0;
    for (const auto& [path, prim] : rep["prims"].items()) {
        for (const auto& ref : prim.value("references", json::array())) referenced.insert(ref.get<std::string>());
        // Composed: the referenced layers' shaders are on the library's stage.
        if (prim["type"] == "Shader" && prim["attributes"]["info:id"]["value"] == "UsdPreviewSurface") ++shaders;
    }
    std::set<std::string> layers;
    for (const auto& m : r.manifest["materials"])
        for (const auto& f : m["material_files"])
            if (f["format"] == "usda") layers.insert(f["file"].get<std::string>());
    EXPECT_EQ(referenced, layers);
    EXPECT_EQ(layers.size(), r.manifest["materials"].size());
    EXPECT_EQ(shaders, layers.size());
}

// library.mtlx holds every material's MaterialX elements in one document that MaterialX's own
// validation passes: one gltf_pbr per material, each reading files that exist relative to the
// library, element names unique across materials (two names that make one identifier included).
TEST(Gltf, MaterialXLibraryHoldsEveryMaterial) {
    const auto& r = ingested("samples");
    bool listed = false;
    for (const auto& f : r.manifest["library"])
        if (f["file"] == "library.mtlx") {
            listed = true;
            EXPECT_EQ(f["format"], "mtlx");
            EXPECT_EQ(f["sha256"], mf::sha256_hex(read_bytes(r.out / "library.mtlx")));
        }
    ASSERT_TRUE(listed) << r.manifest["library"].dump();
    // The samples again beside a copy of one set under a name that makes the same identifier.
    const fs::path dir = temp_dir("library");
    fs::copy(samples(), dir / "in", fs::copy_options::recursive);
    fs::copy(dir / "in" / "Net004A_1K-JPG", dir / "in" / "Net004A-1K-JPG", fs::copy_options::recursive);
    const json two = ingest({dir / "in"}, dir / "out", "gltf", {"--fail-on", "never"});
    for (const auto& [out, materials] :
         {std::pair{r.out, r.manifest["materials"].size()}, std::pair{dir / "out", two["materials"].size()}}) {
        const auto reports = node_checker("mtlx_validate.cjs", {out / "library.mtlx"});
        ASSERT_EQ(reports.size(), 1u);
        const json& rep = reports[0];
        EXPECT_TRUE(rep["valid"].get<bool>()) << rep["message"];
        EXPECT_EQ(rep["shaders"].size(), materials);
        std::set<std::string> files;
        for (const auto& img : rep["images"]) {
            files.insert(img["file"].get<std::string>());
            EXPECT_TRUE(fs::is_regular_file(out / img["file"].get<std::string>())) << img["file"];
        }
        EXPECT_GE(files.size(), 3 * materials) << "each material's own textures";
    }
    EXPECT_EQ(two["materials"].size(), 5u);
}

// An independent renderer: three.js's MaterialXLoader (headless Chromium, WebGL 2 on
// SwiftShader) builds each sample's .mtlx into a material, and its picture on a sphere matches
// the same material loaded from the .gltf by three's GLTFLoader in the same scene: the MaterialX
// graph reads every map into its input (a map dropped, read in the wrong colour space or channel,
// or a normal map not decoded would move the picture by far more). The pictures are left in the
// run's folder, beside the preview's. GLTFLoader hands each file's asset.copyright to the page
// (gltf.asset): the material's credit, none where the licence is unknown.
TEST(Gltf, MaterialXRendersAsItsGltfInThreeJs) {
    const auto& r = ingested("samples");
    ASSERT_TRUE(npm_checkers_installed());
    const fs::path pictures = r.out / "three";
    fs::create_directories(pictures);
    std::vector<std::string> argv{"node",
                                  (mf::testenv::source_dir() / "tests/texture/checkers/mtlx_render.mjs").string(),
                                  mf::testenv::npm_dir().string(), r.out.string(), pictures.string()};
    for (const auto& m : r.manifest["materials"]) argv.push_back(m["name"]);
    const auto p = mf::testbin::spawn(argv, 300);
    ASSERT_EQ(p.code, 0) << p.output;
    std::istringstream lines(p.output);
    size_t n = 0, credited = 0;
    for (std::string line; std::getline(lines, line);) {
        if (line.empty() || line[0] != '{') continue;
        const json rep = json::parse(line);
        SCOPED_TRACE(rep["name"].get<std::string>());
        ++n;
        ASSERT_TRUE(rep["ok"].get<bool>()) << rep["error"];
        EXPECT_EQ(rep["materials"], 1);
        EXPECT_GT(rep["mtlx"]["lit"].get<int>(), 3000) << "the sphere is drawn";
        EXPECT_NEAR(rep["mtlx"]["lit"].get<double>(), rep["gltf"]["lit"].get<double>(),
                    0.03 * rep["gltf"]["lit"].get<double>())
            << "the same pixels cut out";
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(rep["mtlx"]["mean"][c], rep["gltf"]["mean"][c], 0.02) << c;
        EXPECT_GE(rep["psnr_db"].get<double>(), 30.0);
        EXPECT_TRUE(fs::is_regular_file(pictures / (rep["name"].get<std::string>() + ".mtlx.png")));
        for (const auto& m : r.manifest["materials"])
            if (m["name"] == rep["name"]) {
                const auto credit = gltf_credit::of(m);
                EXPECT_EQ(rep["copyright"], credit ? json(credit->line) : json(nullptr));
                credited += credit.has_value();
            }
    }
    EXPECT_EQ(n, r.manifest["materials"].size());
    EXPECT_EQ(credited, 3u) << "every sample but Crystal_003";
}

namespace gltf_sides {

// Over the pixels where `sides` and `front` (three.js with and without the far side) differ by
// more than 12 codes in a channel: how many, and the PSNR of `preview` against each.
struct FarSide {
    size_t pixels = 0;
    double psnr_sides = 0, psnr_front = 0;
};
FarSide far_side(const fs::path& preview, const fs::path& sides, const fs::path& front) {
    const mf::Image8 p = read_codes(preview), a = read_codes(sides), b = read_codes(front);
    FarSide f;
    if (p.width != a.width || p.height != a.height || a.width != b.width || a.height != b.height) {
        ADD_FAILURE() << "sizes differ";
        return f;
    }
    double se_a = 0, se_b = 0;
    for (int y = 0; y < p.height; ++y)
        for (int x = 0; x < p.width; ++x) {
            int most = 0;
            for (int k = 0; k < 3; ++k) most = std::max(most, std::abs(int(a.at(x, y, k)) - int(b.at(x, y, k))));
            if (most <= 12) continue;
            ++f.pixels;
            for (int k = 0; k < 3; ++k) {
                se_a += std::pow(double(p.at(x, y, k)) - double(a.at(x, y, k)), 2);
                se_b += std::pow(double(p.at(x, y, k)) - double(b.at(x, y, k)), 2);
            }
        }
    const auto psnr = [&](double se) {
        const double mse = se / (3.0 * static_cast<double>(std::max<size_t>(f.pixels, 1)));
        return mse > 0 ? 10.0 * std::log10(255.0 * 255.0 / mse) : 100.0;
    };
    f.psnr_sides = psnr(se_a);
    f.psnr_front = psnr(se_b);
    return f;
}

}  // namespace gltf_sides

// Issue 49: a cut-out is double-sided (its .gltf says so, as every engine draws a net or foliage)
// and the preview shows its far side through the holes. three.js (checkers/gltf_sides.mjs) draws
// ambientCG's Net004A from its .gltf in the reference scene with the far side and without it:
// where the two differ (the far side seen through the net), the preview agrees with the first by a
// wide margin, and over the whole sphere it agrees with it as a renderer of another BRDF does.
TEST(Gltf, CutOutShowsItsFarSideAsThreeJsDrawsIt) {
    const auto& r = ingested("corpus");
    ASSERT_TRUE(npm_checkers_installed());
    const std::string name = "Net004A";
    const json* entry = nullptr;
    for (const auto& m : r.manifest["materials"])
        if (m["name"] == name) entry = &m;
    ASSERT_NE(entry, nullptr);
    ASSERT_EQ((*entry)["alpha_mode"], "mask");
    const fs::path dir = r.out / "sides";
    fs::create_directories(dir);
    constexpr int kSize = 256;
    preview_reference(r.out / "manifest.json", dir / "preview", kSize);
    const auto p = mf::testbin::spawn({"node",
                                       (mf::testenv::source_dir() / "tests/texture/checkers/gltf_sides.mjs").string(),
                                       mf::testenv::npm_dir().string(), r.out.string(), dir.string(),
                                       std::to_string(kSize), name},
                                      300);
    ASSERT_EQ(p.code, 0) << p.output;
    const size_t at = p.output.find("{\"");
    ASSERT_NE(at, std::string::npos) << p.output;
    const json rep = json::parse(p.output.substr(at, p.output.find('\n', at) - at));
    EXPECT_TRUE(rep["double_sided"].get<bool>()) << "the .gltf asks for both sides";
    EXPECT_DOUBLE_EQ(rep["alpha_test"].get<double>(), (*entry)["alpha_cutoff"].get<double>());
    const fs::path preview = dir / "preview" / (name + ".png");
    const auto f = gltf_sides::far_side(preview, dir / (name + ".sides.png"), dir / (name + ".front.png"));
    std::printf("far side: %zu pixels; preview against three.js with it %.2f dB, without it %.2f dB\n", f.pixels,
                f.psnr_sides, f.psnr_front);
    EXPECT_GT(f.pixels, 3000u) << "the far side is seen through the net";
    EXPECT_GE(f.psnr_sides, f.psnr_front + 6.0) << "the preview shows the far side where three.js does";
    // Lit: a channel above 0; three.js leaves the unlit far side at exactly 0 where the preview's
    // sRGB rounding keeps a code or two (0.74 measured).
    expect_agrees_with_preview(preview, dir / (name + ".sides.png"), 22.0, {0.6, 1.2}, "three.js");
}

// The checker itself: a misspelled input, an input of the wrong type and a connection to no
// node each make a sample's document invalid; the document as written is valid.
TEST(Gltf, MaterialXCheckerRefusesBrokenDocuments) {
    const auto& r = ingested("samples");
    const fs::path doc = r.out / "Metal_Damaged_001" / "Metal_Damaged_001.mtlx";
    auto broken = [&](const std::string& from, const std::string& to, const std::string& name) {
        return damaged_copy(doc, from, to, r.out / name);
    };
    const std::vector<fs::path> files{doc, broken("name=\"base_color\"", "name=\"base_colour\"", "misspelled.mtlx"),
                                      broken("name=\"base_color\" type=\"color3\"",
                                             "name=\"base_color\" type=\"float\"", "mistyped.mtlx"),
                                      broken("nodename=\"img_", "nodename=\"missing_img_", "dangling.mtlx")};
    const auto reports = node_checker("mtlx_validate.cjs", files);
    ASSERT_EQ(reports.size(), 4u);
    EXPECT_TRUE(reports[0]["valid"].get<bool>()) << reports[0]["message"];
    for (size_t i = 1; i < 4; ++i) EXPECT_FALSE(reports[i]["valid"].get<bool>()) << files[i];
}

TEST(Gltf, MaterialXBesideEachGltfPassesMaterialXValidation) {
    expect_mtlx({&ingested("samples"), &ingested("corpus")});
}

// MaterialX's own GLSL generator (PyPI materialx, checkers/mtlx_open.py) makes a pixel and a
// vertex shader of every material of every .mtlx and of library.mtlx, and glslang compiles each:
// the documents are not only valid but usable by a renderer built on MaterialX. A document with
// an input of the wrong type, or that is not XML, is refused by the same checker.
TEST(Gltf, MaterialXGeneratesGlslThatCompilesForEveryMaterial) {
    for (const auto* r : {&ingested("samples"), &ingested("corpus")}) {
        std::vector<std::string> args{(r->out / "glsl").string()};
        std::set<std::string> names;
        for (const auto& m : r->manifest["materials"]) {
            names.insert(m["name"].get<std::string>());
            for (const auto& f : m["material_files"])
                if (f["format"] == "mtlx") args.push_back((r->out / f["file"].get<std::string>()).string());
        }
        ASSERT_EQ(args.size(), names.size() + 1) << "one .mtlx per material";
        args.push_back((r->out / "library.mtlx").string());
        const std::vector<json> reps = py_checker("mtlx_open.py", args);
        ASSERT_EQ(reps.size(), args.size() - 1);
        // Each material's doc (MaterialX's getDocString), in its document and in the library: its
        // credit, "" where the licence is unknown.
        std::multiset<std::string> docs, library_docs;
        for (const auto& m : r->manifest["materials"]) {
            const auto credit = gltf_credit::of(m);
            docs.insert(credit ? credit->line : "");
        }
        for (size_t i = 0; i < reps.size(); ++i) {
            const json& rep = reps[i];
            SCOPED_TRACE(rep["file"].get<std::string>());
            ASSERT_TRUE(rep["ok"].get<bool>()) << rep["error"];
            const bool library = i + 1 == reps.size();
            EXPECT_EQ(rep["materials"].size(), library ? names.size() : 1u);
            for (const auto& m : rep["materials"]) {
                EXPECT_EQ(m["frag"], "") << m["name"];
                EXPECT_EQ(m["vert"], "") << m["name"];
                if (library) library_docs.insert(m["doc"].get<std::string>());
            }
            if (!library) {
                const auto credit = gltf_credit::of(r->manifest["materials"][i]);
                EXPECT_EQ(rep["materials"][0]["doc"], credit ? credit->line : "");
            }
        }
        EXPECT_EQ(library_docs, docs);
        fs::remove_all(r->out / "glsl");
    }
    const auto& r = ingested("samples");
    const fs::path one = r.out / r.manifest["materials"][0]["name"].get<std::string>();
    damaged_copy(one / (one.filename().string() + ".mtlx"), "type=\"color3\"", "type=\"float\"", one / "typed.mtlx");
    write_text(one / "not.mtlx", "<materialx");
    const std::vector<json> bad = py_checker("mtlx_open.py", {(r.out / "glsl").string(), (one / "typed.mtlx").string(),
                                                              (one / "not.mtlx").string()});
    ASSERT_EQ(bad.size(), 2u);
    EXPECT_FALSE(bad[0]["ok"].get<bool>());
    EXPECT_NE(bad[0]["error"].get<std::string>().find("Mismatched types"), std::string::npos) << bad[0];
    EXPECT_FALSE(bad[1]["ok"].get<bool>());
    fs::remove(one / "typed.mtlx");
    fs::remove(one / "not.mtlx");
    fs::remove_all(r.out / "glsl");
}

// Blender itself (PyPI bpy 4.5, checkers/blender_open.py) imports every .gltf of the samples and
// the corpus through its own glTF importer, and the material it makes reads each written texture
// where the manifest says: base colour (RGB) and alpha (A, where the set is cut out or blended)
// from the sRGB base colour texture, metallic (B) and roughness (G) through a Separate Color of
// the ORM, the normal through a Normal Map node, emission from its sRGB texture; every data
// texture Non-Color, every image loaded at the written size. Blender is no rubber stamp: a
// texture that is not there loads nothing, and a .gltf that is not JSON does not import.
TEST(Gltf, BlenderImportsEveryGltfWithEachTextureInItsSlot) {
    static const std::map<std::string, std::pair<std::string, std::string>> kSlot{
        // role -> (Principled BSDF input, channel Blender reads it from)
        {"albedo", {"Base Color", "RGB"}}, {"opacity", {"Alpha", "A"}},   {"metalness", {"Metallic", "B"}},
        {"roughness", {"Roughness", "G"}}, {"normal", {"Normal", "RGB"}}, {"emissive", {"Emission Color", "RGB"}}};
    for (const auto* r : {&ingested("samples"), &ingested("corpus")}) {
        std::vector<std::string> files;
        std::vector<const json*> mats;
        for (const auto& m : r->manifest["materials"])
            for (const auto& f : m["material_files"])
                if (f["format"] == "gltf") {
                    files.push_back((r->out / f["file"].get<std::string>()).string());
                    mats.push_back(&m);
                }
        ASSERT_EQ(mats.size(), r->manifest["materials"].size());
        const std::vector<json> reps = py_checker("blender_open.py", files);
        ASSERT_EQ(reps.size(), mats.size());
        for (size_t i = 0; i < reps.size(); ++i) {
            const json& m = *mats[i];
            SCOPED_TRACE(reps[i]["file"].get<std::string>());
            ASSERT_TRUE(reps[i]["ok"].get<bool>()) << reps[i]["error"];
            ASSERT_EQ(reps[i]["materials"].size(), 1u);
            const json& in = reps[i]["materials"][0]["inputs"];
            size_t bound = 0;
            for (const auto& o : m["outputs"])
                for (const auto& [key, role] : o["channels"].items()) {
                    const auto slot = kSlot.find(role.get<std::string>());
                    if (slot == kSlot.end()) continue;
                    if (role == "opacity" && m.value("alpha_mode", std::string("opaque")) == "opaque") continue;
                    const auto& [input, channel] = slot->second;
                    ASSERT_TRUE(in.contains(input))
                        << role << " is written (" << o["file"] << ") but " << input << " reads no texture";
                    const json& got = in[input];
                    EXPECT_EQ(fs::path(got["image"].get<std::string>()),
                              fs::weakly_canonical(r->out / o["file"].get<std::string>()))
                        << input;
                    EXPECT_EQ(got["channel"], channel) << input;
                    EXPECT_EQ(got["colorspace"], o["color_space"] == "sRGB" ? "sRGB" : "Non-Color") << input;
                    EXPECT_TRUE(got["loaded"].get<bool>()) << input;
                    EXPECT_EQ(got["size"], json::array({o["width"], o["height"]})) << input;
                    if (role == "normal") {
                        EXPECT_EQ(got["via"], json::array({"NORMAL_MAP"}));
                    }
                    ++bound;
                }
            EXPECT_EQ(bound, in.size()) << "Blender reads no texture matforge did not write for it: " << in.dump();
        }
    }
    const auto& r = ingested("samples");
    const std::string name = r.manifest["materials"][0]["name"];
    const fs::path dir = r.out / name;
    damaged_copy(dir / (name + ".gltf"), "_orm.png", "_gone.png", dir / "gone.gltf");
    write_text(dir / "not.gltf", "{not json");
    const std::vector<json> bad = py_checker("blender_open.py",
                                             {(dir / "gone.gltf").string(), (dir / "not.gltf").string()});
    ASSERT_EQ(bad.size(), 2u);
    ASSERT_TRUE(bad[0]["ok"].get<bool>()) << bad[0]["error"];
    EXPECT_FALSE(bad[0]["materials"][0]["inputs"]["Roughness"]["loaded"].get<bool>()) << bad[0].dump();
    EXPECT_FALSE(bad[1]["ok"].get<bool>());
    fs::remove(dir / "gone.gltf");
    fs::remove(dir / "not.gltf");
}

// Blender renders every material as `matforge preview` does. Each .gltf of sample_materials/ and
// the corpus is imported by Blender's own glTF importer and, apart, its .usda's material by
// Blender's own USD importer put on the glTF's sphere; Cycles renders both on the CPU under the
// preview's `reference` scene (checkers/blender_render.py: the camera, the one white sun of
// irradiance 3, black world, direct light only, no tone mapping, a box pixel filter) and the
// pictures are compared with `matforge preview --scene reference --aa 4` over the pixels lit in
// both away from the silhouette. Two renderers written apart (Blender's Principled BSDF,
// matforge's Cook-Torrance: docs/shading.md) agree at 32.1-47.3 dB on these 23 materials
// (docs/engines.md), and the .usda's picture is the .gltf's, pixel for pixel. A flipped normal
// green costs 16 dB (Rocks004: 18.4 dB against 34.8); what a picture shows little of (a rough dielectric's roughness
// read as sRGB: 1 dB) is Gltf.BlenderImportsEveryGltfWithEachTextureInItsSlot's to catch, input by input. The lit share
// catches a cut-out drawn solid (Blender lights a little more near the terminator, where the normal map bends the
// shading normal toward the light: up to 1.32x on the net's strands).
TEST(Gltf, BlenderRendersEveryGltfAndUsdAsThePreviewDoes) {
    constexpr double kMinPsnrDb = 30.0;
    constexpr int size = 160;
    const std::string samples = "32";
    size_t compared = 0;
    for (const auto* r : {&ingested("samples"), &ingested("corpus")}) {
        const fs::path dir = r->out.string() + "-renders";
        mf::testbin::register_test_dir(dir);
        preview_reference(r->out / "manifest.json", dir / "preview", size);
        std::vector<std::string> files, names;
        for (const auto& m : r->manifest["materials"])
            for (const auto& f : m["material_files"])
                if (f["format"] == "gltf") {
                    files.push_back((r->out / f["file"].get<std::string>()).string());
                    names.push_back(m["name"]);
                }
        ASSERT_EQ(names.size(), r->manifest["materials"].size());
        for (const bool usd : {false, true}) {
            std::vector<std::string> args;
            if (usd) args.push_back("--usd");
            args.insert(args.end(), {std::to_string(size), samples, (dir / "blender").string()});
            args.insert(args.end(), files.begin(), files.end());
            const std::vector<json> reps = py_checker("blender_render.py", args);
            ASSERT_EQ(reps.size(), files.size());
            for (size_t i = 0; i < reps.size(); ++i) {
                const std::string who = names[i] + (usd ? " (.usda)" : " (.gltf)");
                ASSERT_TRUE(reps[i]["ok"].get<bool>()) << who << ": " << reps[i]["error"];
                if (usd) {  // the same picture as the .gltf's: both importers make one material
                    const fs::path gltf_png = dir / "blender" / (fs::path(files[i]).stem().string() + ".blender.png");
                    EXPECT_GE(interior_psnr(gltf_png, reps[i]["png"].get<std::string>()).psnr_db, 50.0) << who;
                }
                expect_agrees_with_preview(dir / "preview" / (names[i] + ".png"), reps[i]["png"].get<std::string>(),
                                           kMinPsnrDb, {0.95, 1.5}, "blender " + who);
                ++compared;
            }
        }
    }
    EXPECT_GE(compared, 2u * (4 + 15));
}
