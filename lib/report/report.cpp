#include "report/report.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <cctype>
#include <condition_variable>
#include <cstdio>
#include <fstream>
#include <map>
#include <mutex>
#include <set>
#include <span>
#include <thread>

#include "base/budget.hpp"
#include "base/interrupt.hpp"
#include "base/parallel.hpp"
#include "core/files.hpp"
#include "core/text.hpp"
#include "core/version.hpp"
#include "report/card.hpp"
#include "report/html.hpp"
#include "texture/texture.hpp"

namespace mf::report {
namespace fs = std::filesystem;
namespace {

using manifest::Channel;

std::string safe_component(const std::string& name) {
    std::string s;
    for (const char ch : name) {
        const auto c = static_cast<unsigned char>(ch);
        s += std::isalnum(c) || c == '.' || c == '_' || c == '-' ? ch : '_';
    }
    while (!s.empty() && s.front() == '.') s.front() = '_';
    if (s.size() > 96) s.resize(96);
    if (s.empty()) s = "material";
    return s;
}

// Inside `dir` lexically (no absolute path, no ".."): a manifest must not make the report read
// files elsewhere unless its user allows it (as preview does).
bool inside(const fs::path& rel) {
    const auto n = rel.lexically_normal();
    return !n.is_absolute() && !n.empty() && *n.begin() != "..";
}

// The pictures' atomic writes finished (each file's fsync, its rename, its folder's fsync) on a
// thread of their own, as ingest's output folder finishes its files: the workers that decode and
// encode never wait on the disk (the corpus's 239 pictures were 484 fsyncs on the workers, a
// worker idle through each), and a group of files costs one fsync of their folder, not one each.
class Committer {
public:
    struct Failure {
        size_t job;
        std::string rel, error;
    };
    Committer() : thread_([this] { loop(); }) {}
    Committer(const Committer&) = delete;
    Committer& operator=(const Committer&) = delete;
    ~Committer() { finish(); }

    // Waits while kMaxQueued files are waiting already: each holds two descriptors (the file and
    // its folder), and a slow disk must not run a large library's report out of them.
    void add(size_t job, std::string rel, StagedFile file) {
        {
            std::unique_lock lock(mutex_);
            room_.wait(lock, [this] { return queue_.size() < kMaxQueued; });
            queue_.push_back({job, std::move(rel), std::move(file)});
        }
        wake_.notify_one();
    }
    // Every file added is in place (or failed): the failures, in the order they came.
    std::vector<Failure> finish() {
        {
            const std::lock_guard lock(mutex_);
            done_ = true;
        }
        wake_.notify_one();
        if (thread_.joinable()) thread_.join();
        return std::move(failures_);
    }

private:
    struct Item {
        size_t job;
        std::string rel;
        StagedFile file;
    };
    void loop() {
        for (;;) {
            std::vector<Item> group;
            {
                std::unique_lock lock(mutex_);
                wake_.wait(lock, [this] { return done_ || !queue_.empty(); });
                if (queue_.empty()) return;
                group.swap(queue_);
            }
            room_.notify_all();
            std::vector<bool> placed(group.size());
            for (size_t i = 0; i < group.size(); ++i) {
                std::string error;
                placed[i] = group[i].file.sync(error) && group[i].file.rename(error);
                if (!placed[i]) failures_.push_back({group[i].job, group[i].rel, error});
            }
            std::set<std::pair<dev_t, ino_t>> folders;  // each folder of the group synced once
            for (size_t i = 0; i < group.size(); ++i) {
                struct stat st {};
                const int dir = group[i].file.folder();
                if (placed[i] && ::fstat(dir, &st) == 0 && folders.emplace(st.st_dev, st.st_ino).second)
                    ::fsync(dir);  // makes the renames durable
            }
        }
    }

