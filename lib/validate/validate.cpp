#include "validate/validate.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>

#include "material/routing.hpp"
#include "validate/albedo_stats.hpp"
#include "validate/band_stream.hpp"
#include "validate/map_stats.hpp"

namespace mf::validate {
namespace {

using detail::BandStream;
using detail::MapStats;

std::string display_name(const MapInput& m) { return m.name.empty() ? m.file.display : m.name; }

struct Source {
    int map = -1;     // index into maps
    int channel = 0;  // channel holding the value
};

// Channel `channel` of the pixels at xs[i] of a row of `channels`-channel samples, into out[i]:
// another map's row resampled onto this one's grid, its kind (codes or floats) decided once a row,
// not a branch per sample through Samples::operator[].
void gather(const Samples& row, const std::vector<int>& xs, size_t channels, size_t channel, float* out) {
    auto each = [&](auto value) {
        for (size_t x = 0; x < xs.size(); ++x) out[x] = value(static_cast<size_t>(xs[x]) * channels + channel);
    };
    const std::array<float, 256>& unorm = unorm8_values();
    if (row.codes) each([&](size_t i) { return unorm[row.codes[i]]; });
    else each([&](size_t i) { return row.floats[i]; });
}

// The first map of input role `r` whose header could be read, -1 when none.
int first_readable(const std::vector<MapInput>& maps, const std::vector<bool>& readable, Role r) {
    for (size_t i = 0; i < maps.size(); ++i)
        if (readable[i] && !maps[i].alternate && maps[i].role == r) return static_cast<int>(i);
    return -1;
}

}  // namespace

bool read_file_bands(const InputFile& in, int band_rows, ImageInfo& info, std::string& error,
                     const std::function<void(int, int, Samples)>& fn) {
    return read_bands(
        in, band_rows, info, error, [&](int y0, int rows, const float* px) { fn(y0, rows, {px}); },
        [&](int y0, int rows, const uint8_t* codes) {
            fn(y0, rows, {nullptr, codes});
        });
}

std::optional<MapInput> make_map_input(Role role, InputFile file, std::string name, NormalConvention name_convention,
                                       std::string& error) {
    MapInput m;
    m.role = role;
    m.name = std::move(name);
    m.name_convention = name_convention;
    auto info = read_info(file, error);
    if (!info) return std::nullopt;
    m.info = *info;
    m.color_tag = read_color_tag(file);
    m.file = std::move(file);
    return m;
}

namespace {

// One validate_set call, stage by stage: headers -> sources -> readers -> the joint passes
// (albedo, normal) -> per-map findings -> configuration and order.
struct SetRun {
    std::vector<MapInput> maps;
    const rules::RuleConfig& cfg;
    const ValidateOptions& opt;
    const rules::Thresholds& t;
    std::vector<bool> readable;
    std::vector<std::string> read_errors;
    Source albedo, metal, opacity, normal, height;
    std::vector<std::unique_ptr<MapStats>> stats;
    std::vector<std::unique_ptr<BandStream>> streams;
    std::vector<Finding> found;
    std::optional<NormalVerdict> verdict;  // pass 2's, judged once the normal map is known valid
    SetValidation result;

    SetRun(const std::vector<MapInput>& m, const rules::RuleConfig& c, const ValidateOptions& o)
        : maps(m),
          cfg(c),
          opt(o),
          t(c.thresholds),
          readable(m.size(), true),
          read_errors(m.size()),
          stats(m.size()),
          streams(m.size()) {}

    const ImageInfo& info(const Source& s) const { return maps[static_cast<size_t>(s.map)].info; }
    bool albedo_pass() const { return albedo.map >= 0 && info(albedo).channels >= 3; }
    bool normal_pass() const { return normal.map >= 0 && info(normal).channels >= 2; }
    Samples row_of(const Source& s, int r) const {
        return s.map >= 0 && streams[static_cast<size_t>(s.map)] ? streams[static_cast<size_t>(s.map)]->row(r)
                                                                 : Samples{};
    }

    // Header facts first (cheap); a map whose header fails is reported and left out.
    void read_headers() {
        for (size_t i = 0; i < maps.size(); ++i) {
            if (maps[i].info.width > 0) continue;
            std::string err;
            if (auto hd = read_info(maps[i].file, err)) maps[i].info = *hd;
            else {
                readable[i] = false;
                read_errors[i] = err;
            }
        }
    }

