#include "preview/batch.hpp"

#include <algorithm>
#include <condition_variable>
#include <deque>
#include <exception>
#include <map>
#include <memory>
#include <mutex>
#include <thread>

#include "base/parallel.hpp"
#include "base/stopwatch.hpp"
#include "base/thread_priority.hpp"
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

// How far below the pipeline's other threads the workers run (lower_this_thread_priority).
constexpr int kWorkerNice = 5;

// What one material comes to: its messages in the order one loop would say them, whether it
// failed, and its 8-bit image for the contact sheet.
struct Outcome {
    std::vector<std::string> lines;
    bool failed = false;
    std::vector<uint8_t> rgba8;
};

// The reading half, on a worker: files decoded, textures converted and their mips made
// (render::Renderer::prepare makes no Vulkan call that needs the renderer's thread).
struct Loaded {
    std::optional<render::PreparedMaterial> prepared;
    std::vector<std::string> notes;
    std::string error;
    uint64_t bytes = 0;  // held against the budget until uploaded
};

// Thrown inside a worker's read when the batch stops before the renderers exist.
struct Stopped {};

// One pipeline run: the workers, the lanes, and the caller's thread saying the outcomes in order.
// Every shared field below is guarded by mutex_ and signalled by changed_.
class Batch {
public:
    Batch(const SceneFile& sf, const std::vector<Job>& jobs, const BatchOptions& opt,
          const std::function<void(const std::string&)>& say)
        : sf_(sf), jobs_(jobs), opt_(opt), say_(say), loaded_(jobs.size()), outcomes_(jobs.size()) {}

    ~Batch() { shut_down(); }
    Batch(const Batch&) = delete;
    Batch& operator=(const Batch&) = delete;

    BatchResult run() {
        // The first materials are read while the device starts, and prepared while the renderers
        // are made (pipelines, the scene's load-time passes: the studio environment's
        // prefiltering): a read waits only for the device, whose formats render::samples and
        // render::prepare need.
        BatchTimes& times = result_.times;
        const unsigned hw = std::max(1u, std::thread::hardware_concurrency());
        const unsigned workers = opt_.jobs > 0 ? opt_.jobs : hw;
        for (unsigned w = 0; w < std::max(1u, workers) && !jobs_.empty(); ++w)
            workers_.emplace_back([this] { work(); });
        times.workers = static_cast<unsigned>(workers_.size());
        try {
            if (opt_.device_ahead && opt_.device_ahead->made.valid()) context_ = opt_.device_ahead->made.get();
            else context_ = std::make_unique<render::Context>(opt_.context);
            {
                const std::lock_guard<std::mutex> lock(mutex_);
                device_ready_ = true;
            }
            changed_.notify_all();
            times.device = start_.elapsed();
            const unsigned lanes =
                std::max(1u, std::min<unsigned>(opt_.lanes > 0 ? opt_.lanes : lanes_for(context_->info()),
                                                static_cast<unsigned>(std::max<size_t>(1, jobs_.size()))));
            if (opt_.progress)
                say_(context_->info().name + (context_->info().cpu ? " (CPU)" : "") + ", " +
                     std::to_string(sf_.scene.width) + "x" + std::to_string(sf_.scene.height) + ", " +
                     std::to_string(jobs_.size()) + " material(s)" +
                     (lanes > 1 ? ", " + std::to_string(lanes) + " lanes" : ""));
            // Every lane's renderer at once: each compiles its load-time passes' pipelines and runs
            // them; the first to need render::Device's shading choice measures it while the others
            // wait. Their notes are alike but for that measurement's: each said once, in lane order.
            renderers_.resize(lanes);
            std::vector<std::vector<std::string>> notes(lanes);
            parallel_for_rethrow(lanes, static_cast<int>(lanes), [&](size_t k) {
                renderers_[k] = std::make_unique<render::Renderer>(*context_, sf_.scene);
                notes[k] = renderers_[k]->take_notes();
            });
            std::set<std::string> said;
            for (const std::vector<std::string>& lane_notes : notes)
                for (const std::string& n : lane_notes)
                    if (said.insert(n).second) say_("note: " + n);
        } catch (...) {
            stop();
            throw;
        }
        {
            const std::lock_guard<std::mutex> lock(mutex_);
            ready_ = true;
        }
        changed_.notify_all();
        times.renderers = start_.elapsed();
        times.lanes = static_cast<unsigned>(renderers_.size());
        for (size_t k = 0; k < renderers_.size(); ++k) lanes_.emplace_back([this, k] { lane(k); });

        for (size_t i = 0; i < jobs_.size(); ++i) {
            Outcome o;
            {
                std::unique_lock<std::mutex> lock(mutex_);
                changed_.wait(lock, [&] { return outcomes_[i].has_value() || fatal_; });
                if (!outcomes_[i]) break;  // a lane's renderer failed: nothing later is said
                o = std::move(*outcomes_[i]);
                outcomes_[i].reset();
                held_ -= o.rgba8.size();
            }
            changed_.notify_all();
            report(i, std::move(o));
            if (i == 0) times.first = start_.elapsed();
        }
        shut_down();
        times.total = start_.elapsed();
        for (const auto& r : renderers_) times.lanes_host += r->host_times();
        times.read = spent_.read;
        times.read_wait = spent_.read_wait;
        times.upload = spent_.upload;
        times.draw = spent_.draw;
        times.write = spent_.write;
        if (fatal_) std::rethrow_exception(fatal_);
        for (const auto& [text, n] : repeated_notes_)
            if (n > 1) say_("note said above, for " + std::to_string(n - 1) + " more material(s) too: " + text);
        return std::move(result_);
    }

private:
    // Stops the lanes and workers (a worker finishes the writes queued) and waits for them; the
    // drawn materials they free go before the renderers that made them.
    void shut_down() {
        stop();
        for (std::thread& t : lanes_) t.join();
        lanes_.clear();
        for (std::thread& t : workers_) t.join();
        workers_.clear();
    }

