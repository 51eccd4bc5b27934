// Scene files and --light specs.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>

#include "preview/preview.hpp"

namespace mf::preview {
namespace {

using nlohmann::json;

TEST(SceneFile, ReferenceSceneIsTheExactOne) {
    const SceneFile s = reference_scene();
    EXPECT_EQ(s.scene.width, 512u);
    ASSERT_EQ(s.scene.lights.size(), 1u);  // one white directional key light
    EXPECT_EQ(s.scene.lights[0].type, render::LightType::directional);
    EXPECT_EQ(s.scene.lights[0].intensity, 3.f);
    EXPECT_EQ(s.scene.shape.type, render::ShapeType::sphere);
    EXPECT_EQ(s.scene.background, (render::Vec3{0, 0, 0}));
    EXPECT_FALSE(s.scene.environment);
    EXPECT_EQ(s.output.transfer, render::Transfer::srgb);
    EXPECT_EQ(s.output.tonemap, render::Tonemap::none);
    // A scene file starts from it: an empty one is the reference scene.
    std::string error;
    const auto empty = parse_scene(json::object(), "/", "empty.json", error);
    ASSERT_TRUE(empty) << error;
    EXPECT_FALSE(empty->scene.environment);
    EXPECT_EQ(empty->output.tonemap, render::Tonemap::none);
    EXPECT_EQ(empty->scene.lights.size(), 1u);
}

TEST(SceneFile, DefaultIsTheLookDevStudio) {
    const SceneFile s = default_scene();
    ASSERT_TRUE(s.scene.environment);
    EXPECT_EQ(s.scene.environment->width, 512u);
    EXPECT_EQ(s.scene.environment->height, 256u);
    ASSERT_EQ(s.scene.lights.size(), 1u);
    EXPECT_EQ(s.output.tonemap, render::Tonemap::neutral);
    EXPECT_EQ(s.scene.background, (render::Vec3{0.18f, 0.18f, 0.18f}));
    // The key light travels away from the key softbox, which is the environment's brightest
    // region: the light comes from above, camera left, toward the camera side.
    const render::Vec3 d = s.scene.lights[0].direction;
    EXPECT_LT(d[1], -0.5f);
    EXPECT_GT(d[0], 0.2f);
    EXPECT_LT(d[2], -0.2f);
    const auto& env = *s.scene.environment;
    auto radiance = [&](render::Vec3 from) {  // render::Environment's mapping
        const float len = std::sqrt(from[0] * from[0] + from[1] * from[1] + from[2] * from[2]);
        const float u = 0.5f + std::atan2(from[0] / len, -from[2] / len) / (2.f * 3.14159265f);
        const float v = std::acos(from[1] / len) / 3.14159265f;
        const auto x = std::min(env.width - 1, static_cast<uint32_t>(u * static_cast<float>(env.width)));
        const auto y = std::min(env.height - 1, static_cast<uint32_t>(v * static_cast<float>(env.height)));
        return env.rgba[(size_t{y} * env.width + x) * 4 + 1];
    };
    EXPECT_NEAR(radiance({-d[0], -d[1], -d[2]}), 5.f * 0.97f + 0.136f, 0.05f);  // inside the key softbox
    EXPECT_NEAR(radiance({0.f, -1.f, 0.f}), 0.08f, 0.005f);                     // the floor: the darkest grey
    float sum = 0.f;
    for (size_t i = 0; i < env.rgba.size(); ++i) {
        ASSERT_TRUE(std::isfinite(env.rgba[i]));
        ASSERT_GE(env.rgba[i], 0.f);
        if (i % 4 != 3) sum += env.rgba[i];
    }
    EXPECT_GT(sum, 0.f);
    // Deterministic: the same radiance every time (a generated environment, no file).
    EXPECT_EQ(studio_environment()->rgba, env.rgba);
}

TEST(Placement, TexelsStaySquareOnTheShape) {
    SceneFile sf = default_scene();  // keep_aspect
    render::Material m;
    m.textures.resize(1);
    m.albedo.texture = 0;
    auto scale_for = [&](render::ShapeType shape, uint32_t w, uint32_t h) {
        sf.scene.shape.type = shape;
        m.textures[0].width = w;
        m.textures[0].height = h;
        place_textures(sf, m);
        return m.uv_scale;
    };
    using S = std::array<float, 2>;
    EXPECT_EQ(scale_for(render::ShapeType::sphere, 1024, 1024), (S{2.f, 1.f}));  // twice around
    EXPECT_EQ(scale_for(render::ShapeType::sphere, 2048, 1024), (S{1.f, 1.f}));  // once, unstretched
    EXPECT_EQ(scale_for(render::ShapeType::plane, 2048, 1024), (S{0.5f, 1.f}));  // the left half
    EXPECT_EQ(scale_for(render::ShapeType::shaderball, 512, 1024), (S{4.f, 1.f}));
    sf.uv_scale = {3.f, 2.f};
    sf.uv_offset = {0.25f, 0.5f};
    EXPECT_EQ(scale_for(render::ShapeType::cube, 1024, 1024), (S{3.f, 2.f}));
    EXPECT_EQ(m.uv_offset, (S{0.25f, 0.5f}));
    sf.keep_aspect = false;
    EXPECT_EQ(scale_for(render::ShapeType::sphere, 1024, 1024), (S{3.f, 2.f}));
    // Read from a scene file; out-of-range values are errors naming the key.
    std::string error;
    auto parsed = parse_scene(json::parse(R"({"uv": {"scale": [2, 1], "offset": [0.5, 0], "aspect": "keep"}})"), "/",
                              "uv.json", error);
    ASSERT_TRUE(parsed) << error;
    EXPECT_EQ(parsed->uv_scale, (S{2.f, 1.f}));
    EXPECT_TRUE(parsed->keep_aspect);
    EXPECT_FALSE(parse_scene(json::parse(R"({"uv": {"scale": -1}})"), "/", "uv.json", error));
    EXPECT_NE(error.find("uv.json: uv.scale"), std::string::npos) << error;
}

TEST(SceneFile, GroundIsReadAndChecked) {
    std::string error;
    auto s = parse_scene(json::parse(R"({"ground": true})"), "/", "g.json", error);
    ASSERT_TRUE(s) << error;
    EXPECT_TRUE(s->scene.ground.enabled);
    s = parse_scene(json::parse(R"({"ground": {"albedo": 0.3, "roughness": 0.9}})"), "/", "g.json", error);
    ASSERT_TRUE(s) << error;
    EXPECT_TRUE(s->scene.ground.enabled);
    EXPECT_FLOAT_EQ(s->scene.ground.albedo, 0.3f);
    EXPECT_FALSE(reference_scene().scene.ground.enabled);
    EXPECT_FALSE(default_scene().scene.ground.enabled);  // only when asked
    EXPECT_FALSE(parse_scene(json::parse(R"({"ground": {"albedo": 2}})"), "/", "g.json", error));
    EXPECT_NE(error.find("g.json: ground.albedo"), std::string::npos) << error;
}

// The look-dev default multisamples and takes the fast texture path; the reference and scene
// files do neither unless asked (image.msaa), as the exactness tests need.
TEST(SceneFile, AntiAliasingAndTexturePath) {
    EXPECT_EQ(default_scene().scene.msaa, 4u);
    EXPECT_EQ(default_scene().scene.supersample, 1u);
    EXPECT_TRUE(default_scene().scene.fast_textures);
    EXPECT_EQ(reference_scene().scene.msaa, 1u);
    EXPECT_FALSE(reference_scene().scene.fast_textures);
    std::string error;
    auto s = parse_scene(json::parse(R"({"image": {"msaa": 4, "supersample": 2}})"), "/", "a.json", error);
    ASSERT_TRUE(s) << error;
    EXPECT_EQ(s->scene.msaa, 4u);
    EXPECT_EQ(s->scene.supersample, 2u);
    EXPECT_FALSE(s->scene.fast_textures);
    for (const char* bad : {R"({"image": {"msaa": 3}})", R"({"image": {"msaa": 16}})", R"({"image": {"msaa": 0}})"}) {
        EXPECT_FALSE(parse_scene(json::parse(bad), "/", "a.json", error)) << bad;
        EXPECT_NE(error.find("a.json: image.msaa"), std::string::npos) << error;
    }
}

// The look-dev default shades on the faster path of the device (measured); the reference and
// scene files on raster, the same image everywhere, unless image.shading asks.
TEST(SceneFile, ShadingPath) {
    EXPECT_EQ(default_scene().scene.shading, render::Shading::automatic);
    EXPECT_EQ(reference_scene().scene.shading, render::Shading::raster);
    std::string error;
    auto s = parse_scene(json::parse(R"({"image": {"shading": "compute"}})"), "/", "a.json", error);
    ASSERT_TRUE(s) << error;
    EXPECT_EQ(s->scene.shading, render::Shading::compute);
    s = parse_scene(json::parse(R"({"image": {}})"), "/", "a.json", error);
    ASSERT_TRUE(s) << error;
    EXPECT_EQ(s->scene.shading, render::Shading::raster);
    for (const char* bad : {R"({"image": {"shading": "gpu"}})", R"({"image": {"shading": 1}})"}) {
        EXPECT_FALSE(parse_scene(json::parse(bad), "/", "a.json", error)) << bad;
        EXPECT_NE(error.find("a.json: image.shading"), std::string::npos) << error;
    }
}

TEST(Placement, OrbitKeepsTheTargetAndDistance) {
    render::Camera c;  // (0, 0, 4) looking at the origin
    std::string error;
    auto o = orbit_camera(c, std::array<float, 2>{90.f, 0.f}, std::nullopt, error);
    ASSERT_TRUE(o) << error;
    EXPECT_NEAR(o->position[0], 4.f, 1e-5f);
    EXPECT_NEAR(o->position[1], 0.f, 1e-5f);
    EXPECT_NEAR(o->position[2], 0.f, 1e-5f);
    o = orbit_camera(c, std::array<float, 2>{0.f, 30.f}, 2.f, error);
    ASSERT_TRUE(o) << error;
    EXPECT_NEAR(o->position[1], 1.f, 1e-5f);             // 2 sin 30°
    EXPECT_NEAR(o->position[2], std::sqrt(3.f), 1e-5f);  // 2 cos 30°
    o = orbit_camera(c, std::nullopt, 8.f, error);       // the same direction, farther
    ASSERT_TRUE(o) << error;
    EXPECT_NEAR(o->position[2], 8.f, 1e-5f);
    EXPECT_FALSE(orbit_camera(c, std::array<float, 2>{0.f, 90.f}, std::nullopt, error));
    c.position = c.target;
    EXPECT_FALSE(orbit_camera(c, std::nullopt, 2.f, error));
    EXPECT_NE(error.find("sits on its target"), std::string::npos);
}

TEST(SceneFile, ToneMappingIsReadAndChecked) {
    std::string error;
    auto s = parse_scene(json::parse(R"({"output": {"tonemap": "aces"}})"), "/", "t.json", error);
    ASSERT_TRUE(s) << error;
    EXPECT_EQ(s->output.tonemap, render::Tonemap::aces);
    EXPECT_FALSE(parse_scene(json::parse(R"({"output": {"tonemap": "filmic"}})"), "/", "t.json", error));
    EXPECT_NE(error.find("t.json: output.tonemap"), std::string::npos) << error;
}

TEST(SceneFile, ReadsTheSpecExample) {
    const json j = json::parse(R"({
      "image":  { "width": 512, "height": 256 },
      "camera": { "position": [0, 0, 4], "target": [0, 0, 0], "up": [0, 1, 0], "yfov_deg": 35.0 },
      "shape":  { "type": "sphere", "radius": 1.5 },
      "background": [0.1, 0.2, 0.3],
      "lights": [
        { "type": "directional", "direction": [0.57735, -0.57735, -0.57735], "color": [1, 1, 1], "intensity": 3.0 },
        { "type": "point", "position": [2.5, -0.5, 1.5], "color": [0.3, 0.5, 1.0], "intensity": 10.0 }
      ],
      "environment": { "file": "studio.hdr", "intensity": 0.5 },
      "material": { "albedo": [1.0, 0.766, 0.336], "roughness": 0.3, "metalness": 1.0,
                    "maps": { "roughness": "mr.png#G", "normal": "n.png" }, "normal_convention": "dx" },
      "output": { "transfer": "linear", "exposure": 2.0 }
    })");
    std::string error;
    const auto parsed = parse_scene(j, "/scenes", "test.json", error);
    ASSERT_TRUE(parsed) << error;
    const SceneFile& s = *parsed;
    EXPECT_EQ(s.scene.width, 512u);
    EXPECT_EQ(s.scene.height, 256u);
    EXPECT_FLOAT_EQ(s.scene.shape.size, 1.5f);
    ASSERT_EQ(s.scene.lights.size(), 2u);
    EXPECT_EQ(s.scene.lights[1].type, render::LightType::point);
    EXPECT_FLOAT_EQ(s.scene.lights[1].intensity, 10.f);
    EXPECT_EQ(s.environment, std::filesystem::path("/scenes/studio.hdr"));
    EXPECT_FLOAT_EQ(s.environment_intensity, 0.5f);
    ASSERT_TRUE(s.material);
    EXPECT_FLOAT_EQ(*s.material->metalness, 1.f);
    ASSERT_TRUE(s.material->roughness_map);
    EXPECT_EQ(s.material->roughness_map->file, std::filesystem::path("/scenes/mr.png"));
    EXPECT_EQ(s.material->roughness_map->channel, render::Channel::G);
    EXPECT_EQ(s.material->normal_convention, NormalConvention::dx);
    EXPECT_EQ(s.output.transfer, render::Transfer::linear);
    EXPECT_FLOAT_EQ(s.output.exposure, 2.f);
}

TEST(SceneFile, ShapesTakeTheirOwnDefaultSize) {
    std::string error;
    const auto parsed = parse_scene(json::parse(R"({"shape": {"type": "cube"}})"), ".", "t", error);
    ASSERT_TRUE(parsed) << error;
    const SceneFile& s = *parsed;
    EXPECT_EQ(s.scene.shape.type, render::ShapeType::cube);
    EXPECT_FLOAT_EQ(s.scene.shape.size, default_shape_size(render::ShapeType::cube));
    EXPECT_FALSE(s.shape_size_given);
}

TEST(SceneFile, MistakesAreErrorsNamingTheKey) {
    const char* bad[] = {
        R"({"camera": {"yfov_deg": 0}})",
        R"({"image": {"width": 0}})",
        R"({"lights": [{"type": "spot"}]})",
        R"({"lights": [{"type": "point"}]})",
        R"({"lights": [{"type": "directional", "direction": [0, 0, 0]}]})",
        R"({"shape": {"type": "torus"}})",
        R"({"material": {"maps": {"roughness": "mr.png#X"}}})",
        R"({"output": {"transfer": "gamma22"}})",
        R"({"cammera": {}})",
        R"({"background": [1, 2]})",
        R"({"background": [1, 1e300, 1]})",  // finite as a double, infinite as a float
        // Wrong JSON types: UsageErrors, never a JSON type_error (the scene fuzzer found the first).
        R"({"lights": [{"type": 10.0}]})",
        R"({"lights": [3]})",
        R"({"shape": {"type": 3}})",
        R"({"environment": {"file": 3}})",
        R"({"output": {"transfer": 1}})",
        R"({"material": {"maps": {"roughness": 1}}})",
        R"({"material": {"normal_convention": 1}})",
        R"({"image": {"width": "512"}})",
        // Values outside what the quantity can be.
        R"({"material": {"albedo": [-0.1, 0.5, 0.5]}})",
        R"({"material": {"albedo": [1.5, 0.5, 0.5]}})",
        R"({"material": {"metalness": 7}})",
        R"({"material": {"roughness": -3}})",
        R"({"material": {"emissive": [0, -1, 0]}})",
        R"({"background": [-1, 0, 0]})",
        R"({"lights": [{"type": "directional", "color": [1, -0.5, 1]}]})",
        R"({"environment": {"file": "e.hdr", "intensity": -1}})",
    };
    std::string error;
    for (const char* text : bad) {
        error.clear();
        EXPECT_FALSE(parse_scene(json::parse(text), ".", "t", error)) << text;
        EXPECT_EQ(error.rfind("t: ", 0), 0u) << text << " -> " << error;
    }
    EXPECT_FALSE(parse_scene(json::parse(R"({"lights": [{"type": "point"}]})"), ".", "scene.json", error));
    EXPECT_NE(error.find("scene.json: lights[0]"), std::string::npos) << error;
    EXPECT_FALSE(parse_scene(json::parse(R"({"material": {"metalness": 7}})"), ".", "scene.json", error));
    EXPECT_NE(error.find("scene.json: material.metalness"), std::string::npos) << error;
}

TEST(SceneFile, DeeplyNestedJsonIsRefusedNamingTheFile) {
    const std::filesystem::path f = std::filesystem::temp_directory_path() / "matforge_deep_scene.json";
    std::ofstream(f) << std::string(100000, '[') << std::string(100000, ']');
    std::string error;
    EXPECT_FALSE(read_scene_file(f, error));
    EXPECT_NE(error.find(f.string()), std::string::npos) << error;
    EXPECT_NE(error.find("nested deeper"), std::string::npos) << error;
    std::filesystem::remove(f);
}

TEST(LightSpec, DirectionalAndPoint) {
    std::string err;
    auto d = parse_light_spec("dir:0,-1,0", err);
    ASSERT_TRUE(d) << err;
    EXPECT_EQ(d->type, render::LightType::directional);
    EXPECT_FLOAT_EQ(d->intensity, 3.f);
    auto p = parse_light_spec("point:1,2,3:25:0.5,0.5,1", err);
    ASSERT_TRUE(p) << err;
    EXPECT_EQ(p->type, render::LightType::point);
    EXPECT_EQ(p->position, (render::Vec3{1, 2, 3}));
    EXPECT_FLOAT_EQ(p->intensity, 25.f);
    EXPECT_EQ(p->color, (render::Vec3{0.5f, 0.5f, 1}));
    for (const char* bad :
         {"dir", "dir:1,2", "spot:1,2,3", "dir:0,0,0", "point:1,2,3:-1", "point:1,2,3:x", "dir:1,2,3:1:1,1"})
        EXPECT_FALSE(parse_light_spec(bad, err)) << bad;
}

}  // namespace
}  // namespace mf::preview
