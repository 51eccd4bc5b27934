// Provenance through the binary on real sets of the corpus: ATTRIBUTION.md of an ingest, a user's
// file of that name never replaced, LICENCE_UNKNOWN raised to an error by a rules file (exit
// code), and the vendor's preview recorded as the `preview` input and never read as a map.
#include <set>
#include <span>

#include "cli_util.hpp"

using namespace mft;

namespace provenance_cli {

// The sets of `names` from the corpus as inputs of one run (read in place).
std::string corpus_inputs(const std::vector<std::string>& names) {
    std::string args;
    for (const auto& n : names) args += (args.empty() ? "" : " ") + q(corpus_set(n));
    return args;
}

const nlohmann::json* finding_of(const nlohmann::json& mat, const std::string& code) {
    for (const auto& f : mat["findings"])
        if (f["code"] == code) return &f;
    return nullptr;
}

}  // namespace provenance_cli

using namespace provenance_cli;

// Every material of the output folder with its source and licence, in name order: a vendor
// known by its names (ambientCG, Poly Haven, with their pages), a licence read from the file
// beside the textures with the credit it asks for (the Godot demo's LICENSE.md), and the same
// demo's textures without it (unknown, and why). Listed in the manifest's library with its
// digest; the same bytes from a second run.
TEST(ProvenanceCli, AttributionFileOfACorpusIngest) {
    const fs::path work = temp_dir("attribution");
    const std::string in = corpus_inputs({"ambientcg_Net004A_1K-JPG", "godot_tps-demo_container1",
                                          "godot_tps-demo_reactor_cylinder", "polyhaven_brown_planks_09_1k_jpg+webp"});
    const fs::path out = work / "out";
    const auto r = run("ingest " + in + " -o " + q(out) + " --preset separate --no-cache -q --fail-on never");
    ASSERT_EQ(r.code, 0) << r.output;
    const std::string text = bytes_of(out / "ATTRIBUTION.md");
    const std::string why =
        "no licence found: no licence or readme file in the set, no sidecar states one, and its names (naming: "
        "generic) follow no vendor's scheme with a known licence";
    const std::string rows =
        "| material | vendor | asset | licence | how it is known | attribution | source |\n"
        "| --- | --- | --- | --- | --- | --- | --- |\n"
        "| Net004A | ambientCG | Net004A | CC0-1.0 | vendor (Net004A_1K-JPG_Color.jpg): named the ambientCG way "
        "(<id>_<res>-<format>_<map>); ambientCG publishes every asset under CC0-1.0 | not required | "
        "https://ambientcg.com/view?id=Net004A |\n"
        "| brown_planks_09 | Poly Haven | brown_planks_09 | CC0-1.0 | vendor (brown_planks_09_arm_1k.jpg): named the "
        "Poly Haven way (<slug>_<map>_<res>, in lower case); Poly Haven publishes every asset under CC0-1.0 | not "
        "required | https://polyhaven.com/a/brown_planks_09 |\n"
        "| container1 | — | — | CC-BY-3.0 | file (LICENSE.md): LICENSE.md names it | All assets Copyright (c) 2018 "
        "Juan Linietsky, Fernando Miguel Calabr\xC3\xB3; licensed under CC-BY-3.0 "
        "(https://creativecommons.org/licenses/by/3.0/) | — |\n"
        "| reactor_cylinder | — | — | unknown | " +
        why +
        " | — | — |\n"
        "\n4 materials: CC-BY-3.0 1, CC0-1.0 2, unknown 1.\n";
    EXPECT_TRUE(text.starts_with("# Attribution\n")) << text;
    EXPECT_NE(text.find(rows), std::string::npos) << text;
    EXPECT_TRUE(text.ends_with(rows)) << text;

    const nlohmann::json m = read_json(out / "manifest.json");
    ASSERT_FALSE(m["library"].empty());
    EXPECT_EQ(m["library"][0]["file"], "ATTRIBUTION.md");
    EXPECT_EQ(m["library"][0]["format"], "md");
    EXPECT_EQ(m["library"][0]["sha256"],
              mf::sha256_hex(std::span(reinterpret_cast<const unsigned char*>(text.data()), text.size())));
    const auto* reactor = material(m, "reactor_cylinder");
    ASSERT_TRUE(reactor);
    ASSERT_TRUE(finding_of(*reactor, "LICENCE_UNKNOWN"));
    EXPECT_EQ((*finding_of(*reactor, "LICENCE_UNKNOWN"))["message"], why);
    EXPECT_FALSE(reactor->contains("provenance"));

    const auto again = run("ingest " + in + " -o " + q(out) + " --preset separate --no-cache -q --fail-on never");
    ASSERT_EQ(again.code, 0) << again.output;
    EXPECT_EQ(bytes_of(out / "ATTRIBUTION.md"), text);
}

