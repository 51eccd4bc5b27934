#include "plan/plan.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>

#include "base/parallel.hpp"
#include "core/files.hpp"
#include "findings/catalog.hpp"
#include "material/families.hpp"
#include "plan/missing.hpp"
#include "validate/validate.hpp"

namespace mf {
namespace {

// What a plan works from: the set, each file opened once (a zip entry is read once).
struct Files {
    const MaterialSource& src;
    std::map<std::string, InputFile> opened;

    const InputFile& open(const std::string& f) {
        auto it = opened.find(f);
        if (it == opened.end()) it = opened.emplace(f, src.open(f)).first;
        return it->second;
    }
};

Finding make_finding(std::string_view code, Role role, std::string file, std::string msg, Figures figures = {}) {
    return finding(code, std::string(role_name(role)), std::move(file), std::move(msg), std::move(figures));
}

// The first `max` bytes of a file of the set; a larger file is refused with `too_large` unless
// `head_only`. "" + `error` when it cannot be read.
std::string read_text(const InputFile& in, size_t max, bool head_only, const char* too_large, std::string& error) {
    std::string text;
    if (in.bytes) {
        if (in.bytes->size() > max && !head_only) error = too_large;
        else
            text.assign(in.bytes->begin(),
                        in.bytes->begin() + static_cast<std::ptrdiff_t>(std::min(in.bytes->size(), max)));
    } else if (!in.open_error.empty()) {
        error = in.open_error;
    } else if (const auto why = not_a_regular_file(in.path)) {
        error = *why;
    } else {
        std::error_code ec;
        const auto size = std::filesystem::file_size(in.path, ec);
        if (ec) error = ec.message();
        else if (size > max && !head_only) error = too_large;
        else {
            std::ifstream stream(in.path, std::ios::binary);
            text.resize(std::min<uintmax_t>(size, max));
            stream.read(text.data(), static_cast<std::streamsize>(text.size()));
            text.resize(static_cast<size_t>(stream.gcount()));
        }
    }
    return text;
}

// The set's licence and readme files (material/provenance.hpp), the first kLicenceFileMaxBytes of each.
std::vector<SetText> read_licence_files(Files& files, const std::vector<std::string>& candidates) {
    std::vector<SetText> out;
    for (const std::string& f : candidates) {
        if (!is_licence_file_name(f)) continue;
        SetText t{f, {}, {}};
        t.text = read_text(files.open(f), kLicenceFileMaxBytes, true, "", t.error);
        out.push_back(std::move(t));
    }
    return out;
}

// The set's glTF and Megascans JSON sidecars, read for the roles they state (at most
// kSidecarMaxBytes each: a .glb's JSON chunk comes first; a larger .gltf or .json is left to the
// names, with the reason).
std::vector<SidecarRoles> read_sidecars(Files& files) {
    std::vector<SidecarRoles> out;
    for (const std::string& f : files.src.files) {
        if (!is_sidecar_name(f)) continue;
        const InputFile& in = files.open(f);
        std::string error;
        const std::string text = read_text(in, kSidecarMaxBytes, in.extension() == "glb", "larger than 8 MiB", error);
        if (!error.empty()) {
            SidecarRoles failed;
            failed.source = f;
            failed.error = error;
            out.push_back(std::move(failed));
            continue;
        }
        out.push_back(sidecar_roles(f, text));
    }
    return out;
}

// Whether a map's pixels are colour: R, G and B apart by more than NOT_GRAYSCALE's JPEG
// tolerance in more than its share of pixels (that rule's thresholds: a map it would call "not
// grayscale" is colour here too). nullopt when the file cannot be read or has no RGB.
std::optional<bool> is_colour_image(const InputFile& in, const rules::Thresholds& t) {
    Decoded d;
    ImageInfo info;
    std::string error;
    if (!read_image(in, d, info, error) || d.channels() < 3) return std::nullopt;
    const int c = d.channels();
    const size_t pixels = static_cast<size_t>(d.width()) * static_cast<size_t>(d.height());
    size_t differing = 0;
    auto apart = [&](float r, float g, float b) {
        return std::max({std::abs(r - g), std::abs(r - b), std::abs(g - b)}) > t.grayscale_tolerance_jpeg;
    };
    for (size_t i = 0; i < pixels; ++i) {
        const size_t k = i * static_cast<size_t>(c);
        if (d.is_codes()) {
            const auto& p = d.codes.pixels;
            differing += apart(p[k] / 255.f, p[k + 1] / 255.f, p[k + 2] / 255.f);
        } else {
            const auto& p = d.floats.pixels;
            differing += apart(p[k], p[k + 1], p[k + 2]);
        }
    }
    return pixels > 0 && static_cast<double>(differing) > t.grayscale_max_share * static_cast<double>(pixels);
}

}  // namespace

namespace {
// A map read from its file, for one plan or a share's readers.
bool read_map(const InputFile& in, SharedMap& out, std::string& error) {
    auto m = std::make_shared<DecodedMap>();
    const bool ok = read_image(in, m->img, m->info, error);
    out = ok ? std::move(m) : nullptr;
    return ok;
}
}  // namespace

bool PlanShare::read(const InputFile& in, const std::string& file, SharedMap& out, std::string& error) {
    auto decode = [&] { return read_map(in, out, error); };
    {
        std::lock_guard lock(mutex_);
        const auto it = entries_.find(file);
        if (it != entries_.end() && !it->second.gone) {
            if (it->second.error) {
                error = *it->second.error;
                return false;
            }
            out = it->second.map;
            // The last plan that reads it: the share lets go (one read more, as a file two roles
            // read, decodes again).
            if (++it->second.reads >= plans_) {
                it->second.map.reset();
                it->second.gone = true;
            }
            return true;
        }
        if (it != entries_.end()) return decode();
    }
    Entry e;
    const bool ok = decode();
    if (ok && plans_ > 1) e.map = out;
    else if (!ok) e.error = error;
    e.gone = ok && plans_ <= 1;
    std::lock_guard lock(mutex_);
    entries_.emplace(file, std::move(e));
    return ok;
}

validate::ColorTagInfo PlanShare::color_tag(const InputFile& in, const std::string& file) {
    {
        std::lock_guard lock(mutex_);
        if (const auto it = tags_.find(file); it != tags_.end()) return it->second;
    }
    validate::ColorTagInfo tag = validate::read_color_tag(in);  // outside the lock: another map may be decoding
    std::lock_guard lock(mutex_);
    return tags_.emplace(file, std::move(tag)).first->second;
}

validate::SetValidation PlanShare::validate(const std::vector<validate::MapInput>& maps, const rules::RuleConfig& rules,
                                            const validate::ValidateOptions& vo) {
    std::vector<MapKey> keys;
    keys.reserve(maps.size());
    for (const auto& m : maps)
        keys.push_back({m.role, m.name, m.file.display, m.alternate, m.name_convention, m.engine_convention, m.unused});
    {
        std::lock_guard lock(mutex_);
        for (const Validated& v : validated_)
            if (v.rules == rules && v.maps == keys) return v.result;
    }
    validate::SetValidation v = validate::validate_set(maps, rules, vo);
    std::lock_guard lock(mutex_);
    validated_.push_back({rules, std::move(keys), v});
    return v;
}

namespace {

// Estimated peak bytes of a set: its decoded maps (8-bit files as codes, others as float) plus
// the planes made from them.
uint64_t estimated_bytes(const SetDiscovery& d) {
    uint64_t total = 0;
    for (const auto& c : d.choices)
        total += uint64_t{c.chosen.header.bit_depth == 8 && !c.chosen.header.is_float ? 1U : 4U} *
                 static_cast<uint64_t>(std::max(0, c.chosen.header.width)) *
                 static_cast<uint64_t>(std::max(0, c.chosen.header.height)) *
                 static_cast<uint64_t>(std::clamp(c.chosen.header.channels, 1, 4));
    return total * 2;
}

// One readable map per input role: each choice's candidates in order until one reads (decode
// mode: the whole image, in parallel for large sets; stream mode: the header). Every candidate
// that fails is an UNREADABLE_FILE finding, and the set is partial. `failed`: files known
// unreadable (stream mode: their pixels failed the rules' pass), failing here with that error.
void read_choices(SetPlan& plan, Files& files, const SetDiscovery& d, PlanMode mode, bool two_threads,
                  const std::function<bool()>& spare, PlanShare* share,
                  const std::map<std::string, std::string>& failed, std::vector<validate::MapInput>& maps) {
    std::vector<std::vector<const Candidate*>> orders;
    for (const auto& choice : d.choices) {
        std::vector<const Candidate*> order{&choice.chosen};
        for (const auto& r : choice.rejected) order.push_back(&r);
        for (const Candidate* c : order) files.open(c->file);  // the map of files is not thread-safe
        orders.push_back(std::move(order));
    }
    struct Outcome {
        const Candidate* used = nullptr;
        SharedMap decoded;
        std::optional<validate::MapInput> map;
        std::vector<std::pair<const Candidate*, std::string>> errors;
    };
    std::vector<Outcome> outcomes(orders.size());
    auto read_one = [&](size_t i) {
        Outcome& o = outcomes[i];
        const Role role = d.choices[i].role;
        for (const Candidate* c : orders[i]) {
            const InputFile& in = files.opened.at(c->file);
            std::string err;
            if (const auto bad = failed.find(c->file); bad != failed.end()) {
                o.errors.emplace_back(c, bad->second);
                continue;
            }
            if (mode == PlanMode::decode) {
                if (share ? share->read(in, c->file, o.decoded, err) : read_map(in, o.decoded, err)) {
                    validate::MapInput m;
                    m.role = role;
                    m.file = in;
                    m.name = c->file;
                    m.info = o.decoded->info;
                    m.color_tag = share ? share->color_tag(in, c->file) : validate::read_color_tag(in);
                    m.name_convention = c->match.normal;
                    o.map = std::move(m);
                }
            } else {
                o.map = validate::make_map_input(role, in, c->file, c->match.normal, err);
            }
            if (o.map) o.map->unused = c->match.unused;
            if (o.map) o.map->engine_convention = c->match.engine_normal;
            if (o.map) {
                o.used = c;
                return;
            }
            o.errors.emplace_back(c, err);
        }
    };
    const bool decode = mode == PlanMode::decode;
    if (decode && !two_threads && spare) parallel_for_spare(orders.size(), spare, read_one);
    else parallel_for(orders.size(), decode && two_threads ? 2 : 1, read_one);
    for (size_t i = 0; i < orders.size(); ++i) {
        const Role role = d.choices[i].role;
        for (const auto& [c, err] : outcomes[i].errors) {
            plan.partial = true;
            plan.findings.push_back(make_finding(code::unreadable_file, role, c->file, err + "; the file is skipped"));
        }
        if (!outcomes[i].used) continue;
        for (const auto& [c, msg] : outcomes[i].map->info.notes)  // MULTIPART_IMAGE, ORIENTATION_IGNORED
            plan.findings.push_back(make_finding(c, role, outcomes[i].used->file, msg));
        plan.inputs.emplace(role, *outcomes[i].used);
        if (mode == PlanMode::decode) plan.decoded.emplace(outcomes[i].used->file, std::move(outcomes[i].decoded));
        maps.push_back(std::move(*outcomes[i].map));
    }
    // The candidates not used are still files of the set a user ships: the rules of a map alone
    // judge them too (streamed from the file in both modes), so a defect in a WebP copy beside
    // its JPEG original is reported. Those that cannot be read were reported above or are now.
    for (size_t i = 0; i < orders.size(); ++i) {
        const Role role = d.choices[i].role;
        bool past_used = outcomes[i].used == nullptr;
        for (const Candidate* c : orders[i]) {
            if (!past_used) {
                past_used = c == outcomes[i].used;
                continue;
            }
            if (!outcomes[i].used) break;  // all failed: each was reported
            std::string err;
            auto m = validate::make_map_input(role, files.opened.at(c->file), c->file, c->match.normal, err);
            if (!m) {
                plan.findings.push_back(make_finding(code::unreadable_file, role, c->file,
                                                     err + "; the file is skipped"));
                continue;
            }
            m->alternate = true;
            maps.push_back(std::move(*m));
        }
    }
}

// Serves decoded maps to the rules band by band, as validate::read_file_bands would read them:
// an 8-bit map as its codes (the rules read them through unorm8_values: the same figures, and
// the map is never converted to floats), a float map as its floats.
validate::BandReader memory_reader(std::map<std::string, const DecodedMap*> by_display) {
    return [by_display = std::move(by_display)](const InputFile& in, int band_rows, ImageInfo& info, std::string& error,
                                                const std::function<void(int, int, validate::Samples)>& fn) {
        const auto it = by_display.find(in.display);
        if (it == by_display.end()) return validate::read_file_bands(in, band_rows, info, error, fn);  // an alternate
        const Decoded& d = it->second->img;
        info = it->second->info;
        for (int y0 = 0; y0 < d.height(); y0 += band_rows) {
            const int rows = std::min(band_rows, d.height() - y0);
            if (d.is_codes()) fn(y0, rows, {nullptr, &d.codes.pixels[d.codes.index(0, y0)]});
            else fn(y0, rows, {&d.floats.pixels[d.floats.index(0, y0)]});
        }
        return true;
    };
}

// The normal map's convention: the name's, else the content's verdict (validate_set decides).
manifest::NormalFacts normal_facts(const Candidate& c, const std::optional<validate::NormalCheck>& check) {
    manifest::NormalFacts f;
    f.convention = c.match.normal;
    if (f.convention != NormalConvention::unknown) f.source = "name";
    if (check && check->file == c.file) {
        f.convention = check->resolved;
        f.source = check->source == "none" ? "" : check->source;
        if (check->source == "content") {
            f.confidence = check->content.confidence;
            f.method = check->content.method;
        }
    }
    return f;
}

// Routes over the maps that were read; the albedo's alpha is the opacity only when some texel
// is below opaque (codes 254 and below read under 0.999).
void route(SetPlan& plan, const validate::SetValidation& checked) {
    plan.routes = route_roles(
        [&](Role r) {
            const auto it = plan.inputs.find(r);
            return it == plan.inputs.end() ? 0 : std::max(0, it->second.header.channels);
        },
        true,
        [&](Role out, Role from) {
            const auto& u = plan.inputs.at(from).match.unused;
            return std::find(u.begin(), u.end(), out) != u.end();
        });
    // A map that is no tangent-space normal map is not written as one: a flat normal instead,
    // and its NORMAL_INVALID error says so.
    if (const auto n = plan.routes.find(Role::normal); n != plan.routes.end() && checked.normal_invalid) {
        const std::string& file = plan.inputs.at(n->second.from).file;
        for (auto& f : plan.findings)
            if (f.code == code::normal_invalid && f.file == file)
                f.message += "; it is not written into the normal slot: the material gets a flat normal";
        plan.routes.erase(n);
    }
    const auto op = plan.routes.find(Role::opacity);
    if (op == plan.routes.end()) return;
    // An opacity that hides the whole surface is not what the artist meant (3dtextures.me ships
    // all-black placeholders): not applied, the material stays opaque (OPACITY_ALL_TRANSPARENT).
    // The file keeps its role in the manifest's inputs: it is the set's opacity map, unused.
    if (checked.opacity_invisible) {
        plan.routes.erase(op);
        return;
    }
    if (!op->second.from_alpha) return;
    if (!checked.albedo_alpha_min || !(*checked.albedo_alpha_min < 0.999)) {
        plan.routes.erase(op);
        return;
    }
    plan.findings.push_back(make_finding(code::packed_input_unpacked, Role::opacity, plan.inputs.at(Role::albedo).file,
                                         "opacity taken from the albedo map's alpha channel"));
}

// "R = metalness, A = smoothness (roughness = 1 - A)" for a packed role: every channel it holds,
// what it leaves unused, and what a channel the file lacks means.
std::string packing_text(Role p, int file_channels) {
    static constexpr const char* kCh[] = {"R", "G", "B", "A"};
    const auto layout = packed_layout(p);
    std::string parts;
    for (size_t i = 0; i < layout.size(); ++i) {
        if (!layout[i]) continue;
        std::string part = std::string(kCh[i]) + " = ";
        part += layout[i]->invert ? "smoothness (" + std::string(role_name(layout[i]->role)) + " = 1 - " + kCh[i] + ")"
                                  : std::string(role_name(layout[i]->role));
        if (static_cast<int>(i) >= file_channels)
            part += " (missing: the file has " + std::to_string(file_channels) + " channels)";
        parts += (parts.empty() ? "" : ", ") + part;
    }
    if (p == Role::ort) parts += " (translucency is not metalness)";
    if (p == Role::mask_map) parts += "; B is the detail mask, not used";
    if (p == Role::specular_smoothness)
        parts += "; RGB is the specular colour of a specular-workflow material: kept as it is, never read as "
                 "metalness (metalness takes the preset's constant)";
    return parts;
}

// ["R=metalness", "A=smoothness"]: the packing as a finding's figure states it.
std::vector<std::string> packing_figure(Role p) {
    std::vector<std::string> f;
    for (const auto& [channel, what] : packing_channels(p)) f.push_back(channel + "=" + what);
    return f;
}

// What each route does to its input, said once: the normal convention conversion, gloss
// inversion and packed inputs split into roles.
void conversion_findings(SetPlan& plan, NormalConvention target) {
    std::set<Role> unpacked;
    for (const auto& [out, r] : plan.routes) {
        const Candidate& c = plan.inputs.at(r.from);
        if (out == Role::normal) {
            const NormalConvention from = plan.normal_from();
            if (from != target)
                plan.findings.push_back(
                    make_finding(code::normal_convention_converted, out, c.file,
                                 "green channel flipped from " + std::string(convention_name(from)) + " to " +
                                     std::string(convention_name(target)) + " for the preset",
                                 {{"from", convention_name(from)}, {"to", convention_name(target)}}));
        }
        if (r.invert && out == Role::height)
            plan.findings.push_back(make_finding(code::height_stored_as_depth, out, c.file,
                                                 c.file + " is stored as depth (white = deep: " +
                                                     (plan.height_named_depth
                                                          ? "its name says so, and no normal map's slopes say otherwise"
                                                          : "its slopes run against the normal map's") +
                                                     "); read inverted, so a height output is white = high"));
        else if (r.invert && !traits(r.from).packed)  // a packed smoothness channel: said below
            plan.findings.push_back(make_finding(code::gloss_inverted, out, c.file,
                                                 "gloss map converted to roughness (roughness = 1 - gloss)"));
        if (traits(r.from).packed) unpacked.insert(r.from);
    }
    for (Role p : unpacked) {
        const Candidate& c = plan.inputs.at(p);
        plan.findings.push_back(make_finding(code::packed_input_unpacked, p, c.file,
                                             "packed " + std::string(role_name(p)) + " map split into " +
                                                 packing_text(p, std::max(0, c.header.channels)),
                                             {{"channels", packing_figure(p)}, {"rule", c.match.rule}}));
    }
}

// One size for the set. The routed maps' shapes are compared, not their widths and heights
// apart: an N×1 albedo beside a 1×N roughness must not become an N×N set (N² pixels resampled
// from N). Maps whose aspect ratios are within 2x of each other share a shape; the set takes the
// shape most maps have (ties: the largest map's, then role order) at the size of the largest map
// of that shape, so the set never holds more pixels than its largest file (the per-file pixel
// budget bounds the set). A map of another shape is not stretched: ASPECT_MISMATCH (error) names
// it and both sizes, and its roles take the preset's constants. Maps of at most 4x4 pixels hold
// a constant in all but name and fit any shape. limit_size() then applies the preset's max_size.
void decide_size(SetPlan& plan) {
    struct Map {
        Role role;
        int w, h;
    };
    std::vector<Map> maps;
    for (const auto& [out, r] : plan.routes) {
        const HeaderInfo& hd = plan.inputs.at(r.from).header;
        // A copy: clang 14 cannot capture a structured binding.
        if (std::none_of(maps.begin(), maps.end(), [from = r.from](const Map& m) { return m.role == from; }))
            maps.push_back({r.from, std::max(1, hd.width), std::max(1, hd.height)});
    }
    std::sort(maps.begin(), maps.end(), [](const Map& a, const Map& b) { return a.role < b.role; });
    auto pixels = [](const Map& m) { return int64_t{m.w} * m.h; };
    auto tiny = [](const Map& m) { return std::max(m.w, m.h) <= 4; };
    // Within 2x: w1/h1 <= 2 w2/h2 and w2/h2 <= 2 w1/h1, in integers.
    auto fits = [](int w1, int h1, int w2, int h2) {
        return int64_t{w1} * h2 <= 2 * int64_t{w2} * h1 && int64_t{w2} * h1 <= 2 * int64_t{w1} * h2;
    };
    const Map* shape = nullptr;
    int best = -1;
    for (const Map& m : maps) {
        if (tiny(m)) continue;
        int n = 0;
        for (const Map& o : maps) n += tiny(o) || fits(m.w, m.h, o.w, o.h);
        if (n > best || (n == best && pixels(m) > pixels(*shape))) {
            best = n;
            shape = &m;
        }
    }
    int w = 0, h = 0;
    const Map* largest = nullptr;
    for (const Map& m : maps)
        if ((!shape || tiny(m) || fits(shape->w, shape->h, m.w, m.h)) && (!largest || pixels(m) > pixels(*largest)))
            largest = &m;
    if (largest) {
        w = largest->w;
        h = largest->h;
    }
    for (const Map& m : maps) {
        if (tiny(m) || fits(w, h, m.w, m.h)) continue;
        const std::string file = plan.inputs.at(m.role).file;
        plan.findings.push_back(make_finding(code::aspect_mismatch, m.role, file,
                                             file + " is " + std::to_string(m.w) + "x" + std::to_string(m.h) +
                                                 ", a shape more than 2x off the set's " + std::to_string(w) + "x" +
                                                 std::to_string(h) + " (" + plan.inputs.at(largest->role).file +
                                                 "); it is not stretched to fit and not used",
                                             {{"size", {m.w, m.h}}, {"set_size", {w, h}}}));
        for (auto it = plan.routes.begin(); it != plan.routes.end();)
            it = it->second.from == m.role ? plan.routes.erase(it) : std::next(it);
        plan.inputs.erase(m.role);
        if (std::none_of(plan.inputs.begin(), plan.inputs.end(), [&](const auto& i) { return i.second.file == file; }))
            plan.decoded.erase(file);
    }
    // RESOLUTION_MISMATCH: here, where the set's size is decided, for each kept map that is
    // resampled to it (the refused ones are not used at all: ASPECT_MISMATCH said so). Not for a
    // tiny map: a constant written small (ingest's own 2x2 outputs, CONSTANT_MAP's advice), which
    // stretching does not change; validating matforge's outputs warned of each.
    std::map<std::string, std::string> sizes;  // by file name, as the figure lists them
    for (const Map& m : maps)
        if (const auto in = plan.inputs.find(m.role); in != plan.inputs.end())
            sizes[in->second.file] = in->second.file + " " + std::to_string(m.w) + "x" + std::to_string(m.h);
    std::vector<std::string> size_list;
    size_list.reserve(sizes.size());
    for (const auto& [file, text] : sizes) size_list.push_back(text);
    std::set<std::string> said;
    for (const Map& m : maps) {
        const auto in = plan.inputs.find(m.role);
        if (in == plan.inputs.end() || (m.w == w && m.h == h) || tiny(m) || !said.insert(in->second.file).second)
            continue;
        const std::string& file = in->second.file;
        plan.findings.push_back(make_finding(
            code::resolution_mismatch, m.role, file,
            file + " is " + std::to_string(m.w) + "x" + std::to_string(m.h) + " but the set is " + std::to_string(w) +
                "x" + std::to_string(h) + " (" + plan.inputs.at(largest->role).file + "); it will be resampled",
            {{"width", m.w}, {"height", m.h}, {"reference_width", w}, {"reference_height", h}, {"sizes", size_list}}));
    }
    plan.width = w;
    plan.height = h;
}

// The set's size within the preset's max_size (RESIZED).
void limit_size(SetPlan& plan, const Preset& preset) {
    int w = plan.width, h = plan.height;
    if (preset.max_size > 0 && std::max(w, h) > preset.max_size) {
        const int ow = w, oh = h;
        const double k = static_cast<double>(preset.max_size) / std::max(w, h);
        w = std::max(1, static_cast<int>(std::lround(w * k)));
        h = std::max(1, static_cast<int>(std::lround(h * k)));
        plan.findings.push_back(finding(code::resized, "", "",
                                        "downsampled from " + std::to_string(ow) + "x" + std::to_string(oh) + " to " +
                                            std::to_string(w) + "x" + std::to_string(h) + " (preset max_size " +
                                            std::to_string(preset.max_size) + ")",
                                        {{"from", {ow, oh}}, {"to", {w, h}}}));
    }
    plan.width = w;
    plan.height = h;
}

}  // namespace

NormalConvention SetPlan::normal_from() const {
    return normal && normal->convention != NormalConvention::unknown ? normal->convention : NormalConvention::gl;
}

namespace {

// Discovery, the start of every plan: each file's role by its name and the set's sidecars, the
// rules' exclusions, one file chosen per role (headers read through `files`); the findings it
// raises, then the set's own (NAMES_MERGED, …), then LICENCE_UNKNOWN when the set's provenance
// (into `provenance` when given) has no licence.
SetDiscovery discover_in(const MaterialSource& src, Files& files, const Preset& preset, const rules::RuleConfig* rules,
                         Provenance* provenance = nullptr) {
    auto header = [&](const std::string& f) -> std::optional<HeaderInfo> {
        std::string err;
        auto info = read_info(files.open(f), err);
        if (!info) return std::nullopt;
        return HeaderInfo{info->width, info->height, info->channels, info->bit_depth, info->is_float};
    };
    // Files the rules exclude are no candidates (an unrecognized file each, saying why).
    std::vector<std::string> candidates;
    std::vector<Finding> excluded;
    for (const std::string& f : src.files) {
        const rules::Exclusion* e = rules ? rules->excluded(src.name, f) : nullptr;
        if (!e) {
            candidates.push_back(f);
            continue;
        }
        const std::string why = "excluded by the rules (\"" + e->file + "\"" +
                                (e->reason.empty() ? std::string() : ": " + e->reason) + ")";
        excluded.push_back(finding(code::unrecognized_file, "", f, why + "; not used as a map", {{"reason", why}}));
    }
    const rules::Thresholds thresholds = rules ? rules->thresholds : rules::Thresholds{};
    auto colour = [&](const std::string& f) { return is_colour_image(files.open(f), thresholds); };
    auto normal = [&](const std::string& f) { return validate::is_tangent_normal_map(files.open(f), thresholds); };
    const std::vector<SidecarRoles> sidecars = read_sidecars(files);
    SetDiscovery d = discover_set(candidates, header,
                                  ChoicePolicy{preset.normal_convention, preset.max_size, src.shared_folder}, sidecars,
                                  colour, normal);
    d.findings.insert(d.findings.end(), excluded.begin(), excluded.end());
    d.findings.insert(d.findings.end(), src.findings.begin(), src.findings.end());
    ProvenanceResult found = find_provenance({candidates, d, sidecars, read_licence_files(files, candidates),
                                              src.shared_folder});
    if (!found.provenance.licence)
        d.findings.push_back(finding(code::licence_unknown, "", std::move(found.unknown_file), std::move(found.unknown),
                                     std::move(found.figures)));
    if (provenance) *provenance = std::move(found.provenance);
    return d;
}

SetPlan plan_once(const MaterialSource& src, const PlanOptions& opt, const std::map<std::string, std::string>& failed,
                  std::map<std::string, std::string>& newly_failed) {
    const Preset& preset = *opt.preset;
    SetPlan plan;
    Files files{src, {}};
    const SetDiscovery d = discover_in(src, files, preset, opt.rules, &plan.provenance);
    plan.convention = d.convention;
    plan.preview = d.preview;
    plan.findings = d.findings;
    plan.footprint = estimated_bytes(d);
    // A share keeps no copy: the set's next plan reads the same decoded maps (SharedMap).
    if (opt.mode == PlanMode::decode) plan.lease = std::make_unique<BudgetLease>(opt.budget, plan.footprint);

    // Sets of 4 Mpixel maps and up decode their maps on two threads, and any set while a core is
    // idle; small ones stay on one otherwise (the batch is already parallel across sets).
    std::vector<validate::MapInput> maps;
    read_choices(plan, files, d, opt.mode, plan.footprint > (uint64_t{64} << 20), opt.spare_core, opt.share, failed,
                 maps);
    if (maps.empty()) {
        std::string msg = src.display + ": no map of the set could be read";
        for (const auto& f : plan.findings)
            if (f.code == code::unreadable_file) msg += "; " + f.message;
        plan.failure = std::move(msg);
        return plan;
    }

    validate::ValidateOptions vo;
    vo.material = src.name;
    if (opt.mode == PlanMode::decode) {
        std::map<std::string, const DecodedMap*> by_display;
        for (const auto& [role, c] : plan.inputs)
            by_display[files.open(c.file).display] = plan.decoded.at(c.file).get();
        vo.reader = memory_reader(std::move(by_display));
    }
    const validate::SetValidation checked = opt.share ? opt.share->validate(maps, *opt.rules, vo)
                                                      : validate::validate_set(maps, *opt.rules, vo);
    // Stream mode reads a map's header here and its pixels in the rules: a chosen map whose pixels
    // fail is planned again as decode mode saw it, a file that does not read (the next candidate,
    // or no map: MISSING_MAP).
    for (const auto& [role, c] : plan.inputs)
        if (const auto bad = checked.unreadable.find(c.file); bad != checked.unreadable.end())
            newly_failed.insert(*bad);
    if (!newly_failed.empty()) return plan;
    plan.findings.insert(plan.findings.end(), checked.findings.begin(), checked.findings.end());
    maps.clear();
    files.opened.clear();  // read (decode mode) or streamed (stream mode): free zip bytes early

    route(plan, checked);
    decide_size(plan);  // first: a map it leaves out (ASPECT_MISMATCH) is converted by nothing
    plan.normal_z_rebuilt = checked.normal_z_rebuilt;
    if (const auto n = plan.routes.find(Role::normal); n != plan.routes.end())
        plan.normal = normal_facts(plan.inputs.at(n->second.from), checked.normal);
    // A height map the GL/DX test found stored as depth (white = deep) is read inverted: every
    // output holds height white = high (HEIGHT_STORED_AS_DEPTH, conversion_findings). So is one
    // named depth (families.cpp "depth") unless the slopes show it holds height.
    if (const auto h = plan.routes.find(Role::height); h != plan.routes.end() && h->second.from == Role::height) {
        const validate::NormalVerdict* slopes = checked.normal ? &checked.normal->content : nullptr;
        const bool named = plan.inputs.at(Role::height).match.rule == naming::kDepthRule;
        if (slopes && slopes->height_is_depth) {
            h->second.invert = true;
        } else if (named && !(slopes && slopes->height_is_height)) {
            h->second.invert = true;
            plan.height_named_depth = true;
        }
    }
    conversion_findings(plan, preset.normal_convention);
    limit_size(plan, preset);

    // Missing roles: constants where an output needs them, reported per the preset.
    std::set<Role> available;
    for (const auto& [r, route] : plan.routes) available.insert(r);
    const std::set<Role> written = written_roles(preset, available);
    auto missing = missing_map_findings(preset, available, written, plan.constants, opt.mode == PlanMode::decode);
    plan.findings.insert(plan.findings.end(), missing.begin(), missing.end());
    // A map that shades the surface but that no output of the preset holds (d3d11 has no
    // occlusion or emission texture): said, never dropped without a word. Height, a displacement
    // input, is not a shading term an engine without a slot for it loses.
    for (const auto& [r, route] : plan.routes) {
        if (written.count(r) || (r != Role::occlusion && r != Role::emissive && r != Role::opacity)) continue;
        const std::string rn(role_name(r));
        plan.findings.push_back(make_finding(code::map_not_written, r, plan.inputs.at(route.from).file,
                                             "the preset '" + preset.name + "' has no output for " + rn + ": " +
                                                 plan.inputs.at(route.from).file +
                                                 " is read but not written, and the engine renders without it",
                                             {{"preset", preset.name}}));
    }
    return plan;
}

}  // namespace

SetDiscovery discover_roles(const MaterialSource& src, const Preset& preset, const rules::RuleConfig* rules) {
    Files files{src, {}};
    return discover_in(src, files, preset, rules);
}

SetPlan plan_set(const MaterialSource& src, const PlanOptions& opt) {
    std::map<std::string, std::string> failed;
    for (;;) {  // at most once more per chosen map: each pass fails at least one more file
        std::map<std::string, std::string> newly_failed;
        SetPlan plan = plan_once(src, opt, failed, newly_failed);
        if (newly_failed.empty()) return plan;
        failed.merge(newly_failed);
    }
}

std::vector<Finding> reported_findings(std::vector<Finding> findings, const std::string& material,
                                       const rules::RuleConfig& rules) {
    rules::apply_config(findings, material, rules);
    return findings;
}

manifest::Material material_entry(SetPlan& plan, const std::string& name, std::string source,
                                  const rules::RuleConfig& rules) {
    manifest::Material m;
    m.name = name;
    m.source = std::move(source);
    m.convention = plan.convention;
    m.status = plan.partial ? manifest::Status::partial : manifest::Status::ok;
    m.inputs = manifest_inputs(plan);
    if (!plan.provenance.empty()) m.provenance = plan.provenance;
    m.constants = std::move(plan.constants);
    m.findings = reported_findings(std::move(plan.findings), name, rules);
    return m;
}

std::vector<manifest::Input> manifest_inputs(const SetPlan& plan) {
    std::vector<manifest::Input> inputs;
    for (const auto& [role, c] : plan.inputs) {
        manifest::Input in;
        in.role = role;
        in.file = c.file;
        in.family = c.match.family;
        in.rule = c.match.rule;
        const HeaderInfo& hd = c.header;
        in.width = hd.width;
        in.height = hd.height;
        in.channels = hd.channels;
        in.bit_depth = hd.bit_depth;
        in.is_float = hd.is_float;
        in.color_space = !is_color_role(role) ? "data" : hd.is_float ? "linear" : "sRGB";
        if (role == Role::normal) in.normal = plan.normal.value_or(manifest::NormalFacts{});
        if (const auto h = plan.routes.find(Role::height); role == Role::height && h != plan.routes.end())
            in.stored_as_depth = h->second.from == Role::height && h->second.invert;
        // An opacity map no route reads is not applied (route(): it would hide the whole surface).
        // A normal map that is no normal map (NORMAL_INVALID) is not applied either (route()).
        in.unused = (role == Role::opacity || role == Role::normal) && !plan.routes.count(role);
        inputs.push_back(std::move(in));
    }
    if (plan.preview) {  // recorded as discovery found it (its header): never read as a map
        const Candidate& c = *plan.preview;
        manifest::Input in;
        in.role = Role::preview;
        in.file = c.file;
        in.family = c.match.family;
        in.rule = c.match.rule;
        in.width = c.header.width;
        in.height = c.header.height;
        in.channels = c.header.channels;
        in.bit_depth = c.header.bit_depth;
        in.is_float = c.header.is_float;
        in.color_space = c.header.is_float ? "linear" : "sRGB";
        inputs.push_back(std::move(in));
    }
    return inputs;
}

}  // namespace mf
