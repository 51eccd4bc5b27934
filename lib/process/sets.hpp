// Finding material sets: folders (recursively), .zip archives read in place, and flat folders
// holding several materials (split by file-name stem).
#pragma once
#include <filesystem>
#include <string>
#include <vector>

#include "core/findings.hpp"
#include "image/image.hpp"

namespace mf {

struct MaterialSource {
    std::string name;                 // unique in the batch, safe as a folder name
    std::filesystem::path root;       // the folder holding the files, or the .zip file
    std::string zip_folder;           // inside a .zip: the folder of the set ("" = top), '/'-separated
    bool is_zip = false;
    std::vector<std::string> files;   // relative to root (or to zip_folder), sorted
    std::string display;              // "path/to/set" or "path/to/x.zip/folder" for messages

    InputFile open(const std::string& file) const;  // zip entries are read into memory
};

// Every material set under `inputs`. Skips `exclude` (the output folder, when it lies inside an
// input), hidden files and folders, __MACOSX, and does not follow symbolic links to folders
// (no loops). Names are made unique by appending _2, _3 … in path order.
std::vector<MaterialSource> find_material_sets(const std::vector<std::filesystem::path>& inputs,
                                               const std::filesystem::path& exclude,
                                               std::vector<InputFailure>& failures);

// Non-empty (a message) when `out_dir` is one of `inputs` or holds one: outputs would then be
// found as inputs by the next run. An output folder inside an input is fine (it is skipped).
std::string output_overlaps_input(const std::filesystem::path& out_dir,
                                  const std::vector<std::filesystem::path>& inputs);

// A name safe as one path component: [A-Za-z0-9._-] kept, others '_', no leading dot, ≤ 96 bytes.
std::string safe_name(const std::string& name);

}  // namespace mf