// An ATTRIBUTION.md of the user's in the output folder is not matforge's: never replaced (the run
// fails naming it, and the file keeps its bytes).
TEST(ProvenanceCli, AUsersAttributionFileIsNeverReplaced) {
    const fs::path work = temp_dir("users-attribution");
    const std::string in = corpus_inputs({"polyhaven_brown_planks_09_1k_jpg+webp"});
    const fs::path out = work / "out";
    write_text(out / "ATTRIBUTION.md", "our studio's credits\n");
    const auto r = run("ingest " + in + " -o " + q(out) + " --preset separate --no-cache -q");
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_NE(r.output.find("ATTRIBUTION.md"), std::string::npos) << r.output;
    EXPECT_EQ(bytes_of(out / "ATTRIBUTION.md"), "our studio's credits\n");
}

// LICENCE_UNKNOWN is info by default; a rules file makes it an error for a library that must
// clear every asset: validate and ingest then fail on the hand-named set (a good set otherwise),
// not on the set whose licence file says CC-BY 3.0; a suppression clears it again.
TEST(ProvenanceCli, LicenceUnknownRaisedToErrorFailsTheRun) {
    const fs::path work = temp_dir("licence-error");
    const std::string in = corpus_inputs({"handnamed_crystal_tutorial", "godot_tps-demo_container1"});
    const fs::path rules = work / "rules.json", suppressed = work / "suppressed.json";
    write_text(rules, R"({"rules": {"LICENCE_UNKNOWN": "error"}})");
    write_text(suppressed, R"({"rules": {"LICENCE_UNKNOWN": "error"},
      "suppress": [{"material": "crystal", "code": "LICENCE_UNKNOWN", "reason": "cleared by hand"}]})");
    EXPECT_EQ(run("validate " + in).code, 0);
    const fs::path report = work / "report.json";
    const auto r = run("validate " + in + " --rules " + q(rules) + " --report json --report-file " + q(report));
    EXPECT_EQ(r.code, 1) << r.output;
    const nlohmann::json rep = read_json(report);
    ASSERT_TRUE(material(rep, "crystal"));
    const auto* f = finding_of(*material(rep, "crystal"), "LICENCE_UNKNOWN");
    ASSERT_TRUE(f);
    EXPECT_EQ((*f)["severity"], "error");
    ASSERT_TRUE(material(rep, "container1"));
    EXPECT_FALSE(finding_of(*material(rep, "container1"), "LICENCE_UNKNOWN"));
    EXPECT_EQ((*material(rep, "container1"))["provenance"]["licence"]["spdx"], "CC-BY-3.0");
    // The text report names the error and the set.
    const auto text = run("validate " + in + " --rules " + q(rules));
    EXPECT_EQ(text.code, 1);
    EXPECT_NE(text.output.find("LICENCE_UNKNOWN"), std::string::npos) << text.output;
    // Ingest fails the same way, and records the severity the rules gave it.
    const auto ing = run("ingest " + in + " -o " + q(work / "out") + " --rules " + q(rules) + " --no-cache -q");
    EXPECT_EQ(ing.code, 1) << ing.output;
    const nlohmann::json m = read_json(work / "out" / "manifest.json");
    ASSERT_TRUE(material(m, "crystal"));
    EXPECT_EQ((*finding_of(*material(m, "crystal"), "LICENCE_UNKNOWN"))["severity"], "error");
    EXPECT_EQ(run("validate " + in + " --rules " + q(suppressed)).code, 0);
}

