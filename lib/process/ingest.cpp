#include "process/ingest.hpp"

#include <algorithm>
#include <map>
#include <mutex>
#include <set>
#include <thread>

#include "core/files.hpp"
#include "core/json.hpp"
#include "core/parallel.hpp"
#include "material/discovery.hpp"
#include "pack/pack.hpp"
#include "process/missing.hpp"
#include "validate/validate.hpp"

namespace mf {
namespace fs = std::filesystem;
namespace {

struct Loaded {
    Decoded img;  // 8-bit files stay codes until a step needs floats
    ImageInfo info;
};

// The decoded state of one set, shared by the steps of Ingestor::process.
struct SetState {
    const MaterialSource& src;
    std::map<std::string, InputFile> opened;  // each file opened once (zip entries read once)
    std::map<std::string, Loaded> loaded;     // decoded maps by file
    std::map<Role, const Candidate*> used;    // input role -> the candidate that decoded
    std::vector<Finding> findings;
    bool partial = false;

    const InputFile& open(const std::string& f) {
        auto it = opened.find(f);
        if (it == opened.end()) it = opened.emplace(f, src.open(f)).first;
        return it->second;
    }
    void add(std::string_view code, Severity s, Role role, std::string file, std::string msg,
             nlohmann::json figures = nlohmann::json::object()) {
        findings.push_back({std::string(code), s, std::string(role_name(role)), std::move(file), std::move(msg),
                            std::move(figures)});
    }
};

std::string input_color_space(Role r, const ImageInfo& info) {
    if (!is_color_role(r)) return "data";
    return info.is_float ? "linear" : "sRGB";
}

bool has_real_alpha(const Decoded& d) {
    const int nc = d.channels();
    if (nc != 4 && nc != 2) return false;
    auto any_alpha_below = [step = static_cast<size_t>(nc)](const auto& pixels, auto limit) {
        for (size_t i = step - 1; i < pixels.size(); i += step)
            if (pixels[i] < limit) return true;
        return false;
    };
    // Code 254 reads as 0.996, 255 as 1: the same test on codes and on floats.
    return d.is_codes() ? any_alpha_below(d.codes.pixels, uint8_t{255}) : any_alpha_below(d.floats.pixels, 0.999f);
}

std::string relative_to(const fs::path& p, const fs::path& base) {
    std::error_code ec;
    const fs::path a = fs::absolute(p, ec).lexically_normal();
    const fs::path b = fs::absolute(base, ec).lexically_normal();
    fs::path r = a.lexically_relative(b);
    if (r.empty()) r = a;
    return r.generic_string();
}

std::string source_of(const MaterialSource& s, const fs::path& out_dir) {
    return relative_to(s.root, out_dir) + (s.is_zip && !s.zip_folder.empty() ? "/" + s.zip_folder : "");
}

nlohmann::json channels_json(const std::vector<ChannelSpec>& channels) {
    nlohmann::json j = nlohmann::json::object();
    for (const auto& c : channels) {
        switch (c.kind) {
            case ChannelSpec::Kind::role: j[c.key] = role_name(c.role); break;
            case ChannelSpec::Kind::smoothness: j[c.key] = "smoothness"; break;
            case ChannelSpec::Kind::constant: j[c.key] = c.value; break;
            case ChannelSpec::Kind::unused: j[c.key] = "unused"; break;
        }
    }
    return j;
}

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

// Decodes the chosen map of every input role (in parallel for large sets: one decoder runs on
// one core), falling back to the next candidate.
void load_maps(SetState& st, const SetDiscovery& d, int threads) {
    std::vector<std::vector<const Candidate*>> orders;
    for (const auto& choice : d.choices) {
        std::vector<const Candidate*> order{&choice.chosen};
        for (const auto& r : choice.rejected) order.push_back(&r);
        for (const Candidate* c : order) st.open(c->file);  // the map is not thread-safe
        orders.push_back(std::move(order));
    }
    struct Outcome {
        const Candidate* used = nullptr;
        Loaded loaded;
        std::vector<std::pair<const Candidate*, std::string>> errors;
    };
    std::vector<Outcome> outcomes(orders.size());
    parallel_for(orders.size(), threads, [&](size_t i) {
        for (const Candidate* c : orders[i]) {
            std::string err;
            if (read_image(st.opened.at(c->file), outcomes[i].loaded.img, outcomes[i].loaded.info, err)) {
                outcomes[i].used = c;
                return;
            }
            outcomes[i].errors.emplace_back(c, err);
        }
    });
    for (size_t i = 0; i < orders.size(); ++i) {
        const Role role = d.choices[i].role;
        for (const auto& [c, err] : outcomes[i].errors) {
            st.partial = true;
            st.add(code::unreadable_file, Severity::error, role, c->file, err + "; the file is skipped");
        }
        if (!outcomes[i].used) continue;
        st.used[role] = outcomes[i].used;
        st.loaded.emplace(outcomes[i].used->file, std::move(outcomes[i].loaded));
    }
}

// Runs every validation rule over the decoded maps (served from memory, not read again).
validate::SetValidation validate_loaded(SetState& st, const validate::RuleConfig& rules) {
    std::vector<validate::MapInput> maps;
    std::map<std::string, const Loaded*> by_display;
    for (const auto& [role, c] : st.used) {
        validate::MapInput m;
        m.role = role;
        m.file = st.open(c->file);
        m.name = c->file;
        m.info = st.loaded.at(c->file).info;
        m.color_tag = validate::read_color_tag(m.file);
        m.name_convention = c->match.normal;
        by_display[m.file.display] = &st.loaded.at(c->file);
        maps.push_back(std::move(m));
    }
    validate::ValidateOptions vo;
    vo.material = st.src.name;
    vo.reader = [&by_display](const InputFile& in, int band_rows, ImageInfo& info, std::string& error,
                              const std::function<void(int, int, const float*)>& fn) {
        const auto it = by_display.find(in.display);
        if (it == by_display.end()) {
            error = in.display + ": not decoded";
            return false;
        }
        const Decoded& d = it->second->img;
        info = it->second->info;
        if (!d.is_codes()) {
            for (int y0 = 0; y0 < d.floats.height; y0 += band_rows)
                fn(y0, std::min(band_rows, d.floats.height - y0), &d.floats.pixels[d.floats.index(0, y0)]);
            return true;
        }
        // Codes are served as the floats read_image would give, one band at a time (the band
        // stays in cache; the map is never held as floats).
        const Image8& c = d.codes;
        std::vector<float> band(static_cast<size_t>(c.width) * c.channels * static_cast<size_t>(band_rows));
        for (int y0 = 0; y0 < c.height; y0 += band_rows) {
            const int rows = std::min(band_rows, c.height - y0);
            to_float(&c.pixels[c.index(0, y0)], static_cast<size_t>(c.width) * c.channels * static_cast<size_t>(rows),
                     band.data());
            fn(y0, rows, band.data());
        }
        return true;
    };
    return validate::validate_set(maps, rules, vo);
}

// The normal map's convention: the name's, else the content's (validation's verdict).
struct NormalFacts {
    NormalConvention convention = NormalConvention::unknown;
    nlohmann::json manifest = nlohmann::json::object();
};
NormalFacts normal_facts(const Candidate& c, const std::optional<validate::NormalCheck>& check) {
    NormalFacts f;
    f.convention = c.match.normal;
    std::string source = f.convention == NormalConvention::unknown ? "none" : "name";
    double confidence = 1.0;
    if (check && check->file == c.file) {
        f.convention = check->resolved;
        source = check->source;
        confidence = check->content.confidence;
    }
    f.manifest["normal_convention"] = convention_name(f.convention);
    if (source != "none") f.manifest["normal_convention_source"] = source;
    if (source == "content") f.manifest["normal_convention_confidence"] = confidence;
    return f;
}

// Set indices, largest input first (longest-processing-time scheduling): a 4K set started last
// would leave the other threads idle while it runs alone. Sizes come from the file system (a
// set inside a .zip counts its archive's size); results keep input order whatever this says.
std::vector<size_t> largest_first(const std::vector<MaterialSource>& sets) {
    std::vector<uintmax_t> bytes(sets.size(), 0);
    for (size_t i = 0; i < sets.size(); ++i) {
        std::error_code ec;
        if (sets[i].is_zip) {
            const uintmax_t b = fs::file_size(sets[i].root, ec);
            bytes[i] = ec ? 0 : b;
            continue;
        }
        for (const auto& f : sets[i].files) {
            const uintmax_t b = fs::file_size(sets[i].root / f, ec);
            if (!ec) bytes[i] += b;
        }
    }
    std::vector<size_t> order(sets.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return bytes[a] > bytes[b]; });
    return order;
}

}  // namespace

