#include "report/viewer.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cstddef>
#include <cstring>
#include <mutex>
#include <nlohmann/json.hpp>
#include <span>
#include <vector>

#include "core/files.hpp"
#include "core/text.hpp"
#include "image/image.hpp"
#include "preview/preview.hpp"
#include "render/render.hpp"
#include "report/report.hpp"
#include "texture/texture.hpp"

namespace mf::report {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// The renderer's shaders as ESSL 3.00 (cmake/WebglShader.cmake) and the viewer's script.
#include "report/webgl/encode_frag.inc"
#include "report/webgl/shade_frag.inc"
#include "report/webgl/shade_vert.inc"
#include "viewer_js_embedded.inc"

constexpr const char* kLookdevScript = "viewer/lookdev.js";

// The shapes a view offers, the first shown first. Sizes as `preview --shape` gives them.
constexpr render::ShapeType kShapes[] = {render::ShapeType::sphere, render::ShapeType::plane,
                                         render::ShapeType::shaderball};
const char* shape_name(render::ShapeType t) {
    switch (t) {
        case render::ShapeType::sphere: return "sphere";
        case render::ShapeType::cube: return "cube";
        case render::ShapeType::plane: return "plane";
        case render::ShapeType::shaderball: return "shaderball";
    }
    return "sphere";
}

std::string base64(std::span<const unsigned char> in) {
    static constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    out.reserve((in.size() + 2) / 3 * 4);
    size_t i = 0;
    for (; i + 2 < in.size(); i += 3) {
        const uint32_t v = uint32_t{in[i]} << 16 | uint32_t{in[i + 1]} << 8 | in[i + 2];
        for (int s = 18; s >= 0; s -= 6) out += kAlphabet[(v >> s) & 63u];
    }
    if (i < in.size()) {
        const uint32_t v = uint32_t{in[i]} << 16 | (i + 1 < in.size() ? uint32_t{in[i + 1]} << 8 : 0u);
        out += kAlphabet[(v >> 18) & 63u];
        out += kAlphabet[(v >> 12) & 63u];
        out += i + 1 < in.size() ? kAlphabet[(v >> 6) & 63u] : '=';
        out += '=';
    }
    return out;
}
template <class T>
std::string base64_of(const std::vector<T>& v) {
    return base64(std::span(reinterpret_cast<const unsigned char*>(v.data()), v.size() * sizeof(T)));
}

// IEEE binary16, rounded to nearest even (WebGL takes half floats as 16-bit words). The
// prefiltered cubes are half floats on the device already: exact for them.
uint16_t to_half(float f) {
    uint32_t x = 0;
    std::memcpy(&x, &f, sizeof x);
    const auto sign = static_cast<uint16_t>((x >> 16) & 0x8000u);
    const uint32_t mag = x & 0x7fffffffu;
    if (mag >= 0x7f800000u) return static_cast<uint16_t>(sign | 0x7c00u | (mag > 0x7f800000u ? 0x200u : 0u));
    if (mag >= 0x477ff000u) return static_cast<uint16_t>(sign | 0x7c00u);  // rounds past 65504
    uint32_t v = 0, rest = 0, halfway = 0;
    if (mag < 0x38800000u) {  // below 2^-14: a subnormal half, in units of 2^-24
        const uint32_t shift = 126u - (mag >> 23);
        if (shift > 24u) return sign;
        const uint32_t m = (mag & 0x7fffffu) | 0x800000u;
        v = m >> shift;
        rest = m & ((1u << shift) - 1u);
        halfway = 1u << (shift - 1u);
    } else {
        v = (mag - 0x38000000u) >> 13;  // exponent rebiased from 127 to 15
        rest = mag & 0x1fffu;
        halfway = 0x1000u;
    }
    if (rest > halfway || (rest == halfway && (v & 1u))) ++v;
    return static_cast<uint16_t>(sign | v);
}

// Mip `level` of `e`, channels [0, channels) of its RGBA, as half floats.
std::vector<uint16_t> halves(const render::ImageExport& e, size_t level, int channels) {
    const std::vector<float>& src = e.levels[level];
    std::vector<uint16_t> out;
    out.reserve(src.size() / 4 * static_cast<size_t>(channels));
    for (size_t i = 0; i < src.size(); i += 4)
        for (int c = 0; c < channels; ++c) out.push_back(to_half(src[i + static_cast<size_t>(c)]));
    return out;
}
json cube_json(const render::ImageExport& e) {
    std::vector<uint16_t> all;  // mip by mip, face by face: RGB (the alpha of radiance is 1)
    for (size_t m = 0; m < e.levels.size(); ++m) {
        const std::vector<uint16_t> level = halves(e, m, 3);
        all.insert(all.end(), level.begin(), level.end());
    }
    return {{"size", e.width}, {"levels", e.levels.size()}, {"rgb16f", base64_of(all)}};
}

// A texture as 8-bit codes, as the renderer holds it before its upload (8-bit as read; 16-bit
// and float samples quantized: the view's PNGs are 8-bit).
Image8 codes_of(const render::Texture& t) {
    Image8 img(static_cast<int>(t.width), static_cast<int>(t.height), static_cast<int>(t.channels));
    const size_t n = img.pixels.size();
    for (size_t i = 0; i < n; ++i) {
        switch (t.type) {
            case render::TexelType::u8: img.pixels[i] = t.data[i]; break;
            case render::TexelType::u16: {
                uint16_t v = 0;
                std::memcpy(&v, t.data.data() + 2 * i, sizeof v);
                img.pixels[i] = static_cast<uint8_t>((uint32_t{v} * 255u + 32767u) / 65535u);
                break;
            }
            case render::TexelType::f32: {
                float v = 0.f;
                std::memcpy(&v, t.data.data() + 4 * i, sizeof v);
                img.pixels[i] = quantize8(v);
                break;
            }
        }
    }
    return img;
}

// `t` at most kViewerTextureSize on a side: the first level of its mip chain that fits, box
// filtered as the renderer's mips are (sRGB color in linear light, a normal map's vectors
// renormalized, data as stored).
Image8 fitted(const render::Texture& t, bool normal) {
    Image8 level = codes_of(t);
    if (std::max(level.width, level.height) <= kViewerTextureSize) return level;
    std::vector<texture::ChannelKind> kinds(static_cast<size_t>(level.channels), texture::ChannelKind::data);
    const int color = level.channels >= 3 ? 3 : 1;  // RGB, or gray (+ alpha)
    for (int c = 0; c < color; ++c)
        if (t.srgb) kinds[static_cast<size_t>(c)] = texture::ChannelKind::srgb_color;
    if (normal && level.channels >= 3) std::fill_n(kinds.begin(), 3, texture::ChannelKind::normal);
    texture::MipOptions mo;
    mo.filter = MipFilter::box;
    for (Image8& l : texture::make_mips(level, kinds, mo))
        if (std::max(l.width, l.height) <= kViewerTextureSize) return std::move(l);
    return level;  // unreachable: the chain ends at 1x1
}

// The fewest channels a PNG decoder gives back as the same RGBA (gray → g, g, g; no alpha → 1),
// as the renderer expands them (a role reads any channel of any texture).
Image8 png_channels(Image8 img) {
    const auto px = static_cast<size_t>(img.width) * static_cast<size_t>(img.height);
    const auto ch = static_cast<size_t>(img.channels);
    const bool has_alpha = ch == 2 || ch == 4;
    bool opaque = has_alpha, gray = ch >= 3;
    for (size_t p = 0; p < px && (opaque || gray); ++p) {
        const uint8_t* s = &img.pixels[p * ch];
        if (has_alpha && s[ch - 1] != 255) opaque = false;
        if (ch >= 3 && (s[0] != s[1] || s[0] != s[2])) gray = false;
    }
    const size_t out_ch = (gray || ch <= 2 ? 1 : 3) + (has_alpha && !opaque ? 1 : 0);
    if (out_ch == ch) return img;
    Image8 out(img.width, img.height, static_cast<int>(out_ch));
    for (size_t p = 0; p < px; ++p) {
        const uint8_t* s = &img.pixels[p * ch];
        uint8_t* d = &out.pixels[p * out_ch];
        const size_t color = out_ch - (has_alpha && !opaque ? 1 : 0);
        for (size_t c = 0; c < color; ++c) d[c] = s[c];
        if (color < out_ch) d[color] = s[ch - 1];
    }
    return out;
}

std::span<const unsigned char> as_bytes(const std::string& s) {
    return {reinterpret_cast<const unsigned char*>(s.data()), s.size()};
}

std::string kb(uint64_t bytes) { return std::to_string((bytes + 512) / 1024) + " KB"; }

}  // namespace

