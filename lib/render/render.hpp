// matforge preview renderer core: headless offscreen Vulkan rendering of one material on a
// sphere, cube or plane, with a Cook-Torrance BRDF (GGX, Schlick Fresnel with a colored F0,
// Schlick-GGX or height-correlated Smith visibility, energy-conserving Lambert diffuse).
//
// Conventions of this module (decided once here):
//  - links Vulkan (loaded at run time) and the standard library only: pixels come in and go out
//    as plain buffers; image files and JSON are the business of the layer above (lib/preview);
//  - world space is right-handed, Y up, metres (glTF); colors are linear Rec.709;
//  - light units: L = Σ f(l,v) · E · max(n·l, 0) with E = color · intensity for a directional
//    light and color · intensity / d² for a point light; f includes Lambert's albedo/π, so a
//    white Lambertian surface facing a directional light of intensity π has radiance 1;
//  - images are rows top to bottom, RGBA interleaved;
//  - errors throw: NoDeviceError when no usable Vulkan device exists (a configuration problem,
//    exit code 2 for a CLI), Error for everything else.
//
// Does NOT do: shadows, ambient light, parallax/height, anisotropy, clear coat, transmission.
// Only what the scene and the material call for is simulated (see Renderer).
#pragma once
#include <array>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "render/shaders/interface.h"  // the GPU interface, shared with the shaders (array sizes)

namespace mf::render {

using Vec3 = std::array<float, 3>;

class Error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};
// No Vulkan loader, no driver, or no device of the requested kind. The message names the
// package to install.
class NoDeviceError : public Error {
public:
    using Error::Error;
};

// ---------------------------------------------------------------------------------------------
// Device

// For `matforge --version`: the Vulkan headers built against. The loader and the driver are
// loaded by `preview` alone, at run time (dlopen), so --version does not touch them.
std::string vulkan_header_version();

enum class DeviceKind { automatic, gpu, cpu };                    // automatic: a real GPU if any, else lavapipe (CPU)
std::optional<DeviceKind> parse_device_kind(std::string_view s);  // "auto" | "gpu" | "cpu"

// Collects validation-layer and loader messages of severity warning or error. Shared so that it
// outlives the context: objects left undestroyed are reported while the device is destroyed.
class MessageLog {
public:
    void add(std::string message);
    size_t count() const;
    std::vector<std::string> messages() const;

private:
    mutable std::mutex mutex_;
    std::vector<std::string> messages_;
};

struct ContextOptions {
    DeviceKind device = DeviceKind::automatic;
    // Enables VK_LAYER_KHRONOS_validation with synchronization validation and a debug messenger
    // that feeds `log` (required when validation is on).
    bool validation = false;
    std::shared_ptr<MessageLog> log;
    // On a CPU device (lavapipe), upload 8-bit textures as 16-bit linear UNORM, sRGB decoded
    // here with the exact curve: lavapipe filters 8-bit texels in 8-bit fixed point (magnified
    // gradients band in steps of 1/255) and decodes sRGB with an approximation (about 3e-4
    // absolute). Off: the same _SRGB / 8-bit formats as on a GPU. GPUs are not affected.
    bool precise_cpu_textures = true;
};

struct DeviceInfo {
    std::string name;          // "NVIDIA H200", "llvmpipe (LLVM 15.0.6, 256 bits)"
    std::string driver;        // driver name and version text
    bool cpu = false;          // a software rasterizer (lavapipe)
    uint32_t api_version = 0;  // VK_MAKE_API_VERSION of the device
    bool timestamps = false;   // timestamp queries usable on the queue we render with
    double timestamp_period_ns = 1.0;
};

class Context {
public:
    explicit Context(const ContextOptions& options = {});
    ~Context();
    Context(const Context&) = delete;
    Context& operator=(const Context&) = delete;

    const DeviceInfo& info() const;

