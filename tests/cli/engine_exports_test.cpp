// Libraries exported for another engine (issue 44): real CC0 pixels from the corpus, packed and
// named the way Unity (Standard/URP, HDRP), Substance's engine templates and Megascans' Unreal-style
// exports write them, through the binary. Sources and outputs are read and written with
// OpenImageIO here (not matforge's own readers): every unpacked channel must equal its source
// channel code for code, smoothness inverted exactly (255 - k).
#include <OpenImageIO/imageio.h>
#include <webp/encode.h>

#include <functional>
#include <map>
#include <set>

#include "cli_util.hpp"
#include "oiio_oracle.hpp"

using namespace mft;

namespace engine_exports {

// An 8-bit image as OpenImageIO reads it: codes, interleaved, alpha unassociated.
struct Codes {
    int width = 0, height = 0, channels = 0;
    std::vector<uint8_t> px;
    uint8_t at(int x, int y, int c) const {
        return px[(static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x)) *
                      static_cast<size_t>(channels) +
                  static_cast<size_t>(c)];
    }
};

Codes oiio_read(const fs::path& p) {
    Codes c;
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);  // the stored values, not premultiplied
    auto in = OIIO::ImageInput::open(p.string(), &config);
    EXPECT_TRUE(in) << p;
    if (!in) return c;
    const OIIO::ImageSpec& spec = in->spec();
    c.width = spec.width;
    c.height = spec.height;
    c.channels = spec.nchannels;
    c.px.resize(static_cast<size_t>(c.width) * static_cast<size_t>(c.height) * static_cast<size_t>(c.channels));
    EXPECT_TRUE(in->read_image(0, 0, 0, c.channels, OIIO::TypeDesc::UINT8, c.px.data())) << p;
    return c;
}

// Writes a PNG of `channels` channels whose channel k at (x, y) is fill(x, y, k) (OpenImageIO's
// writer: an independent encoder, unassociated alpha).
void oiio_write_png(const fs::path& p, int w, int h, int channels, const std::function<uint8_t(int, int, int)>& fill) {
    std::vector<uint8_t> px(static_cast<size_t>(w) * static_cast<size_t>(h) * static_cast<size_t>(channels));
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int k = 0; k < channels; ++k)
                px[(static_cast<size_t>(y) * static_cast<size_t>(w) + static_cast<size_t>(x)) *
                       static_cast<size_t>(channels) +
                   static_cast<size_t>(k)] = fill(x, y, k);
    mf::testenv::oiio_write_png8(p, w, h, channels, px);
}

// The corpus set whose pixels the engine exports below are made of: a metal with a metalness map
// that is not constant (Sci-Fi_Wall_014: 190 distinct values) and real roughness and AO.
struct Source {
    fs::path dir = corpus_set("3dtextures_Sci-Fi_Wall_014");
    Codes color = oiio_read(dir / "Sci-Fi_Wall_014_basecolor.jpg");
    Codes metal = oiio_read(dir / "Sci-Fi_Wall_014_metallic.jpg");
    Codes rough = oiio_read(dir / "Sci-Fi_Wall_014_roughness.jpg");
    Codes ao = oiio_read(dir / "Sci-Fi_Wall_014_ambientOcclusion.jpg");
    int w() const { return color.width; }
    int h() const { return color.height; }
};
const Source& source() {
    static const Source s;
    return s;
}

// The warnings and errors (code, role) of a material: packing the same pixels must not change
// them (the source's metalness is truly not binary: those findings are right both ways).
std::set<std::pair<std::string, std::string>> blocking(const nlohmann::json& mat) {
    std::set<std::pair<std::string, std::string>> out;
    for (const auto& f : mat["findings"])
        if (f["severity"] != "info") out.emplace(f["code"], f.value("role", ""));
    return out;
}

struct Ingest {
    int code = -1;
    std::string output;
    nlohmann::json manifest;
};
Ingest ingest(const fs::path& in, const fs::path& out, const std::string& preset = "gltf");