    // Which maps feed the joint statistics: the routes ingest uses (material/routing).
    void choose_sources() {
        const Routes routes = route_roles(
            [&](Role r) {
                const int i = first_readable(maps, readable, r);
                return i < 0 ? 0 : maps[static_cast<size_t>(i)].info.channels;
            },
            true,
            [&](Role out, Role from) {
                const auto& u = maps[static_cast<size_t>(first_readable(maps, readable, from))].unused;
                return std::find(u.begin(), u.end(), out) != u.end();
            });
        auto source_of = [&](Role out) {
            const auto it = routes.find(out);
            if (it == routes.end()) return Source{};
            return Source{first_readable(maps, readable, it->second.from), std::max(0, it->second.channel)};
        };
        albedo = source_of(Role::albedo);
        metal = source_of(Role::metalness);
        opacity = source_of(Role::opacity);
        normal = source_of(Role::normal);
        height = source_of(Role::height);
    }

    // Every reader starts; per-map statistics run on the reader threads. The maps a joint pass
    // needs are read in lockstep with it.
    void start_readers() {
        std::vector<bool> lockstep(maps.size(), false);
        if (albedo_pass())
            for (const Source& s : {albedo, metal, opacity})
                if (s.map >= 0) lockstep[static_cast<size_t>(s.map)] = true;
        if (normal_pass())
            for (const Source& s : {normal, height})
                if (s.map >= 0) lockstep[static_cast<size_t>(s.map)] = true;
        const BandReader reader = opt.reader ? opt.reader : BandReader(&read_file_bands);
        const int band_rows = std::max(1, opt.band_rows);
        for (size_t i = 0; i < maps.size(); ++i) {
            if (!readable[i]) continue;
            stats[i] = std::make_unique<MapStats>(maps[i], maps[i].info, t);
            // OPACITY_ALL_TRANSPARENT looks at the map (and channel) that is the set's opacity.
            stats[i]->opacity_channel = opacity.map == static_cast<int>(i) ? opacity.channel : -1;
            MapStats* st = stats[i].get();
            const ImageInfo expected = maps[i].info;
            streams[i] = std::make_unique<BandStream>(
                reader, maps[i].file, band_rows, expected.width * expected.channels,
                [st](int y0, int rows, Samples px) { st->add_band(y0, rows, px); }, lockstep[i]);
        }
    }

    // Pass 1: albedo on its own grid with metalness and opacity resampled onto it. Pixels the
    // opacity hides are counted apart: an opacity that hides everything is not applied
    // (OPACITY_ALL_TRANSPARENT, known once its reader finishes), and the albedo is then judged
    // whole, as the opaque material ingest writes (visible + hidden).
    std::optional<detail::AlbedoStats> albedo_visible, albedo_hidden;
    void albedo_stats() {
        const ImageInfo& ai = info(albedo);
        albedo_visible.emplace(t, ai.is_float);
        if (opacity.map >= 0) albedo_hidden.emplace(t, ai.is_float);
        std::vector<int> mx, ox;
        auto xmap = [&](const Source& s, std::vector<int>& v) {
            if (s.map < 0) return;
            v.resize(static_cast<size_t>(ai.width));
            for (int x = 0; x < ai.width; ++x) v[static_cast<size_t>(x)] = nearest_index(x, ai.width, info(s).width);
        };
        xmap(metal, mx);
        xmap(opacity, ox);
        for (int y = 0; y < ai.height; ++y) {
            const Samples a = row_of(albedo, y);
            if (a.empty()) break;
            const Samples m = metal.map >= 0 ? row_of(metal, nearest_index(y, ai.height, info(metal).height))
                                             : Samples{};
            const Samples o = opacity.map == albedo.map ? a
                              : opacity.map >= 0 ? row_of(opacity, nearest_index(y, ai.height, info(opacity).height))
                                                 : Samples{};
            if (a.codes) albedo_row(a.codes, m, o, mx, ox);
            else albedo_row(a.floats, m, o, mx, ox);
        }
    }
    // One albedo row (floats or codes) with its metalness and opacity rows (either kind, or
    // empty), resampled onto the albedo's grid; pixels the opacity hides go to albedo_hidden.
    std::vector<float> metal_row;
    std::vector<uint8_t> visible_row;
    template <class T>
    void albedo_row(const T* a, const Samples& m, const Samples& o, const std::vector<int>& mx,
                    const std::vector<int>& ox) {
        const ImageInfo& ai = info(albedo);
        const auto w = static_cast<size_t>(ai.width);
        const auto nc = static_cast<size_t>(ai.channels);
        if (!m.empty()) {
            const auto mc = static_cast<size_t>(info(metal).channels), ch = static_cast<size_t>(metal.channel);
            metal_row.resize(w);
            gather(m, mx, mc, ch, metal_row.data());
        }
        const float* mv = m.empty() ? nullptr : metal_row.data();
        if (o.empty()) {
            albedo_visible->add_row(a, nc, mv, w);
            return;
        }
        const bool own_alpha = opacity.map == albedo.map;
        const size_t oc = own_alpha ? nc : static_cast<size_t>(info(opacity).channels);
        const size_t ch = own_alpha ? 3 : static_cast<size_t>(opacity.channel);
        visible_row.resize(w);
        for (size_t x = 0; x < w; ++x) {
            const size_t at = (own_alpha ? x : static_cast<size_t>(ox[x])) * oc + ch;
            visible_row[x] = o[at] >= t.opacity_visible ? 1 : 0;  // NaN: hidden
        }
        albedo_visible->add_row(a, nc, mv, w, visible_row.data(), 1);
        albedo_hidden->add_row(a, nc, mv, w, visible_row.data(), 0);
    }
    void albedo_findings() {
        if (!albedo_visible) return;
        const bool masked = opacity.map >= 0 && !result.opacity_invisible;
        if (!masked && albedo_hidden) albedo_visible->merge(*albedo_hidden);
        albedo_visible->findings(display_name(maps[static_cast<size_t>(albedo.map)]), metal.map >= 0, masked, found);
    }