    struct Impl;
    Impl& impl() { return *impl_; }

private:
    std::unique_ptr<Impl> impl_;
};

// ---------------------------------------------------------------------------------------------
// Scene

struct Camera {
    Vec3 position{0.f, 0.f, 4.f};
    Vec3 target{0.f, 0.f, 0.f};
    Vec3 up{0.f, 1.f, 0.f};
    float yfov_deg = 35.f;
};

enum class ShapeType { sphere, cube, plane, shaderball };
struct Shape {
    ShapeType type = ShapeType::sphere;
    // Sphere: radius (the UV sphere of three.js SphereGeometry(r, 128, 64), shaded on the exact
    // sphere). Cube: edge length (turned to show three faces). Plane: side of a square facing +Z.
    // Shaderball: overall radius; a sphere of 0.7 × size girdled by a tilted torus ring (tube
    // 0.16 × size), whose inner side meets the sphere in concave creases: convex, concave and
    // saddle curvature in one view, as look-dev shader balls have.
    float size = 1.f;
};

enum class LightType { directional, point };
struct Light {
    LightType type = LightType::directional;
    Vec3 direction{0.57735027f, -0.57735027f, -0.57735027f};  // the way the light travels
    Vec3 position{0.f, 0.f, 0.f};
    Vec3 color{1.f, 1.f, 1.f};
    float intensity = 3.f;  // directional: irradiance scale; point: intensity (E = I / d²)
};

// Equirectangular environment, linear radiance. Direction d maps to
// u = 0.5 + atan2(d.x, -d.z) / 2π, v = acos(d.y) / π (rows top to bottom): the image's centre
// is seen looking along −Z, its top row is straight up.
struct Environment {
    uint32_t width = 0, height = 0;
    std::vector<float> rgba;  // width * height * 4
    float intensity = 1.f;
};

enum class Brdf {
    // GGX D, Schlick F with F0 = lerp(0.04, albedo, metalness), Schlick-GGX visibility with
    // k = (r+1)²/8, Lambert diffuse albedo/π × (1 − F)(1 − metalness)
    standard,
    // height-correlated Smith visibility + multiple-scattering energy compensation
    accurate,
    // Standard with Lambert's diffuse lacking its 1/π (albedo · N·L): diffuse π times too strong
    // against the specular lobe, for comparison with engines that do this. CLI value
    // "assignment".
    unnormalized_diffuse,
};
std::optional<Brdf> parse_brdf(std::string_view s);  // "standard" | "accurate" | "assignment"

inline constexpr size_t kMaxLights = gpu::kMaxLights;

// Where the shape's pixels are shaded (both write the same linear radiance target, encoded by the
// same pass; both share the shading code, shaders/shading.glsl, and pass the same CPU-reference
// tests):
enum class Shading {
    // On a GPU, measured once per Context (measure_shading: a 512×512 constant-material frame
    // with the scene's anti-aliasing, timed on both paths), compute chosen when it is at least
    // 1.5× faster (datacenter GPUs with few raster units); the decision and both times are said
    // once in take_notes(). On a CPU device (lavapipe) raster, unmeasured: compute never
    // measured 1.5× faster there (docs/bench/README.md), and a measurement near the margin could
    // pick either path from run to run. Raster where compute does not cover the scene (below).
    automatic,
    // The mesh rasterized (shade.vert, shade.frag): every shape, the ground plane, MSAA coverage.
    raster,
    // One compute dispatch (shade.comp): each pixel's rays (each supersample's, and with
    // Scene::msaa each of its samples at the standard positions, averaged) intersected with the
    // analytic sphere, cube or plane. The shaderball (a mesh) and the ground plane (its shadow)
    // are not covered: those scenes are shaded on the raster path, said in take_notes().
    compute,
};
std::optional<Shading> parse_shading(std::string_view s);  // "auto" | "raster" | "compute"