const std::set<std::pair<std::string, std::string>>& separate_maps_findings() {
    static const std::set<std::pair<std::string, std::string>> once = [] {
        const Source& s = source();
        const fs::path set = temp_dir("separate") / "Wall";
        fs::create_directories(set);
        fs::copy_file(s.dir / "Sci-Fi_Wall_014_basecolor.jpg", set / "Wall_BaseColor.jpg");
        fs::copy_file(s.dir / "Sci-Fi_Wall_014_metallic.jpg", set / "Wall_Metallic.jpg");
        fs::copy_file(s.dir / "Sci-Fi_Wall_014_roughness.jpg", set / "Wall_Roughness.jpg");
        fs::copy_file(s.dir / "Sci-Fi_Wall_014_ambientOcclusion.jpg", set / "Wall_AO.jpg");
        const Ingest r = ingest(set, set.parent_path() / "out");
        std::set<std::pair<std::string, std::string>> found;
        if (!r.manifest["materials"].empty()) found = blocking(r.manifest["materials"][0]);
        // What the separate maps get: the metal is not binary, and its albedo dark for a metal.
        EXPECT_TRUE(found.count({"METALNESS_NOT_BINARY", "metalness"})) << r.manifest.dump(1);
        return found;
    }();
    return once;
}

Ingest ingest(const fs::path& in, const fs::path& out, const std::string& preset) {
    Ingest r;
    const auto res = run("ingest " + q(in) + " -o " + q(out) + " --preset " + preset + " --no-cache -q");
    r.code = res.code;
    r.output = res.output;
    if (fs::exists(out / "manifest.json")) r.manifest = read_json(out / "manifest.json");
    return r;
}

const nlohmann::json& only_material(const Ingest& r) {
    static const nlohmann::json empty;
    EXPECT_EQ(r.manifest["materials"].size(), 1u) << r.manifest.dump(1) << r.output;
    return r.manifest["materials"].empty() ? empty : r.manifest["materials"][0];
}

// The same pixels as separate maps, ingested once: what an engine export of them must be judged.
const std::set<std::pair<std::string, std::string>>& separate_maps_findings();

void expect_quiet(const nlohmann::json& mat) {
    EXPECT_EQ(blocking(mat), separate_maps_findings()) << mat["findings"].dump(1);
}

// The ORM output of a gltf material, read by OpenImageIO.
Codes orm_of(const fs::path& out, const nlohmann::json& mat) {
    const nlohmann::json* o = output_with(mat, "G", "roughness");
    EXPECT_TRUE(o) << mat["outputs"].dump(1);
    return o ? oiio_read(out / (*o)["file"].get<std::string>()) : Codes{};
}

// Every pixel of channel `c` of `got` is fn(x, y).
void expect_channel(const Codes& got, int c, const std::function<int(int, int)>& fn, const char* what) {
    ASSERT_GT(got.width, 0);
    long long wrong = 0;
    for (int y = 0; y < got.height; ++y)
        for (int x = 0; x < got.width; ++x) wrong += got.at(x, y, c) != fn(x, y);
    EXPECT_EQ(wrong, 0) << what << ": pixels that differ from their source channel";
}

// The ORM output holds the source's maps code for code: R its occlusion (when `occlusion`: a set
// packed without one gets a constant there), G its roughness, B its metalness. `how` says where
// each came from in the packed input.
void expect_source_orm(const Codes& orm, const Source& s, bool occlusion, const char* how) {
    SCOPED_TRACE(how);
    if (occlusion)
        expect_channel(
            orm, 0, [&](int x, int y) { return s.ao.at(x, y, 0); }, "occlusion");
    expect_channel(
        orm, 1, [&](int x, int y) { return s.rough.at(x, y, 0); }, "roughness");
    expect_channel(
        orm, 2, [&](int x, int y) { return s.metal.at(x, y, 0); }, "metalness");
}

}  // namespace engine_exports

using namespace engine_exports;

