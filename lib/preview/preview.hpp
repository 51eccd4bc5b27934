// `matforge preview`: renders the materials of a manifest (or a scene's own material) with the
// renderer core, headless, to PNG (8-bit, sRGB-encoded) or EXR (linear radiance).
//
// Conventions of this module:
//  - paths inside a scene file are relative to the scene file; paths inside a manifest follow
//    the spec (outputs[].file relative to the manifest's folder);
//  - a bad option, scene or manifest is a UsageError (exit code 2); a material whose textures
//    cannot be read is reported and skipped (exit code 1); the others are still rendered;
//  - textures are read with unassociated alpha (a 4th channel is data, never premultiplied)
//    and handed to the renderer as stored; the renderer decodes sRGB and builds mips per role.
#pragma once
#include <filesystem>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "render/render.hpp"

namespace mf::preview {

class UsageError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// ---- scene file (shared/spec/interface.md, "Scene file")

struct SceneMaterial {
    std::optional<render::Vec3> albedo, emissive;
    std::optional<float> roughness, metalness;
    struct Map {
        std::filesystem::path file;  // absolute (resolved against the scene file's folder)
        std::optional<render::Channel> channel;  // "#R" … "#A"; none: RGB (or R for scalars)
    };
    std::optional<Map> albedo_map, normal_map, roughness_map, metalness_map, occlusion_map,
        emissive_map, opacity_map;
    bool normal_dx = false;
};

struct SceneFile {
    render::Scene scene;            // defaults: 512², one white key light, sphere, black
    render::OutputOptions output;   // transfer and exposure
    std::optional<SceneMaterial> material;
    std::optional<std::filesystem::path> environment;  // resolved path
    float environment_intensity = 1.f;
    bool shape_size_given = false;
};

SceneFile default_scene();
// Throws UsageError naming the file and the offending key.
SceneFile parse_scene(const nlohmann::json& j, const std::filesystem::path& base_dir,
                      const std::string& display_name);
SceneFile read_scene_file(const std::filesystem::path& file);

// Default size of a shape when the scene gives none: sphere radius 1, cube edge 1.2, plane side 2
// (all fill a 35° view from 4 m).
float default_shape_size(render::ShapeType t);

// --light SPEC: "dir:X,Y,Z[:INTENSITY[:R,G,B]]" (direction of travel) or
// "point:X,Y,Z[:INTENSITY[:R,G,B]]". Returns nullopt and sets `error` when malformed.
std::optional<render::Light> parse_light_spec(const std::string& spec, std::string& error);

// ---- manifest (version 1)

struct ManifestOutput {
    std::filesystem::path file;  // resolved
    std::string color_space;     // "sRGB" | "linear"
    std::vector<std::pair<std::string, nlohmann::json>> channels;  // key → role/number/…
    std::string normal_convention;  // "gl" | "dx" | ""
};
struct ManifestMaterial {
    std::string name;
    std::vector<ManifestOutput> outputs;
    std::vector<std::pair<std::string, nlohmann::json>> constants;
};
struct Manifest {
    std::filesystem::path dir;
    std::vector<ManifestMaterial> materials;
};

Manifest parse_manifest(const nlohmann::json& j, const std::filesystem::path& dir);
Manifest read_manifest(const std::filesystem::path& file);  // throws UsageError

// Reads the material's output textures and maps their channels to roles. Notes for roles the
// preview does not simulate (height) or channel values it does not understand go to `notes`.
// Throws std::runtime_error when a texture cannot be read.
render::Material load_manifest_material(const ManifestMaterial& m, std::vector<std::string>& notes);

// Applies a scene file's material: its maps replace the manifest's for their roles; its
// constants apply where a role has no map.
void apply_scene_material(const SceneMaterial& s, render::Material& m);

// ---- image files (OpenImageIO)

render::Texture read_texture(const std::filesystem::path& file);  // throws std::runtime_error
render::Environment read_environment(const std::filesystem::path& file, float intensity);
// Written aside and renamed into place: an interrupted run leaves no half-written file.
void write_png(const std::filesystem::path& file, uint32_t width, uint32_t height,
               const std::vector<uint8_t>& rgba8);
void write_exr(const std::filesystem::path& file, uint32_t width, uint32_t height,
               const std::vector<float>& rgba32f);

// ---- contact sheet

struct SheetTile {
    std::string label;
    uint32_t width = 0, height = 0;
    std::vector<uint8_t> rgba8;
};
// All tiles on one RGBA8 image, in rows, each labeled underneath in the built-in font.
void compose_contact_sheet(const std::vector<SheetTile>& tiles, uint32_t& width, uint32_t& height,
                           std::vector<uint8_t>& rgba8);
// Draws `text` with the built-in 5×7 font, `scale` pixels per font pixel, clipped to the image.
void draw_text(std::vector<uint8_t>& rgba8, uint32_t width, uint32_t height, int x, int y,
               const std::string& text, int scale, const uint8_t color[3]);
int text_width(const std::string& text, int scale);

// ---- the command

struct Options {
    std::optional<std::filesystem::path> manifest;
    std::filesystem::path out_dir;
    std::optional<std::filesystem::path> scene;
    std::optional<uint32_t> size;
    std::optional<std::string> shape;
    std::vector<std::string> lights;  // --light specs; when given they replace the scene's
    std::optional<std::filesystem::path> env;
    std::string format = "png";
    std::optional<std::filesystem::path> contact_sheet;
    std::string device = "auto";
    std::optional<std::string> brdf;  // overrides the scene file's "brdf"
    bool validation = false;  // --validate: Khronos validation layer (diagnostics)
    bool quiet = false;
};

// Renders everything asked for; progress and problems go to `log`. Returns the exit code
// (0 done, 1 some material failed, 2 usage/configuration error or no Vulkan device).
int run(const Options& options, std::ostream& log);

}  // namespace mf::preview