Ingestor::Ingestor(Preset preset, std::shared_ptr<const ColorContext> color, IngestOptions opt)
    : preset_(std::move(preset)), color_(std::move(color)), opt_(std::move(opt)) {
    // --normal-convention overrides the preset everywhere: choice, conversion, encoding, manifest.
    if (opt_.normal_override) preset_.normal_convention = *opt_.normal_override;
}

MaterialResult Ingestor::process(const MaterialSource& src, MemoryBudget* budget) const {
    struct InFlight {  // counts this set as running until it returns or throws
        std::atomic<int>& n;
        explicit InFlight(std::atomic<int>& c) : n(c) { ++n; }
        ~InFlight() { --n; }
        InFlight(const InFlight&) = delete;
        InFlight& operator=(const InFlight&) = delete;
    } in_flight(in_flight_);
    MaterialResult res;
    SetState st{src, {}, {}, {}, {}, false};
    const NormalConvention target = preset_.normal_convention;

    auto header = [&](const std::string& f) -> std::optional<HeaderInfo> {
        std::string err;
        auto info = read_info(st.open(f), err);
        if (!info) return std::nullopt;
        return HeaderInfo{info->width, info->height, info->channels, info->bit_depth, info->is_float};
    };
    const SetDiscovery d = discover_set(src.files, header, ChoicePolicy{target, preset_.max_size});
    st.findings.insert(st.findings.end(), d.findings.begin(), d.findings.end());
    const uint64_t footprint = estimated_bytes(d);
    const BudgetLease lease(budget, footprint);
    // Sets of 4 Mpixel maps and up decode their maps on two threads; small ones stay on one
    // (the batch is already parallel across sets).
    load_maps(st, d, footprint > (uint64_t{64} << 20) ? 2 : 1);
    if (st.loaded.empty()) {
        res.failed = true;
        res.failure_message = src.display + ": no map of the set could be read";
        for (const auto& f : st.findings)
            if (f.code == code::unreadable_file) res.failure_message += "; " + f.message;
        return res;
    }
    const validate::SetValidation checked = validate_loaded(st, opt_.rules);
    st.findings.insert(st.findings.end(), checked.findings.begin(), checked.findings.end());
    for (auto& [f, in] : st.opened) in.bytes.reset();  // decoded; free zip bytes early

    // Canonical planes per output role, from the best provider that decoded.
    Planes planes;
    std::map<Role, Provider> route_of;
    for (int ri = 0; ri < kOutputRoleCount; ++ri) {
        const Role out = static_cast<Role>(ri);
        for (const Provider& r : providers_of(out))
            if (st.used.count(r.from)) {
                route_of[out] = r;
                break;
            }
    }
    // Opacity carried in the albedo's alpha, when no opacity map exists.
    if (!route_of.count(Role::opacity) && route_of.count(Role::albedo) && route_of[Role::albedo].channel < 0) {
        const Candidate& c = *st.used.at(route_of[Role::albedo].from);
        const Decoded& img = st.loaded.at(c.file).img;
        if (has_real_alpha(img)) {
            route_of[Role::opacity] = Provider{route_of[Role::albedo].from, img.channels() - 1, false};
            st.add(code::packed_input_unpacked, Severity::info, Role::opacity, c.file,
                   "opacity taken from the albedo map's alpha channel");
        }
    }
    // A decoded map is freed after its last plane is made: peak memory is one set's maps.
    std::map<std::string, int> uses;
    for (const auto& [out, route] : route_of) ++uses[st.used.at(route.from)->file];

    std::set<Role> unpacked;
    nlohmann::json normal_manifest = nlohmann::json::object();
    for (const auto& [out, route] : route_of) {
        const Candidate& c = *st.used.at(route.from);
        Loaded& l = st.loaded.at(c.file);
        const bool last_use = --uses[c.file] == 0;
        RolePlane plane;
        Decoded& img = l.img;
        if (out == Role::albedo || out == Role::emissive) {
            if (img.is_codes()) plane.codes = last_use && img.codes.channels == 3 ? std::move(img.codes) : to_rgb(img.codes);
            else plane.image = last_use && img.floats.channels == 3 ? std::move(img.floats) : to_rgb(img.floats);
            plane.encoding = l.info.is_float ? ColorEncoding::linear : ColorEncoding::srgb;
        } else if (out == Role::normal) {
            const NormalFacts nf = normal_facts(c, checked.normal);
            normal_manifest = nf.manifest;
            if (nf.convention == NormalConvention::unknown)
                st.add(code::normal_convention_unknown, Severity::warning, out, c.file,
                       "neither the file name nor the content decides OpenGL (+Y) vs DirectX (-Y); assumed OpenGL: "
                       "check the preview, or rename the file with _gl/_dx");
            const NormalConvention effective =
                nf.convention == NormalConvention::unknown ? NormalConvention::gl : nf.convention;
            if (img.is_codes()) {  // decoded when packed (pack_output8) or resampled (fit_plane)
                plane.codes = last_use ? std::move(img.codes) : img.codes;
                plane.codes_convention = effective;
            } else {
                decode_normal(img.floats, nf.convention, plane.image);
            }
            if (effective != target)
                st.add(code::normal_convention_converted, Severity::info, out, c.file,
                       "green channel flipped from " + std::string(convention_name(effective)) + " to " +
                           std::string(convention_name(target)) + " for the preset",
                       {{"from", convention_name(effective)}, {"to", convention_name(target)}});
        } else {
            const int ch = route.channel < 0 ? 0 : route.channel;
            if (img.is_codes()) {
                plane.codes = last_use && img.codes.channels == 1 ? std::move(img.codes) : extract_channel(img.codes, ch);
                if (route.invert) invert(plane.codes);
            } else {
                plane.image = last_use && img.floats.channels == 1 ? std::move(img.floats) : extract_channel(img.floats, ch);
                if (route.invert) invert(plane.image);
            }
            if (route.invert)
                st.add(code::gloss_inverted, Severity::info, out, c.file,
                       "gloss map converted to roughness (roughness = 1 - gloss)");
        }
        if (last_use) st.loaded.erase(c.file);
        if (traits(route.from).packed) unpacked.insert(route.from);
        planes.emplace(out, std::move(plane));
    }
    for (Role p : unpacked) {
        std::string parts;
        const auto layout = packed_layout(p);
        static constexpr const char* kCh[] = {"R", "G", "B"};
        for (size_t i = 0; i < 3; ++i)
            if (layout[i]) parts += (parts.empty() ? "" : ", ") + std::string(kCh[i]) + " = " + std::string(role_name(*layout[i]));
        st.add(code::packed_input_unpacked, Severity::info, p, st.used.at(p)->file,
               "packed " + std::string(role_name(p)) + " map split into " + parts +
                   (p == Role::ort ? " (translucency is not metalness)" : ""));
    }
    st.loaded.clear();  // planes hold what is needed from here on

    // One size for the set: the largest map, within the preset's limit.
    int w = 0, h = 0;
    std::set<std::pair<int, int>> sizes;
    for (const auto& [r, p] : planes) {
        sizes.insert({p.width(), p.height()});
        w = std::max(w, p.width());
        h = std::max(h, p.height());
    }
    if (preset_.max_size > 0 && std::max(w, h) > preset_.max_size) {
        const int ow = w, oh = h;
        const double k = static_cast<double>(preset_.max_size) / std::max(w, h);
        w = std::max(1, static_cast<int>(std::lround(w * k)));
        h = std::max(1, static_cast<int>(std::lround(h * k)));
        st.findings.push_back({std::string(code::resized), Severity::info, "", "",
                               "downsampled from " + std::to_string(ow) + "x" + std::to_string(oh) + " to " +
                                   std::to_string(w) + "x" + std::to_string(h) + " (preset max_size " +
                                   std::to_string(preset_.max_size) + ")",
                               {{"from", {ow, oh}}, {"to", {w, h}}}});
    }
    for (auto& [r, p] : planes) fit_plane(r, p, w, h, *color_);

    // Missing roles: constants where an output needs them, reported per the preset.
    std::set<Role> available;
    for (const auto& [r, p] : planes) available.insert(r);
    nlohmann::json constants = nlohmann::json::object();
    auto missing = missing_map_findings(preset_, available, written_roles(preset_, available), constants);
    st.findings.insert(st.findings.end(), missing.begin(), missing.end());

    // Pack, encode, write.
    const fs::path mat_dir = opt_.out_dir / src.name;
    remove_stale_temps(mat_dir);
    // The outputs of a large set are packed and encoded on two threads (each output on one:
    // deflate is serial) when a worker is idle, so a 4K set running alone (at the end of a batch,
    // or on its own) keeps both cores busy; with every worker busy that would only oversubscribe.
    struct Written {
        std::optional<nlohmann::json> entry;  // set when written
        std::optional<Finding> failure;
    };
    std::vector<const OutputSpec*> wanted;
    for (const auto& o : preset_.outputs)
        if (output_needed(o, planes)) wanted.push_back(&o);
    std::vector<Written> written(wanted.size());
    auto write_output = [&](const OutputSpec& o) -> Written {
        auto failed = [](std::string msg) {
            return Written{std::nullopt, Finding{std::string(code::output_write_failed), Severity::error, "", "",
                                                 std::move(msg), {}}};
        };
        const std::string rel = preset_.output_path(src.name, o);
        const fs::path rel_path = fs::path(rel).lexically_normal();
        if (rel_path.is_absolute() || rel_path.empty() || *rel_path.begin() == "..")
            return failed("output path '" + rel + "' leaves the output folder; skipped");
        const auto roles = o.roles();
        const bool any_map = std::any_of(roles.begin(), roles.end(), [&](Role r) { return planes.count(r) > 0; });
        const Size size = any_map ? Size{w, h} : Size{preset_.constant_size, preset_.constant_size};
        // 8-bit outputs of codes planes go from codes to codes; anything else through floats.
        std::optional<Image8> packed8 = pack_output8(o, planes, preset_, size, *color_);
        const EncodeOptions enc{preset_.format, o.bit_depth};
        std::vector<unsigned char> bytes;
        std::string err;
        const bool encoded = packed8 ? encode_image(*packed8, enc, bytes, err)
                                     : encode_image(pack_output(o, planes, preset_, size, *color_), enc, bytes, err);
        packed8.reset();
        if (!encoded || !write_file_atomic(opt_.out_dir / rel_path, bytes, err)) return failed(rel + ": " + err);
        nlohmann::json e;
        e["file"] = rel_path.generic_string();
        e["color_space"] = o.srgb ? "sRGB" : "linear";
        e["channels"] = channels_json(effective_channels(o, planes));
        if (std::find(roles.begin(), roles.end(), Role::normal) != roles.end())
            e["normal_convention"] = convention_name(target);
        e["width"] = size.width;
        e["height"] = size.height;
        e["bit_depth"] = o.bit_depth;
        e["format"] = preset_.format;
        e["sha256"] = sha256_hex(bytes);
        return Written{std::move(e), std::nullopt};
    };
    const int workers = opt_.jobs > 0 ? opt_.jobs : static_cast<int>(std::max(1U, std::thread::hardware_concurrency()));
    const bool idle_worker = in_flight_.load() < workers;
    parallel_for(wanted.size(), footprint > (uint64_t{64} << 20) && idle_worker ? 2 : 1, [&](size_t i) {
        try {
            written[i] = write_output(*wanted[i]);
        } catch (const std::exception& e) {  // parallel_for's fn must not throw (bad_alloc)
            written[i].failure = Finding{std::string(code::output_write_failed), Severity::error, "", "",
                                         preset_.output_path(src.name, *wanted[i]) + ": " + e.what(), {}};
        }
    });
    nlohmann::json outputs = nlohmann::json::array();
    for (auto& r : written) {  // preset order, whatever finished first
        if (r.entry) outputs.push_back(std::move(*r.entry));
        if (r.failure) {
            st.findings.push_back(std::move(*r.failure));
            st.partial = true;
        }
    }

    validate::apply_config(st.findings, src.name, opt_.rules);  // suppressions reach every finding

    // Manifest entry.
    nlohmann::json inputs = nlohmann::json::object();
    for (const auto& [role, c] : st.used) {
        nlohmann::json in = {{"file", c->file}, {"family", c->match.family}, {"rule", c->match.rule}};
        const HeaderInfo& hd = c->header;
        in["width"] = hd.width;
        in["height"] = hd.height;
        in["channels"] = hd.channels;
        in["bit_depth"] = hd.bit_depth;
        in["color_space"] = input_color_space(role, ImageInfo{hd.width, hd.height, hd.channels, hd.bit_depth, hd.is_float, ""});
        if (hd.is_float) in["float"] = true;
        if (role == Role::normal) in.update(normal_manifest);
        inputs[std::string(role_name(role))] = std::move(in);
    }
    nlohmann::json m;
    m["name"] = src.name;
    m["source"] = source_of(src, opt_.out_dir);
    if (src.is_zip) m["archive"] = relative_to(src.root, opt_.out_dir);
    m["convention"] = d.convention;
    m["status"] = st.partial ? "partial" : "ok";
    m["inputs"] = std::move(inputs);
    m["constants"] = std::move(constants);
    m["outputs"] = std::move(outputs);
    nlohmann::json fj = nlohmann::json::array();
    for (const auto& f : st.findings) fj.push_back(to_json(f));
    m["findings"] = std::move(fj);
    res.manifest_entry = std::move(m);
    res.findings = std::move(st.findings);
    return res;
}