    static constexpr size_t kMaxQueued = 128;
    std::mutex mutex_;
    std::condition_variable wake_, room_;
    std::vector<Item> queue_;
    bool done_ = false;
    std::vector<Failure> failures_;  // the thread's own until finish() joins it
    std::thread thread_;             // last: started once the members above exist
};

// The work of one material: its pictures (run(), on a worker) and its card (card(), once its
// pictures are in place).
class MaterialJob {
public:
    MaterialJob(const Options& o, const fs::path& manifest_dir, const manifest::Material& m, std::string stem,
                size_t index, const manifest::Material* other, fs::path other_dir, std::string other_preset)
        : opt_(o),
          dir_(manifest_dir),
          m_(m),
          stem_(std::move(stem)),
          index_(index),
          other_(other),
          other_dir_(std::move(other_dir)),
          other_preset_(std::move(other_preset)) {}

    void run() {
        if (viewer) pics_.viewer = viewer->material(m_, dir_, stem_, problems);  // first: its maps freed before ours
        if (opt_.previews) pics_.preview = preview_pic(*opt_.previews, "preview.png");
        read_outputs();
        if (opt_.sources) read_sources();
        overlays();
        if (other_) compare();
    }

    void card() {
        CardHtml c = write_card({m_, pics_, *opt_.thresholds, stem_, index_, other_, other_preset_});
        card_html = std::move(c.card);
        sheet_html = std::move(c.tile);
    }

    // A picture whose write did not finish (Committer): a note, and the card shows none there.
    void unwritten(const std::string& rel, const std::string& error) {
        problem(error);
        --images;
        auto drop = [&rel](std::optional<Pic>& p) {
            if (p && p->rel == rel) p.reset();
        };
        for (std::optional<Pic>* p :
             {&pics_.preview, &pics_.compare_preview, &pics_.sheet, &pics_.albedo, &pics_.metalness})
            drop(*p);
        for (std::vector<OutputPics>* list : {&pics_.outputs, &pics_.compare})
            for (OutputPics& o : *list) {
                if (o.main.rel == rel) o.main = Pic{};
                std::erase_if(o.channels, [&rel](const auto& c) { return c.second.rel == rel; });
            }
        for (Pic& p : pics_.sources)
            if (p.rel == rel) p = Pic{};
    }

    std::string card_html, sheet_html;
    std::vector<std::string> problems;
    size_t images = 0;
    const Viewer* viewer = nullptr;  // --viewer
    Committer* committer = nullptr;  // finishes the pictures' writes

private:
    void problem(const std::string& what) { problems.push_back(m_.name + ": " + what); }

    // A picture as an 8-bit PNG in this material's folder: grey pictures as one channel (a third
    // of the bytes), and a picture this material already has (a source copied unchanged, a
    // preset that packs the same map) is not written twice: the page points at the first.
    std::optional<Pic> write_pic(const Image& image, const std::string& name) {
        bool grey = true;
        for (size_t p = 0; grey && p + 2 < image.pixels.size(); p += 3)
            grey = image.pixels[p] == image.pixels[p + 1] && image.pixels[p] == image.pixels[p + 2];
        Image one;
        if (grey) {
            one = Image(image.width, image.height, 1);
            for (size_t p = 0; p < one.pixels.size(); ++p) one.pixels[p] = image.pixels[p * 3];
        }
        std::vector<unsigned char> bytes;
        std::string error;
        if (!encode_image(grey ? one : image, EncodeOptions{FileFormat::png, 8}, bytes, error)) {
            problem(error);
            return std::nullopt;
        }
        const std::string hash = sha256_hex(bytes);
        if (const auto it = written_.find(hash); it != written_.end()) return it->second;
        std::optional<StagedFile> staged;  // none: the file holds these bytes already
        if (!stage_file_under(opt_.out, stem_ + "/" + name, bytes, staged, error)) {
            problem(error);
            return std::nullopt;
        }
        if (staged) committer->add(index_, stem_ + "/" + name, std::move(*staged));
        ++images;
        const Pic pic{stem_ + "/" + name, image.width, image.height};
        written_.emplace(hash, pic);
        return pic;
    }

