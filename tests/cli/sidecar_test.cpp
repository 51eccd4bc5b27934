// Sidecars in a set: textures a .gltf references take their roles from its material (and glTF's
// +Y normal convention); a metallicFactor of 0 means the texture's metalness is not used.
#include "cli_util.hpp"

using namespace mft;

TEST(Sidecar, GltfMaterialGivesRolesAndMetallicFactorZeroIsNotUsed) {
    const fs::path work = temp_dir("gltf");
    const fs::path set = work / "in/Chair";
    // Names that say nothing about roles: only the glTF tells.
    write_png(set / "tex_a.png", mf::Image(8, 8, 3, 0.6f));
    mf::Image mr(8, 8, 3, 0.f);
    for (size_t i = 0; i < mr.pixels.size(); i += 3) {
        mr.pixels[i + 1] = 0.4f;  // G roughness
        mr.pixels[i + 2] = 1.0f;  // B metalness (not used: metallicFactor 0)
    }
    write_png(set / "tex_b.png", mr);
    mf::Image n(8, 8, 3, 0.5f);
    for (size_t i = 2; i < n.pixels.size(); i += 3) n.pixels[i] = 1.f;
    write_png(set / "tex_c.png", n);
    write_text(set / "chair.gltf", R"({"asset": {"version": "2.0"},
      "images": [{"uri": "tex_a.png"}, {"uri": "tex_b.png"}, {"uri": "tex_c.png"}],
      "textures": [{"source": 0}, {"source": 1}, {"source": 2}],
      "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0},
                     "metallicRoughnessTexture": {"index": 1}, "metallicFactor": 0.0},
                     "normalTexture": {"index": 2}}]})");
    const auto r = run("ingest " + q(work / "in") + " -o " + q(work / "out") + " -q");
    ASSERT_EQ(r.code, 0) << r.output;
    const auto manifest = read_json(work / "out/manifest.json");
    const auto* m = material(manifest, "Chair");
    ASSERT_TRUE(m) << manifest.dump(2);
    EXPECT_EQ((*m)["inputs"]["albedo"]["file"], "tex_a.png");
    EXPECT_EQ((*m)["inputs"]["metallic_roughness"]["file"], "tex_b.png");
    EXPECT_EQ((*m)["inputs"]["normal"]["file"], "tex_c.png");
    EXPECT_EQ((*m)["inputs"]["normal"]["normal_convention"], "gl");
    // Roughness from G; metalness is the generated constant 0, not the texture's 1.
    EXPECT_EQ((*m)["constants"]["metalness"], 0.0) << m->dump(2);
    const auto* orm = output_with(*m, "B", "metalness");
    ASSERT_TRUE(orm);
    const mf::Image out = read_pixels(work / "out" / (*orm)["file"].get<std::string>());
    EXPECT_EQ(code8(out.pixels[1]), code8(0.4f));
    EXPECT_EQ(code8(out.pixels[2]), 0) << "metalness must not come from the texture";
    EXPECT_FALSE(has_finding(*m, "UNRECOGNIZED_FILE")) << m->dump(2);
    // validate decides the same.
    const auto v = run("validate " + q(work / "in") + " --report json");
    ASSERT_EQ(v.code, 0) << v.output;
    const auto report = nlohmann::json::parse(v.output);
    EXPECT_EQ(report["materials"][0]["inputs"], (*m)["inputs"]);
    EXPECT_EQ(report["materials"][0]["constants"], (*m)["constants"]);
}
