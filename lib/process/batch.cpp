#include "process/batch.hpp"

#include <algorithm>

#include "core/version.hpp"
#include "process/work.hpp"

namespace mf {

Batch Batch::find(const std::vector<std::filesystem::path>& inputs, const std::vector<std::filesystem::path>& outputs) {
    Batch b;
    b.sets = find_material_sets(inputs, outputs, b.failures, &b.output_conflict, &b.skipped);
    b.bytes.reserve(b.sets.size());
    for (const auto& s : b.sets) b.bytes.push_back(set_bytes(s));
    return b;
}

std::vector<size_t> Batch::largest_first() const {
    std::vector<size_t> order(sets.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return bytes[a] > bytes[b]; });
    return order;
}

Batch::Split Batch::split(int n) const { return {n, assign_shards(sets, bytes, n)}; }

std::string Batch::split_digest(const Split& split, const std::string& context) const {
    return plan_digest(sets, bytes, split.shard, split.n, context);
}

void Batch::keep_shard(const Split& split, int index) {
    size_t kept = 0;
    for (size_t i = 0; i < sets.size(); ++i)
        if (split.shard[i] == index) {
            if (kept != i) {  // a self-move would empty the set
                sets[kept] = std::move(sets[i]);
                bytes[kept] = bytes[i];
            }
            ++kept;
        }
    sets.resize(kept);
    bytes.resize(kept);
}

Plan Plan::of(const Batch& batch, const std::string& preset, const std::string& context, int shards,
              const std::map<std::string, std::string>* earlier) {
    Plan p;
    p.generator = std::string(kGenerator);
    p.preset = preset;
    p.context = context;
    p.shards = shards;
    p.failures = batch.failures;
    const Batch::Split split = batch.split(shards);
    p.digest = batch.split_digest(split, context);
    for (size_t i = 0; i < batch.sets.size(); ++i) {
        const MaterialSource& src = batch.sets[i];
        Set s{src.name, src.display, batch.bytes[i], src.files.size(), split.shard[i], std::nullopt, std::nullopt};
        std::string error;
        if (auto key = action_key(src, context, error)) s.key = std::move(key);
        else s.error = std::move(error);
        if (earlier) {
            const auto it = earlier->find(src.name);
            if (it != earlier->end() && !it->second.empty() && s.key == it->second) {
                ++p.unchanged;
                continue;
            }
        }
        p.sets.push_back(std::move(s));
    }
    return p;
}

bool Plan::unreadable() const {
    return !failures.empty() || std::any_of(sets.begin(), sets.end(), [](const Set& s) { return s.error.has_value(); });
}

nlohmann::json Plan::to_json() const {
    nlohmann::json list = nlohmann::json::array();
    for (const Set& s : sets) {
        nlohmann::json item{
            {"name", s.name}, {"source", s.source}, {"bytes", s.bytes}, {"files", s.files}, {"shard", s.shard}};
        if (s.key) item["key"] = *s.key;
        if (s.error) item["error"] = *s.error;
        list.push_back(std::move(item));
    }
    nlohmann::json fl = nlohmann::json::array();
    for (const auto& f : failures) fl.push_back(mf::to_json(f));
    nlohmann::json j{{"plan_version", 1}, {"generator", generator}, {"preset", preset}, {"context", context},
                     {"plan", digest},    {"shards", shards},       {"sets", list},     {"failures", fl}};
    if (changed_since) {
        j["changed_since"] = *changed_since;
        j["unchanged"] = unchanged;
    }
    return j;
}

}  // namespace mf