    // An output or preview file as the engine samples it: an 8-bit file kept as its codes (a
    // quarter of the memory of floats: an 8192² RGBA map is 256 MB, not 1 GB), any other as
    // floats; a block-compressed output (.dds, .ktx2; `o` names its block format) level 0
    // decoded by the codec that wrote it (the blocks the engine samples, as the preview renders
    // them), to the channels the manifest lists. Only a regular file is opened (never a link).
    static bool read(const fs::path& file, const manifest::Output* o, Decoded& image, std::string& error) {
        if (const auto why = not_a_regular_file(file)) {
            error = file.string() + ": " + *why;
            return false;
        }
        if (!o || o->block_format.empty()) {
            InputFile in;
            in.display = file.string();
            in.path = file;
            ImageInfo info;
            return read_image(in, image, info, error);
        }
        int channels = 0;
        for (const Channel& c : o->channels) channels += c.key == "RGB" ? 3 : 1;
        std::vector<uint8_t> bytes;
        texture::GpuTexture gt;
        if (!read_file(file, bytes, error) || !texture::read_gpu_texture(bytes, gt, error) ||
            !texture::decode_top_level(gt, std::clamp(channels, 1, 4), o->normal_z_reconstructed, image.codes, error)) {
            error = file.string() + ": " + error;
            return false;
        }
        return true;
    }
    static Image thumbnail_of(const Decoded& d, int max_size, bool srgb) {
        return d.is_codes() ? thumbnail(d.codes, max_size, srgb) : thumbnail(d.floats, max_size, srgb);
    }
    static Image channel_thumbnail_of(const Decoded& d, int channel, int max_size) {
        return d.is_codes() ? channel_thumbnail(d.codes, channel, max_size)
                            : channel_thumbnail(d.floats, channel, max_size);
    }
    // Channel `ch` of `d` alone, codes or floats as `d` holds it.
    static std::shared_ptr<Decoded> plane_of(const Decoded& d, int ch) {
        auto plane = std::make_shared<Decoded>();
        auto copy = [&](const auto& src, auto& dst) {
            dst = std::remove_reference_t<decltype(dst)>(src.width, src.height, 1);
            for (size_t p = 0; p < dst.pixels.size(); ++p)
                dst.pixels[p] = src.pixels[p * static_cast<size_t>(src.channels) + static_cast<size_t>(ch)];
        };
        if (d.is_codes()) copy(d.codes, plane->codes);
        else copy(d.floats, plane->floats);
        return plane;
    }

    std::optional<Pic> preview_pic(const fs::path& folder, const std::string& name) {
        const auto file = preview_file(folder, m_.name);
        if (!file) return std::nullopt;
        Decoded image;
        std::string error;
        if (!read(*file, nullptr, image, error)) {
            problem(error);
            return std::nullopt;
        }
        return write_pic(thumbnail_of(image, opt_.thumb_size, true), name);
    }

    // Thumbnails of one output; `keep` receives the decoded image when the overlays need it.
    OutputPics output_pics(const manifest::Output& o, const fs::path& base, const std::string& prefix, Decoded* keep) {
        OutputPics pics;
        if (!opt_.allow_outside && !inside(o.file)) {
            pics.problem = "\"" + o.file + "\" lies outside the manifest's folder (allow it with --allow-outside)";
            return pics;
        }
        Decoded image;
        std::string error;
        if (!read(base / o.file, &o, image, error)) {
            pics.problem = error;
            return pics;
        }
        bool color_rgb = false, packed = false;
        for (const Channel& c : o.channels) {
            if (c.key == "RGB" && c.kind == Channel::Kind::role && is_color_role(c.role)) color_rgb = true;
            if (c.key != "RGB") packed = true;
        }
        std::string stem = safe_component(fs::path(o.file).stem().string());
        for (int n = 2; !taken_.insert(ascii_lower(prefix + stem)).second; ++n)
            stem = safe_component(fs::path(o.file).stem().string()) + "_" + std::to_string(n);
        if (auto p = write_pic(thumbnail_of(image, opt_.thumb_size, o.srgb && color_rgb), prefix + stem + ".png"))
            pics.main = *p;
        if (packed) {
            for (const Channel& c : o.channels) {
                if (c.key == "RGB" || c.kind == Channel::Kind::constant || c.kind == Channel::Kind::unused) continue;
                const int ch = channel_index(c.key);
                if (ch >= image.channels()) continue;
                if (auto p = write_pic(channel_thumbnail_of(image, ch, std::max(16, opt_.thumb_size / 4)),
                                       prefix + stem + "." + c.key + ".png"))
                    pics.channels.emplace_back(c.key, *p);
            }
        }
        if (keep) *keep = std::move(image);
        return pics;
    }

