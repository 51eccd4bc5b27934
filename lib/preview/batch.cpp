#include "preview/batch.hpp"

#include <deque>
#include <future>
#include <map>
#include <memory>

#include "core/text.hpp"

namespace mf::preview {

std::string unique_stem(const std::string& name, std::set<std::string>& taken) {
    std::string s = name;
    for (char& c : s)
        if (c == '/' || c == '\\' || c == ':' || c == '*' || c == '?' || c == '"' || c == '<' || c == '>' || c == '|')
            c = '_';
    if (s.empty() || s == "." || s == "..") s = "material";
    std::string candidate = s;
    for (int n = 2; !taken.insert(ascii_lower(candidate)).second; ++n) candidate = s + "_" + std::to_string(n);
    return candidate;
}

std::optional<std::vector<Job>> manifest_jobs(const std::filesystem::path& manifest, const SceneFile& sf,
                                              bool allow_outside, std::string& error) {
    auto m = manifest::read_manifest(manifest.string(), error);
    if (!m) return std::nullopt;
    std::vector<Job> jobs;
    std::set<std::string> stems;
    const std::filesystem::path dir = manifest.parent_path();
    const MaterialOptions mo{allow_outside, {}};
    for (manifest::Material& mm : m->materials) {
        std::string stem = unique_stem(mm.name, stems);
        std::string name = mm.name;
        jobs.push_back({std::move(name), std::move(stem),
                        [mm = std::move(mm), dir, mo, &sf](const BlockSupport& samples, std::vector<std::string>& notes,
                                                           std::string& err) -> std::optional<render::Material> {
                            MaterialOptions o = mo;
                            o.samples = samples;
                            auto mat = load_material(mm, dir, o, notes, err);
                            if (mat && sf.material && !apply_scene_material(*sf.material, *mat, err))
                                return std::nullopt;
                            if (mat) place_textures(sf, *mat);
                            return mat;
                        }});
    }
    return jobs;
}

std::optional<std::vector<Job>> scene_jobs(const std::filesystem::path& scene_file, const SceneFile& sf,
                                           std::string& error) {
    if (!sf.material) {
        error = scene_file.string() + ": without a manifest the scene must hold a \"material\"";
        return std::nullopt;
    }
    std::set<std::string> stems;
    const std::string name = scene_file.stem().string();
    std::vector<Job> jobs;
    jobs.push_back({name, unique_stem(name, stems),
                    [name, &sf](const BlockSupport&, std::vector<std::string>&,
                                std::string& err) -> std::optional<render::Material> {
                        render::Material m;
                        m.name = name;
                        if (!apply_scene_material(*sf.material, m, err)) return std::nullopt;
                        place_textures(sf, m);
                        return m;
                    }});
    return jobs;
}

namespace {

// What one material comes to: its messages in the order one loop would say them, whether it
// failed, and its 8-bit image for the contact sheet.
struct Outcome {
    std::vector<std::string> lines;
    bool failed = false;
    std::vector<uint8_t> rgba8;
};

// The reading half, on a worker thread: files decoded, textures converted and their mips made
// (render::Renderer::prepare makes no Vulkan call that needs the renderer's thread).
struct Loaded {
    std::optional<render::PreparedMaterial> prepared;
    std::vector<std::string> notes;
    std::string error;
};

std::future<Outcome> ready_outcome(Outcome o) {
    std::promise<Outcome> p;
    p.set_value(std::move(o));
    return p.get_future();
}

// How many materials the reading runs ahead of the rendering, after one of `bytes` of
// textures: two, one where the textures took more than 128 MB (4K maps), none past 512 MB (8K:
// each in memory alone, as without the pipeline). On lavapipe, whose passes are not all
// multithreaded, reading ahead fills idle cores.
size_t read_ahead(size_t bytes) { return bytes > (size_t{512} << 20) ? 0 : bytes > (size_t{128} << 20) ? 1 : 2; }

// One pipeline run: the readers, the renderer's thread (the caller's), the writers.
class Batch {
public:
    Batch(const SceneFile& sf, const std::vector<Job>& jobs, const BatchOptions& opt,
          const std::function<void(const std::string&)>& say)
        : sf_(sf), jobs_(jobs), opt_(opt), say_(say) {}

    BatchResult run() {
        // The first material is read while the device starts and the scene's load-time passes
        // run (the studio environment's prefiltering): the reading waits for the renderer only
        // where it needs it, to know a GPU texture file's formats and to prepare the textures.
        if (!jobs_.empty()) launch();
        // Destroyed before `loading_` (which waits for the readers): unset, it wakes them.
        std::promise<void> made = std::move(made_early_);
        try {
            context_.emplace(opt_.context);
            if (opt_.progress)
                say_(context_->info().name + (context_->info().cpu ? " (CPU)" : "") + ", " +
                     std::to_string(sf_.scene.width) + "x" + std::to_string(sf_.scene.height) + ", " +
                     std::to_string(jobs_.size()) + " material(s)");
            renderer_.emplace(*context_, sf_.scene);
            made.set_value();
        } catch (...) {
            made.set_exception(std::current_exception());
            throw;
        }
        for (const std::string& n : renderer_->take_notes()) say_("note: " + n);
        for (size_t i = 0; i < jobs_.size(); ++i) {
            if (launched_ == i) launch();
            Loaded l = loading_.front().get();
            loading_.pop_front();
            const size_t ahead = read_ahead(l.prepared ? l.prepared->bytes() : 0);
            while (launched_ < jobs_.size() && launched_ <= i + ahead) launch();
            pending_.push_back(render_one(i, std::move(l)));
            flush(1);
        }
        flush(0);
        for (const auto& [text, n] : repeated_notes_)
            if (n > 1) say_("note said above, for " + std::to_string(n - 1) + " more material(s) too: " + text);
        return std::move(result_);
    }

private:
    void launch() {
        const size_t i = launched_++;
        loading_.push_back(std::async(std::launch::async, [this, i] { return load(i); }));
    }