// Unity Standard/URP: `_AlbedoTransparency` (RGB colour, A opacity) and `_MetallicSmoothness`
// (R metallic, A smoothness; G/B unused, here noise that must not leak anywhere). The metal is
// the metal and smoothness becomes roughness exactly; never a gloss map of a second material.
TEST(EngineExports, UnityMetallicSmoothnessIsMetalAndInvertedSmoothness) {
    const Source& s = source();
    const fs::path set = temp_dir("unity") / "Crate";
    oiio_write_png(set / "Crate_AlbedoTransparency.png", s.w(), s.h(), 4, [&](int x, int y, int k) {
        return k < 3 ? s.color.at(x, y, k) : static_cast<uint8_t>(y < s.h() / 8 ? 0 : 255);  // a cut-out strip
    });
    oiio_write_png(set / "Crate_MetallicSmoothness.png", s.w(), s.h(), 4, [&](int x, int y, int k) {
        if (k == 0) return s.metal.at(x, y, 0);
        if (k == 3) return static_cast<uint8_t>(255 - s.rough.at(x, y, 0));
        return static_cast<uint8_t>((x * 7 + y * 13) & 255);  // unused channels
    });
    fs::copy_file(s.dir / "Sci-Fi_Wall_014_normal.jpg", set / "Crate_Normal.jpg");
    const Ingest r = ingest(set.parent_path(), set.parent_path().parent_path() / "out-unity");
    const nlohmann::json& mat = only_material(r);
    ASSERT_TRUE(mat.is_object());
    EXPECT_EQ(mat["name"], "Crate");
    EXPECT_EQ(mat["convention"], "unity");
    EXPECT_EQ(mat["inputs"]["metallic_smoothness"]["file"], "Crate_MetallicSmoothness.png") << mat["inputs"].dump(1);
    EXPECT_EQ(mat["inputs"]["metallic_smoothness"]["packing"],
              nlohmann::json({{"R", "metalness"}, {"A", "smoothness"}}));
    EXPECT_EQ(mat["inputs"]["albedo"]["file"], "Crate_AlbedoTransparency.png");
    EXPECT_FALSE(mat["inputs"].contains("gloss")) << "smoothness is no gloss map of another material";
    EXPECT_FALSE(mat["constants"].contains("metalness")) << "the metal keeps its metal";
    EXPECT_EQ(mat["inputs"]["normal"]["normal_convention"], "gl");  // Unity's convention
    EXPECT_EQ(mat.value("alpha_mode", "opaque"), "mask") << mat.dump(1);
    expect_quiet(mat);
    expect_source_orm(orm_of(set.parent_path().parent_path() / "out-unity", mat), s, false,
                      "roughness = 255 - smoothness (A), metalness = R");
}

// HDRP Lit's `_MaskMap`: R metallic, G occlusion, B detail mask (not a PBR role), A smoothness.
TEST(EngineExports, HdrpMaskMapUnpacksEveryChannel) {
    const Source& s = source();
    const fs::path set = temp_dir("hdrp") / "Panel";
    fs::copy_file(s.dir / "Sci-Fi_Wall_014_basecolor.jpg", set.parent_path() / "tmp.jpg");
    fs::create_directories(set);
    fs::rename(set.parent_path() / "tmp.jpg", set / "Panel_BaseColor.jpg");
    oiio_write_png(set / "Panel_MaskMap.png", s.w(), s.h(), 4, [&](int x, int y, int k) {
        switch (k) {
            case 0: return s.metal.at(x, y, 0);
            case 1: return s.ao.at(x, y, 0);
            case 2: return static_cast<uint8_t>(x & 255);  // the detail mask
            default: return static_cast<uint8_t>(255 - s.rough.at(x, y, 0));
        }
    });
    const fs::path out = set.parent_path() / "out";
    const Ingest r = ingest(set, out);
    const nlohmann::json& mat = only_material(r);
    ASSERT_TRUE(mat.is_object());
    EXPECT_EQ(mat["inputs"]["mask_map"]["packing"],
              nlohmann::json({{"R", "metalness"}, {"G", "occlusion"}, {"A", "smoothness"}}));
    expect_quiet(mat);
    expect_source_orm(orm_of(out, mat), s, true, "occlusion = G, roughness = 255 - A, metalness = R");
}