class Context;
// The shade pass of a constant-material sphere, 512×512, with `msaa` and `supersample` as in a
// Scene, on each path: the least of five timestamped frames after two warm-up frames, the two
// paths' frames interleaved so that a load that comes and goes weighs on both alike. 0 where the
// device gave no time. What Shading::automatic decides by on a GPU; usable on any device.
struct ShadingTimes {
    double raster_ms = 0.0, compute_ms = 0.0;
};
ShadingTimes measure_shading(Context& context, uint32_t msaa = 1, uint32_t supersample = 1);

struct Scene {
    uint32_t width = 512, height = 512;
    // Anti-aliasing: N×N samples per pixel at the sub-pixel centres ((i + 0.5) / N), shaded as a
    // frame N times larger and box-averaged in linear radiance before tone mapping and encoding
    // (1: one sample at the pixel centre, the reference tests' setting). 1..4; the cost is N².
    uint32_t supersample = 1;
    // Multisampling: coverage (and depth) at `msaa` samples a pixel, the shader run once a pixel,
    // the samples averaged in linear radiance (a resolve into the target, then the encode pass
    // with the supersamples). 1 (off), 2, 4 or 8. Anti-aliases silhouettes at about the cost of
    // one sample a pixel; inside the silhouette it shades as one sample does (trilinear texture
    // filtering, no extra samples of specular detail), once per triangle where a mesh edge crosses
    // the pixel. The analytic sphere is hit along the ray
    // through the centroid of the covered samples. Where the device lacks the count for the
    // RGBA32F target (or the depth buffer), N×N supersampling with N² ≥ msaa is used instead
    // (said in take_notes()). On the compute path (Shading::compute) the pixel is instead shaded
    // at each of the `msaa` standard sample positions (2: the diagonal pair, 4: the rotated grid,
    // 8: Vulkan's standard eight) and the samples averaged in linear radiance before the write:
    // silhouettes alike, and texture and specular detail inside them supersampled too, at
    // `msaa` times the shading.
    uint32_t msaa = 1;
    // The fast texture path (look-dev previews of a library): an 8-bit texture's level 0 is
    // converted on the host by a table of its 256 codes and the rest of its mip chain is made on
    // the device (vkCmdBlitImage level by level, linear filter: 2×2 averages at even sizes, each
    // level from the one above as stored, sRGB decoded and re-encoded by the device, normals not
    // renormalized). Formats as the exact path's, but for color on a CPU device: 8-bit sRGB as on
    // a GPU, where ContextOptions::precise_cpu_textures would promote it to float (data keeps its
    // 16-bit promotion, so that inverted channels average alike). Off: the exact path, every
    // level averaged on the CPU in float (area weights, color in linear light, renormalized
    // normals), as the reference tests use. 16-bit, float and block-compressed textures, and
    // formats the device cannot blit, take the exact path either way.
    bool fast_textures = false;
    // Benchmarks only (bench/render_bench "floor"): the shape's pixels written with a constant and
    // nothing computed, the device's fill-rate floor every shading figure is compared with.
    bool fill_only = false;
    Camera camera;
    Shape shape;
    Vec3 background{0.f, 0.f, 0.f};  // linear
    std::vector<Light> lights{Light{}};
    std::shared_ptr<const Environment> environment;  // null: no image-based lighting
    // A ground plane under the shape, only when asked (nothing of it is computed otherwise): a
    // square of 16 × the shape's size at the shape's lowest point, a grey dielectric, shaded by
    // the scene's lights and environment, with a soft contact shadow: the key light (the first
    // directional light, seen as a disc of `ground_light_deg` angular radius) occluded by the
    // shape's bounding sphere, and the environment occluded by that sphere too (the shadow the
    // shape casts on the floor of a photo studio).
    struct Ground {
        bool enabled = false;
        float albedo = 0.5f, roughness = 0.7f;
        float light_deg = 4.f;  // key light's angular radius: the penumbra's width
    } ground;
    Brdf brdf = Brdf::standard;
    // Raster by default: the same path, hence the same image, on every device (reference
    // tests, scene files); the preview CLI asks for automatic.
    Shading shading = Shading::raster;
};