    // Pass 2: normal with height resampled onto the normal's grid -> the convention verdict.
    void normal_stats() {
        const ImageInfo& ni = info(normal);
        const bool wh = height.map >= 0;
        NormalConventionDetector det(ni.width, wh, opt.detector);
        NormalRow row;
        std::vector<float> hrow(wh ? static_cast<size_t>(ni.width) : 0);
        std::vector<int> hx;
        if (wh) {
            hx.resize(static_cast<size_t>(ni.width));
            for (int x = 0; x < ni.width; ++x)
                hx[static_cast<size_t>(x)] = nearest_index(x, ni.width, info(height).width);
        }
        const size_t hc = wh ? static_cast<size_t>(info(height).channels) : 0;
        const auto hch = static_cast<size_t>(height.channel);
        for (int y = 0; y < ni.height; ++y) {
            const Samples n = row_of(normal, y);
            if (n.empty()) break;
            // The reader thread decided the decoding on the first band, before this row.
            const MapStats& ns = *stats[static_cast<size_t>(normal.map)];
            if (n.codes) decode_normal_row(n.codes, ni.channels, ni.width, row, ns.rebuilds_z());
            else decode_normal_row(n.floats, ni.channels, ni.width, ns.normal_signed == 1, row, ns.rebuilds_z());
            const Samples h = wh ? row_of(height, nearest_index(y, ni.height, info(height).height)) : Samples{};
            if (!h.empty()) gather(h, hx, hc, hch, hrow.data());
            det.add_row(row, h.empty() ? nullptr : hrow.data());
        }
        verdict = det.verdict();
    }

    // The normal map's convention from its name and pass 2's verdict, and its findings:
    // NORMAL_CONVENTION_MISMATCH (the name and the content disagree) and _UNKNOWN (neither
    // decides; a flat map has no convention to decide), emitted here only, and only for a map
    // that is a normal map (`valid`: NORMAL_INVALID says all of one that is not).
    void convention_findings(const NormalVerdict& content, bool valid) {
        const MapInput& m = maps[static_cast<size_t>(normal.map)];
        NormalCheck nc;
        nc.file = display_name(m);
        nc.name = m.name_convention;
        nc.content = content;
        const double need = t.normal_convention_min_confidence;
        const bool decided = nc.content.convention != NormalConvention::unknown && nc.content.confidence >= need;
        if (nc.name != NormalConvention::unknown) {
            nc.resolved = nc.name;
            nc.source = "name";
        } else if (decided) {
            nc.resolved = nc.content.convention;
            nc.source = "content";
        } else if (m.engine_convention != NormalConvention::unknown) {
            nc.resolved = m.engine_convention;
            nc.source = "engine";
        }
        Figures fig = nc.content.figures;
        fig["name_convention"] = convention_name(nc.name);
        fig["content_convention"] = convention_name(nc.content.convention);
        fig["leaning"] = convention_name(nc.content.leaning);
        fig["confidence"] = nc.content.confidence;
        fig["method"] = nc.content.method;
        fig["min_confidence"] = need;
        const std::string percent = std::to_string(static_cast<int>(std::lround(nc.content.confidence * 100)));
        auto emit = [&](std::string_view code, std::string message) {
            found.push_back(finding(code, "normal", nc.file, std::move(message), fig));
        };
        if (!valid) {
            result.normal = std::move(nc);
            return;
        }
        if (nc.name != NormalConvention::unknown && decided && nc.content.convention != nc.name)
            emit(code::normal_convention_mismatch,
                 nc.file + ": the name says " + std::string(convention_name(nc.name)) + " but the content says " +
                     std::string(convention_name(nc.content.convention)) + " (confidence " + percent + " %, " +
                     nc.content.method + " test); check the green channel before trusting the name");
        else if (nc.name == NormalConvention::unknown && !decided && !nc.content.flat &&  // flat: GL = DX
                 m.engine_convention == NormalConvention::unknown)
            emit(code::normal_convention_unknown,
                 nc.file + ": neither the name nor the content decides GL or DX (content confidence " + percent +
                     " %); assumed OpenGL (+Y): check the preview, or rename it with a _gl/_dx suffix");
        result.normal = std::move(nc);
    }