// Packed maps whose names state their channel order, in any case and separator style.
TEST(EngineExports, PackedMapsUnpackInTheOrderTheirNamesState) {
    const Source& s = source();
    struct Case {
        std::string file;
        std::string role;
        std::array<int, 3> order;  // which source (0 ao, 1 roughness, 2 metalness) each of R, G, B holds
    };
    const std::vector<Case> cases{
        {"Wall_MRA.png", "mra", {2, 1, 0}},  {"Wall-rma.png", "rma", {1, 2, 0}},
        {"Wall_MRAO.png", "mra", {2, 1, 0}}, {"Wall_OcclusionRoughnessMetallic.png", "orm", {0, 1, 2}},
        {"Wall.arm.png", "orm", {0, 1, 2}},
    };
    const fs::path root = temp_dir("packed");
    int i = 0;
    for (const auto& c : cases) {
        SCOPED_TRACE(c.file);
        const fs::path set = root / ("set" + std::to_string(i));
        const fs::path out = root / ("out" + std::to_string(i++));
        fs::create_directories(set);
        fs::copy_file(s.dir / "Sci-Fi_Wall_014_basecolor.jpg", set / "Wall_BaseColor.jpg");
        const Codes* src[] = {&s.ao, &s.rough, &s.metal};
        oiio_write_png(set / c.file, s.w(), s.h(), 3,
                       [&](int x, int y, int k) { return src[c.order[static_cast<size_t>(k)]]->at(x, y, 0); });
        const Ingest r = ingest(set, out);
        const nlohmann::json& mat = only_material(r);
        ASSERT_TRUE(mat.is_object());
        EXPECT_EQ(mat["inputs"][c.role]["file"], c.file) << mat["inputs"].dump(1);
        expect_quiet(mat);
        for (const auto& f : mat["findings"]) EXPECT_NE(f["code"], "PACKED_CHANNELS_IDENTICAL") << f.dump();
        expect_source_orm(orm_of(out, mat), s, true, "in the order the name states");
    }
}

// A packed name on pixels that are not packed is a finding, not a silent guess: one greyscale
// image in R, G and B (a roughness map saved as `_ORM`) is PACKED_CHANNELS_IDENTICAL, a colour
// photo under a packed name fails its metal channel (METALNESS_NOT_BINARY); the real packing of
// the same set (above) gets neither.
TEST(EngineExports, PackedNameOnUnpackedPixelsIsAFinding) {
    const Source& s = source();
    const fs::path root = temp_dir("packed_lies");
    auto codes_of = [](const nlohmann::json& mat, const std::string& role) {
        std::map<std::string, std::string> out;  // code -> severity
        for (const auto& f : mat["findings"])
            if (f.value("role", "") == role) out[f["code"]] = f["severity"];
        return out;
    };
    {
        const fs::path set = root / "grey";
        fs::create_directories(set);
        fs::copy_file(s.dir / "Sci-Fi_Wall_014_basecolor.jpg", set / "Wall_BaseColor.jpg");
        oiio_write_png(set / "Wall_ORM.png", s.w(), s.h(), 3, [&](int x, int y, int) { return s.rough.at(x, y, 0); });
        const Ingest r = ingest(set, root / "grey_out");
        const nlohmann::json& mat = only_material(r);
        ASSERT_TRUE(mat.is_object());
        const auto got = codes_of(mat, "orm");
        ASSERT_TRUE(got.count("PACKED_CHANNELS_IDENTICAL")) << mat["findings"].dump(1);
        EXPECT_EQ(got.at("PACKED_CHANNELS_IDENTICAL"), "warning");
    }
    {
        const fs::path set = root / "photo";
        fs::create_directories(set);
        fs::copy_file(s.dir / "Sci-Fi_Wall_014_basecolor.jpg", set / "Wall_BaseColor.jpg");
        oiio_write_png(set / "Wall_ORM.png", s.w(), s.h(), 3,
                       [&](int x, int y, int k) { return s.color.at(x, y, std::min(k, s.color.channels - 1)); });
        const Ingest r = ingest(set, root / "photo_out");
        const nlohmann::json& mat = only_material(r);
        ASSERT_TRUE(mat.is_object());
        bool metal_not_binary = false;
        for (const auto& f : mat["findings"])
            metal_not_binary = metal_not_binary || (f["code"] == "METALNESS_NOT_BINARY" && f["severity"] == "warning" &&
                                                    f.value("file", "") == "Wall_ORM.png");
        EXPECT_TRUE(metal_not_binary) << mat["findings"].dump(1);
        EXPECT_FALSE(codes_of(mat, "orm").count("PACKED_CHANNELS_IDENTICAL"));
    }
}