    void read_outputs() {
        for (const manifest::Output& o : m_.outputs) {
            bool needed = false;  // the overlays read the albedo, metalness and opacity
            for (const Channel& c : o.channels)
                if ((c.kind == Channel::Kind::role) &&
                    (c.role == Role::albedo || c.role == Role::metalness || c.role == Role::opacity))
                    needed = true;
            Decoded image;
            OutputPics pics = output_pics(o, dir_, "out-", needed ? &image : nullptr);
            if (!pics.problem.empty()) problem(pics.problem);
            pics_.outputs.push_back(std::move(pics));
            if (image.width() == 0) continue;
            bool albedo = false;
            for (const Channel& c : o.channels) {
                if (c.kind != Channel::Kind::role) continue;
                if (c.role == Role::albedo && c.key == "RGB") {
                    albedo = true;
                    albedo_srgb_ = o.srgb;
                    if (!pics_.sheet && !pics_.outputs.back().main.rel.empty()) pics_.sheet = pics_.outputs.back().main;
                } else if (c.role == Role::metalness || c.role == Role::opacity) {
                    const int ch = std::min(channel_index(c.key), image.channels() - 1);
                    (c.role == Role::metalness ? metalness_ : opacity_) = plane_of(image, ch);
                }
            }
            // Its last use: moved, never copied.
            if (albedo) albedo_ = std::make_shared<Decoded>(std::move(image));
        }
    }

    void read_sources() {
        // A material with no outputs (validate's) is judged on its sources, as the rules judged
        // it: the albedo, metalness and opacity maps as stored (a packed input's channels are
        // not unpacked here; the page names the maps it read).
        const bool judge_sources = m_.outputs.empty();
        for (const manifest::Input& in : m_.inputs) {
            if (m_.archive) break;  // entries of a .zip are not files: the card says so
            const fs::path file = dir_ / m_.source / in.file;
            Decoded image;
            std::string error;
            if (!read(file, nullptr, image, error)) {
                problem("source " + error);
                pics_.sources.emplace_back();
                continue;
            }
            const bool srgb = is_color_role(in.role) && in.color_space == "sRGB";
            auto p = write_pic(thumbnail_of(image, opt_.thumb_size, srgb),
                               "src-" + std::string(role_name(in.role)) + ".png");
            pics_.sources.push_back(p.value_or(Pic{}));
            if (!judge_sources) continue;
            if (in.role == Role::albedo) {
                albedo_srgb_ = srgb;
                albedo_ = std::make_shared<Decoded>(std::move(image));
            } else if (in.role == Role::metalness || (in.role == Role::opacity && !in.unused)) {
                (in.role == Role::metalness ? metalness_ : opacity_) = plane_of(image, 0);
            }
        }
    }

    static Scalar scalar_of(const std::shared_ptr<Decoded>& plane, const manifest::Material& m, Role role,
                            float fallback) {
        Scalar s;
        s.constant = fallback;
        for (const manifest::Constant& c : m.constants)
            if (c.role == role && !c.value.empty()) s.constant = c.value[0];
        if (plane && plane->is_codes()) s.codes = &plane->codes;
        else if (plane) s.image = &plane->floats;
        return s;
    }

    void overlays() {
        if (albedo_) {
            const Scalar metal = scalar_of(metalness_, m_, Role::metalness, 0.f);
            const Scalar opacity = scalar_of(opacity_, m_, Role::opacity, 1.f);
            const rules::Thresholds& t = *opt_.thresholds;
            pics_.albedo = write_pic(albedo_->is_codes() ? albedo_overlay(albedo_->codes, albedo_srgb_, metal, opacity,
                                                                          t, pics_.albedo_stats, opt_.thumb_size)
                                                         : albedo_overlay(albedo_->floats, albedo_srgb_, metal, opacity,
                                                                          t, pics_.albedo_stats, opt_.thumb_size),
                                     "albedo-range.png");
        }
        // A constant metalness written into a channel (glTF's B = 0) is no map to judge.
        const bool constant_metal = std::any_of(m_.constants.begin(), m_.constants.end(),
                                                [](const manifest::Constant& c) { return c.role == Role::metalness; });
        if (metalness_ && !constant_metal) {
            const Scalar metal = scalar_of(metalness_, m_, Role::metalness, 0.f);
            pics_.metalness = write_pic(metalness_overlay(metal, metalness_->width(), metalness_->height(),
                                                          *opt_.thresholds, pics_.metal_stats, opt_.thumb_size),
                                        "metalness.png");
        }
        albedo_.reset();
        metalness_.reset();
        opacity_.reset();
    }

