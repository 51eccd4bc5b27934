// The deterministic work list of a library: every set, its size and its action key, and a
// stable assignment of sets to shards balanced by size (`matforge plan`, `ingest --shard I/N`).
//
// The action key is a SHA-256 over everything that decides a set's outputs: matforge's version,
// the versions of the libraries that decode and encode (OpenImageIO, OpenColorIO, libsquish,
// astcenc, zstd), the resolved preset, the rules configuration, the OpenColorIO config, and the
// name and bytes of every file of the set (content, never time stamps). Equal keys, equal outputs
// of one build (the result cache names the build besides: store/cache.hpp).
#pragma once
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "color/color.hpp"
#include "findings/rules.hpp"
#include "preset/preset.hpp"
#include "sets/sets.hpp"

namespace mf {

// The part of every key that does not depend on the set (hex SHA-256).
std::string context_digest(const Preset& preset, const rules::RuleConfig& rules, const ColorContext& color);

// The SHA-256 (hex) of an input file's bytes; nullopt + `error` when it cannot be read.
using Digest = std::function<std::optional<std::string>(const InputFile&, std::string& error)>;

// A Digest that reads and hashes the file (a map in pieces: a 150 MB map is not held to be hashed).
std::optional<std::string> read_and_hash(const InputFile& in, std::string& error);

// The set's action key, or nullopt + `error` when one of its files cannot be read. `digest`:
// how a file's SHA-256 is had (a cache remembers them by stat); empty: read_and_hash.
std::optional<std::string> action_key(const MaterialSource& set, const std::string& context, std::string& error,
                                      const Digest& digest = {});

// The bytes of the set's files (a set inside a .zip counts its entries' sizes as stored).
uint64_t set_bytes(const MaterialSource& set);

// shard[i] in [0, n) for set i: longest processing time first (largest set to the lightest
// shard; ties by name, then by lower shard), so shards differ by at most one set's size and the
// same library always splits the same way.
std::vector<int> assign_shards(const std::vector<MaterialSource>& sets, const std::vector<uint64_t>& bytes, int n);

// The digest of a sharded run's plan (hex SHA-256): `context`, the number of shards, and every
// set of the library in order with its name, its files, its size and its shard. Every shard of
// one run computes the same one; a library changed between two shards' runs (a set added,
// removed or resized, which moves sets between shards) gives another, and `merge` refuses.
// Names and sizes, not contents: a shard never reads the files of the others.
std::string plan_digest(const std::vector<MaterialSource>& sets, const std::vector<uint64_t>& bytes,
                        const std::vector<int>& shard, int n, const std::string& context);

// "I/N" -> {I, N} with 0 <= I < N; nullopt when malformed.
std::optional<std::pair<int, int>> parse_shard(const std::string& spec);

}  // namespace mf