// Megascans named the Unreal way: "_A" is the albedo (a colour image is never an opacity mask)
// and "_D" the displacement; Epic's own style ("_D" colour, "_A" a grey mask) stays as it was.
TEST(EngineExports, UnrealLettersAreDecidedByThePixels) {
    const fs::path src = corpus_set("3dtextures_Ground_Wet_002");
    const fs::path root = temp_dir("letters");
    const fs::path mega = root / "mega", epic = root / "epic";
    fs::create_directories(mega);
    fs::create_directories(epic);
    fs::copy_file(src / "Ground_Wet_002_basecolor.jpg", mega / "T_GroundWet_A.jpg");
    fs::copy_file(src / "Ground_Wet_002_normal.jpg", mega / "T_GroundWet_N.jpg");
    fs::copy_file(src / "Ground_Wet_002_roughness.jpg", mega / "T_GroundWet_R.jpg");
    fs::copy_file(src / "Ground_Wet_002_height.png", mega / "T_GroundWet_D.png");
    // Megascans' "_T" translucency is a colour map (unity-cn/MegascansAbandonedApartment_URP's
    // T_BurntPaper_01_T: orange, imported sRGB): read as colour, and not NOT_GRAYSCALE.
    fs::copy_file(src / "Ground_Wet_002_basecolor.jpg", mega / "T_GroundWet_T.jpg");
    Ingest r = ingest(mega, root / "out-mega");
    const nlohmann::json m = only_material(r);
    ASSERT_TRUE(m.is_object());
    EXPECT_EQ(m["inputs"]["albedo"]["file"], "T_GroundWet_A.jpg") << m["inputs"].dump(1);
    EXPECT_EQ(m["inputs"]["height"]["file"], "T_GroundWet_D.png");
    // The material is GroundWet: "T_" is Unreal's texture prefix, not part of its name (the
    // unreal preset then writes T_GroundWet_BC, never T_T_GroundWet_BC).
    EXPECT_EQ(m["name"], "GroundWet");
    EXPECT_EQ(m["inputs"]["translucency"]["file"], "T_GroundWet_T.jpg");
    EXPECT_EQ(m["inputs"]["translucency"]["color_space"], "sRGB");
    for (const auto& f : m["findings"]) EXPECT_NE(f["code"], "NOT_GRAYSCALE") << f.dump();
    EXPECT_FALSE(m["inputs"].contains("opacity"));
    EXPECT_EQ(m.value("alpha_mode", "opaque"), "opaque");

    fs::copy_file(src / "Ground_Wet_002_basecolor.jpg", epic / "T_Leaf_D.jpg");
    fs::copy_file(src / "Ground_Wet_002_normal.jpg", epic / "T_Leaf_N.jpg");
    const Codes rough = oiio_read(src / "Ground_Wet_002_roughness.jpg");
    oiio_write_png(epic / "T_Leaf_A.png", rough.width, rough.height, 1,
                   [&](int x, int, int) { return static_cast<uint8_t>(x < rough.width / 2 ? 0 : 255); });
    r = ingest(epic, root / "out-epic");
    const nlohmann::json e = only_material(r);
    ASSERT_TRUE(e.is_object());
    EXPECT_EQ(e["inputs"]["albedo"]["file"], "T_Leaf_D.jpg") << e["inputs"].dump(1);
    EXPECT_EQ(e["inputs"]["opacity"]["file"], "T_Leaf_A.png");
    r = ingest(epic, root / "out-epic-unreal", std::string("unreal"));
    ASSERT_TRUE(only_material(r).is_object());
    EXPECT_EQ(only_material(r)["name"], "Leaf");
    EXPECT_TRUE(fs::is_regular_file(root / "out-epic-unreal" / "Leaf" / "T_Leaf_BC.png"));
}

// Two ambientCG downloads side by side in one flat folder (each with its own .mtlx) are two
// materials, each with its own maps; a stray colour map of a third id is not either's albedo.
TEST(EngineExports, TwoAmbientCgSetsInOneFolderAreTwoMaterials) {
    const fs::path flat = temp_dir("two-acg") / "flat";
    fs::create_directories(flat);
    for (const char* name : {"ambientcg_WoodFloor040_1K-JPG", "ambientcg_Net004A_1K-JPG"})
        for (const auto& e : fs::directory_iterator(corpus_set(name)))
            fs::copy_file(e.path(), flat / e.path().filename());
    const Ingest r = ingest(flat, flat.parent_path() / "out");
    ASSERT_EQ(r.manifest["materials"].size(), 2u) << r.manifest.dump(1) << r.output;
    std::map<std::string, std::string> albedo;
    for (const auto& m : r.manifest["materials"]) {
        albedo[m["name"]] = m["inputs"]["albedo"]["file"];
        for (const auto& f : m["findings"])  // GL beside DX is a choice of each set; the colour map is not
            EXPECT_FALSE(f["code"] == "AMBIGUOUS_MAP" && f["role"] == "albedo") << f.dump();
    }
    EXPECT_EQ(albedo["WoodFloor040"], "WoodFloor040_1K-JPG_Color.jpg");
    EXPECT_EQ(albedo["Net004A"], "Net004A_1K-JPG_Color.jpg");
}