// ---------------------------------------------------------------------------------------------
// Material: textures as decoded from their files plus, per role, where its value comes from.

enum class TexelType : uint8_t { u8, u16, f32 };
struct Texture {
    uint32_t width = 0, height = 0, channels = 0;  // channels 1..4; 1: gray, 2: gray+alpha
    TexelType type = TexelType::u8;
    std::vector<uint8_t> data;  // width*height*channels samples of `type`, native byte order
    // RGB hold sRGB-encoded color (albedo, emissive): 8-bit ones are uploaded as an _SRGB format
    // and decoded by the sampler; alpha is always linear.
    bool srgb = false;
    // Block-compressed texels as a GPU texture file (DDS, KTX2) holds them: `block_format` is
    // the VkFormat value of the blocks (a BCn or ASTC LDR format; its _SRGB variant is chosen
    // from `srgb`) and `block_levels` every mip level's blocks, largest first, each level half
    // the one before (at least 1). Uploaded as they are: the chain that was written is the one
    // sampled. `data` and `type` are unused. render::samples() says whether the device can.
    // kDecodedLevels: such a chain decoded on the CPU, 8-bit RGBA texels as "blocks" of one.
    uint32_t block_format = 0;
    std::vector<std::vector<uint8_t>> block_levels;
};
// Texture::block_format of decoded levels: VK_FORMAT_R8G8B8A8_UNORM (its _SRGB variant from
// `srgb`), every device samples it.
inline constexpr uint32_t kDecodedLevels = 37;
// Whether a block format decodes to exact 8-bit codes on every device (BC7: its interpolation is
// integer arithmetic in the specification), so that decoded levels sample as its blocks do; BC4
// and BC5 decode to more than 8 bits on GPUs and lavapipe, BC1-3 within a tolerance.
bool decodes_exactly(uint32_t block_format);

enum class Channel : uint8_t { R = 0, G = 1, B = 2, A = 3 };
struct ScalarRole {
    int texture = -1;  // index into Material::textures; < 0: `value` is used, nothing is sampled
    Channel channel = Channel::R;
    bool invert = false;  // stored as 1 − value (smoothness for roughness)
    float value = 0.f;
};
struct ColorRole {
    int texture = -1;  // RGB of that texture, or `value` (linear) when < 0
    Vec3 value{0.f, 0.f, 0.f};
    // Multiplies the texture (emissive only): an HDR emissive stored as emissive / strength in
    // an 8-bit file (manifest `emissive_strength`, glTF KHR_materials_emissive_strength).
    float strength = 1.f;
};
struct NormalRole {
    int texture = -1;         // tangent-space normal in RGB; < 0: no normal mapping
    bool green_down = false;  // DirectX convention (−Y); OpenGL (+Y) otherwise
    bool z_from_xy = false;   // only X, Y stored (BC5): Z = sqrt(1 − x² − y²) in the shader
};

inline constexpr size_t kMaxTextures = gpu::kMaxTextures;

// How a material's opacity applies (glTF 2.0 alphaMode): blend mixes the surface over what lies
// behind it by opacity; mask makes it opaque at or above Material::alpha_cutoff and drops it below
// (a cut-out: a net, foliage); opaque ignores opacity.
enum class AlphaMode { blend, mask, opaque };