    Loaded load(size_t i) {
        Loaded l;
        try {
            auto m = jobs_[i].load(
                [&](uint32_t f) {
                    ready_.get();
                    return renderer_->samples(f);
                },
                l.notes, l.error);
            if (m) {
                ready_.get();
                l.prepared = renderer_->prepare(*m);
            }
        } catch (const std::exception& e) {  // this material's textures (or the renderer); the others go on
            l.error = e.what();
        }
        return l;
    }

    // Upload and draw on this thread; encode and write on a thread of its own while the next
    // material renders.
    std::future<Outcome> render_one(size_t i, Loaded l) {
        const Job& job = jobs_[i];
        Outcome o;
        for (const std::string& n : l.notes) o.lines.push_back("note: " + n);
        if (!l.prepared) {
            o.lines.push_back(job.name + ": " + l.error);
            o.failed = true;
            return ready_outcome(std::move(o));
        }
        try {
            render::GpuMaterial gm = renderer_->upload(std::move(*l.prepared));
            for (const std::string& n : renderer_->take_notes()) o.lines.push_back(job.name + ": note: " + n);
            const bool png = opt_.format == "png";
            std::vector<uint8_t> rgba8;
            std::vector<float> rgba32f;
            if (png || opt_.contact_sheet) rgba8 = renderer_->render(gm, sf_.output).rgba8;
            if (!png) {
                render::OutputOptions lin;
                lin.format = render::PixelFormat::rgba32f;
                rgba32f = renderer_->render(gm, lin).rgba32f;
            }
            const std::filesystem::path out = opt_.out / (job.stem + "." + opt_.format);
            std::string progress = "[" + std::to_string(i + 1) + "/" + std::to_string(jobs_.size()) + "] ";
            return std::async(std::launch::async, [this, &job, png, out, progress = std::move(progress),
                                                   o = std::move(o), rgba8 = std::move(rgba8),
                                                   rgba32f = std::move(rgba32f), gm = std::move(gm)]() mutable {
                { render::GpuMaterial freed = std::move(gm); }  // its device objects, off the render thread
                const uint32_t w = sf_.scene.width, h = sf_.scene.height;
                std::string error;
                bool written = false;
                try {
                    written = png ? write_png(out, w, h, rgba8, error) : write_exr(out, w, h, rgba32f, error);
                } catch (const std::exception& e) {
                    error = e.what();
                }
                if (!written) {
                    o.lines.push_back(job.name + ": " + error);
                    o.failed = true;
                } else if (opt_.progress) {
                    o.lines.push_back(progress + out.string());
                }
                o.rgba8 = std::move(rgba8);
                return std::move(o);
            });
        } catch (const render::NoDeviceError&) {
            throw;
        } catch (const std::exception& e) {  // this material's upload or draw failed; the others go on
            o.lines.push_back(job.name + ": " + e.what());
            o.failed = true;
            return ready_outcome(std::move(o));
        }
    }

    // Outcomes in job order, said as they complete; at most `keep` left in flight (the last
    // material's image may still be being written while the next one renders).
    void flush(size_t keep) {
        while (pending_.size() > keep) {
            Outcome o = pending_.front().get();
            pending_.pop_front();
            const Job& job = jobs_[reported_++];
            for (const std::string& line : o.lines) {
                // A note said for many materials alike (the same fallback, the same missing
                // feature) is said once, and counted at the end (issue 45: once per material hid
                // the rest of the log).
                const size_t at = line.rfind("note: ", 0) == 0 ? 0 : line.find(": note: ");
                if (at != std::string::npos) {
                    const std::string text = line.substr(at == 0 ? 6 : at + 8);
                    if (repeated_notes_[text]++ > 0) continue;
                }
                say_(line);
            }
            ++(o.failed ? result_.failed : result_.rendered);
            if (!o.failed && opt_.contact_sheet)
                result_.tiles.push_back({job.name, sf_.scene.width, sf_.scene.height, std::move(o.rgba8)});
        }
    }

    const SceneFile& sf_;
    const std::vector<Job>& jobs_;
    const BatchOptions& opt_;
    const std::function<void(const std::string&)>& say_;
    BatchResult result_;
    std::map<std::string, size_t> repeated_notes_;  // a note's text -> how many materials had it
    std::optional<render::Context> context_;
    std::optional<render::Renderer> renderer_;
    std::promise<void> made_early_;
    std::shared_future<void> ready_ = made_early_.get_future().share();
    // Declared after the renderer: destroyed first, so every reader and writer has finished
    // (a future from std::async waits in its destructor) before the renderer goes.
    std::deque<std::future<Outcome>> pending_;
    std::deque<std::future<Loaded>> loading_;
    size_t launched_ = 0, reported_ = 0;
};

}  // namespace

BatchResult render_batch(const SceneFile& sf, const std::vector<Job>& jobs, const BatchOptions& opt,
                         const std::function<void(const std::string&)>& say) {
    return Batch(sf, jobs, opt, say).run();
}

}  // namespace mf::preview
