#include "manifest/manifest.hpp"

#include <algorithm>
#include <cctype>
#include <functional>
#include <limits>
#include <map>
#include <tuple>

#include "core/json.hpp"
#include "core/text.hpp"

namespace mf::manifest {
using nlohmann::json;

namespace {

// Reading: a ParseError carries the message to the one catch in manifest_from_json.
struct ParseError {
    std::string message;
};
[[noreturn]] void fail(const std::string& where, const std::string& what) { throw ParseError{where + ": " + what}; }

const json* member(const json& o, const char* key) {
    const auto it = o.find(key);
    return it == o.end() ? nullptr : &*it;
}

std::string string_of(const json& o, const char* key, const std::string& where, bool required,
                      const std::string& fallback = {}) {
    const json* v = member(o, key);
    if (!v) {
        if (required) fail(where, std::string("no \"") + key + "\"");
        return fallback;
    }
    if (!v->is_string()) fail(where, std::string("\"") + key + "\" is not a string");
    return v->get<std::string>();
}

int int_of(const json& o, const char* key, const std::string& where, int lo = 0,
           int hi = std::numeric_limits<int>::max()) {
    const json* v = member(o, key);
    if (!v) return 0;
    const auto i = json_int(*v, lo, hi);
    if (!i)
        fail(where,
             std::string("\"") + key + "\" is not an integer in " + std::to_string(lo) + ".." + std::to_string(hi));
    return *i;
}

// The texture-value range of constants: the half-float range admits HDR emissive.
constexpr double kValueMin = -65504.0, kValueMax = 65504.0;

float float_of(const json& v, const std::string& where, const std::string& what) {
    const auto f = json_float(v, kValueMin, kValueMax);
    if (!f) fail(where, what + " is not a finite number in [-65504, 65504]");
    return *f;
}

const json& object_of(const json& v, const std::string& where) {
    if (!v.is_object()) fail(where, "is not an object");
    return v;
}

Role role_of(const std::string& name, const std::string& where) {
    const auto r = role_from_name(name);
    if (!r) fail(where, "unknown role \"" + name + "\"");
    return *r;
}

NormalConvention convention_of(const std::string& name, const std::string& where) {
    const auto c = convention_from_name(name);
    if (!c) fail(where, "unknown normal convention \"" + name + "\" (gl, dx or unknown)");
    return *c;
}

bool is_channel_key(const std::string& k) { return k == "RGB" || k == "R" || k == "G" || k == "B" || k == "A"; }

Input input_of(const std::string& role, const json& j, const std::string& where) {
    object_of(j, where);
    Input in;
    in.role = role_of(role, where);
    in.file = string_of(j, "file", where, true);
    in.family = string_of(j, "family", where, false);
    in.rule = string_of(j, "rule", where, false);
    in.width = int_of(j, "width", where);
    in.height = int_of(j, "height", where);
    in.channels = int_of(j, "channels", where);
    in.bit_depth = int_of(j, "bit_depth", where);
    in.color_space = string_of(j, "color_space", where, false);
    if (const json* f = member(j, "float")) {
        if (!f->is_boolean()) fail(where, "\"float\" is not a boolean");
        in.is_float = f->get<bool>();
    }
    if (const json* d = member(j, "stored_as_depth")) {
        if (!d->is_boolean()) fail(where, "\"stored_as_depth\" is not a boolean");
        in.stored_as_depth = d->get<bool>();
    }
    if (const json* u = member(j, "unused")) {
        if (!u->is_boolean()) fail(where, "\"unused\" is not a boolean");
        in.unused = u->get<bool>();
    }
    if (member(j, "normal_convention")) {
        NormalFacts n;
        n.convention = convention_of(string_of(j, "normal_convention", where, true), where);
        n.source = string_of(j, "normal_convention_source", where, false);
        if (const json* c = member(j, "normal_convention_confidence")) {
            const auto v = json_float(*c, 0.0, 1.0);
            if (!v) fail(where, "\"normal_convention_confidence\" is not a number in [0, 1]");
            n.confidence = c->get<double>();
        }
        n.method = string_of(j, "normal_convention_method", where, false);
        in.normal = std::move(n);
    }
    return in;
}

Output output_of(const json& j, const std::string& where) {
    object_of(j, where);
    Output o;
    o.file = string_of(j, "file", where, true);
    if (o.file.empty()) fail(where, "\"file\" is empty");
    // Written as "sRGB" / "linear"; read in any case (presets and hand-made manifests say "srgb").
    const std::string cs = ascii_lower(string_of(j, "color_space", where, false, "linear"));
    if (cs != "srgb" && cs != "linear")
        fail(where, "\"color_space\" must be \"sRGB\" or \"linear\", not \"" + cs + "\"");
    o.srgb = cs == "srgb";
    if (const json* ch = member(j, "channels")) {
        for (const auto& [key, value] : object_of(*ch, where + ": channels").items()) {
            const std::string at = where + ": channel " + key;
            if (!is_channel_key(key)) fail(at, "unknown channel key (RGB, R, G, B or A)");
            Channel c;
            c.key = key;
            if (value.is_number()) {
                c.kind = Channel::Kind::constant;
                c.value = float_of(value, at, "the constant");
            } else if (!value.is_string()) {
                fail(at, "is neither a role name nor a number");
            } else if (value == "smoothness") {
                c.kind = Channel::Kind::smoothness;
                c.role = Role::roughness;
            } else if (value == "unused") {
                c.kind = Channel::Kind::unused;
            } else {
                c.kind = Channel::Kind::role;
                c.role = role_of(value.get<std::string>(), at);
            }
            o.channels.push_back(std::move(c));
        }
    }
    if (member(j, "normal_convention"))
        o.normal_convention = convention_of(string_of(j, "normal_convention", where, true), where);
    if (member(j, "normal_converted_from"))
        o.normal_converted_from = convention_of(string_of(j, "normal_converted_from", where, true), where);
    o.width = int_of(j, "width", where);
    o.height = int_of(j, "height", where);
    o.bit_depth = int_of(j, "bit_depth", where);
    o.format = string_of(j, "format", where, false);
    o.sha256 = string_of(j, "sha256", where, false);
    o.block_format = string_of(j, "block_format", where, false);
    o.gpu_format = string_of(j, "gpu_format", where, false);
    o.supercompression = string_of(j, "supercompression", where, false);
    if (const json* z = member(j, "normal_z")) {
        if (*z != "reconstructed") fail(where, "\"normal_z\" must be \"reconstructed\"");
        o.normal_z_reconstructed = true;
    }
    if (member(j, "dilated_texels")) o.dilated_texels = int_of(j, "dilated_texels", where, 0);
    if (const json* levels = member(j, "levels")) {
        if (!levels->is_array()) fail(where, "\"levels\" is not an array");
        for (size_t i = 0; i < levels->size(); ++i) {
            const std::string at = where + ": levels[" + std::to_string(i) + "]";
            const json& l = object_of((*levels)[i], at);
            LevelError e;
            e.width = int_of(l, "width", at, 1);
            e.height = int_of(l, "height", at, 1);
            auto number = [&](const char* key, double hi) -> std::optional<double> {
                const json* v = member(l, key);
                if (!v) return std::nullopt;
                if (!json_float(*v, 0.0, hi))
                    fail(at,
                         std::string("\"") + key + "\" is not a number in 0.." + std::to_string(static_cast<int>(hi)));
                return v->get<double>();
            };
            e.psnr_db = number("psnr_db", 100.0);
            e.mean_angle_deg = number("mean_angle_deg", 180.0);
            e.max_angle_deg = number("max_angle_deg", 180.0);
            e.coverage = number("coverage", 1.0);
            o.levels.push_back(e);
        }
    }
    return o;
}

bool bool_of(const json& o, const char* key, const std::string& where) {
    const json* v = member(o, key);
    if (!v) return false;
    if (!v->is_boolean()) fail(where, std::string("\"") + key + "\" is not a boolean");
    return v->get<bool>();
}

Provenance provenance_of(const json& j, const std::string& where) {
    object_of(j, where);
    Provenance p;
    p.vendor = string_of(j, "vendor", where, false);
    p.vendor_name = string_of(j, "vendor_name", where, false);
    p.asset_id = string_of(j, "asset_id", where, false);
    p.asset_id_from = string_of(j, "asset_id_from", where, false);
    p.attribution = string_of(j, "attribution", where, false);
    p.url = string_of(j, "url", where, false);
    if (const json* l = member(j, "licence")) {
        const std::string at = where + ": licence";
        object_of(*l, at);
        Provenance::Licence lic;
        lic.spdx = string_of(*l, "spdx", at, false);
        lic.name = string_of(*l, "name", at, true);
        lic.url = string_of(*l, "url", at, false);
        lic.attribution_required = bool_of(*l, "attribution_required", at);
        lic.vendor_licence = bool_of(*l, "vendor_licence", at);
        const json* e = member(*l, "evidence");
        if (!e) fail(at, "no \"evidence\"");
        const std::string eat = at + ": evidence";
        object_of(*e, eat);
        lic.evidence.how = string_of(*e, "how", eat, true);
        if (lic.evidence.how != "vendor" && lic.evidence.how != "file" && lic.evidence.how != "sidecar")
            fail(eat, "\"how\" must be \"vendor\", \"file\" or \"sidecar\"");
        lic.evidence.file = string_of(*e, "file", eat, false);
        lic.evidence.field = string_of(*e, "field", eat, false);
        lic.evidence.detail = string_of(*e, "detail", eat, false);
        p.licence = std::move(lic);
    }
    return p;
}

Material material_of(const json& j, const std::string& at) {
    object_of(j, at);
    Material m;
    m.name = string_of(j, "name", at, true);
    if (m.name.empty()) fail(at, "\"name\" is empty");
    const std::string where = "material " + m.name;
    m.source = string_of(j, "source", where, false);
    if (member(j, "archive")) m.archive = string_of(j, "archive", where, true);
    m.convention = string_of(j, "convention", where, false);
    if (const json* p = member(j, "provenance")) m.provenance = provenance_of(*p, where + ": provenance");
    m.key = string_of(j, "key", where, false);
    const std::string status = string_of(j, "status", where, false, "ok");
    if (status != "ok" && status != "partial") fail(where, "\"status\" must be \"ok\" or \"partial\"");
    m.status = status == "ok" ? Status::ok : Status::partial;
    if (const json* in = member(j, "inputs"))
        for (const auto& [role, v] : object_of(*in, where + ": inputs").items())
            m.inputs.push_back(input_of(role, v, where + ": input " + role));
    std::sort(m.inputs.begin(), m.inputs.end(), [](const Input& a, const Input& b) { return a.role < b.role; });
    if (const json* c = member(j, "constants")) {
        for (const auto& [role, v] : object_of(*c, where + ": constants").items()) {
            const std::string cat = where + ": constant " + role;
            Constant k;
            k.role = role_of(role, cat);
            if (v.is_array()) {
                if (v.size() != 3) fail(cat, "an RGB constant has 3 numbers");
                for (const json& x : v) k.value.push_back(float_of(x, cat, "a component"));
            } else {
                k.value.push_back(float_of(v, cat, "the value"));
            }
            m.constants.push_back(std::move(k));
        }
    }
    std::sort(m.constants.begin(), m.constants.end(),
              [](const Constant& a, const Constant& b) { return a.role < b.role; });
    if (const json* o = member(j, "outputs")) {
        if (!o->is_array()) fail(where, "\"outputs\" is not an array");
        for (size_t i = 0; i < o->size(); ++i)
            m.outputs.push_back(output_of((*o)[i], where + ": outputs[" + std::to_string(i) + "]"));
    }
    if (const json* files = member(j, "material_files")) {
        if (!files->is_array()) fail(where, "\"material_files\" is not an array");
        for (size_t i = 0; i < files->size(); ++i) {
            const std::string fat = where + ": material_files[" + std::to_string(i) + "]";
            const json& f = object_of((*files)[i], fat);
            m.material_files.push_back({string_of(f, "file", fat, true), string_of(f, "format", fat, true),
                                        string_of(f, "sha256", fat, false)});
        }
    }
    if (const json* s = member(j, "emissive_strength")) {
        const auto v = json_float(*s, 1.0, 1e9);
        if (!v) fail(where + ": emissive_strength", "must be a number >= 1");
        m.emissive_strength = *v;
    }
    if (const json* a = member(j, "alpha_mode")) {
        const std::string mode = a->is_string() ? a->get<std::string>() : "";
        for (AlphaMode v : {AlphaMode::opaque, AlphaMode::mask, AlphaMode::blend})
            if (mode == alpha_mode_name(v)) m.alpha_mode = v;
        if (!m.alpha_mode) fail(where + ": alpha_mode", "must be \"opaque\", \"mask\" or \"blend\"");
        if (*m.alpha_mode == AlphaMode::mask) {
            const json* c = member(j, "alpha_cutoff");
            const auto v = c ? json_float(*c, 0.0, 1.0) : std::nullopt;
            if (!v) fail(where + ": alpha_cutoff", "must be a number within 0..1 with alpha_mode \"mask\"");
            m.alpha_cutoff = *v;
        }
    }
    if (const json* f = member(j, "findings")) {
        if (!f->is_array()) fail(where, "\"findings\" is not an array");
        for (size_t i = 0; i < f->size(); ++i) {
            std::string error;
            auto finding = finding_from_json((*f)[i], error);
            if (!finding) fail(where + ": findings[" + std::to_string(i) + "]", error);
            m.findings.push_back(std::move(*finding));
        }
    }
    return m;
}

}  // namespace

std::string_view status_name(Status s) { return s == Status::ok ? "ok" : "partial"; }

bool double_sided(std::optional<AlphaMode> a) { return a && *a != AlphaMode::opaque; }

std::string_view alpha_mode_name(AlphaMode a) {
    return a == AlphaMode::opaque ? "opaque" : a == AlphaMode::mask ? "mask" : "blend";
}

json to_json(const Input& in) {
    json j = {{"file", in.file}, {"family", in.family}, {"rule", in.rule}};
    j["width"] = in.width;
    j["height"] = in.height;
    j["channels"] = in.channels;
    j["bit_depth"] = in.bit_depth;
    j["color_space"] = in.color_space;
    if (in.is_float) j["float"] = true;
    if (in.stored_as_depth) j["stored_as_depth"] = true;
    if (in.unused) j["unused"] = true;
    // What each channel of a packed input held: from the role (packed_layout), never stored apart.
    for (const auto& [channel, what] : packing_channels(in.role)) j["packing"][channel] = what;
    if (in.normal) {
        j["normal_convention"] = convention_name(in.normal->convention);
        if (!in.normal->source.empty()) j["normal_convention_source"] = in.normal->source;
        if (in.normal->confidence) j["normal_convention_confidence"] = *in.normal->confidence;
        if (!in.normal->method.empty()) j["normal_convention_method"] = in.normal->method;
    }
    return j;
}

json to_json(const std::vector<Input>& inputs) {
    json j = json::object();
    for (const Input& in : inputs) j[std::string(role_name(in.role))] = to_json(in);
    return j;
}

json to_json(const std::vector<Constant>& constants) {
    json j = json::object();
    for (const Constant& c : constants) {
        const std::string r(role_name(c.role));
        if (c.value.size() == 1) j[r] = c.value[0];
        else j[r] = c.value;
    }
    return j;
}

json to_json(const Output& o) {
    json j;
    j["file"] = o.file;
    j["color_space"] = o.srgb ? "sRGB" : "linear";
    json ch = json::object();
    for (const Channel& c : o.channels) {
        switch (c.kind) {
            case Channel::Kind::role: ch[c.key] = role_name(c.role); break;
            case Channel::Kind::smoothness: ch[c.key] = "smoothness"; break;
            case Channel::Kind::constant: ch[c.key] = c.value; break;
            case Channel::Kind::unused: ch[c.key] = "unused"; break;
        }
    }
    j["channels"] = std::move(ch);
    if (o.normal_convention) j["normal_convention"] = convention_name(*o.normal_convention);
    if (o.normal_converted_from) j["normal_converted_from"] = convention_name(*o.normal_converted_from);
    j["width"] = o.width;
    j["height"] = o.height;
    j["bit_depth"] = o.bit_depth;
    j["format"] = o.format;
    j["sha256"] = o.sha256;
    if (!o.block_format.empty()) j["block_format"] = o.block_format;
    if (!o.gpu_format.empty()) j["gpu_format"] = o.gpu_format;
    if (!o.supercompression.empty()) j["supercompression"] = o.supercompression;
    if (o.normal_z_reconstructed) j["normal_z"] = "reconstructed";
    if (o.dilated_texels) j["dilated_texels"] = *o.dilated_texels;
    if (!o.levels.empty()) {
        json levels = json::array();
        for (const LevelError& e : o.levels) {
            json l = {{"width", e.width}, {"height", e.height}};
            if (e.psnr_db) l["psnr_db"] = *e.psnr_db;
            if (e.mean_angle_deg) l["mean_angle_deg"] = *e.mean_angle_deg;
            if (e.max_angle_deg) l["max_angle_deg"] = *e.max_angle_deg;
            if (e.coverage) l["coverage"] = *e.coverage;
            levels.push_back(std::move(l));
        }
        j["levels"] = std::move(levels);
    }
    return j;
}

json to_json(const Provenance& p) {
    json j = json::object();
    const auto put = [&](const char* key, const std::string& v) {
        if (!v.empty()) j[key] = v;
    };
    put("vendor", p.vendor);
    put("vendor_name", p.vendor_name);
    put("asset_id", p.asset_id);
    put("asset_id_from", p.asset_id_from);
    put("attribution", p.attribution);
    put("url", p.url);
    if (p.licence) {
        const Provenance::Licence& l = *p.licence;
        json lj = {{"name", l.name}};
        if (!l.spdx.empty()) lj["spdx"] = l.spdx;
        if (!l.url.empty()) lj["url"] = l.url;
        lj["attribution_required"] = l.attribution_required;
        if (l.vendor_licence) lj["vendor_licence"] = true;
        json e = {{"how", l.evidence.how}};
        if (!l.evidence.file.empty()) e["file"] = l.evidence.file;
        if (!l.evidence.field.empty()) e["field"] = l.evidence.field;
        if (!l.evidence.detail.empty()) e["detail"] = l.evidence.detail;
        lj["evidence"] = std::move(e);
        j["licence"] = std::move(lj);
    }
    return j;
}

namespace {

// material_files and library: [{file, format, sha256}, ...]
json files_json(const std::vector<MaterialFile>& files) {
    json out = json::array();
    for (const MaterialFile& f : files) out.push_back({{"file", f.file}, {"format", f.format}, {"sha256", f.sha256}});
    return out;
}

// The manifest without its materials (an empty array in their place): to_json fills it,
// manifest_text streams them into its text.
json manifest_head(const Manifest& m) {
    json j;
    j["manifest_version"] = m.manifest_version;
    j["generator"] = m.generator;
    j["preset"] = m.preset;
    j["normal_convention"] = convention_name(m.normal_convention);
    j["materials"] = json::array();
    json failures = json::array();
    for (const InputFailure& f : m.failures) failures.push_back(mf::to_json(f));
    j["failures"] = std::move(failures);
    if (!m.library.empty()) j["library"] = files_json(m.library);
    if (!m.thresholds.empty()) j["thresholds"] = m.thresholds;
    if (m.shard)
        j["shard"] = {{"index", m.shard->index},
                      {"count", m.shard->count},
                      {"context", m.shard->context},
                      {"plan", m.shard->plan},
                      {"sets", m.shard->sets}};
    return j;
}

}  // namespace

json to_json(const Material& m) {
    json j;
    j["name"] = m.name;
    j["source"] = m.source;
    if (m.archive) j["archive"] = *m.archive;
    j["convention"] = m.convention;
    if (m.provenance) j["provenance"] = to_json(*m.provenance);
    if (!m.key.empty()) j["key"] = m.key;
    j["status"] = status_name(m.status);
    j["inputs"] = to_json(m.inputs);
    j["constants"] = to_json(m.constants);
    json outputs = json::array();
    for (const Output& o : m.outputs) outputs.push_back(to_json(o));
    j["outputs"] = std::move(outputs);
    if (!m.material_files.empty()) j["material_files"] = files_json(m.material_files);
    if (m.emissive_strength > 1.f) j["emissive_strength"] = m.emissive_strength;
    if (m.alpha_mode) {
        j["alpha_mode"] = alpha_mode_name(*m.alpha_mode);
        if (*m.alpha_mode == AlphaMode::mask) j["alpha_cutoff"] = m.alpha_cutoff;
    }
    json findings = json::array();
    for (const Finding& f : m.findings) findings.push_back(mf::to_json(f));
    j["findings"] = std::move(findings);
    return j;
}

json to_json(const Manifest& m) {
    json j = manifest_head(m);
    for (const Material& mat : m.materials) j["materials"].push_back(to_json(mat));
    return j;
}

std::string manifest_text(const Manifest& m) {
    return json_text_with_array(manifest_head(m), "materials", m.materials.size(),
                                [&](size_t i) { return to_json(m.materials[i]); });
}

std::optional<Manifest> manifest_from_json(const json& j, std::string& error) {
    try {
        if (!j.is_object()) fail("manifest", "is not a JSON object");
        Manifest m;
        const json* v = member(j, "manifest_version");
        const auto version = v ? json_int(*v, 1, std::numeric_limits<int>::max()) : std::nullopt;
        if (!version) fail("manifest", "missing or invalid \"manifest_version\" (an integer, 1)");
        if (*version > kVersion)
            fail("manifest", "version " + std::to_string(*version) + " is newer than this matforge reads (" +
                                 std::to_string(kVersion) + ")");
        m.manifest_version = *version;
        m.generator = string_of(j, "generator", "manifest", false);
        m.preset = string_of(j, "preset", "manifest", false);
        if (member(j, "normal_convention"))
            m.normal_convention = convention_of(string_of(j, "normal_convention", "manifest", true), "manifest");
        const json* mats = member(j, "materials");
        if (!mats || !mats->is_array()) fail("manifest", "no \"materials\" array");
        for (size_t i = 0; i < mats->size(); ++i)
            m.materials.push_back(material_of((*mats)[i], "materials[" + std::to_string(i) + "]"));
        if (const json* files = member(j, "library")) {
            if (!files->is_array()) fail("manifest", "\"library\" is not an array");
            for (size_t i = 0; i < files->size(); ++i) {
                const std::string at = "library[" + std::to_string(i) + "]";
                const json& f = object_of((*files)[i], at);
                m.library.push_back({string_of(f, "file", at, true), string_of(f, "format", at, true),
                                     string_of(f, "sha256", at, false)});
            }
        }
        if (const json* tj = member(j, "thresholds")) {
            for (const auto& [code, values] : object_of(*tj, "thresholds").items())
                for (const auto& [name, value] : object_of(values, "thresholds." + code).items()) {
                    if (!value.is_number()) fail("thresholds." + code, "\"" + name + "\" is not a number");
                    m.thresholds[code][name] = value.get<double>();
                }
        }
        if (const json* sj = member(j, "shard")) {
            const json& o = object_of(*sj, "shard");
            const json* c = member(o, "count");
            const json* i = member(o, "index");
            const int count = c ? json_int(*c, 1, 100000).value_or(0) : 0;
            const int index = i && count > 0 ? json_int(*i, 0, count - 1).value_or(-1) : -1;
            if (count == 0 || index < 0)
                fail("shard", "\"index\" and \"count\" must be integers, 0 <= index < count <= 100000");
            const json* n = member(o, "sets");
            const int sets = n ? json_int(*n, 0, 100000000).value_or(-1) : -1;
            if (sets < 0)
                fail("shard", "\"sets\" must be an integer >= 0 (a shard of an older matforge: run it again)");
            m.shard = Manifest::Shard{index, count, string_of(o, "context", "shard", true),
                                      string_of(o, "plan", "shard", true), sets};
        }
        if (const json* f = member(j, "failures")) {
            if (!f->is_array()) fail("manifest", "\"failures\" is not an array");
            for (size_t i = 0; i < f->size(); ++i) {
                auto failure = input_failure_from_json((*f)[i], error);
                if (!failure) fail("failures[" + std::to_string(i) + "]", error);
                m.failures.push_back(std::move(*failure));
            }
        }
        return m;
    } catch (const ParseError& e) {
        error = e.message;
        return std::nullopt;
    }
}

std::optional<Manifest> read_manifest(const std::string& path, std::string& error) {
    const auto j = read_json_file(path, error);
    if (!j) return std::nullopt;
    auto m = manifest_from_json(*j, error);
    if (!m) error = path + ": " + error;
    return m;
}

std::optional<Material> material_from_json(const json& j, const std::string& at, std::string& error) {
    try {
        return material_of(j, at);
    } catch (const ParseError& e) {
        error = e.message;
        return std::nullopt;
    }
}

std::optional<Manifest> read_manifest(const std::string& path,
                                      const std::function<bool(Material&&, std::string& error)>& each,
                                      std::string& error) {
    size_t index = 0;
    const auto head = read_json_file(
        path, "materials",
        [&](json& element, std::string& e) {
            auto m = material_from_json(element, "materials[" + std::to_string(index++) + "]", e);
            return m && each(std::move(*m), e);
        },
        error);
    if (!head) return std::nullopt;
    auto m = manifest_from_json(*head, error);
    if (!m) error = path + ": " + error;
    return m;
}

namespace {

// merge(), stage 1: the parts were written by one run's configuration (the more specific
// differences first: they make the clearer message).
bool same_run(const std::vector<Manifest>& parts, const std::function<std::string(size_t)>& name, std::string& error) {
    const Manifest& p0 = parts[0];
    for (size_t i = 1; i < parts.size(); ++i) {
        const Manifest& p = parts[i];
        auto differs = [&](const std::string& what, const std::string& a, const std::string& b) {
            error = name(0) + " and " + name(i) + " are not parts of one run: " + what + " \"" + a + "\" vs \"" + b +
                    "\"";
            return false;
        };
        if (p.manifest_version != p0.manifest_version)
            return differs("manifest_version", std::to_string(p0.manifest_version), std::to_string(p.manifest_version));
        if (p.generator != p0.generator) return differs("generator", p0.generator, p.generator);
        if (p.preset != p0.preset) return differs("preset", p0.preset, p.preset);
        if (p.normal_convention != p0.normal_convention)
            return differs("normal_convention", std::string(convention_name(p0.normal_convention)),
                           std::string(convention_name(p.normal_convention)));
        if (p.shard && p0.shard && p.shard->count != p0.shard->count)
            return differs("shard count", std::to_string(p0.shard->count), std::to_string(p.shard->count));
        if (p.shard && p0.shard && p.shard->context != p0.shard->context) {
            error =
                name(0) + " and " + name(i) +
                " are not parts of one run: made with other preset content, rules, OpenColorIO config or library versions";
            return false;
        }
        if (p.shard && p0.shard && p.shard->plan != p0.shard->plan) {
            error = name(0) + " and " + name(i) +
                    " are not parts of one run: made from other libraries, or from one that changed between the "
                    "shards' runs (a set added, removed or resized moves sets between shards); run every shard again";
            return false;
        }
    }
    return true;
}

// merge(), stage 2: every part is a shard, each index of the N-way run exactly once (a missing
// shard would give a manifest that silently lacks its sets).
bool every_shard_once(const std::vector<Manifest>& parts, const std::function<std::string(size_t)>& name,
                      std::string& error) {
    std::vector<int> seen;
    for (size_t i = 0; i < parts.size(); ++i) {
        const auto& s = parts[i].shard;
        if (!s) {
            error = name(i) + " is not the manifest of a shard (ingest --shard I/N writes manifest.shard-I-of-N.json)";
            return false;
        }
        if (seen.empty()) seen.assign(static_cast<size_t>(s->count), -1);
        int& at = seen[static_cast<size_t>(s->index)];
        if (at >= 0) {
            error = "shard " + std::to_string(s->index) + " of " + std::to_string(s->count) +
                    " is given twice: " + name(static_cast<size_t>(at)) + " and " + name(i);
            return false;
        }
        at = static_cast<int>(i);
    }
    std::string missing;
    for (size_t k = 0; k < seen.size(); ++k)
        if (seen[k] < 0) missing += (missing.empty() ? "" : ", ") + std::to_string(k);
    if (!missing.empty()) {
        error = "shard(s) " + missing + " of " + std::to_string(seen.size()) +
                " missing: the merged manifest would lack their sets (give every manifest.shard-I-of-N.json)";
        return false;
    }
    return true;
}

}  // namespace

std::optional<Manifest> merge_heads(const std::vector<Manifest>& parts, const std::vector<std::string>& names,
                                    std::string& error) {
    if (parts.empty()) {
        error = "no manifest to merge";
        return std::nullopt;
    }
    const std::function<std::string(size_t)> name = [&](size_t i) {
        return i < names.size() ? names[i] : "manifest " + std::to_string(i + 1);
    };
    if (!same_run(parts, name, error) || !every_shard_once(parts, name, error)) return std::nullopt;
    // Stage 3: what one unsharded run writes beside its materials (no `shard` member).
    Manifest out;
    out.manifest_version = parts[0].manifest_version;
    out.generator = parts[0].generator;
    out.preset = parts[0].preset;
    out.normal_convention = parts[0].normal_convention;
    out.thresholds = parts[0].thresholds;  // one run's: the shards' context digest holds its rules
    // The files every shard writes alike (the folder's engine include: process/material_file.hpp
    // write_folder_files), the same in each part: its context digest holds the preset.
    out.library = parts[0].library;
    for (const Manifest& p : parts) out.failures.insert(out.failures.end(), p.failures.begin(), p.failures.end());
    auto key = [](const InputFailure& f) { return std::tie(f.source, f.code, f.message); };
    std::sort(out.failures.begin(), out.failures.end(), [&](const auto& a, const auto& b) { return key(a) < key(b); });
    out.failures.erase(std::unique(out.failures.begin(), out.failures.end(),
                                   [&](const auto& a, const auto& b) { return key(a) == key(b); }),
                       out.failures.end());
    return out;
}

std::array<size_t, 3> count_findings(const Manifest& m) {
    std::array<size_t, 3> n{0, 0, 0};
    for (const Material& mat : m.materials)
        for (const Finding& f : mat.findings) ++n[static_cast<size_t>(f.severity)];
    return n;
}

}  // namespace mf::manifest