    void stop() {
        {
            const std::lock_guard<std::mutex> lock(mutex_);
            stopping_ = true;
        }
        changed_.notify_all();
    }

    // Whether a worker may start reading the next material: always when nothing is held or being
    // read (a material larger than the budget runs alone); else when the largest material seen
    // so far still fits (before any was seen, two read at once).
    bool may_read() const {
        if (next_read_ >= jobs_.size()) return false;
        if (held_ == 0 && reading_ == 0) return true;
        const uint64_t largest = largest_ > 0 ? largest_ : estimated_;
        if (largest == 0) return reading_ < 2;
        return held_ + (reading_ + 1) * largest <= opt_.memory_budget;
    }

    void hold(uint64_t bytes) {  // under mutex_
        held_ += bytes;
        result_.held_most = std::max(result_.held_most, held_);
    }

    void work() {
        // Below the threads the pipeline waits on: the device's creation, the renderers' (the
        // first picture waits for them) and the lanes'. With a worker a core decoding at full
        // tilt, those got a core's share like any worker; the workers keep every core the others
        // leave idle.
        lower_this_thread_priority(kWorkerNice);
        std::unique_lock<std::mutex> lock(mutex_);
        for (;;) {
            changed_.wait(lock, [&] { return !writes_.empty() || stopping_ || may_read(); });
            if (!writes_.empty()) {  // first: a write frees memory and lets the outcome be said
                std::function<void()> write = std::move(writes_.front());
                writes_.pop_front();
                lock.unlock();
                write();
                lock.lock();
                continue;
            }
            if (stopping_) return;
            const size_t i = next_read_++;
            ++reading_;
            lock.unlock();
            const Stopwatch reading;
            Loaded l = read(i);
            lock.lock();
            --reading_;
            hold(l.bytes);
            largest_ = std::max(largest_, l.bytes);
            if (l.prepared) {  // its size is known: the next reads start while it warms its variant
                lock.unlock();
                changed_.notify_all();
                warm(i, *l.prepared);
                lock.lock();
            }
            spent_.read += reading.elapsed();
            loaded_[i] = std::move(l);
            changed_.notify_all();
        }
    }

    // The first reads wait for the device (render::prepare needs it: 0.16 s on the H200), and
    // until a size is known only two read (may_read). A material decoded tells the other workers
    // how many may start meanwhile, by the most it can come to once prepared: every texel as four
    // 32-bit floats (the widest format render::prepare stores: lavapipe's exact path widens 8-bit
    // colour to it) with a mip chain; blocks as they are. 1K materials of three maps: 64 MiB, 16 of
    // them within the default budget. The first prepared size replaces the estimate.
    void decoded(const render::Material& m) {
        uint64_t bytes = 0;
        for (const render::Texture& t : m.textures) {
            if (t.block_format == 0) bytes += uint64_t{t.width} * t.height * 16 * 4 / 3;
            for (const std::vector<uint8_t>& level : t.block_levels) bytes += level.size();
        }
        {
            const std::lock_guard<std::mutex> lock(mutex_);
            if (bytes <= estimated_) return;
            estimated_ = bytes;
        }
        changed_.notify_all();
    }