// A field added here is copied by roles_of (upload.cpp), which copies everything but the texels.
struct Material {
    std::string name;
    std::vector<Texture> textures;  // at most kMaxTextures
    ColorRole albedo{-1, {0.8f, 0.8f, 0.8f}};
    ColorRole emissive{-1, {0.f, 0.f, 0.f}};
    NormalRole normal;
    ScalarRole roughness{-1, Channel::R, false, 0.5f};
    ScalarRole metalness{-1, Channel::R, false, 0.f};
    ScalarRole occlusion{-1, Channel::R, false, 1.f};  // scales environment light only
    ScalarRole opacity{-1, Channel::R, false, 1.f};    // blends over the background
    // Texture coordinates sampled: (u, v) × uv_scale + uv_offset (tiling; a scale that keeps a
    // texture's texels square on the shape is the caller's choice: preview::uv_for_aspect).
    std::array<float, 2> uv_scale{1.f, 1.f};
    std::array<float, 2> uv_offset{0.f, 0.f};
    AlphaMode alpha_mode = AlphaMode::blend;
    float alpha_cutoff = 0.5f;  // with AlphaMode::mask, within [0, 1]
    // The shape's far side shaded too, under the near one, its normal reversed (glTF
    // doubleSided): what engines show through a cut-out or translucent sheet. Raster: the back
    // faces drawn before the front ones, each blended; compute: the ray's far hit under its near one.
    bool double_sided = false;
};

// Throws Error when roles point at missing textures or a normal map is also marked sRGB.
void check_material(const Material& m);

// ---------------------------------------------------------------------------------------------
// Rendering

enum class Transfer { srgb, linear };
// Applied once to the exposed linear radiance before the transfer curve (rgba8 only):
//  none     clipped at 1 (the reference scenes: exact against the CPU evaluation);
//  neutral  Khronos PBR Neutral (Khronos 3D Commerce, 2024): base colors up to 0.8 stay as
//           they are (hue and value of a material's albedo under unit light read true), highlights
//           compress smoothly to 1 and desaturate toward white;
//  aces     the ACES reference rendering + sRGB output transform as fitted by Hill (2016): a
//           filmic contrast curve that darkens and saturates mid-tones.
enum class Tonemap { none, neutral, aces };
std::optional<Tonemap> parse_tonemap(std::string_view s);  // "none" | "neutral" | "aces"
enum class PixelFormat { rgba8, rgba32f };
struct OutputOptions {
    PixelFormat format = PixelFormat::rgba8;
    // Rgba8 only: linear radiance × exposure, encoded once with `transfer` (exact IEC 61966-2-1
    // curve for sRGB), rounded to nearest. Rgba32F is the linear radiance itself.
    Transfer transfer = Transfer::srgb;
    float exposure = 1.f;
    Tonemap tonemap = Tonemap::none;
};

struct Frame {
    uint32_t width = 0, height = 0;
    std::vector<uint8_t> rgba8;  // PixelFormat::rgba8
    std::vector<float> rgba32f;  // PixelFormat::rgba32f
};

struct PassTime {
    std::string name;
    double ms = 0.0;  // GPU time from timestamp queries (0 when the device has none)
};

class Renderer;

// The host half of Renderer::upload(): a material's textures converted to their upload formats
// with their mips (or only level 0 where the device makes them, Scene::fast_textures). Made by
// Renderer::prepare(), which makes no Vulkan call that needs synchronizing: it may run on another
// thread while the renderer uploads or renders other materials.
class PreparedMaterial {
public:
    PreparedMaterial();
    ~PreparedMaterial();
    PreparedMaterial(PreparedMaterial&&) noexcept;
    PreparedMaterial& operator=(PreparedMaterial&&) noexcept;
    // Host memory its textures hold (their levels as they will be uploaded).
    size_t bytes() const;
    // Equal for materials prepared for one scene that draw with one pipeline variant: a batch
    // has each variant made once, ahead of the uploads (Renderer::warm).
    std::string variant_key() const;

    struct Impl;
    Impl& impl() const { return *impl_; }

private:
    friend class Renderer;
    friend PreparedMaterial prepare(Context& context, const Scene& scene, const Material& material);
    std::unique_ptr<Impl> impl_;
};