    void compare() {
        if (opt_.compare_previews) pics_.compare_preview = preview_pic(*opt_.compare_previews, "compare-preview.png");
        for (const manifest::Output& o : other_->outputs) {
            OutputPics pics = output_pics(o, other_dir_, "compare-", nullptr);
            if (!pics.problem.empty()) problem("--compare: " + pics.problem);
            pics_.compare.push_back(std::move(pics));
        }
    }

    const Options& opt_;
    const fs::path& dir_;
    const manifest::Material& m_;
    std::string stem_;
    size_t index_;
    const manifest::Material* other_;
    fs::path other_dir_;
    std::string other_preset_;

    std::set<std::string> taken_;
    std::map<std::string, Pic> written_;  // sha256 of a PNG -> where it is
    MaterialPictures pics_;
    std::shared_ptr<Decoded> albedo_, metalness_, opacity_;
    bool albedo_srgb_ = true;
};

}  // namespace

std::vector<std::string> material_stems(const std::vector<std::string>& names) {
    std::set<std::string> taken{"index.html", "rules.html"};
    std::vector<std::string> stems;
    for (const std::string& name : names) {
        const std::string base = safe_component(name);
        std::string s = base;
        for (int n = 2; !taken.insert(ascii_lower(s)).second; ++n) {
            std::string suffix = "_";  // appended: see temp_name (core/files.cpp), GCC 12 -O3 -Wrestrict
            suffix.append(std::to_string(n));
            s = base.substr(0, std::min(base.size(), 96 - suffix.size())) + suffix;
        }
        stems.push_back(s);
    }
    return stems;
}

std::optional<fs::path> preview_file(const fs::path& dir, const std::string& name) {
    std::string s = name;
    for (char& c : s)
        if (c == '/' || c == '\\' || c == ':' || c == '*' || c == '?' || c == '"' || c == '<' || c == '>' || c == '|')
            c = '_';
    if (s.empty() || s == "." || s == "..") s = "material";
    const fs::path file = dir / (s + ".png");
    if (not_a_regular_file(file)) return std::nullopt;
    return file;
}

namespace {

// What a material's job holds at most: the largest of its outputs being read, the albedo kept
// for the overlay, and the metalness and opacity planes; 8-bit files as their codes, others as
// floats (as read() keeps them).
uint64_t decoded_bytes(const manifest::Material& m) {
    uint64_t largest = 0, albedo = 0, plane = 0;
    for (const manifest::Output& o : m.outputs) {
        uint64_t channels = 0;
        for (const Channel& c : o.channels) channels += c.key.size();
        const uint64_t sample = o.bit_depth <= 8 ? 1 : sizeof(float);
        const uint64_t pixels = uint64_t(std::max(o.width, 0)) * uint64_t(std::max(o.height, 0));
        const uint64_t bytes = pixels * std::max<uint64_t>(channels, 1) * sample;
        largest = std::max(largest, bytes);
        for (const Channel& c : o.channels)
            if (c.kind == Channel::Kind::role && c.role == Role::albedo) albedo = bytes;
        plane = std::max(plane, pixels * sample);
    }
    return largest + albedo + 2 * plane;
}

// The pixels a material's job decodes (its outputs, and its sources unless --no-sources): what
// its time grows with, to order the jobs by.
uint64_t pixels_to_read(const manifest::Material& m, const Options& o) {
    uint64_t n = 0;
    auto add = [&n](int w, int h) { n += uint64_t(std::max(w, 0)) * uint64_t(std::max(h, 0)); };
    for (const manifest::Output& out : m.outputs) add(out.width, out.height);
    if (o.sources)
        for (const manifest::Input& in : m.inputs) add(in.width, in.height);
    return n;
}

// The report folder may be neither the output folder of the manifest (which holds what the
// manifest lists) nor a material's source folder or a folder inside one: the next ingest of
// the library would take the report's pictures for material maps.
fs::path canonical_or_self(const fs::path& p) {
    std::error_code ec;
    return fs::weakly_canonical(fs::absolute(p, ec), ec);
}

std::string output_folder_conflict(const fs::path& out, const fs::path& manifest_dir) {
    if (canonical_or_self(out) != canonical_or_self(manifest_dir)) return {};
    return out.string() + " is the output folder of " + (manifest_dir / "manifest.json").string() +
           "; give the report a folder of its own (e.g. " + (manifest_dir / "report").string() + ")";
}

std::string source_folder_conflict(const fs::path& out, const fs::path& sources_dir, const manifest::Manifest& m) {
    const fs::path o = canonical_or_self(out);
    for (const auto& mm : m.materials) {
        if (mm.source.empty() || mm.archive) continue;
        const fs::path src = canonical_or_self(sources_dir / mm.source);
        const fs::path rel = o.lexically_relative(src);
        if (!rel.empty() && *rel.begin() != "..")
            return out.string() + " lies in the source folder of the material '" + mm.name + "' (" + src.string() +
                   "): the next ingest would take the report's pictures for material maps; give the report a folder "
                   "outside the material sets";
    }
    return {};
}

// A report replaces only what a report wrote: a folder that holds anything must hold our marker
// (written before the first picture, so an interrupted report's folder is ours too) or our page
// (index.html naming matforge as its generator: reports before the marker), so a user's folder
// is never written into.
constexpr const char* kMarker = ".matforge-report";
constexpr std::string_view kMarkerText = "a matforge report folder: matforge report rewrites what is here\n";

std::string foreign_report_folder(const fs::path& out) {
    std::error_code ec;
    if (!fs::exists(fs::symlink_status(out, ec)) || fs::is_empty(out, ec)) return {};
    if (fs::is_regular_file(fs::symlink_status(out / kMarker, ec))) return {};
    const fs::path index = out / "index.html";
    if (fs::is_regular_file(fs::symlink_status(index, ec))) {
        std::ifstream f(index, std::ios::binary);
        std::string head(4096, '\0');
        f.read(head.data(), static_cast<std::streamsize>(head.size()));
        head.resize(static_cast<size_t>(f.gcount()));
        if (head.find("<meta name=\"generator\" content=\"matforge ") != std::string::npos) return {};
    }
    return out.string() + " holds files that no matforge report wrote; give the report an empty or new folder "
                          "(or one an earlier report wrote)";
}

// The page of `m`, whose sources are relative to `dir` (see write_report).
bool write_page(const Options& options, const manifest::Manifest& m_in, const fs::path& dir, Result& result,
                std::string& error) {
    result = {};
    Options opt = options;
    const manifest::Manifest* m = &m_in;
    const std::string label = opt.manifest.empty() ? std::string("matforge validate") : opt.manifest.string();
    if (!opt.thresholds) {  // the run's (older manifests: the defaults it then had)
        opt.thresholds = rules::thresholds_from(m->thresholds, error);
        if (!opt.thresholds) {
            error = label + ": " + error;
            return false;
        }
    }
    std::optional<manifest::Manifest> other;
    std::map<std::string, const manifest::Material*> other_by_name;
    if (opt.compare) {
        other = manifest::read_manifest(opt.compare->string(), error);
        if (!other) return false;
        for (const auto& om : other->materials) other_by_name[om.name] = &om;
    }
    const fs::path other_dir = opt.compare ? opt.compare->parent_path() : fs::path{};
    if (std::string why = source_folder_conflict(opt.out, dir, *m); !why.empty()) {
        error = why;
        return false;
    }
    if (std::string why = foreign_report_folder(opt.out); !why.empty()) {
        error = why;
        return false;
    }
    std::error_code mkdir_error;
    fs::create_directories(opt.out, mkdir_error);  // the folder itself; what is below it: write_file_under
    if (!write_file_under(opt.out, kMarker,
                          std::span(reinterpret_cast<const unsigned char*>(kMarkerText.data()), kMarkerText.size()),
                          error))
        return false;
    std::vector<std::string> names;
    for (const auto& mm : m->materials) names.push_back(mm.name);
    const std::vector<std::string> stems = material_stems(names);

    std::unique_ptr<Viewer> viewer;  // --viewer: the look-dev renderers and viewer/lookdev.js
    if (opt.viewer) {
        std::string why;
        viewer = Viewer::create(opt, *m, why);
        if (!viewer) result.problems.push_back("interactive views: " + why);
    }
    Committer committer;
    std::vector<std::unique_ptr<MaterialJob>> jobs;
    for (size_t i = 0; i < m->materials.size(); ++i) {
        const auto it = other_by_name.find(m->materials[i].name);
        jobs.push_back(std::make_unique<MaterialJob>(opt, dir, m->materials[i], stems[i], i,
                                                     it == other_by_name.end() ? nullptr : it->second, other_dir,
                                                     other ? other->preset : std::string()));
        jobs.back()->viewer = viewer.get();
        jobs.back()->committer = &committer;
    }
    // The largest materials first (longest-processing-time order): the last to start is then a
    // small one, and no core idles through a large material's tail at the end. The page keeps
    // the manifest's order (each job's results stay in its slot).
    std::vector<size_t> order(jobs.size());
    std::vector<uint64_t> work(jobs.size());
    for (size_t i = 0; i < jobs.size(); ++i) {
        order[i] = i;
        work[i] = pixels_to_read(m->materials[i], opt);
    }
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return work[a] > work[b]; });
    // A stop asked by a signal: no new material starts, and no page is written that would name
    // pictures of materials never done (the CLI exits 130/143).
    MemoryBudget budget(opt.memory_budget);
    parallel_for(jobs.size(), opt.jobs, [&](size_t k) {
        const size_t i = order[k];
        const BudgetLease lease(&budget, decoded_bytes(m->materials[i]));
        if (!stop_requested()) jobs[i]->run();
    });
    // The cards once every picture is in place, so a picture whose write failed is not shown.
    for (const Committer::Failure& f : committer.finish()) jobs[f.job]->unwritten(f.rel, f.error);
    if (stop_requested()) {
        error = "stopped before the end; no index.html written";
        return false;
    }
    parallel_for(jobs.size(), opt.jobs, [&](size_t i) { jobs[i]->card(); });