    // Blocks until the device exists (not the renderers: their load-time passes and pipelines
    // take most of the start, and the first materials are prepared meanwhile); throws Stopped
    // when the batch stops first.
    render::Context& device() {
        std::unique_lock<std::mutex> lock(mutex_);
        const Stopwatch waiting;
        changed_.wait(lock, [&] { return device_ready_ || stopping_; });
        spent_.read_wait += waiting.elapsed();
        if (!device_ready_) throw Stopped{};
        return *context_;
    }

    Loaded read(size_t i) {
        Loaded l;
        try {
            auto m = jobs_[i].load(
                [&](uint32_t f) {
                    render::Context& c = device();
                    if (!render::samples(c, f)) return BlockUse::decoded_absent;
                    return c.info().cpu && render::decodes_exactly(f) ? BlockUse::decoded : BlockUse::as_written;
                },
                l.notes, l.error);
            if (m) {
                decoded(*m);
                l.prepared = render::prepare(device(), sf_.scene, *m);
                l.bytes = l.prepared->bytes();
            }
        } catch (const Stopped&) {
            l.error = "stopped";
        } catch (const std::exception& e) {  // this material's textures (or the renderer); the others go on
            l.error = e.what();
        }
        return l;
    }

    // The first material of a pipeline variant has the variant made on every lane's renderer
    // (its own lane's first), here on its worker once the renderers exist, before the material
    // goes to its lane: a lane no longer stops to compile each variant it meets while its
    // materials wait, and the variants compile at once on several workers. The other workers go
    // on reading meanwhile (its read no longer counts against may_read).
    void warm(size_t i, const render::PreparedMaterial& prepared) {
        {
            std::unique_lock<std::mutex> lock(mutex_);
            if (!variants_.insert(prepared.variant_key()).second) return;
            const Stopwatch waiting;
            changed_.wait(lock, [&] { return ready_ || stopping_; });
            spent_.read_wait += waiting.elapsed();
            if (!ready_) return;
        }
        const size_t lanes = renderers_.size();
        try {
            for (size_t k = 0; k < lanes; ++k) renderers_[(i + k) % lanes]->warm(prepared);
        } catch (const std::exception&) {
            // not said here: the material's lane meets the same failure when it draws, and says
            // it for that material (render_one)
        }
    }

    // Lane k: materials k, k + lanes, … in order.
    void lane(size_t k) {
        for (size_t i = k; i < jobs_.size(); i += renderers_.size()) {
            Loaded l;
            {
                std::unique_lock<std::mutex> lock(mutex_);
                changed_.wait(lock, [&] { return loaded_[i].has_value() || stopping_; });
                if (!loaded_[i]) return;
                l = std::move(*loaded_[i]);
                loaded_[i].reset();
            }
            try {
                render_one(k, i, std::move(l));
            } catch (...) {  // the renderer itself (render_one keeps a material's own failure)
                {
                    const std::lock_guard<std::mutex> lock(mutex_);
                    if (!fatal_) fatal_ = std::current_exception();
                    stopping_ = true;
                }
                changed_.notify_all();
                return;
            }
        }
    }

    // `wrote`: the seconds its image's encoding and writing took.
    void finish(size_t i, Outcome o, uint64_t released, double wrote = 0.0) {
        {
            const std::lock_guard<std::mutex> lock(mutex_);
            spent_.write += wrote;
            held_ -= released;
            hold(o.rgba8.size());
            outcomes_[i] = std::move(o);
        }
        changed_.notify_all();
    }