struct Viewer::Impl {
    fs::path out;
    bool allow_outside = false;
    std::unique_ptr<render::Context> context;
    struct Shape {
        render::ShapeType type;
        preview::SceneFile scene;
        std::unique_ptr<render::Renderer> renderer;
    };
    std::vector<Shape> shapes;
    // export_shading writes a renderer's uniform block: one material's exports at a time.
    mutable std::mutex mutex;
    uint64_t lookdev_bytes = 0;
    mutable std::atomic<uint64_t> material_bytes{0};
    mutable std::atomic<size_t> materials{0};

    std::string write_lookdev();  // viewer/lookdev.js; "" or what failed
};

Viewer::Viewer(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Viewer::~Viewer() = default;

std::unique_ptr<Viewer> Viewer::create(const Options& options, const manifest::Manifest& m, std::string& error) {
    auto impl = std::make_unique<Impl>();
    impl->out = options.out;
    impl->allow_outside = options.allow_outside;
    // As large as the stills it turns (`preview --size` is one size for all), else the look-dev
    // scene's own size.
    uint32_t width = preview::default_scene().scene.width, height = preview::default_scene().scene.height;
    if (options.previews)
        for (const manifest::Material& mm : m.materials) {
            const auto file = preview_file(*options.previews, mm.name);
            if (!file) continue;
            InputFile in;
            in.display = file->string();
            in.path = *file;
            std::string why;
            if (const auto info = read_info(in, why)) {
                width = static_cast<uint32_t>(info->width);
                height = static_cast<uint32_t>(info->height);
            }
            break;
        }
    try {
        impl->context = std::make_unique<render::Context>();
        for (const render::ShapeType type : kShapes) {
            Impl::Shape s{type, preview::default_scene(), nullptr};
            render::Scene& sc = s.scene.scene;
            sc.width = width;
            sc.height = height;
            sc.shape = {type, preview::default_shape_size(type)};
            sc.shading = render::Shading::raster;  // what WebGL does
            s.renderer = std::make_unique<render::Renderer>(*impl->context, sc);
            impl->shapes.push_back(std::move(s));
        }
        error = impl->write_lookdev();
    } catch (const render::Error& e) {  // NoDeviceError's message names the package to install
        error = std::string("the look-dev renderers: ") + e.what();
    }
    if (!error.empty()) return nullptr;
    return std::unique_ptr<Viewer>(new Viewer(std::move(impl)));
}

std::string Viewer::Impl::write_lookdev() {
    const preview::SceneFile& sf = shapes.front().scene;
    const render::LightingExport lighting = render::export_lighting(*shapes.front().renderer);
    json shapes_json = json::object(), order = json::array();  // the object's keys come sorted
    for (const Shape& s : shapes) {
        order.push_back(shape_name(s.type));
        const render::MeshExport mesh = render::export_mesh(*s.renderer);
        json m = {{"vertices", base64_of(mesh.vertices)}};
        if (mesh.vertices.size() / 12 <= 65536) {  // 16-bit indices where they reach: half the bytes
            const std::vector<uint16_t> short_indices(mesh.indices.begin(), mesh.indices.end());
            m["indices"] = base64_of(short_indices);
            m["index_bits"] = 16;
        } else {
            m["indices"] = base64_of(mesh.indices);
            m["index_bits"] = 32;
        }
        shapes_json[shape_name(s.type)] = {{"mesh", m}, {"depth", mesh.depth_test}};
    }
    const render::Camera& cam = sf.scene.camera;
    using FD = render::gpu::FrameData;
    constexpr size_t f = sizeof(float);
    using EP = render::gpu::EncodeParams;
    const json data = {
        {"size", {sf.scene.width, sf.scene.height}},
        {"msaa", shapes.front().renderer->scene().msaa},
        {"shaders", {{"vert", kEssl_shade_vert}, {"frag", kEssl_shade_frag}, {"encode", kEssl_encode_frag}}},
        {"output",
         {{"exposure", sf.output.exposure},
          {"srgb", sf.output.transfer == render::Transfer::srgb ? 1 : 0},
          {"tonemap", static_cast<int>(sf.output.tonemap)}}},
        {"camera", {{"position", cam.position}, {"target", cam.target}, {"up", cam.up}}},
        // Where the script writes the camera as it turns, in floats (interface.h's FrameData).
        {"frame_layout",
         {{"view_proj", offsetof(FD, view_proj) / f},
          {"camera_position", offsetof(FD, camera_position) / f},
          {"ray_right", offsetof(FD, ray_right) / f},
          {"ray_up", offsetof(FD, ray_up) / f},
          {"ray_forward", offsetof(FD, ray_forward) / f},
          {"camera_end", offsetof(FD, viewport) / f},
          {"viewport", offsetof(FD, viewport) / f},
          {"background", offsetof(FD, background) / f}}},
        {"frame_bytes", sizeof(FD)},
        {"encode_layout",
         {{"size", offsetof(EP, size) / f},
          {"exposure", offsetof(EP, exposure) / f},
          {"srgb", offsetof(EP, srgb) / f},
          {"tonemap", offsetof(EP, tonemap) / f},
          {"supersample", offsetof(EP, supersample) / f},
          {"bytes", (sizeof(EP) + 15) / 16 * 16}}},
        {"vertex_layout",
         {{"position", render::gpu::kLocationPosition},
          {"normal", render::gpu::kLocationNormal},
          {"tangent", render::gpu::kLocationTangent},
          {"uv", render::gpu::kLocationUv}}},
        {"spec_ids", {{"msaa", render::gpu::kSpecMsaa}, {"double_sided", render::gpu::kSpecDoubleSided}}},
        {"max_textures", render::kMaxTextures},
        {"lighting",
         {{"lut", {{"size", lighting.brdf_lut.width}, {"rgba16f", base64_of(halves(lighting.brdf_lut, 0, 4))}}},
          {"specular", cube_json(lighting.specular)},
          {"irradiance", cube_json(lighting.irradiance)},
          {"anisotropy", lighting.anisotropy}}},
        {"shapes", shapes_json},
        {"shape_order", order},
    };
    const std::string text = std::string(kViewerScript) + "mfViewer.lookdev(" + data.dump() + ");\n";
    std::string error;
    if (!write_file_under(out, kLookdevScript, as_bytes(text), error)) return error;
    lookdev_bytes = text.size();
    return {};
}

std::optional<ViewerCard> Viewer::material(const manifest::Material& mm, const fs::path& manifest_dir,
                                           const std::string& stem, std::vector<std::string>& problems) const {
    const Impl& v = *impl_;
    auto fail = [&](const std::string& why) {
        problems.push_back(mm.name + ": interactive view: " + why);
        return std::nullopt;
    };
    preview::MaterialOptions mo;
    mo.allow_outside = v.allow_outside;
    mo.samples = [](uint32_t) { return preview::BlockUse::top_level; };  // the view takes plain maps (PNGs)
    std::vector<std::string> notes;
    std::string error;
    std::optional<render::Material> full = preview::load_material(mm, manifest_dir, mo, notes, error);
    if (!full) return fail(error);
    // Tiling as `preview` places it on each shape, from the maps as read (their aspect).
    std::vector<std::array<float, 2>> uv_scale, uv_offset;
    for (const Impl::Shape& s : v.shapes) {
        preview::place_textures(s.scene, *full);
        uv_scale.push_back(full->uv_scale);
        uv_offset.push_back(full->uv_offset);
    }
    // The maps the variant samples, fitted and as PNG (the others are not written); each full
    // map freed once fitted.
    std::vector<render::Texture> maps = std::move(full->textures);
    render::Material small = std::move(*full);
    small.textures.clear();
    json textures = json::array();
    for (size_t i = 0; i < maps.size(); ++i) {
        const auto slot = static_cast<int>(i);
        const bool sampled = slot == small.albedo.texture || slot == small.emissive.texture ||
                             slot == small.normal.texture || slot == small.roughness.texture ||
                             slot == small.metalness.texture || slot == small.occlusion.texture ||
                             slot == small.opacity.texture;
        render::Texture t = std::move(maps[i]);
        render::Texture st;
        st.srgb = t.srgb;
        st.channels = t.channels;
        if (!sampled) {  // a stand-in, never drawn: the roles' texture indices stay as they are
            st.width = st.height = 1;
            st.data.assign(st.channels, 0);
            small.textures.push_back(std::move(st));
            textures.push_back(nullptr);
            continue;
        }
        Image8 img = fitted(t, slot == small.normal.texture);
        t = {};
        std::vector<unsigned char> png;
        if (!encode_image(png_channels(img), EncodeOptions{FileFormat::png, 8}, png, error)) return fail(error);
        st.width = static_cast<uint32_t>(img.width);
        st.height = static_cast<uint32_t>(img.height);
        st.data = std::move(img.pixels);
        textures.push_back({{"srgb", st.srgb}, {"width", st.width}, {"height", st.height}, {"png", base64(png)}});
        small.textures.push_back(std::move(st));
    }

    json shapes = json::object();
    try {
        const std::lock_guard<std::mutex> lock(v.mutex);
        for (size_t k = 0; k < v.shapes.size(); ++k) {
            small.uv_scale = uv_scale[k];
            small.uv_offset = uv_offset[k];
            const render::ShadingExport e = render::export_shading(*v.shapes[k].renderer, small);
            json constants = json::array();
            for (const render::SpecConstant& c : e.constants) constants.push_back({c.id, c.value, c.boolean});
            const auto* frame = reinterpret_cast<const unsigned char*>(&e.frame);
            shapes[shape_name(v.shapes[k].type)] = {{"constants", constants},
                                                    {"frame", base64(std::span(frame, sizeof e.frame))}};
        }
    } catch (const render::Error& e) {
        return fail(e.what());
    }
    const json data = {{"name", mm.name}, {"textures", textures}, {"shapes", shapes}};
    const std::string text = "mfViewer.material(" + json(stem).dump() + ", " + data.dump() + ");\n";
    ViewerCard card{stem + "/viewer.js", text.size()};
    if (!write_file_under(v.out, card.script, as_bytes(text), error)) return fail(error);
    v.material_bytes += card.bytes;
    ++v.materials;
    return card;
}

std::string Viewer::card_html(const ViewerCard& card, const std::string& stem) {
    // Hidden until the page's script shows it: without JavaScript the card is as it was.
    return "<div class=\"viewer\" hidden data-stem=\"" + markup_escape(stem) + "\" data-src=\"" +
           markup_escape(percent_encode_path(card.script)) + "\" data-lookdev=\"" + kLookdevScript +
           "\"><button type=\"button\" class=\"viewer-open\">turn it</button> <span class=\"meta\">interactive view "
           "(WebGL2): the preview's look-dev scene drawn by its own shaders; " +
           kb(card.bytes) + " of maps at most " + std::to_string(kViewerTextureSize) +
           " px a side, loaded when opened</span><div class=\"viewer-stage\"></div><div class=\"viewer-status "
           "meta\"></div></div>\n";
}

void Viewer::state_sizes(std::string& html) const {
    const Impl& v = *impl_;
    const size_t at = html.find("<main>\n");
    if (at == std::string::npos) return;
    const uint64_t data = v.lookdev_bytes + v.material_bytes;
    auto note = [&](uint64_t page) {
        return "<p class=\"meta\" id=\"viewer-sizes\">Interactive views: this page is " + std::to_string(page) +
               " bytes; the views' data " + std::to_string(data) + " bytes, loaded only when a view is opened (" +
               kLookdevScript + " " + std::to_string(v.lookdev_bytes) +
               " bytes once: the viewer, the renderer's shaders, look-dev lighting and meshes; " +
               std::to_string(v.material_bytes) + " bytes for " + std::to_string(v.materials.load()) +
               " materials' maps).</p>\n";
    };
    // The page's size counts the note, whose digits count in the size: settle it (two rounds at most).
    uint64_t page = html.size();
    for (int i = 0; i < 4; ++i) {
        const uint64_t next = html.size() + note(page).size();
        if (next == page) break;
        page = next;
    }
    html.insert(at + 7, note(page));
}

}  // namespace mf::report