// ambientCG's "<Id>.png" is the set's preview input (its header as found, the vendor's rule),
// no longer an unrecognized file, and no output holds it. Real pixels renamed the way Poliigon
// names its downloads: the vendor and its "_Sphere" render. In the flat folder of two sets,
// 3dtextures.me's render names no material: neither set's preview.
TEST(ProvenanceCli, VendorPreviewIsRecordedNeverRead) {
    const fs::path work = temp_dir("preview");
    const fs::path net = corpus_set("ambientcg_Net004A_1K-JPG");
    const fs::path poliigon = work / "in" / "Poliigon_RopeNet_7012";
    fs::create_directories(poliigon);
    for (const auto& [from, to] : std::vector<std::pair<std::string, std::string>>{
             {"Net004A_1K-JPG_Color.jpg", "Poliigon_RopeNet_7012_BaseColor.jpg"},
             {"Net004A_1K-JPG_NormalGL.jpg", "Poliigon_RopeNet_7012_Normal.jpg"},
             {"Net004A.png", "Poliigon_RopeNet_7012_Sphere.png"}})
        fs::copy_file(net / from, poliigon / to);
    const auto r = run("ingest " + q(work / "in") + " " +
                       corpus_inputs({"ambientcg_Net004A_1K-JPG", "flat_folder_two_sets"}) + " -o " + q(work / "out") +
                       " --no-cache -q --fail-on never");
    ASSERT_EQ(r.code, 0) << r.output;
    const nlohmann::json m = read_json(work / "out" / "manifest.json");

    const auto* a = material(m, "Net004A");
    ASSERT_TRUE(a);
    const nlohmann::json want = {{"bit_depth", 8},
                                 {"channels", 4},
                                 {"color_space", "sRGB"},
                                 {"family", "ambientcg"},
                                 {"file", "Net004A.png"},
                                 {"height", 1024},
                                 {"rule", "ambientcg:<id>.png (the vendor's preview)"},
                                 {"width", 1024}};
    EXPECT_EQ((*a)["inputs"]["preview"], want);
    for (const auto& f : (*a)["findings"]) EXPECT_NE(f.value("file", ""), "Net004A.png") << f.dump();
    for (const auto& o : (*a)["outputs"])
        for (const auto& [key, role] : o["channels"].items()) EXPECT_NE(role, "preview") << o["file"];
    EXPECT_EQ((*a)["provenance"]["vendor"], "ambientcg");

    const auto* p = material(m, "Poliigon_RopeNet_7012");
    ASSERT_TRUE(p) << m.dump(1);
    EXPECT_EQ((*p)["inputs"]["preview"]["file"], "Poliigon_RopeNet_7012_Sphere.png");
    EXPECT_EQ((*p)["inputs"]["preview"]["rule"], "generic:_Sphere (a preview image)");
    EXPECT_EQ((*p)["provenance"]["vendor"], "poliigon");
    EXPECT_EQ((*p)["provenance"]["asset_id"], "7012");
    EXPECT_EQ((*p)["provenance"]["licence"]["name"], "Poliigon EULA");
    EXPECT_EQ((*p)["provenance"]["licence"]["vendor_licence"], true);
    EXPECT_FALSE((*p)["provenance"].contains("url"));  // no certain URL scheme

    for (const char* name : {"Rocks004", "Surface_Imperfection_001"}) {
        const auto* f = material(m, name);
        ASSERT_TRUE(f) << name;
        EXPECT_FALSE((*f)["inputs"].contains("preview")) << name;
    }
    bool said = false;
    for (const auto& f : (*material(m, "Rocks004"))["findings"])
        said = said || (f["code"] == "UNRECOGNIZED_FILE" && f["file"] == "Material_1586.jpg");
    EXPECT_TRUE(said);
}