    // Every reader finishes (maps outside the joint passes have been running freely), then each
    // map's own findings, or why it could not be read.
    void map_findings() {
        for (size_t i = 0; i < maps.size(); ++i) {
            if (!streams[i]) continue;
            streams[i]->finish();
            if (!streams[i]->ok()) {
                readable[i] = false;
                read_errors[i] = streams[i]->error();
            }
        }
        if (normal.map >= 0 && readable[static_cast<size_t>(normal.map)])
            result.normal_z_rebuilt = stats[static_cast<size_t>(normal.map)]->rebuilds_z();
        // The albedo's alpha: the plan keeps it as the opacity only when some texel is below opaque.
        if (opacity.map >= 0 && opacity.map == albedo.map && readable[static_cast<size_t>(albedo.map)])
            result.albedo_alpha_min = stats[static_cast<size_t>(albedo.map)]->min[static_cast<size_t>(opacity.channel)];
        if (opacity.map >= 0 && readable[static_cast<size_t>(opacity.map)])
            result.opacity_invisible = stats[static_cast<size_t>(opacity.map)]->all_transparent();
        albedo_findings();
        for (size_t i = 0; i < maps.size(); ++i) {
            if (!readable[i]) {
                const std::string file = display_name(maps[i]);
                Finding f = finding(code::unreadable_file, std::string(role_name(maps[i].role)), file,
                                    read_errors[i].empty() ? file + ": could not be read" : read_errors[i]);
                result.unreadable.emplace(f.file, f.message);
                found.push_back(std::move(f));
                continue;
            }
            stats[i]->findings(found);
        }
        // A map that is not a normal map has no green convention: NORMAL_INVALID says it all.
        if (normal.map >= 0 && readable[static_cast<size_t>(normal.map)])
            result.normal_invalid = stats[static_cast<size_t>(normal.map)]->normal_invalid();
        if (verdict) {
            const auto n = static_cast<size_t>(normal.map);
            convention_findings(*verdict, readable[n] && !stats[n]->normal_invalid());
        }
    }

    // The stable order (the catalog's). The rules config is applied by the caller, once over
    // every stage's findings (plan/plan.hpp reported_findings).
    SetValidation finish() {
        const auto& cat = finding_catalog();
        auto rank = [&](const Finding& f) {
            for (size_t i = 0; i < cat.size(); ++i)
                if (cat[i].code == f.code) return i;
            return cat.size();
        };
        std::stable_sort(found.begin(), found.end(),
                         [&](const Finding& a, const Finding& b) { return rank(a) < rank(b); });
        result.findings = std::move(found);
        return std::move(result);
    }
};

}  // namespace

SetValidation validate_set(const std::vector<MapInput>& maps, const rules::RuleConfig& cfg,
                           const ValidateOptions& opt) {
    SetRun run(maps, cfg, opt);
    run.read_headers();
    run.choose_sources();
    run.start_readers();
    if (run.albedo_pass()) run.albedo_stats();
    if (run.normal_pass()) run.normal_stats();
    run.map_findings();
    return run.finish();
}

std::optional<bool> is_tangent_normal_map(const InputFile& file, const rules::Thresholds& t) {
    std::string error;
    auto in = make_map_input(Role::normal, file, file.display, NormalConvention::unknown, error);
    if (!in) return std::nullopt;
    if (in->info.channels < 3) return false;
    MapStats stats(*in, in->info, t);
    ImageInfo info;
    if (!read_file_bands(file, 256, info, error, [&](int y0, int rows, Samples px) { stats.add_band(y0, rows, px); }))
        return std::nullopt;
    return !stats.normal_invalid();
}

}  // namespace mf::validate
