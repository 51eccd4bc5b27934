#include "engine/gltf.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstring>
#include <memory>
#include <numbers>
#include <set>
#include <stdexcept>

#include "core/files.hpp"
#include "core/json.hpp"
#include "core/spool.hpp"
#include "core/text.hpp"
#include "core/version.hpp"
#include "manifest/attribution.hpp"
#include "preset/engine_slots.hpp"

namespace mf::gltf {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

constexpr int kSegments = 64, kRings = 32;
constexpr float kRadius = 0.5f;
constexpr int kVertices = (kSegments + 1) * (kRings + 1);
// Triangles: two per quad except one at each pole row (no degenerate triangles).
constexpr int kIndices = 3 * (2 * kSegments * kRings - 2 * kSegments);

// glTF constants.
constexpr int kFloat = 5126, kUnsignedShort = 5123;
constexpr int kArrayBuffer = 34962, kElementArrayBuffer = 34963;
constexpr int kLinear = 9729, kLinearMipmapLinear = 9987;

struct Layout {  // byte offsets in the buffer
    size_t position = 0, normal = 0, tangent = 0, texcoord = 0, indices = 0, total = 0;
    std::array<float, 3> min{}, max{};
};

Layout make_layout() {
    Layout l;
    l.normal = l.position + size_t{kVertices} * 12;
    l.tangent = l.normal + size_t{kVertices} * 12;
    l.texcoord = l.tangent + size_t{kVertices} * 16;
    l.indices = l.texcoord + size_t{kVertices} * 8;
    l.total = l.indices + size_t{kIndices} * 2;
    l.total = (l.total + 3) / 4 * 4;
    return l;
}

struct Sphere {
    Layout layout;
    std::vector<uint8_t> bytes;
};

// u = i / segments around (+X at the front, so the texture is not mirrored seen from +Z),
// v = j / rings from the north pole (glTF's texture origin is the image's top-left).
const Sphere& sphere() {
    static const Sphere s = [] {
        Sphere out;
        out.layout = make_layout();
        const Layout& l = out.layout;
        out.bytes.assign(l.total, 0);
        auto put = [&](size_t at, float v) { std::memcpy(out.bytes.data() + at, &v, 4); };
        std::array<float, 3> lo{1e9f, 1e9f, 1e9f}, hi{-1e9f, -1e9f, -1e9f};
        for (int j = 0; j <= kRings; ++j)
            for (int i = 0; i <= kSegments; ++i) {
                const size_t k = static_cast<size_t>(j) * (kSegments + 1) + static_cast<size_t>(i);
                const double u = static_cast<double>(i) / kSegments, v = static_cast<double>(j) / kRings;
                const double phi = 2.0 * std::numbers::pi * u, theta = std::numbers::pi * v;
                // Exact zeros at the poles and the seam keep the normals' lengths exactly 1.
                const double st = (j == 0 || j == kRings) ? 0.0 : std::sin(theta);
                const double ct = j == 0 ? 1.0 : j == kRings ? -1.0 : std::cos(theta);
                const std::array<double, 3> n{st * std::sin(phi), ct, st * std::cos(phi)};
                const std::array<double, 3> t{std::cos(phi), 0.0, -std::sin(phi)};  // d(position)/du, normalized
                for (size_t c = 0; c < 3; ++c) {
                    const auto p = static_cast<float>(kRadius * n[c]);
                    put(l.position + k * 12 + c * 4, p);
                    put(l.normal + k * 12 + c * 4, static_cast<float>(n[c]));
                    put(l.tangent + k * 16 + c * 4, static_cast<float>(t[c]));
                    lo[c] = std::min(lo[c], p);
                    hi[c] = std::max(hi[c], p);
                }
                put(l.tangent + k * 16 + 12, 1.f);
                put(l.texcoord + k * 8, static_cast<float>(u));
                put(l.texcoord + k * 8 + 4, static_cast<float>(v));
            }
        out.layout.min = lo;
        out.layout.max = hi;
        size_t at = l.indices;
        auto index = [&](int i, int j) {
            const auto v = static_cast<uint16_t>(j * (kSegments + 1) + i);
            std::memcpy(out.bytes.data() + at, &v, 2);
            at += 2;
        };
        for (int j = 0; j < kRings; ++j)
            for (int i = 0; i < kSegments; ++i) {
                // a = (i, j) b = (i+1, j) c = (i, j+1) d = (i+1, j+1): a-c-d and a-d-b are
                // counter-clockwise seen from outside. On the top row a and b are both the north
                // pole (a-d-b would be degenerate), on the bottom row c and d the south pole.
                if (j != kRings - 1) index(i, j), index(i, j + 1), index(i + 1, j + 1);
                if (j != 0) index(i, j), index(i + 1, j + 1), index(i + 1, j);
            }
        return out;
    }();
    return s;
}

// Buffer views and accessors of the sphere (buffer 0), appended to `doc`; returns the mesh
// primitive's attributes and indices.
json add_sphere(json& doc, const std::string& bin_uri) {
    const Layout& l = sphere().layout;
    doc["buffers"] = json::array({{{"uri", uri_of(bin_uri)}, {"byteLength", l.total}}});
    auto view = [&](size_t offset, size_t length, int target) {
        doc["bufferViews"].push_back(
            {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", length}, {"target", target}});
        return doc["bufferViews"].size() - 1;
    };
    auto accessor = [&](size_t v, int component, size_t count, const char* type) {
        doc["accessors"].push_back({{"bufferView", v}, {"componentType", component}, {"count", count}, {"type", type}});
        return doc["accessors"].size() - 1;
    };
    const auto nv = static_cast<size_t>(kVertices);
    const size_t pos = accessor(view(l.position, nv * 12, kArrayBuffer), kFloat, nv, "VEC3");
    doc["accessors"][pos]["min"] = {l.min[0], l.min[1], l.min[2]};
    doc["accessors"][pos]["max"] = {l.max[0], l.max[1], l.max[2]};
    const size_t nrm = accessor(view(l.normal, nv * 12, kArrayBuffer), kFloat, nv, "VEC3");
    const size_t tan = accessor(view(l.tangent, nv * 16, kArrayBuffer), kFloat, nv, "VEC4");
    const size_t uv = accessor(view(l.texcoord, nv * 8, kArrayBuffer), kFloat, nv, "VEC2");
    const size_t idx = accessor(view(l.indices, size_t{kIndices} * 2, kElementArrayBuffer), kUnsignedShort,
                                static_cast<size_t>(kIndices), "SCALAR");
    return {{"attributes", {{"POSITION", pos}, {"NORMAL", nrm}, {"TANGENT", tan}, {"TEXCOORD_0", uv}}},
            {"indices", idx}};
}

bool holds(const manifest::Output& o, const std::string& key, Role role) {
    return std::any_of(o.channels.begin(), o.channels.end(), [&](const manifest::Channel& c) {
        return c.key == key && c.kind == manifest::Channel::Kind::role && c.role == role;
    });
}

bool has_constant(const manifest::Material& m, Role r) {
    return std::any_of(m.constants.begin(), m.constants.end(),
                       [&](const manifest::Constant& c) { return c.role == r; });
}

std::string text_of(const json& doc) { return json_text(doc); }

}  // namespace

const std::vector<uint8_t>& sphere_buffer() { return sphere().bytes; }

std::string uri_of(const std::string& relative_path) { return percent_encode_path(relative_path); }

bool material_gltf(const manifest::Material& m, const std::string& gltf_file, const std::string& bin_uri, Files& out,
                   std::string& error) {
    const fs::path base = fs::path(gltf_file).parent_path();
    json doc;
    doc["asset"] = {{"version", "2.0"}, {"generator", std::string(kGenerator)}};
    // glTF 2.0's place for "a copyright message suitable for display to credit the content
    // creator": the material's credit, only where its licence is known.
    if (const auto credit = m.provenance ? manifest::material_credit(*m.provenance) : std::nullopt)
        doc["asset"]["copyright"] = credit->line;
    doc["samplers"] = json::array({{{"magFilter", kLinear}, {"minFilter", kLinearMipmapLinear}}});
    doc["images"] = json::array();
    doc["textures"] = json::array();
    // One texture per output file, in the manifest's (preset's) order.
    auto texture_of = [&](const manifest::Output& o) {
        const std::string uri = uri_of(fs::path(o.file).lexically_relative(base).generic_string());
        for (size_t i = 0; i < doc["images"].size(); ++i)
            if (doc["images"][i]["uri"] == uri) return i;
        doc["images"].push_back({{"uri", uri}});
        doc["textures"].push_back({{"sampler", 0}, {"source", doc["images"].size() - 1}});
        return doc["textures"].size() - 1;
    };
    // Each slot of the glTF's table (preset/engine_slots.cpp) names the texture that binds it,
    // outputs in the manifest's order: an ORM texture serves two slots.
    const EngineMaterial& e = *engine_material(MaterialFileKind::gltf);
    json mat = {{"name", m.name}};
    json pbr = json::object();
    std::set<std::string_view> bound;
    for (const manifest::Output& o : m.outputs) {
        if (o.format != "png") {
            error = o.file + ": glTF textures are PNG or JPEG, not " + o.format;
            return false;
        }
        for (const EngineSlot& s : e.slots) {
            const Role role = s.reads.front().role;
            // A slot named only where the set has a map: a constant has nothing to reference.
            if (!s.binds(o.channels, o.srgb) || (s.map_only && has_constant(m, role))) continue;
            if (s.reads_role(Role::normal) && o.normal_convention && *o.normal_convention != e.normal) {
                error = o.file + ": glTF normal textures are " + std::string(convention_name(e.normal)) +
                        "; this one is " + std::string(convention_name(*o.normal_convention)) +
                        " (--normal-convention)";
                return false;
            }
            (s.group.empty() ? mat : pbr[std::string(s.group)])[std::string(s.slot)] = {{"index", texture_of(o)}};
            bound.insert(s.slot);
            using manifest::AlphaMode;
            if (s.reads_role(Role::opacity) && holds(o, "A", Role::opacity) && m.alpha_mode &&
                *m.alpha_mode != AlphaMode::opaque) {
                mat["alphaMode"] = *m.alpha_mode == AlphaMode::mask ? "MASK" : "BLEND";
                if (*m.alpha_mode == AlphaMode::mask) mat["alphaCutoff"] = m.alpha_cutoff;
                mat["doubleSided"] = manifest::double_sided(m.alpha_mode);
            }
            if (role == Role::emissive) {
                mat["emissiveFactor"] = {1.0, 1.0, 1.0};  // the default 0 would switch the texture off
                if (m.emissive_strength > 1.f) {
                    mat["extensions"]["KHR_materials_emissive_strength"] = {{"emissiveStrength", m.emissive_strength}};
                    doc["extensionsUsed"] = json::array({"KHR_materials_emissive_strength"});
                }
            }
        }
    }
    for (const EngineSlot& s : e.slots)
        if (s.reads.front().required && !bound.count(s.slot)) {
            error = m.name + ": no output for the glTF's " + std::string(s.slot) + " to reference";
            return false;
        }
    for (auto& [group, slots] : pbr.items()) mat[group] = std::move(slots);
    doc["materials"] = json::array({std::move(mat)});
    json primitive = add_sphere(doc, bin_uri);
    primitive["material"] = 0;
    doc["meshes"] = json::array({{{"name", m.name}, {"primitives", json::array({std::move(primitive)})}}});
    doc["nodes"] = json::array({{{"name", m.name}, {"mesh", 0}}});
    doc["scenes"] = json::array({{{"name", m.name}, {"nodes", {0}}}});
    doc["scene"] = 0;
    out.gltf = text_of(doc);
    out.bin = sphere_buffer();
    return true;
}

std::optional<ByteProducer> library_gltf(const std::vector<LibraryItem>& items, const fs::path& out_dir,
                                         std::string& error) {
    // The five per-material arrays are spooled as their text (core/spool), the rest is small.
    static constexpr std::array<const char*, 5> kArrays = {"images", "textures", "materials", "meshes", "nodes"};
    std::array<std::shared_ptr<TextSpool>, 5> spools;
    for (auto& s : spools)
        if (!(s = TextSpool::open(out_dir, error))) return std::nullopt;
    auto& [images, textures, materials, meshes, nodes] = spools;
    json doc;
    doc["asset"] = {{"version", "2.0"}, {"generator", std::string(kGenerator)}};
    const json primitive = add_sphere(doc, "library.bin");
    doc["samplers"] = json::array({{{"magFilter", kLinear}, {"minFilter", kLinearMipmapLinear}}});
    for (const char* k : kArrays) doc[k] = json::array();
    auto add = [&](TextSpool& spool, const json& element) {
        if (!spool.append(array_element_text(element), error)) throw std::runtime_error(error);
    };
    const auto side = static_cast<size_t>(std::ceil(std::sqrt(static_cast<double>(items.size()))));
    bool emissive_strength = false;
    // The materials' credits (their files' asset.copyright): the library's when they all have
    // the same one, else a pointer to the list of every material's.
    std::optional<std::string> copyright;
    bool one_copyright = true;
    try {
        for (size_t i = 0; i < items.size(); ++i) {
            const fs::path gltf_path = out_dir / items[i].gltf_file;
            const auto one = read_json_file(gltf_path, error);
            if (!one) return std::nullopt;
            try {
                const json& asset = one->at("asset");
                std::optional<std::string> credit;
                if (const auto c = asset.find("copyright"); c != asset.end()) credit = c->get<std::string>();
                if (i == 0) copyright = credit;
                else if (credit != copyright) one_copyright = false;
                // The material's images move from its folder's URIs to the root's.
                const fs::path base = fs::path(items[i].gltf_file).parent_path();
                const size_t first_texture = textures->size(), first_image = images->size();
                for (const auto& img : one->at("images"))
                    add(*images,
                        {{"uri",
                          uri_of((base / img.at("uri").get<std::string>()).lexically_normal().generic_string())}});
                for (const auto& t : one->at("textures"))
                    add(*textures, {{"sampler", 0}, {"source", first_image + t.at("source").get<size_t>()}});
                json material = one->at("materials").at(0);
                for (auto& [slot, v] : material.items())
                    if (v.is_object() && v.contains("index")) v["index"] = first_texture + v["index"].get<size_t>();
                for (auto& [slot, v] : material["pbrMetallicRoughness"].items())
                    if (v.is_object() && v.contains("index")) v["index"] = first_texture + v["index"].get<size_t>();
                if (material.contains("extensions")) emissive_strength = true;
                add(*materials, material);
            } catch (const json::exception& e) {
                error = gltf_path.string() + ": not a material file of ours (" + e.what() + ")";
                return std::nullopt;
            }
            json p = primitive;
            p["material"] = i;
            add(*meshes, {{"name", items[i].name}, {"primitives", json::array({std::move(p)})}});
            const auto column = i % side, row = i / side;  // the grid cell of material i
            const double x = 1.25 * static_cast<double>(column), y = -1.25 * static_cast<double>(row);
            add(*nodes, {{"name", items[i].name}, {"mesh", i}, {"translation", {x, y, 0.0}}});
        }
    } catch (const std::runtime_error&) {  // a spool's write failed: `error` says why
        return std::nullopt;
    }
    if (emissive_strength) doc["extensionsUsed"] = json::array({"KHR_materials_emissive_strength"});
    if (!one_copyright)
        doc["asset"]["copyright"] =
            "Materials of several sources or licences: each one's source, licence and credit in " +
            std::string(manifest::kAttributionFile) + " beside this file";
    else if (copyright) doc["asset"]["copyright"] = *copyright;
    json scene_nodes = json::array();
    for (size_t i = 0; i < items.size(); ++i) scene_nodes.push_back(i);
    doc["scenes"] = json::array({{{"name", "library"}, {"nodes", std::move(scene_nodes)}}});
    doc["scene"] = 0;
    // glTF requires non-empty arrays where present.
    for (size_t k = 0; k < kArrays.size(); ++k)
        if (spools[k]->size() == 0) doc.erase(kArrays[k]);
    if (!doc.contains("images")) doc.erase("samplers");
    return ByteProducer([doc = std::move(doc), spools](const ByteSink& sink) {
        std::vector<StreamedArray> arrays;
        std::string ignored;  // a spool of our own that cannot be read back: the write fails, the caller says so
        for (size_t k = 0; k < kArrays.size(); ++k)
            arrays.push_back({kArrays[k], spools[k]->size(), [&, k](size_t i, const ByteSink& out) {
                                  return spools[k]->copy(static_cast<uint32_t>(i), out, ignored);
                              }});
        return write_json_text(doc, arrays, sink);
    });
}

RoleSource role_source(const manifest::Material& m, Role role) {
    RoleSource s;
    for (const manifest::Output& o : m.outputs)
        for (const Channel& c : o.channels)
            if (!s.output && c.kind == Channel::Kind::role && c.role == role) {
                s.output = &o;
                s.channel = &c;
            }
    if (s.output) return s;
    for (const manifest::Constant& c : m.constants)
        if (c.role == role && !c.value.empty()) {
            const bool rgb = c.value.size() >= 3;
            s.constant = {c.value[0], rgb ? c.value[1] : c.value[0], rgb ? c.value[2] : c.value[0]};
            break;
        }
    return s;
}

}  // namespace mf::gltf
