// Synthetic material sets for the cases the real sets of sample_materials/ do not have (a set
// shipped as .zip, a gloss map, a Megascans ORT, a glTF metallicRoughness map, a DirectX normal
// named only "_Normal", EXR inputs...): tools/gen_samples writes them, deterministically, into a
// folder at test time. The set names are gen_samples' (its --help lists them).
#pragma once
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "run_binary.hpp"

namespace mf::testbin {

// Writes the named sets (every set when `sets` is empty) into `dir`.
inline ::testing::AssertionResult generate_synthetic(const std::filesystem::path& dir,
                                                     const std::vector<std::string>& sets = {}) {
    std::vector<std::string> argv{mf::testenv::gen_samples(), dir.string()};
    argv.insert(argv.end(), sets.begin(), sets.end());
    const Proc p = spawn(argv, 120);
    if (p.code == 0 && !p.hung) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "gen_samples " << dir << " failed (exit " << p.code << "):\n" << p.output;
}

}  // namespace mf::testbin