IngestResult Ingestor::run(const std::vector<fs::path>& inputs) const {
    IngestResult result;
    std::error_code ec;
    fs::create_directories(opt_.out_dir, ec);
    if (ec || !fs::is_directory(opt_.out_dir, ec)) {
        result.error = opt_.out_dir.string() + ": cannot create the output folder (" + ec.message() + ")";
        return result;
    }
    std::vector<SourceFailure> source_failures;
    const auto sets = find_material_sets(inputs, opt_.out_dir, source_failures);

    std::vector<MaterialResult> results(sets.size());
    MemoryBudget budget(opt_.memory_budget);
    std::mutex progress_mutex;
    size_t done = 0;
    const std::vector<size_t> order = largest_first(sets);
    parallel_for(sets.size(), opt_.jobs, [&](size_t k) {
        const size_t i = order[k];
        try {
            results[i] = process(sets[i], opt_.memory_budget ? &budget : nullptr);
        } catch (const std::exception& e) {  // a bug or exhaustion in one set must not stop the others
            results[i] = MaterialResult{};
            results[i].failed = true;
            results[i].failure_message = sets[i].display + ": internal error: " + e.what();
        }
        std::lock_guard lock(progress_mutex);
        ++done;
        if (opt_.progress)
            opt_.progress(done, sets.size(), sets[i].name,
                          results[i].failed ? "failed" : results[i].manifest_entry.value("status", "ok"));
    });

    nlohmann::json materials = nlohmann::json::array(), failures = nlohmann::json::array();
    for (size_t i = 0; i < sets.size(); ++i) {
        auto& r = results[i];
        if (r.failed) {
            failures.push_back({{"source", source_of(sets[i], opt_.out_dir)},
                                {"code", std::string(code::unreadable_file)},
                                {"message", r.failure_message}});
            result.worst = Severity::error;
            continue;
        }
        if (auto w = worst(r.findings); w && (!result.worst || *w > *result.worst)) result.worst = w;
        materials.push_back(std::move(r.manifest_entry));
    }
    for (const auto& f : source_failures) {
        failures.push_back({{"source", relative_to(f.source, opt_.out_dir)}, {"code", f.code}, {"message", f.message}});
        result.worst = Severity::error;
    }
    std::sort(materials.begin(), materials.end(), [](const auto& a, const auto& b) { return a["name"] < b["name"]; });
    std::sort(failures.begin(), failures.end(), [](const auto& a, const auto& b) { return a["source"] < b["source"]; });
    result.materials = materials.size();
    result.failures = failures.size();

    nlohmann::json m;
    m["manifest_version"] = 1;
    m["generator"] = "matforge 0.1.0";
    m["preset"] = preset_.name;
    m["normal_convention"] = convention_name(preset_.normal_convention);
    m["materials"] = std::move(materials);
    m["failures"] = std::move(failures);
    result.manifest = m;
    const std::string text = json_text(m);  // never throws on non-UTF-8 names
    std::string err;
    if (!write_file_atomic(opt_.out_dir / "manifest.json",
                           std::span(reinterpret_cast<const unsigned char*>(text.data()), text.size()), err))
        result.error = err;
    remove_stale_temps(opt_.out_dir);
    return result;
}

}  // namespace mf
