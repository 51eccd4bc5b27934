// Finding material sets: folders (recursively), .zip archives read in place, and flat folders
// holding several materials (split by file-name stem).
#pragma once
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "findings/findings.hpp"
#include "image/image.hpp"

namespace mf {

// One .zip, opened once and shared by every set it holds (reopening it per map re-parses the
// central directory: quadratic in its entries). Thread-safe; defined in sets.cpp.
class ZipArchive;

struct MaterialSource {
    std::string name;            // unique in the batch (case-insensitively), safe as a folder name
    std::filesystem::path root;  // the folder holding the files, or the .zip file
    std::string zip_folder;      // inside a .zip: the folder of the set ("" = top), '/'-separated
    bool is_zip = false;
    std::vector<std::string> files;       // relative to root (or to zip_folder), sorted
    std::string display;                  // "path/to/set" or "path/to/x.zip/folder" for messages
    std::shared_ptr<ZipArchive> archive;  // is_zip: the archive, opened once
    bool shared_folder = false;           // a flat folder's set: its folder holds other sets too
    // What finding the set decided that the user should know (NAMES_MERGED, DUPLICATE_ENTRY,
    // DUPLICATE_INPUT); plan_set reports them with the set's other findings.
    std::vector<Finding> findings;

    InputFile open(const std::string& file) const;  // zip entries are read into memory
};

// Every material set under `inputs`. Skips the folders of `exclude` (the run's output folders,
// where they lie inside an input), hidden files and folders, __MACOSX, and does not follow symbolic links to folders
// (no loops). A folder or archive reached twice (overlapping inputs, a link to a folder given as
// an input) is read once (by real path), with DUPLICATE_INPUT on its sets. An input in which no
// set is found, and a folder whose maps are only in formats matforge does not read, are
// failures (UNRECOGNIZED_FILE) naming them. Names are made unique (case-insensitively) by
// appending _2, _3 … in path order, skipping names other sets have.
// `output_conflict` (when given): set to a message when a folder of `exclude` is the folder of a set
// (it holds the set's maps): that set would be dropped and the outputs written among its sources.
// A folder holding a manifest or journal matforge wrote, or a report of `matforge report`, is an
// output: it is skipped with all below it, and said in `skipped` (when given), one line each.
std::vector<MaterialSource> find_material_sets(const std::vector<std::filesystem::path>& inputs,
                                               const std::vector<std::filesystem::path>& exclude,
                                               std::vector<InputFailure>& failures,
                                               std::string* output_conflict = nullptr,
                                               std::vector<std::string>* skipped = nullptr);

// Why `input` cannot be read as material sets ("" when it is a folder or a .zip file): it does
// not exist, or it is a file of another kind (a map given alone: "give the folder holding it").
std::string input_problem(const std::filesystem::path& input);
// Non-empty (each input's problem) when no input can be read at all: the command stops before
// it creates anything (an output folder, a manifest, a cache).
std::string no_usable_input(const std::vector<std::filesystem::path>& inputs);

// Non-empty (a message) when `out_dir` is one of `inputs` or holds one: outputs would then be
// found as inputs by the next run. An output folder inside an input is fine (it is skipped).
std::string output_overlaps_input(const std::filesystem::path& out_dir,
                                  const std::vector<std::filesystem::path>& inputs);

// Non-empty (a message) when `file`, which a command is about to write (validate's report, plan's
// work list), is one of the files the run read, or lies in the folder of one of `sets` (the
// next run would read it among the set's maps): an input given, an archive, a set's map.
std::string written_file_conflict(const std::filesystem::path& file, const std::vector<std::filesystem::path>& inputs,
                                  const std::vector<MaterialSource>& sets);

// Non-empty (a message) when the cache folder `cache` would be mixed with what a run reads or
// writes: the output folder, a folder inside it or holding it, an input, or inside or holding one.
std::string cache_overlaps(const std::filesystem::path& cache, const std::filesystem::path& out_dir,
                           const std::vector<std::filesystem::path>& inputs);

// A name safe as one path component: [A-Za-z0-9._-] kept, others '_', no leading dot, ≤ 96 bytes.
inline constexpr size_t kMaxNameBytes = 96;
std::string safe_name(const std::string& name);

// The final names of sets named `wanted` (in order): safe_name() of each, unique compared
// without case, never `reserved` (lower case, e.g. "manifest.json"). A name held by one set only
// is kept; the second and later holders of a name get "_2", "_3" …, skipping every name another
// set holds, cut so that the suffix fits in kMaxNameBytes.
std::vector<std::string> unique_names(const std::vector<std::string>& wanted,
                                      const std::vector<std::string>& reserved = {"manifest.json"});

// For `matforge --version`: libzip, which reads .zip sets in place.
std::string archive_library_version();

}  // namespace mf