    // Upload and draw on lane k's thread; encode and write on a worker while the lane goes on.
    void render_one(size_t k, size_t i, Loaded l) {
        const Job& job = jobs_[i];
        render::Renderer& r = *renderers_[k];
        Outcome o;
        for (const std::string& n : l.notes) o.lines.push_back("note: " + n);
        if (!l.prepared) {
            o.lines.push_back(job.name + ": " + l.error);
            o.failed = true;
            finish(i, std::move(o), l.bytes);
            return;
        }
        try {
            Stopwatch watch;
            render::GpuMaterial gm = r.upload(std::move(*l.prepared));
            l.prepared.reset();
            {
                const std::lock_guard<std::mutex> lock(mutex_);
                held_ -= l.bytes;  // its host copy is on the device now
                spent_.upload += watch.lap();
            }
            changed_.notify_all();
            for (const std::string& n : r.take_notes()) o.lines.push_back(job.name + ": note: " + n);
            const bool png = opt_.format == "png";
            std::vector<uint8_t> rgba8;
            std::vector<float> rgba32f;
            watch.lap();
            if (png || opt_.contact_sheet) rgba8 = r.render(gm, sf_.output).rgba8;
            if (!png) {
                render::OutputOptions lin;
                lin.format = render::PixelFormat::rgba32f;
                rgba32f = r.render(gm, lin).rgba32f;
            }
            {
                const std::lock_guard<std::mutex> lock(mutex_);
                spent_.draw += watch.lap();
            }
            const std::filesystem::path out = opt_.out / (job.stem + "." + opt_.format);
            std::string progress = "[" + std::to_string(i + 1) + "/" + std::to_string(jobs_.size()) + "] ";
            auto write = [this, i, &job, png, out, progress = std::move(progress), o = std::move(o),
                          rgba8 = std::move(rgba8), rgba32f = std::move(rgba32f),
                          gm = std::make_shared<render::GpuMaterial>(std::move(gm))]() mutable {
                const Stopwatch writing;
                gm.reset();  // its device objects, off the lane's thread
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
                finish(i, std::move(o), 0, writing.elapsed());
            };
            {
                const std::lock_guard<std::mutex> lock(mutex_);
                writes_.emplace_back(std::move(write));
            }
            changed_.notify_all();
        } catch (const render::NoDeviceError&) {
            throw;
        } catch (const std::exception& e) {  // this material's upload or draw failed; the others go on
            o.lines.push_back(job.name + ": " + e.what());
            o.failed = true;
            finish(i, std::move(o), l.prepared ? l.bytes : 0);
        }
    }

    // Material i's outcome, said on the caller's thread in job order.
    void report(size_t i, Outcome o) {
        const Job& job = jobs_[i];
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

    const SceneFile& sf_;
    const std::vector<Job>& jobs_;
    const BatchOptions& opt_;
    const std::function<void(const std::string&)>& say_;
    const Stopwatch start_;  // the batch's start: BatchTimes' points
    BatchResult result_;
    struct {
        double read = 0.0, read_wait = 0.0, upload = 0.0, draw = 0.0, write = 0.0;
    } spent_;                                       // thread time, summed (BatchTimes)
    std::map<std::string, size_t> repeated_notes_;  // a note's text -> how many materials had it
    std::unique_ptr<render::Context> context_;
    std::vector<std::unique_ptr<render::Renderer>> renderers_;  // one per lane

    std::mutex mutex_;
    std::condition_variable changed_;
    bool device_ready_ = false;       // context_ exists: materials may be prepared
    bool ready_ = false;              // renderers_ are made: pipeline variants may be warmed
    std::set<std::string> variants_;  // PreparedMaterial::variant_key of those warmed or being warmed
    bool stopping_ = false;           // done, or a renderer failed: lanes and workers end
    std::exception_ptr fatal_;
    size_t next_read_ = 0, reading_ = 0;
    uint64_t held_ = 0;       // bytes of prepared textures and unsaid images
    uint64_t largest_ = 0;    // the largest prepared material so far
    uint64_t estimated_ = 0;  // until one is prepared: the largest a decoded one may come to (decoded())
    std::vector<std::optional<Loaded>> loaded_;
    std::vector<std::optional<Outcome>> outcomes_;
    std::deque<std::function<void()>> writes_;
    // Declared last: destroyed (joined, by shut_down) before the renderers and the context.
    std::vector<std::thread> lanes_, workers_;
};

}  // namespace

std::shared_ptr<DeviceAhead> start_device(const render::ContextOptions& options) {
    auto ahead = std::make_shared<DeviceAhead>();
    ahead->made = std::async(std::launch::async, [options] { return std::make_unique<render::Context>(options); });
    return ahead;
}

unsigned lanes_for(const render::DeviceInfo& device) {
    if (device.cpu) return 1;
    return std::clamp(std::thread::hardware_concurrency() / 4, 1u, 4u);
}

BatchResult render_batch(const SceneFile& sf, const std::vector<Job>& jobs, const BatchOptions& opt,
                         const std::function<void(const std::string&)>& say) {
    const Stopwatch started;
    BatchResult r;
    {
        Batch batch(sf, jobs, opt, say);
        r = batch.run();
    }
    r.times.teardown = std::max(0.0, started.elapsed() - r.times.total);
    return r;
}

}  // namespace mf::preview
