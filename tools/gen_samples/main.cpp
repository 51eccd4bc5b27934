// gen_samples: writes synthetic PBR material sets deterministically, for the tests' cases the
// real sets of sample_materials/ do not cover.
//
//   gen_samples <out-dir> [SET...]      SET: a set's folder/archive name or material name
//
// Each material is one procedural shader (shaders.cpp) baked on a grid (bake.cpp); its maps are
// taken from the bake (maps.cpp) and written as the set table says (sets.cpp: names, sizes,
// formats, packing, clutter) by generate.cpp, with deterministic encoders (files.cpp) and the
// sidecars and README (text.cpp). No clocks and no random devices: the same build writes the
// same bytes on every run.

#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "files.hpp"
#include "generate.hpp"
#include "sets.hpp"
#include "text.hpp"

namespace fs = std::filesystem;

namespace {

void usage(const std::vector<gen::SetDef>& sets) {
    std::cerr << "usage: gen_samples <out-dir> [SET...]\n"
                 "Writes synthetic material sets (all, or the SETs named) and README.md into <out-dir>,\n"
                 "replacing only the set folders/archives it writes. Sets:\n";
    for (const gen::SetDef& s : sets) std::cerr << "  " << s.root << "  (" << s.name << ", " << s.family << ")\n";
}

}  // namespace

int main(int argc, char** argv) {
    const std::vector<gen::SetDef> all = gen::sample_sets();
    const std::vector<std::string> args(argv + 1, argv + argc);
    if (args.empty() || args[0] == "--help" || args[0] == "-h") {
        usage(all);
        return 2;
    }
    std::vector<gen::SetDef> chosen;
    if (args.size() == 1) chosen = all;
    for (size_t i = 1; i < args.size(); ++i) {
        bool found = false;
        for (const gen::SetDef& s : all)
            if (args[i] == s.root || args[i] == s.name) {
                chosen.push_back(s);
                found = true;
                break;
            }
        if (!found) {
            std::cerr << "gen_samples: no set named " << args[i] << "\n";
            usage(all);
            return 2;
        }
    }
    const fs::path out = args[0];
    try {
        fs::create_directories(out);
        for (const gen::SetDef& set : chosen) {
            std::string err;
            if (!gen::generate_set(out, set, err)) {
                std::cerr << "gen_samples: " << set.root << ": " << err << "\n";
                return 1;
            }
            std::cout << "wrote " << (out / set.root).string() << "\n";
        }
        std::string err;
        if (!gen::write_text(out / "README.md", gen::readme(chosen), err)) {
            std::cerr << "gen_samples: " << err << "\n";
            return 1;
        }
    } catch (const fs::filesystem_error& e) {
        std::cerr << "gen_samples: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