// Renderer::prepare before any renderer exists: what a Renderer(context, scene) would prepare,
// for upload on any renderer of that context made with that scene (upload checks it). A batch
// readies its first materials while the renderers start (lib/preview/batch.cpp). Thread-safe.
PreparedMaterial prepare(Context& context, const Scene& scene, const Material& material);
// Whether the device samples and filters textures of this block format (a VkFormat value, see
// Texture::block_format); where it does not, the caller decodes on the CPU.
bool samples(Context& context, uint32_t block_format);

// A material's textures on the device and the pipeline variant it needs. Destroy before the
// Renderer that made it; on any thread once the render() calls that drew it have returned (one
// never drawn first waits for its upload's copies, which upload() submits without waiting; its
// device objects are its own: freeing a 1K material's took ~0.8 ms of the H200 host's 5 ms a
// material, which a library's loop can hand to another thread).
class GpuMaterial {
public:
    GpuMaterial();
    ~GpuMaterial();
    GpuMaterial(GpuMaterial&&) noexcept;
    GpuMaterial& operator=(GpuMaterial&&) noexcept;
    const std::string& name() const;
    // Which pipeline variant shades it, e.g. "sphere dir1 point0 standard albedo:tex normal:tex".
    const std::string& variant() const;

    struct Impl;
    Impl& impl() const { return *impl_; }

private:
    friend class Renderer;
    std::unique_ptr<Impl> impl_;
};

// One scene on one device. Construction runs the load-time passes the scene calls for: the
// BRDF lookup table (accurate BRDF or environment) and, with an environment, the cube map and
// its split-sum prefiltering (Karis 2013). Nothing else is computed.
class Renderer {
public:
    Renderer(Context& context, const Scene& scene);
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    // Uploads textures with their mip chains (linear-light averages for color, renormalized
    // vectors for normals, plain averages for data) and builds the pipeline variant.
    GpuMaterial upload(const Material& material);
    // upload() in two halves: prepare() is the CPU work (conversion, mips) and is safe to call
    // from another thread, concurrently with this renderer's other calls; upload(prepared) makes
    // the device objects and must be called where render() is.
    PreparedMaterial prepare(const Material& material) const;
    GpuMaterial upload(PreparedMaterial prepared);
    // Makes the pipeline variant `prepared` needs on this renderer unless made already, which
    // upload() would otherwise do on its own thread: cold on the H100, the first material's upload
    // took 124 ms against 10 ms for the next (docs/bench/h100_library_bench_2.txt). Safe from any
    // thread, concurrently with this renderer's other calls.
    void warm(const PreparedMaterial& prepared);

    Frame render(const GpuMaterial& material, const OutputOptions& output = {});