// A subfolder of a set that holds maps of its own (an asset's billboard maps) is its own
// material, and validating it alone finds it.
TEST(EngineExports, ABillboardSubfolderIsItsOwnMaterial) {
    const fs::path src = corpus_set("3dtextures_Ground_Wet_002");
    const fs::path set = temp_dir("billboard") / "Fern";
    fs::create_directories(set / "Billboard");
    fs::copy_file(src / "Ground_Wet_002_basecolor.jpg", set / "Fern_2K_Albedo.jpg");
    fs::copy_file(src / "Ground_Wet_002_normal.jpg", set / "Fern_2K_Normal.jpg");
    fs::copy_file(src / "Ground_Wet_002_basecolor.jpg", set / "Billboard" / "Fern_Billboard_2K_Albedo.jpg");
    fs::copy_file(src / "Ground_Wet_002_normal.jpg", set / "Billboard" / "Fern_Billboard_2K_Normal.jpg");
    const Ingest r = ingest(set, set.parent_path() / "out");
    EXPECT_EQ(r.manifest["materials"].size(), 2u) << r.manifest.dump(1) << r.output;
    const auto v = run("validate " + q(set / "Billboard"));
    EXPECT_EQ(v.code, 0) << v.output;
    EXPECT_EQ(v.output.find("no material set found"), std::string::npos) << v.output;
}

// A lone stray image is no material: a screenshot named "normal_map_tutorial.png" alone is
// reported with the reason; beside a real set it is a note, and the set is the only material.
TEST(EngineExports, ALoneMapIsNotAMaterial) {
    const fs::path src = corpus_set("3dtextures_Ground_Wet_002");
    const fs::path root = temp_dir("lone");
    fs::create_directories(root / "lib" / "Ground");
    fs::create_directories(root / "lib" / "shots");
    fs::copy_file(src / "Ground_Wet_002_normal.jpg", root / "lib" / "shots" / "normal_map_tutorial.jpg");
    auto v = run("validate " + q(root / "lib" / "shots"));
    EXPECT_EQ(v.code, 1) << v.output;
    EXPECT_NE(v.output.find("a lone map whose name holds no material name"), std::string::npos) << v.output;
    fs::copy_file(src / "Ground_Wet_002_basecolor.jpg", root / "lib" / "Ground" / "Ground_basecolor.jpg");
    fs::copy_file(src / "Ground_Wet_002_roughness.jpg", root / "lib" / "Ground" / "Ground_roughness.jpg");
    const Ingest r = ingest(root / "lib", root / "out");
    EXPECT_EQ(r.code, 0) << r.output;
    ASSERT_EQ(r.manifest["materials"].size(), 1u) << r.manifest.dump(1);
    EXPECT_EQ(r.manifest["materials"][0]["name"], "Ground");
}

