#include "process/ingest.hpp"

#include <algorithm>
#include <atomic>
#include <map>
#include <mutex>
#include <set>
#include <thread>

#include "core/files.hpp"
#include "material/discovery.hpp"
#include "pack/pack.hpp"

namespace mf {
namespace fs = std::filesystem;
namespace {

struct Loaded {
    Image img;
    ImageInfo info;
};

std::string input_color_space(Role r, const ImageInfo& info) {
    if (!is_color_role(r)) return "data";
    return info.is_float ? "linear" : "sRGB";
}

std::string format_number(float v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", static_cast<double>(v));
    return buf;
}

bool has_real_alpha(const Image& img) {
    if (img.channels != 4 && img.channels != 2) return false;
    for (size_t i = static_cast<size_t>(img.channels) - 1; i < img.pixels.size(); i += static_cast<size_t>(img.channels))
        if (img.pixels[i] < 0.999f) return true;
    return false;
}

std::string relative_to(const fs::path& p, const fs::path& base) {
    std::error_code ec;
    const fs::path a = fs::absolute(p, ec).lexically_normal();
    const fs::path b = fs::absolute(base, ec).lexically_normal();
    fs::path r = a.lexically_relative(b);
    if (r.empty()) r = a;
    return r.generic_string();
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

}  // namespace

Ingestor::Ingestor(Preset preset, std::shared_ptr<const ColorContext> color, IngestOptions opt)
    : preset_(std::move(preset)), color_(std::move(color)), opt_(std::move(opt)) {}

MaterialResult Ingestor::process(const MaterialSource& src) const {
    MaterialResult res;
    auto& findings = res.findings;
    const NormalConvention target = opt_.normal_override.value_or(preset_.normal_convention);

    // Each file is opened once per set (zip entries are read into memory once).
    std::map<std::string, InputFile> opened;
    auto open = [&](const std::string& f) -> const InputFile& {
        auto it = opened.find(f);
        if (it == opened.end()) it = opened.emplace(f, src.open(f)).first;
        return it->second;
    };
    auto header = [&](const std::string& f) -> std::optional<HeaderInfo> {
        std::string err;
        auto info = read_info(open(f), err);
        if (!info) return std::nullopt;
        return HeaderInfo{info->width, info->height, info->channels, info->bit_depth, info->is_float};
    };
    SetDiscovery d = discover_set(src.files, header, ChoicePolicy{target, preset_.max_size});
    findings.insert(findings.end(), d.findings.begin(), d.findings.end());

    // Decode the chosen map of every input role, falling back to the next candidate.
    std::map<std::string, Loaded> loaded;
    std::map<Role, const Candidate*> used;  // input role -> the candidate that decoded
    bool partial = false;
    for (const auto& choice : d.choices) {
        std::vector<const Candidate*> order{&choice.chosen};
        for (const auto& r : choice.rejected) order.push_back(&r);
        for (const Candidate* c : order) {
            Loaded l;
            std::string err;
            if (read_image(open(c->file), l.img, l.info, err)) {
                loaded.emplace(c->file, std::move(l));
                used[choice.role] = c;
                break;
            }
            partial = true;
            findings.push_back({std::string(code::unreadable_file), Severity::error, std::string(role_name(choice.role)),
                                c->file, err + "; the file is skipped", {}});
        }
    }
    for (auto& [f, in] : opened) in.bytes.reset();  // decoded; free zip bytes early

    // Canonical planes per output role.
    Planes planes;
    std::map<Role, Provider> route_of;
    for (int ri = 0; ri < kOutputRoleCount; ++ri) {
        const Role out = static_cast<Role>(ri);
        for (const Provider& r : providers_of(out)) {
            if (!used.count(r.from)) continue;
            route_of[out] = r;
            break;
        }
    }
    std::set<Role> unpacked;
    nlohmann::json normal_facts = nlohmann::json::object();  // convention, its source, confidence
    for (const auto& [out, route] : route_of) {
        const Candidate& c = *used.at(route.from);
        const Loaded& l = loaded.at(c.file);
        const std::string rname(role_name(out));
        RolePlane plane;
        if (out == Role::albedo || out == Role::emissive) {
            plane.image = to_rgb(l.img);
            plane.encoding = l.info.is_float ? ColorEncoding::linear : ColorEncoding::srgb;
        } else if (out == Role::normal) {
            NormalConvention conv = c.match.normal;
            std::string conv_source = "name";
            double confidence = 1.0;
            if (conv == NormalConvention::unknown && detector_) {
                auto [verdict, conf] = detector_(l.img, nullptr);
                if (verdict != NormalConvention::unknown) {
                    conv = verdict;
                    conv_source = "content";
                    confidence = conf;
                }
            }
            if (conv == NormalConvention::unknown) {
                findings.push_back({std::string(code::normal_convention_unknown), Severity::warning, rname, c.file,
                                    "neither the file name nor the content decides OpenGL (+Y) vs DirectX (-Y); "
                                    "assumed OpenGL — check the preview and rename the file with _gl/_dx if wrong",
                                    {}});
            }
            const double bad = decode_normal(l.img, conv, plane.image);
            if (bad > 0.5) {
                findings.push_back({std::string(code::normal_invalid), Severity::warning, rname, c.file,
                                    "most texels are not unit tangent-space normals (length far from 1 or Z < 0): "
                                    "is this really a normal map?",
                                    {{"invalid_share", bad}}});
            }
            const NormalConvention effective = conv == NormalConvention::unknown ? NormalConvention::gl : conv;
            if (effective != target) {
                findings.push_back({std::string(code::normal_convention_converted), Severity::info, rname, c.file,
                                    "green channel flipped from " + std::string(convention_name(effective)) + " to " +
                                        std::string(convention_name(target)) + " for the preset",
                                    {{"from", convention_name(effective)}, {"to", convention_name(target)}}});
            }
            normal_facts = {{"normal_convention", convention_name(conv)}};
            if (conv != NormalConvention::unknown) normal_facts["normal_convention_source"] = conv_source;
            if (conv_source == "content") normal_facts["normal_convention_confidence"] = confidence;
        } else {
            plane.image = extract_channel(l.img, route.channel < 0 ? 0 : route.channel);
            if (route.invert) {
                invert(plane.image);
                findings.push_back({std::string(code::gloss_inverted), Severity::info, rname, c.file,
                                    "gloss map converted to roughness (roughness = 1 - gloss)", {}});
            }
        }
        if (traits(route.from).packed) unpacked.insert(route.from);
        planes.emplace(out, std::move(plane));
    }
    for (Role p : unpacked) {
        const Candidate& c = *used.at(p);
        std::string parts;
        const auto layout = packed_layout(p);
        static constexpr const char* kCh[] = {"R", "G", "B"};
        for (size_t i = 0; i < 3; ++i)
            if (layout[i]) parts += (parts.empty() ? "" : ", ") + std::string(kCh[i]) + " = " + std::string(role_name(*layout[i]));
        std::string msg = "packed " + std::string(role_name(p)) + " map split into " + parts;
        if (p == Role::ort) msg += " (translucency is not metalness)";
        findings.push_back({std::string(code::packed_input_unpacked), Severity::info, std::string(role_name(p)), c.file, msg, {}});
    }
    // Opacity carried in the albedo's alpha, when no opacity map exists.
    if (!planes.count(Role::opacity) && route_of.count(Role::albedo)) {
        const Candidate& c = *used.at(route_of[Role::albedo].from);
        const Loaded& l = loaded.at(c.file);
        if (route_of[Role::albedo].channel < 0 && has_real_alpha(l.img)) {
            planes[Role::opacity].image = extract_channel(l.img, l.img.channels - 1);
            route_of[Role::opacity] = {Role::albedo, l.img.channels - 1, false};
            findings.push_back({std::string(code::packed_input_unpacked), Severity::info, "opacity", c.file,
                                "opacity taken from the albedo map's alpha channel", {}});
        }
    }

    if (loaded.empty()) {
        res.failed = true;
        res.failure_message = src.display + ": no map of the set could be read";
        for (const auto& f : findings)
            if (f.code == code::unreadable_file) res.failure_message += "; " + f.message;
        return res;
    }

    // One size for the set: the largest map, within the preset's limit.
    int w = 0, h = 0;
    std::set<std::pair<int, int>> sizes;
    for (const auto& [r, p] : planes) {
        sizes.insert({p.image.width, p.image.height});
        w = std::max(w, p.image.width);
        h = std::max(h, p.image.height);
    }
    if (sizes.size() > 1) {
        nlohmann::json fig = nlohmann::json::object();
        std::string list;
        for (const auto& [r, p] : planes) {
            fig[std::string(role_name(r))] = {p.image.width, p.image.height};
            list += (list.empty() ? "" : ", ") + std::string(role_name(r)) + " " + std::to_string(p.image.width) + "x" +
                    std::to_string(p.image.height);
        }
        findings.push_back({std::string(code::resolution_mismatch), Severity::warning, "", "",
                            "maps differ in size (" + list + "); all resampled to " + std::to_string(w) + "x" +
                                std::to_string(h),
                            fig});
    }
    if (preset_.max_size > 0 && std::max(w, h) > preset_.max_size) {
        const int ow = w, oh = h;
        const double k = static_cast<double>(preset_.max_size) / std::max(w, h);
        w = std::max(1, static_cast<int>(std::lround(w * k)));
        h = std::max(1, static_cast<int>(std::lround(h * k)));
        findings.push_back({std::string(code::resized), Severity::info, "", "",
                            "downsampled from " + std::to_string(ow) + "x" + std::to_string(oh) + " to " +
                                std::to_string(w) + "x" + std::to_string(h) + " (preset max_size " +
                                std::to_string(preset_.max_size) + ")",
                            {{"from", {ow, oh}}, {"to", {w, h}}}});
    }
    for (auto& [r, p] : planes) fit_plane(r, p, w, h, *color_);

    // Missing roles: constants where an output needs them, reported per the preset.
    std::set<Role> needed_roles;
    std::vector<const OutputSpec*> written;
    for (const auto& o : preset_.outputs) {
        if (!output_needed(o, planes)) continue;
        written.push_back(&o);
        for (const auto& c : effective_channels(o, planes))
            if (c.kind == ChannelSpec::Kind::role || c.kind == ChannelSpec::Kind::smoothness) needed_roles.insert(c.role);
    }
    nlohmann::json constants = nlohmann::json::object();
    for (int ri = 0; ri < kOutputRoleCount; ++ri) {
        const Role r = static_cast<Role>(ri);
        if (planes.count(r)) continue;
        const std::string rname(role_name(r));
        std::string what;
        if (needed_roles.count(r)) {
            if (r == Role::albedo) {
                constants[rname] = preset_.default_albedo;
                what = "generated constant albedo (linear " + format_number(preset_.default_albedo[0]) + ", " +
                       format_number(preset_.default_albedo[1]) + ", " + format_number(preset_.default_albedo[2]) + ")";
            } else if (r == Role::normal || r == Role::emissive) {
                constants[rname] = r == Role::normal ? nlohmann::json{0, 0, 1} : nlohmann::json{0, 0, 0};
                what = r == Role::normal ? "generated a flat normal" : "generated black emission";
            } else {
                const float v = preset_.default_value(r);
                constants[rname] = v;
                what = "generated constant " + format_number(v);
                if (r == Role::metalness) what += v == 0.f ? " (dielectric)" : " (metal)";
            }
        } else {
            what = "nothing written for it";
        }
        auto sev = preset_.missing_severity.find(r);
        if (sev == preset_.missing_severity.end()) continue;
        findings.push_back({std::string(code::missing_map), sev->second, rname, "", "no " + rname + " map; " + what,
                            constants.contains(rname) ? nlohmann::json{{"generated", constants[rname]}}
                                                      : nlohmann::json::object()});
    }

    // Pack, encode, write.
    const fs::path mat_dir = opt_.out_dir / src.name;
    remove_stale_temps(mat_dir);
    nlohmann::json outputs = nlohmann::json::array();
    for (const OutputSpec* o : written) {
        const std::string rel = preset_.output_path(src.name, *o);
        const fs::path rel_path = fs::path(rel).lexically_normal();
        if (rel_path.is_absolute() || rel_path.empty() || *rel_path.begin() == "..") {
            findings.push_back({std::string(code::output_write_failed), Severity::error, "", "",
                                "output path '" + rel + "' leaves the output folder; skipped", {}});
            partial = true;
            continue;
        }
        bool any_map = false;
        for (Role r : o->roles()) any_map = any_map || planes.count(r);
        const Size size = any_map ? Size{w, h} : Size{preset_.constant_size, preset_.constant_size};
        const Image packed = pack_output(*o, planes, preset_, size, *color_);
        std::vector<unsigned char> bytes;
        std::string err;
        if (!encode_image(packed, {preset_.format, o->bit_depth}, bytes, err) ||
            !write_file_atomic(opt_.out_dir / rel_path, bytes, err)) {
            findings.push_back({std::string(code::output_write_failed), Severity::error, "", "", rel + ": " + err, {}});
            partial = true;
            continue;
        }
        nlohmann::json e;
        e["file"] = rel_path.generic_string();
        e["color_space"] = o->srgb ? "sRGB" : "linear";
        e["channels"] = channels_json(effective_channels(*o, planes));
        if (std::any_of(o->channels.begin(), o->channels.end(),
                        [](const ChannelSpec& c) { return c.kind == ChannelSpec::Kind::role && c.role == Role::normal; }))
            e["normal_convention"] = convention_name(target);
        e["width"] = size.width;
        e["height"] = size.height;
        e["bit_depth"] = o->bit_depth;
        e["format"] = preset_.format;
        e["sha256"] = sha256_hex(bytes);
        outputs.push_back(std::move(e));
    }

    // Manifest entry.
    nlohmann::json inputs = nlohmann::json::object();
    for (const auto& [role, c] : used) {
        const Loaded& l = loaded.at(c->file);
        nlohmann::json in = {{"file", c->file},
                             {"width", l.info.width},
                             {"height", l.info.height},
                             {"channels", l.info.channels},
                             {"bit_depth", l.info.bit_depth},
                             {"color_space", input_color_space(role, l.info)},
                             {"family", c->match.family},
                             {"rule", c->match.rule}};
        if (l.info.is_float) in["float"] = true;
        if (role == Role::normal) in.update(normal_facts);
        inputs[std::string(role_name(role))] = std::move(in);
    }
    nlohmann::json m;
    m["name"] = src.name;
    m["source"] = relative_to(src.root, opt_.out_dir) + (src.is_zip && !src.zip_folder.empty() ? "/" + src.zip_folder : "");
    if (src.is_zip) m["archive"] = relative_to(src.root, opt_.out_dir);
    m["convention"] = d.convention;
    m["status"] = partial ? "partial" : "ok";
    m["inputs"] = std::move(inputs);
    m["constants"] = std::move(constants);
    m["outputs"] = std::move(outputs);
    nlohmann::json fj = nlohmann::json::array();
    for (const auto& f : findings) fj.push_back(to_json(f));
    m["findings"] = std::move(fj);
    res.manifest_entry = std::move(m);
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
    std::atomic<size_t> next{0}, done{0};
    std::mutex progress_mutex;
    const unsigned hw = std::max(1u, std::thread::hardware_concurrency());
    const size_t jobs = std::min<size_t>(opt_.jobs > 0 ? static_cast<size_t>(opt_.jobs) : hw, std::max<size_t>(1, sets.size()));
    auto worker = [&] {
        for (size_t i = next++; i < sets.size(); i = next++) {
            try {
                results[i] = process(sets[i]);
            } catch (const std::exception& e) {  // a bug or resource exhaustion in one set must not stop the others
                results[i] = MaterialResult{};
                results[i].failed = true;
                results[i].failure_message = sets[i].display + ": internal error: " + e.what();
            }
            const size_t n = ++done;
            if (opt_.progress) {
                std::lock_guard lock(progress_mutex);
                opt_.progress(n, sets.size(), sets[i].name,
                              results[i].failed ? "failed" : results[i].manifest_entry.value("status", "ok"));
            }
        }
    };
    std::vector<std::thread> pool;
    for (size_t t = 1; t < jobs; ++t) pool.emplace_back(worker);
    worker();
    for (auto& t : pool) t.join();

    nlohmann::json materials = nlohmann::json::array(), failures = nlohmann::json::array();
    for (size_t i = 0; i < sets.size(); ++i) {
        auto& r = results[i];
        if (r.failed) {
            failures.push_back({{"source", relative_to(sets[i].root, opt_.out_dir) +
                                               (sets[i].is_zip && !sets[i].zip_folder.empty() ? "/" + sets[i].zip_folder : "")},
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
    m["normal_convention"] = convention_name(opt_.normal_override.value_or(preset_.normal_convention));
    m["materials"] = std::move(materials);
    m["failures"] = std::move(failures);
    result.manifest = m;
    const std::string text = m.dump(2) + "\n";
    std::string err;
    if (!write_file_atomic(opt_.out_dir / "manifest.json",
                           std::span(reinterpret_cast<const unsigned char*>(text.data()), text.size()), err))
        result.error = err;
    remove_stale_temps(opt_.out_dir);
    return result;
}

}  // namespace mf