    const Scene& scene() const;
    // The path this renderer shades on: raster or compute, Scene::shading resolved.
    Shading shading() const;
    // Upload and load-time passes, in order (waits for an upload submitted and not yet drawn;
    // a lighting another renderer of the device made for this scene is not among them).
    const std::vector<PassTime>& load_times() const;
    const std::vector<PassTime>& frame_times() const;  // passes of the last render()
    // Host seconds spent in upload() and render() since this renderer was made, by part (wall
    // clock on the calling thread): where a library's time goes on its lanes (`preview --timings`).
    struct HostTimes {
        double pipelines = 0.0;      // upload: the material's pipeline variants (compiled the first time)
        double images = 0.0;         // upload: images and their memory created
        double staging = 0.0;        // upload: texels copied into staging memory
        double upload_rest = 0.0;    // upload: the copies and mips recorded and submitted; descriptors
        double upload_retire = 0.0;  // of upload_rest: waiting for the lane's previous upload (its fence)
        double upload_submit = 0.0;  // of upload_rest: vkQueueSubmit, under the queue's lock the lanes share
        double draw_wait = 0.0;      // render: recorded, submitted and waited for (with the copies before it)
        double readback = 0.0;       // render: the picture copied out of the readback buffer
        // The device's own time (timestamp queries; 0 without them): whether a lane waited for
        // its work or for the queue's other work, the other lanes' included.
        double upload_device = 0.0;  // upload: the copies and blitted mips
        double draw_device = 0.0;    // render: its passes
        // The renderer's construction (wall clock on its thread), set as it ends.
        double made = 0.0;       // all of it
        double made_load = 0.0;  // load-time uploads and passes: mesh, placeholders, the environment
        // Then waiting for Shading::automatic's measurement, which ran beside the load-time work
        // (made by one renderer of a device; the others wait for it).
        double made_shading = 0.0;
        HostTimes& operator+=(const HostTimes& o) {
            pipelines += o.pipelines;
            images += o.images;
            staging += o.staging;
            upload_rest += o.upload_rest;
            upload_retire += o.upload_retire;
            upload_submit += o.upload_submit;
            draw_wait += o.draw_wait;
            readback += o.readback;
            upload_device += o.upload_device;
            draw_device += o.draw_device;
            made += o.made;
            made_shading += o.made_shading;
            made_load += o.made_load;
            return *this;
        }
    };
    const HostTimes& host_times() const;
    // Notes on what was changed to fit the device (a texture or environment larger than its
    // maxImageDimension2D previewed downsampled), taken: each is returned once.
    std::vector<std::string> take_notes();

    struct Impl;

private:
    friend const Impl& renderer_impl(const Renderer& renderer);  // for export.cpp
    std::unique_ptr<Impl> impl_;
};

// ---------------------------------------------------------------------------------------------
// Export (export.cpp): what another renderer of the same shaders needs to draw a material as this
// one does. The report's WebGL2 viewer (lib/report/viewer.cpp) draws shade.vert and shade.frag,
// translated to ESSL 3.00 at build time, with these: nothing of the scene is computed twice.
// Call them where render() is called, never during one: they use the renderer's uniform block,
// command pool and queue.

// A specialization constant of shade.frag: its id (a gpu::kSpec*) and value.
struct SpecConstant {
    int id = 0;
    int32_t value = 0;
    bool boolean = false;  // a bool constant (VkBool32): value 0 or 1
};
struct ShadingExport {
    // The variant of shade.frag for the material in this scene, its textures read as stored (no
    // channel stored inverted, as Scene::fast_textures may upload them).
    std::vector<SpecConstant> constants;
    gpu::FrameData frame{};  // the uniform block render() draws the material with
};
ShadingExport export_shading(Renderer& renderer, const Material& material);

// A sampled image of the renderer read back: levels[m] holds mip m, `layers` images of its size
// (width >> m, height >> m, at least 1) one after the other, rows top to bottom, RGBA floats.
// A cube's layers are its faces +X, −X, +Y, −Y, +Z, −Z.
struct ImageExport {
    uint32_t width = 0, height = 0, layers = 0;
    std::vector<std::vector<float>> levels;
};
struct LightingExport {
    ImageExport brdf_lut;              // (A, B, 1 − E, 1 − E_avg) over (√(n·v) across, roughness down)
    ImageExport specular, irradiance;  // the environment's GGX-prefiltered and E(n)/π cubes
    float anisotropy = 0.f;            // the material textures' maximum anisotropy (0: off)
};
// The image-based lighting the renderer computed at construction. Throws Error when the scene
// has no environment.
LightingExport export_lighting(Renderer& renderer);

struct MeshExport {
    std::vector<float> vertices;    // 12 floats a vertex: position, normal, tangent (xyz, w: bitangent sign), uv
    std::vector<uint32_t> indices;  // triangles, counter-clockwise seen from outside
    bool depth_test = false;        // drawn with a depth test (back-face culling alone cannot order it)
};
MeshExport export_mesh(const Renderer& renderer);  // the scene's shape as the raster path draws it

}  // namespace mf::render