    std::set<std::string> codes;
    std::map<std::string, std::array<size_t, 2>> by_code;  // code -> (findings, materials)
    for (const auto& mm : m->materials) {
        std::set<std::string> seen;
        for (const Finding& f : mm.findings) {
            codes.insert(f.code);
            ++by_code[f.code][0];
            if (seen.insert(f.code).second) ++by_code[f.code][1];
            ++result.findings;
        }
    }
    for (const auto& f : m->failures) codes.insert(f.code);
    result.materials = m->materials.size();

    const auto counts = manifest::count_findings(*m);
    std::string h;
    h.reserve(jobs.size() * 8192 + 65536);
    // The generator names the page as matforge's: a walk of an input never reads its folder.
    h += "<!doctype html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<meta name=\"generator\" content=\"" +
         markup_escape(std::string(kGenerator)) +
         "\">\n"
         // Nothing but this folder's pictures and the inline style and script: the page must open
         // the same from disk, from a CI artifact or with no network at all.
         "<meta http-equiv=\"Content-Security-Policy\" content=\"default-src 'none'; img-src 'self' file: data:; "
         "style-src 'unsafe-inline'; script-src 'unsafe-inline'" +
         std::string(viewer ? " file:" : "") +  // the views' data: <script src> of files beside the page
         "\">\n"
         "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
         "<title>matforge report — " +
         markup_escape(label) + "</title>\n<style>\n" + kStyle + "</style>\n</head>\n<body data-page-size=\"" +
         std::to_string(std::max(1, opt.page_size)) +
         "\">\n<header>\n<h1>matforge report</h1>\n<div class=\"meta\"><code>" + markup_escape(label) +
         "</code> · preset <b>" + markup_escape(m->preset) + "</b> · normals " +
         std::string(convention_name(m->normal_convention)) + " · " + markup_escape(m->generator) +
         (other ? " · compared with <code>" + markup_escape(opt.compare->string()) + "</code> (preset " +
                      markup_escape(other->preset) + ")"
                : std::string()) +
         "</div>\n<div class=\"summary\" id=\"summary\">" + std::to_string(m->materials.size()) + " materials · " +
         std::to_string(counts[2]) + " error · " + std::to_string(counts[1]) + " warning · " +
         std::to_string(counts[0]) + " info · " + std::to_string(m->failures.size()) +
         " failed inputs · <a style=\"color:#9cd0ff\" href=\"rules.html\">rules</a></div>\n</header>\n<main>\n";
    h += "<noscript><p class=\"meta\">JavaScript is off: all " + std::to_string(m->materials.size()) +
         " materials are on this one page.</p></noscript>\n";
    if (!m->failures.empty()) {
        h += "<h2>Inputs that could not be processed</h2>\n<table class=\"failures\"><thead><tr><th>source</th>"
             "<th>code</th><th>message</th></tr></thead><tbody>\n";
        for (const auto& f : m->failures)
            h += "<tr class=\"failure\" data-code=\"" + markup_escape(f.code) + "\"><td><code>" +
                 markup_escape(f.source) + "</code></td><td><a href=\"" + rule_link(f.code) + "\">" +
                 markup_escape(f.code) + "</a></td><td>" + markup_escape(f.message) + "</td></tr>\n";
        h += "</tbody></table>\n";
    }
    if (!by_code.empty()) {
        h += "<details><summary>Findings by code</summary><table class=\"by-code\"><thead><tr><th>code</th><th>findings"
             "</th><th>materials</th></tr></thead><tbody>\n";
        for (const auto& [c, n] : by_code)
            h += "<tr><td><a href=\"" + rule_link(c) + "\">" + markup_escape(c) + "</a></td><td>" +
                 std::to_string(n[0]) + "</td><td>" + std::to_string(n[1]) + "</td></tr>\n";
        h += "</tbody></table></details>\n";
    }
    h += "<h2 id=\"contact-sheet\">Contact sheet</h2>\n<div class=\"sheet\">\n";
    for (const auto& j : jobs) h += j->sheet_html;
    h +=
        "</div>\n<h2 id=\"materials\">Materials</h2>\n"
        "<select id=\"filter\" hidden><option value=\"0\">all materials</option><option value=\"1\">with findings</option>"
        "<option value=\"2\">with warnings or errors</option><option value=\"3\">with errors</option></select>\n";
    h += pager_html();
    for (const auto& j : jobs) h += j->card_html;
    h += pager_html();
    h += "</main>\n<script>" + std::string(kScript) + "</script>\n</body>\n</html>\n";

