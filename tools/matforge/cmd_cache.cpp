// matforge cache stats|prune [--cache DIR] [--max-size SIZE]
// The ingest cache (lib/store/cache.hpp): how big it is, and least-recently-used eviction.
#include <chrono>
#include <cstdlib>
#include <memory>

#include "command.hpp"
#include "options.hpp"
#include "store/cache.hpp"

namespace mf::cli {
namespace {

struct CacheArgs {
    std::string action = "stats", dir, max_size = "10G";
    int grace = 60;
};

// "10G", "500M", "2048K", "123" (bytes) -> bytes; nullopt when malformed.
std::optional<uint64_t> parse_size(const std::string& s) {
    if (s.empty()) return std::nullopt;
    size_t used = 0;
    double v = 0;
    try {
        v = std::stod(s, &used);
    } catch (const std::exception&) {
        return std::nullopt;
    }
    const std::string unit = s.substr(used);
    double k = 1;
    if (unit == "K" || unit == "k") k = 1024.0;
    else if (unit == "M" || unit == "m") k = 1024.0 * 1024;
    else if (unit == "G" || unit == "g") k = 1024.0 * 1024 * 1024;
    else if (unit == "T" || unit == "t") k = 1024.0 * 1024 * 1024 * 1024;
    else if (!unit.empty()) return std::nullopt;
    if (!(v >= 0) || v * k > 1.8e19) return std::nullopt;
    return static_cast<uint64_t>(v * k);
}

std::string mib(uint64_t b) { return std::to_string((b + (1u << 19)) >> 20) + " MiB"; }

ExitCode run_cache(const CacheArgs& a) {
    const auto folder = cache_folder(a.dir);
    if (!folder)
        return fail("cache", "name the cache: --cache DIR or $MATFORGE_CACHE (no $HOME or $XDG_CACHE_HOME names "
                             "the default, ~/.cache/matforge)");
    const std::string dir = folder->string();
    std::error_code ec;
    if (a.dir.empty() && !std::filesystem::exists(*folder, ec)) {  // the default, before any ingest
        std::cout << dir << ": no cache yet\n";
        return ExitCode::ok;
    }
    std::string error;
    auto cache = Cache::open(dir, error);  // only a folder with the cache's marker: never a user's
    if (!cache) return fail("cache", error);
    if (a.action == "stats") {
        const auto s = cache->stats();
        std::cout << dir << ": " << s.records << " records, " << s.blobs << " blobs, " << mib(s.blob_bytes)
                  << " of outputs, " << mib(s.other_bytes) << " of records and digests\n";
        return ExitCode::ok;
    }
    const auto max = parse_size(a.max_size);
    if (!max) return fail("cache", "--max-size must be a size such as 500M or 10G, not \"" + a.max_size + "\"");
    const auto removed = cache->prune(*max, std::chrono::seconds(a.grace));
    std::cout << dir << ": removed " << removed.records << " records and " << removed.blobs << " blobs ("
              << mib(removed.blob_bytes) << ")\n";
    if (removed.failed)
        return fail("cache",
                    std::to_string(removed.failed) + " files the limit evicts could not be removed (" + removed.error +
                        ")",
                    ExitCode::findings);
    return ExitCode::ok;
}

const Register register_cache{
    {"cache", 45,
     [](CLI::App& sub) -> std::function<ExitCode()> {
         auto a = std::make_shared<CacheArgs>();
         sub.add_option("action", a->action, "stats | prune")
             ->check(CLI::IsMember({"stats", "prune"}))
             ->capture_default_str();
         sub.add_option(
             "--cache", a->dir,
             "the cache folder (default: ingest's, $MATFORGE_CACHE, else $XDG_CACHE_HOME/matforge or ~/.cache/matforge)");
         sub.add_option("--max-size", a->max_size,
                        "prune: keep the most recently used records within this size (K, M, G, T)")
             ->capture_default_str();
         sub.add_option("--grace", a->grace,
                        "prune: blobs younger than this many seconds stay even when no record names "
                        "them (a run may be about to record them)")
             ->check(CLI::Range(0, 1 << 30))
             ->capture_default_str();
         return [a] { return run_cache(*a); };
     },
     "show the ingest cache's size, or evict the least recently used entries"}};

}  // namespace
}  // namespace mf::cli
