// The layer between the renderer core (lib/render) and files: scene files, manifest materials
// turned into renderer materials, texture and environment files, contact sheets. The render
// loop over many materials is batch.hpp; the command (options, exit codes) is
// tools/matforge/cmd_preview.cpp.
//
// Conventions of this module (decided once here):
//  - errors are returned, never thrown: nullopt / false and `error`, naming the file (and the
//    key) and the problem; render::Error from the renderer core passes through untouched;
//  - paths in a scene file are relative to the scene file; paths in a manifest are relative to
//    the manifest's folder and must stay inside it unless the caller allows more;
//  - image files are read and written through lib/image (unassociated alpha, the decompression
//    bomb guard, no FIFO or device ever opened) and lib/core (atomic writes): an 8-bit file is
//    handed to the renderer as its codes, any other as float; the renderer decodes sRGB.
#pragma once
#include <array>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "manifest/manifest.hpp"
#include "render/render.hpp"

namespace mf::preview {

// ---- scene file (docs/interface.md, "Scene file")

struct SceneMaterial {
    std::optional<render::Vec3> albedo, emissive;
    std::optional<float> roughness, metalness;
    struct Map {
        std::filesystem::path file;              // absolute (resolved against the scene file's folder)
        std::optional<render::Channel> channel;  // "#R" … "#A"; none: RGB (or R for scalars)
    };
    std::optional<Map> albedo_map, normal_map, roughness_map, metalness_map, occlusion_map, emissive_map, opacity_map;
    NormalConvention normal_convention = NormalConvention::gl;  // of normal_map
};

struct SceneFile {
    render::Scene scene;           // defaults: 512², one white key light, sphere, black
    render::OutputOptions output;  // transfer, exposure and tone mapping
    std::optional<SceneMaterial> material;
    std::optional<std::filesystem::path> environment;  // resolved path
    float environment_intensity = 1.f;
    bool shape_size_given = false;
    bool lookdev = false;  // default_scene(): the studio environment is the built-in one
    // Texture placement for every material (scene key "uv"): tiling, and whether the texture's
    // aspect ratio is kept on the shape (place_textures).
    std::array<float, 2> uv_scale{1.f, 1.f}, uv_offset{0.f, 0.f};
    bool keep_aspect = false;  // lookdev: true
};

// Sets `m`'s uv_scale and uv_offset from the scene's: the scale times, with keep_aspect, the
// factor that keeps a texel square on the shape. A shape's (u, v) spans lengths in the ratio
// 2:1 on the sphere and the shaderball (once around, pole to pole) and 1:1 on a plane or a cube
// face; a texture of aspect w/h then needs u scaled by (surface ratio) / (w/h): a square map goes
// twice around the sphere, a 2:1 map once, and on a plane a 2:1 map shows its left half
// unstretched. The texture measured is the albedo's, else the first.
void place_textures(const SceneFile& sf, render::Material& m);

// The camera moved on its orbit around its target: `az_el` degrees (azimuth from +Z toward +X,
// elevation above the target's horizon), at `distance` (default: the camera's own). nullopt +
// `error` when the camera sits on its target (no direction to orbit from) or would look straight
// along its up vector.
std::optional<render::Camera> orbit_camera(const render::Camera& c, std::optional<std::array<float, 2>> az_el,
                                           std::optional<float> distance, std::string& error);

// The look-dev scene `preview` uses when no scene file is given: the built-in studio
// environment (studio_environment) for image-based lighting, one key light from its key
// softbox, a mid-grey background, Khronos PBR Neutral tone mapping.
SceneFile default_scene();
// `--scene reference` and the base every scene file starts from: one white directional light
// (intensity 3), a sphere, a black background, no environment, no tone mapping (the scenes the
// CPU-reference tests hold the renderer to).
SceneFile reference_scene();
// A photographic studio generated deterministically (512x256, linear radiance): a grey
// cyclorama with a large warm key softbox (camera left, above), a cool fill (right), a narrow rim
// strip behind and an overhead light. Generated rather than shipped: the same radiance on every
// machine, no licence to track, no file to read.
std::shared_ptr<const render::Environment> studio_environment();
// nullopt + `error` naming `display_name` and the offending key. Values are range-checked:
// colors are non-negative, albedo, roughness and metalness within [0, 1].
std::optional<SceneFile> parse_scene(const nlohmann::json& j, const std::filesystem::path& base_dir,
                                     const std::string& display_name, std::string& error);
std::optional<SceneFile> read_scene_file(const std::filesystem::path& file, std::string& error);

// Default size of a shape when the scene gives none: sphere radius 1, cube edge 1.2, plane side 2
// (all fill a 35° view from 4 m).
float default_shape_size(render::ShapeType t);
std::optional<render::ShapeType> parse_shape(std::string_view name);  // "sphere" | "cube" | "plane"

// --light SPEC: "dir:X,Y,Z[:INTENSITY[:R,G,B]]" (direction of travel) or
// "point:X,Y,Z[:INTENSITY[:R,G,B]]". Returns nullopt and sets `error` when malformed.
std::optional<render::Light> parse_light_spec(const std::string& spec, std::string& error);

// ---- manifest materials

// How a GPU texture file's blocks (DDS, KTX2) reach the renderer, by their VkFormat.
enum class BlockUse {
    // Uploaded as the file holds them: the device samples the format.
    as_written,
    // Every level decoded here once, to 8-bit RGBA as a GPU returns the blocks, the file's own mip
    // chain kept (render::kDecodedLevels): a CPU device, which samples the format but decodes
    // blocks on every fetch (lavapipe drew a 1K BC7/BC5 material in 0.75 s, its PNGs in 0.09 s).
    decoded,
    // As `decoded`, with a note: the device does not sample the format.
    decoded_absent,
    // Level 0 decoded; the renderer makes its mips (the report's viewer, which takes plain maps).
    top_level,
};
using BlockSupport = std::function<BlockUse(uint32_t vk_format)>;

struct MaterialOptions {
    bool allow_outside = false;  // textures may lie outside the manifest's folder
    BlockSupport samples;        // DDS/KTX2 blocks: as written when unset
};

// The material's output textures, read, with their channels mapped to the renderer's slots.
// Notes for what the preview does not simulate (height) go to `notes`; nullopt + `error` when a
// texture cannot be read or lies outside `manifest_dir` (unless allowed).
std::optional<render::Material> load_material(const manifest::Material& m, const std::filesystem::path& manifest_dir,
                                              const MaterialOptions& opt, std::vector<std::string>& notes,
                                              std::string& error);

// Applies a scene file's material: its maps replace the material's for their roles; its
// constants apply where a role has no map. False + `error` when a map cannot be read.
bool apply_scene_material(const SceneMaterial& s, render::Material& m, std::string& error);

// ---- image files (through lib/image and lib/core)

std::optional<render::Texture> read_texture(const std::filesystem::path& file, std::string& error);
// A .dds or .ktx2 file (what ingest's GPU presets write; texture::is_gpu_texture_name): its
// blocks and mip chain as written, or decoded on the CPU, as `samples` says (BlockUse).
std::optional<render::Texture> read_gpu_texture(const std::filesystem::path& file, const BlockSupport& samples,
                                                std::vector<std::string>& notes, std::string& error);
std::optional<render::Environment> read_environment(const std::filesystem::path& file, float intensity,
                                                    std::string& error);
// RGB of an RGBA frame, written atomically (aside, fsync, rename): an interrupted run leaves no
// half-written file. PNG: 8-bit sRGB-encoded codes; EXR: linear float.
bool write_png(const std::filesystem::path& file, uint32_t width, uint32_t height, const std::vector<uint8_t>& rgba8,
               std::string& error);
bool write_exr(const std::filesystem::path& file, uint32_t width, uint32_t height, const std::vector<float>& rgba32f,
               std::string& error);

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
void draw_text(std::vector<uint8_t>& rgba8, uint32_t width, uint32_t height, int x, int y, const std::string& text,
               int scale, const uint8_t color[3]);
int text_width(const std::string& text, int scale);

}  // namespace mf::preview
