// Scene files and --light specs.
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include <nlohmann/json.hpp>

#include "base/limits.hpp"
#include "core/json.hpp"
#include "preview/preview.hpp"

namespace mf::preview {

using nlohmann::json;

float default_shape_size(render::ShapeType t) {
    switch (t) {
        case render::ShapeType::sphere: return 1.f;
        case render::ShapeType::cube: return 1.2f;
        case render::ShapeType::plane: return 2.f;
        case render::ShapeType::shaderball: return 1.f;
    }
    return 1.f;
}

namespace {

// Parsing stops at the first problem: a SceneError carries it to the one catch in parse_scene.
struct SceneError {
    std::string message;
};
[[noreturn]] void fail(const std::string& where, const std::string& what) { throw SceneError{where + ": " + what}; }

float number(const json& j, const std::string& where) {
    if (!j.is_number()) fail(where, "expected a number, got " + j.dump());
    const auto v = json_float(j, -std::numeric_limits<float>::max(), std::numeric_limits<float>::max());
    if (!v) fail(where, "not a finite number within the float range, got " + j.dump());
    return *v;
}

render::Vec3 vec3(const json& j, const std::string& where) {
    if (!j.is_array() || j.size() != 3) fail(where, "expected [x, y, z], got " + j.dump());
    return {number(j[0], where), number(j[1], where), number(j[2], where)};
}

// A number within [lo, hi] (a roughness of -3 or a metalness of 7 is a mistake, not a value).
float number_in(const json& j, const std::string& where, float lo, float hi) {
    const float v = number(j, where);
    if (!(v >= lo && v <= hi))
        fail(where, "must be within [" + json(lo).dump() + ", " + json(hi).dump() + "], got " + j.dump());
    return v;
}

// An RGB triple each of whose components is within [lo, hi] (linear colors are never negative).
render::Vec3 color(const json& j, const std::string& where, float hi = std::numeric_limits<float>::max()) {
    const render::Vec3 c = vec3(j, where);
    for (float v : c)
        if (!(v >= 0.f && v <= hi))
            fail(where, "components must be within [0, " + (hi < 1e30f ? json(hi).dump() : std::string("inf")) +
                            "], got " + j.dump());
    return c;
}

const json* find(const json& obj, const char* key) {
    const auto it = obj.find(key);
    return it == obj.end() ? nullptr : &*it;
}

void check_keys(const json& obj, const std::string& where, std::initializer_list<const char*> known) {
    if (!obj.is_object()) fail(where, "expected an object, got " + obj.dump());
    for (const auto& [k, v] : obj.items()) {
        bool ok = false;
        for (const char* n : known) ok = ok || k == n;
        if (!ok) fail(where, "unknown key \"" + k + "\"");
    }
}

uint32_t dimension(const json& j, const std::string& where) {
    if (!j.is_number_integer() || j.get<int64_t>() < 1 || j.get<int64_t>() > kMaxImageSide)
        fail(where, "expected an integer in 1.." + std::to_string(kMaxImageSide) + ", got " + j.dump());
    return static_cast<uint32_t>(j.get<int64_t>());
}

SceneMaterial::Map map_ref(const json& j, const std::filesystem::path& base, const std::string& where) {
    if (!j.is_string()) fail(where, "expected \"file.png\" or \"file.png#G\"");
    std::string s = j.get<std::string>();
    SceneMaterial::Map m;
    const auto hash = s.rfind('#');
    if (hash != std::string::npos) {
        const std::string ch = s.substr(hash + 1);
        static const char* const names[] = {"R", "G", "B", "A"};
        for (int i = 0; i < 4; ++i)
            if (ch == names[i]) m.channel = static_cast<render::Channel>(i);
        if (!m.channel) fail(where, "channel must be #R, #G, #B or #A, got #" + ch);
        s.resize(hash);
    }
    m.file = base / s;
    return m;
}

// The stages of parse_scene_or_throw: one per key of the scene file, each reading its object
// into the scene (or the scene file) and throwing SceneError naming the key on a bad value.

void read_image(const json& img, const std::string& name, render::Scene& sc) {
    check_keys(img, name + ": image", {"width", "height", "supersample", "msaa", "shading"});
    if (const json* v = find(img, "supersample")) {
        const auto n = json_int(*v, 1, 4);
        if (!n) fail(name + ": image.supersample", "must be an integer 1..4, got " + v->dump());
        sc.supersample = static_cast<uint32_t>(*n);
    }
    if (const json* v = find(img, "msaa")) {
        const auto n = json_int(*v, 1, 8);
        if (!n || (*n & (*n - 1)) != 0) fail(name + ": image.msaa", "must be 1, 2, 4 or 8, got " + v->dump());
        sc.msaa = static_cast<uint32_t>(*n);
    }
    if (const json* v = find(img, "shading")) {
        const auto sh = v->is_string() ? render::parse_shading(v->get<std::string>()) : std::nullopt;
        if (!sh) fail(name + ": image.shading", "must be \"auto\", \"raster\" or \"compute\", got " + v->dump());
        sc.shading = *sh;
    }
    if (const json* w = find(img, "width")) sc.width = dimension(*w, name + ": image.width");
    if (const json* h = find(img, "height")) sc.height = dimension(*h, name + ": image.height");
}

void read_camera(const json& cam, const std::string& name, render::Scene& sc) {
    const std::string w = name + ": camera";
    check_keys(cam, w, {"position", "target", "up", "yfov_deg"});
    if (const json* v = find(cam, "position")) sc.camera.position = vec3(*v, w + ".position");
    if (const json* v = find(cam, "target")) sc.camera.target = vec3(*v, w + ".target");
    if (const json* v = find(cam, "up")) sc.camera.up = vec3(*v, w + ".up");
    if (const json* v = find(cam, "yfov_deg")) {
        sc.camera.yfov_deg = number(*v, w + ".yfov_deg");
        if (!(sc.camera.yfov_deg > 0.f && sc.camera.yfov_deg < 180.f)) fail(w + ".yfov_deg", "must be in (0, 180)");
    }
    // A camera at its target looks nowhere; an up along the view has no "up" to keep.
    const render::Vec3 p = sc.camera.position, t = sc.camera.target, u = sc.camera.up;
    const float d[3] = {t[0] - p[0], t[1] - p[1], t[2] - p[2]};
    const float dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2], uu = u[0] * u[0] + u[1] * u[1] + u[2] * u[2];
    if (!(dd > 0.f)) fail(w, "position and target are the same point: the camera has no direction to look in");
    if (!(uu > 0.f)) fail(w + ".up", "must not be [0, 0, 0]");
    const float cx = d[1] * u[2] - d[2] * u[1], cy = d[2] * u[0] - d[0] * u[2], cz = d[0] * u[1] - d[1] * u[0];
    if (!(cx * cx + cy * cy + cz * cz > 1e-12f * dd * uu))
        fail(w + ".up", "is parallel to the direction from position to target: choose an up that is not");
}

void read_shape(const json& sh, const std::string& name, SceneFile& out) {
    render::Scene& sc = out.scene;
    const std::string w = name + ": shape";
    check_keys(sh, w, {"type", "radius", "size"});
    if (const json* t = find(sh, "type")) {
        const std::string type = t->is_string() ? t->get<std::string>() : "";
        const auto shape = parse_shape(type);
        if (!shape) fail(w + ".type", "expected \"sphere\", \"cube\", \"plane\" or \"shaderball\", got " + t->dump());
        sc.shape.type = *shape;
    }
    sc.shape.size = default_shape_size(sc.shape.type);
    const json* size = find(sh, sc.shape.type == render::ShapeType::sphere ? "radius" : "size");
    if (!size) size = find(sh, "size");
    if (!size) size = find(sh, "radius");
    if (size) {
        sc.shape.size = number(*size, w + ".radius/size");
        if (!(sc.shape.size > 0.f)) fail(w, "size must be positive");
        out.shape_size_given = true;
    }
}

void read_lights(const json& lights, const std::string& name, render::Scene& sc) {
    if (!lights.is_array()) fail(name + ": lights", "expected an array");
    if (lights.size() > render::kMaxLights)
        fail(name + ": lights", "at most " + std::to_string(render::kMaxLights) + " lights");
    sc.lights.clear();
    for (size_t i = 0; i < lights.size(); ++i) {
        const json& l = lights[i];
        const std::string w = name + ": lights[" + std::to_string(i) + "]";
        check_keys(l, w, {"type", "direction", "position", "color", "intensity"});
        render::Light light;
        const json* t = find(l, "type");
        if (t && !t->is_string()) fail(w + ".type", "expected \"directional\" or \"point\"");
        const std::string type = t ? t->get<std::string>() : "directional";
        if (type == "directional") {
            light.type = render::LightType::directional;
            if (const json* d = find(l, "direction")) light.direction = vec3(*d, w + ".direction");
            const auto& d = light.direction;
            if (d[0] * d[0] + d[1] * d[1] + d[2] * d[2] < 1e-12f) fail(w + ".direction", "zero length");
        } else if (type == "point") {
            light.type = render::LightType::point;
            const json* p = find(l, "position");
            if (!p) fail(w, "a point light needs a position");
            light.position = vec3(*p, w + ".position");
            light.intensity = 10.f;
        } else {
            fail(w + ".type", "expected \"directional\" or \"point\"");
        }
        if (const json* c = find(l, "color")) light.color = color(*c, w + ".color");
        if (const json* v = find(l, "intensity")) light.intensity = number(*v, w + ".intensity");
        if (light.intensity < 0.f) fail(w + ".intensity", "must not be negative");
        sc.lights.push_back(light);
    }
}

void read_environment(const json& env, const std::filesystem::path& base, const std::string& name, SceneFile& out) {
    const std::string w = name + ": environment";
    check_keys(env, w, {"file", "intensity"});
    const json* f = find(env, "file");
    if (!f || !f->is_string()) fail(w, "needs \"file\"");
    out.environment = base / f->get<std::string>();
    if (const json* v = find(env, "intensity"))
        out.environment_intensity = number_in(*v, w + ".intensity", 0.f, std::numeric_limits<float>::max());
}

SceneMaterial read_material(const json& m, const std::filesystem::path& base, const std::string& name) {
    const std::string w = name + ": material";
    check_keys(m, w, {"albedo", "roughness", "metalness", "emissive", "maps", "normal_convention"});
    SceneMaterial sm;
    if (const json* v = find(m, "albedo")) sm.albedo = color(*v, w + ".albedo", 1.f);
    if (const json* v = find(m, "emissive")) sm.emissive = color(*v, w + ".emissive");
    if (const json* v = find(m, "roughness")) sm.roughness = number_in(*v, w + ".roughness", 0.f, 1.f);
    if (const json* v = find(m, "metalness")) sm.metalness = number_in(*v, w + ".metalness", 0.f, 1.f);
    if (const json* v = find(m, "normal_convention")) {
        if (*v != "gl" && *v != "dx") fail(w + ".normal_convention", "expected \"gl\" or \"dx\"");
        sm.normal_convention = *v == "dx" ? NormalConvention::dx : NormalConvention::gl;
    }
    if (const json* maps = find(m, "maps")) {
        const std::string wm = w + ".maps";
        check_keys(*maps, wm, {"albedo", "normal", "roughness", "metalness", "occlusion", "emissive", "opacity"});
        auto get = [&](const char* role, std::optional<SceneMaterial::Map>& dst) {
            if (const json* v = find(*maps, role)) dst = map_ref(*v, base, wm + "." + role);
        };
        get("albedo", sm.albedo_map);
        get("normal", sm.normal_map);
        get("roughness", sm.roughness_map);
        get("metalness", sm.metalness_map);
        get("occlusion", sm.occlusion_map);
        get("emissive", sm.emissive_map);
        get("opacity", sm.opacity_map);
    }
    return sm;
}

void read_output(const json& o, const std::string& name, render::OutputOptions& output) {
    const std::string w = name + ": output";
    check_keys(o, w, {"transfer", "exposure", "tonemap"});
    if (const json* t = find(o, "tonemap")) {
        const auto tm = t->is_string() ? render::parse_tonemap(t->get<std::string>()) : std::nullopt;
        if (!tm) fail(w + ".tonemap", "expected \"none\", \"neutral\" or \"aces\"");
        output.tonemap = *tm;
    }
    if (const json* t = find(o, "transfer")) {
        if (*t == "srgb") output.transfer = render::Transfer::srgb;
        else if (*t == "linear") output.transfer = render::Transfer::linear;
        else fail(w + ".transfer", "expected \"srgb\" or \"linear\"");
    }
    if (const json* e = find(o, "exposure")) {
        output.exposure = number(*e, w + ".exposure");
        if (output.exposure < 0.f) fail(w + ".exposure", "must not be negative");
    }
}

void read_ground(const json& g, const std::string& name, render::Scene& sc) {
    const std::string w = name + ": ground";
    if (g.is_boolean()) {
        sc.ground.enabled = g.get<bool>();
    } else {
        if (!g.is_object())
            fail(w, "expected true, false or {\"albedo\", \"roughness\", \"light_deg\"}, got " + g.dump());
        check_keys(g, w, {"albedo", "roughness", "light_deg"});
        sc.ground.enabled = true;
        if (const json* v = find(g, "albedo")) sc.ground.albedo = number_in(*v, w + ".albedo", 0.f, 1.f);
        if (const json* v = find(g, "roughness")) sc.ground.roughness = number_in(*v, w + ".roughness", 0.f, 1.f);
        if (const json* v = find(g, "light_deg")) sc.ground.light_deg = number_in(*v, w + ".light_deg", 0.1f, 45.f);
    }
}

void read_uv(const json& uv, const std::string& name, SceneFile& out) {
    const std::string w = name + ": uv";
    check_keys(uv, w, {"scale", "offset", "aspect"});
    if (const json* v = find(uv, "scale")) {
        if (v->is_number()) {
            out.uv_scale[0] = out.uv_scale[1] = number_in(*v, w + ".scale", 1e-3f, 1e3f);
        } else {
            if (!v->is_array() || v->size() != 2) fail(w + ".scale", "expected a number or [u, v], got " + v->dump());
            out.uv_scale = {number_in((*v)[0], w + ".scale", 1e-3f, 1e3f),
                            number_in((*v)[1], w + ".scale", 1e-3f, 1e3f)};
        }
    }
    if (const json* v = find(uv, "offset")) {
        if (!v->is_array() || v->size() != 2) fail(w + ".offset", "expected [u, v], got " + v->dump());
        out.uv_offset = {number_in((*v)[0], w + ".offset", -1e3f, 1e3f),
                         number_in((*v)[1], w + ".offset", -1e3f, 1e3f)};
    }
    if (const json* v = find(uv, "aspect")) {
        if (*v != "keep" && *v != "stretch") fail(w + ".aspect", "expected \"keep\" or \"stretch\"");
        out.keep_aspect = *v == "keep";
    }
}

void read_brdf(const json& b, const std::string& name, render::Scene& sc) {
    const auto brdf = b.is_string() ? render::parse_brdf(b.get<std::string>()) : std::nullopt;
    if (!brdf) fail(name + ": brdf", "expected \"standard\", \"accurate\" or \"assignment\"");
    sc.brdf = *brdf;
}

SceneFile parse_scene_or_throw(const json& j, const std::filesystem::path& base, const std::string& name) {
    SceneFile out = reference_scene();  // a scene file says what it wants on top of the reference
    render::Scene& sc = out.scene;
    check_keys(j, name,
               {"image", "camera", "shape", "background", "lights", "environment", "material", "output", "brdf", "uv",
                "ground"});
    if (const json* v = find(j, "image")) read_image(*v, name, sc);
    if (const json* v = find(j, "camera")) read_camera(*v, name, sc);
    if (const json* v = find(j, "shape")) read_shape(*v, name, out);
    if (const json* v = find(j, "background")) sc.background = color(*v, name + ": background");
    if (const json* v = find(j, "lights")) read_lights(*v, name, sc);
    if (const json* v = find(j, "environment")) read_environment(*v, base, name, out);
    if (const json* v = find(j, "material")) out.material = read_material(*v, base, name);
    if (const json* v = find(j, "output")) read_output(*v, name, out.output);
    if (const json* v = find(j, "ground")) read_ground(*v, name, sc);
    if (const json* v = find(j, "uv")) read_uv(*v, name, out);
    if (const json* v = find(j, "brdf")) read_brdf(*v, name, sc);
    return out;
}

}  // namespace