// An object-space normal map beside the tangent-space one never takes the normal slot; an
// image that is no normal map is not written as one (a flat normal, and the error says so).
TEST(EngineExports, ObjectSpaceAndInvalidNormalsStayOutOfTheNormalSlot) {
    const fs::path src = corpus_set("3dtextures_Ground_Wet_002");
    const fs::path root = temp_dir("normals");
    const fs::path set = root / "rock";
    fs::create_directories(set);
    fs::copy_file(src / "Ground_Wet_002_basecolor.jpg", set / "rock_diffuse.jpg");
    fs::copy_file(src / "Ground_Wet_002_normal.jpg", set / "rock_nm_tangent.jpg");
    fs::copy_file(src / "Ground_Wet_002_basecolor.jpg", set / "rock_nm.jpg");  // object space: any colours
    Ingest r = ingest(set, root / "out");
    const nlohmann::json m = only_material(r);
    ASSERT_TRUE(m.is_object());
    EXPECT_EQ(m["inputs"]["normal"]["file"], "rock_nm_tangent.jpg") << m["inputs"].dump(1);
    bool said = false;
    for (const auto& f : m["findings"])
        said = said || (f["code"] == "UNRECOGNIZED_FILE" && f["file"] == "rock_nm.jpg" && f["severity"] == "info");
    EXPECT_TRUE(said) << m["findings"].dump(1);

    const fs::path bad = root / "bad";
    fs::create_directories(bad);
    fs::copy_file(src / "Ground_Wet_002_basecolor.jpg", bad / "bad_basecolor.jpg");
    fs::copy_file(src / "Ground_Wet_002_basecolor.jpg", bad / "bad_normal.jpg");  // a photo named normal
    r = ingest(bad, root / "out-bad");
    const nlohmann::json b = only_material(r);
    ASSERT_TRUE(b.is_object());
    EXPECT_EQ(r.code, 1);
    bool error = false;
    for (const auto& f : b["findings"])
        error = error || (f["code"] == "NORMAL_INVALID" && f["severity"] == "error" &&
                          f["message"].get<std::string>().find("flat normal") != std::string::npos);
    EXPECT_TRUE(error) << b["findings"].dump(1);
    EXPECT_EQ(b["inputs"]["normal"].value("unused", false), true);
    // glTF's flat normal is no normalTexture: no output holds the photo as a normal map.
    EXPECT_FALSE(output_with(b, "RGB", "normal")) << b["outputs"].dump(1);
}

// A WebP with alpha decodes to its stored values (libwebp's RGBA, unassociated), bit for bit:
// its base colour under low alpha is not moved by a premultiply round trip.
TEST(EngineExports, WebpWithAlphaDecodesBitExact) {
    const Codes color = oiio_read(corpus_set("3dtextures_Ground_Wet_002") / "Ground_Wet_002_basecolor.jpg");
    const int w = color.width, h = color.height;
    std::vector<uint8_t> rgba(static_cast<size_t>(w) * static_cast<size_t>(h) * 4);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const size_t i = (static_cast<size_t>(y) * static_cast<size_t>(w) + static_cast<size_t>(x)) * 4;
            for (int k = 0; k < 3; ++k) rgba[i + static_cast<size_t>(k)] = color.at(x, y, k);
            rgba[i + 3] = static_cast<uint8_t>(y * 255 / (h - 1));  // from clear to opaque
        }
    uint8_t* encoded = nullptr;
    const size_t size = WebPEncodeLosslessRGBA(rgba.data(), w, h, w * 4, &encoded);
    ASSERT_GT(size, 0u);
    const fs::path set = temp_dir("webp") / "Leaf";
    fs::create_directories(set);
    std::ofstream(set / "Leaf_Color.webp", std::ios::binary)
        .write(reinterpret_cast<const char*>(encoded), static_cast<std::streamsize>(size));
    WebPFree(encoded);
    fs::copy_file(corpus_set("3dtextures_Ground_Wet_002") / "Ground_Wet_002_roughness.jpg", set / "Leaf_Roughness.jpg");
    const fs::path out = set.parent_path() / "out";
    const Ingest r = ingest(set, out);
    const nlohmann::json m = only_material(r);
    ASSERT_TRUE(m.is_object());
    const nlohmann::json* base = output_with(m, "RGB", "albedo");
    ASSERT_TRUE(base) << m["outputs"].dump(1);
    const Codes got = oiio_read(out / (*base)["file"].get<std::string>());
    ASSERT_EQ(got.width, w);
    ASSERT_EQ(got.channels, 4);
    // Where the texel is seen at all (alpha > 0; ingest may fill fully clear texels).
    long long wrong = 0, seen = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            if (got.at(x, y, 3) != y * 255 / (h - 1)) ++wrong;
            if (got.at(x, y, 3) == 0) continue;
            ++seen;
            for (int k = 0; k < 3; ++k) wrong += got.at(x, y, k) != color.at(x, y, k);
        }
    EXPECT_GT(seen, static_cast<long long>(w) * (h - 8));
    EXPECT_EQ(wrong, 0) << "base colour and alpha = the stored values";
}