    for (const auto& j : jobs) {
        result.images += j->images;
        result.problems.insert(result.problems.end(), j->problems.begin(), j->problems.end());
    }
    if (viewer) viewer->state_sizes(h);
    result.index = opt.out / "index.html";
    auto bytes = [](const std::string& s) {
        return std::span(reinterpret_cast<const unsigned char*>(s.data()), s.size());
    };
    // Never through a link in the report folder: a file outside -o is never written.
    if (!write_file_under(opt.out, "index.html", bytes(h), error)) return false;
    const std::string rules = rules_page(codes);
    return write_file_under(opt.out, "rules.html", bytes(rules), error);
}

}  // namespace

bool write_report(const Options& options, Result& result, std::string& error) {
    result = {};
    const auto m = manifest::read_manifest(options.manifest.string(), error);
    if (!m) return false;
    const fs::path dir = options.manifest.parent_path();
    if (std::string why = output_folder_conflict(options.out, dir); !why.empty()) {
        error = why;
        return false;
    }
    return write_page(options, *m, dir, result, error);
}

bool write_report(const Options& options, const manifest::Manifest& m, const fs::path& sources_dir, Result& result,
                  std::string& error) {
    Options opt = options;
    opt.manifest.clear();
    return write_page(opt, m, sources_dir, result, error);
}

}  // namespace mf::report