std::optional<SceneFile> parse_scene(const json& j, const std::filesystem::path& base, const std::string& name,
                                     std::string& error) {
    try {
        return parse_scene_or_throw(j, base, name);
    } catch (const SceneError& e) {
        error = e.message;
        return std::nullopt;
    }
}

std::optional<SceneFile> read_scene_file(const std::filesystem::path& file, std::string& error) {
    const auto j = read_json_file(file, error);
    if (!j) return std::nullopt;
    return parse_scene(*j, file.parent_path(), file.string(), error);
}

std::optional<render::ShapeType> parse_shape(std::string_view name) {
    if (name == "sphere") return render::ShapeType::sphere;
    if (name == "cube") return render::ShapeType::cube;
    if (name == "plane") return render::ShapeType::plane;
    if (name == "shaderball") return render::ShapeType::shaderball;
    return std::nullopt;
}

std::optional<render::Light> parse_light_spec(const std::string& spec, std::string& error) {
    std::vector<std::string> parts;
    std::stringstream ss(spec);
    for (std::string p; std::getline(ss, p, ':');) parts.push_back(p);
    auto triple = [](const std::string& s, render::Vec3& v) {
        std::stringstream t(s);
        char c1 = 0, c2 = 0;
        if (!(t >> v[0] >> c1 >> v[1] >> c2 >> v[2]) || c1 != ',' || c2 != ',') return false;
        t >> std::ws;
        return t.eof() && std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]);
    };
    error = "expected dir:X,Y,Z[:INTENSITY[:R,G,B]] or point:X,Y,Z[:INTENSITY[:R,G,B]], got \"" + spec + "\"";
    if (parts.size() < 2 || parts.size() > 4) return std::nullopt;
    render::Light l;
    if (parts[0] == "dir" || parts[0] == "directional") {
        l.type = render::LightType::directional;
        if (!triple(parts[1], l.direction)) return std::nullopt;
        const auto& d = l.direction;
        if (d[0] * d[0] + d[1] * d[1] + d[2] * d[2] < 1e-12f) {
            error = "light direction has zero length: \"" + spec + "\"";
            return std::nullopt;
        }
    } else if (parts[0] == "point") {
        l.type = render::LightType::point;
        l.intensity = 10.f;
        if (!triple(parts[1], l.position)) return std::nullopt;
    } else {
        return std::nullopt;
    }
    if (parts.size() >= 3) {
        try {
            size_t used = 0;
            l.intensity = std::stof(parts[2], &used);
            if (used != parts[2].size() || !(l.intensity >= 0.f) || !std::isfinite(l.intensity)) return std::nullopt;
        } catch (const std::exception&) {
            return std::nullopt;
        }
    }
    if (parts.size() == 4 && !triple(parts[3], l.color)) return std::nullopt;
    error.clear();
    return l;
}

}  // namespace mf::preview
