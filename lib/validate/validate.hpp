// `matforge validate`'s engine: every rule over one material set, each map read once.
//
// Conventions (decided once here):
//  - the caller (discovery/ingest) names the maps: one MapInput per chosen input file, with its
//    input role (packed orm / metallic_roughness / ort give their channels' roles, see
//    mf::packed_layout), header facts and the file's own color tag;
//  - values: 8/16-bit albedo and emissive are sRGB-encoded, float (EXR/HDR) albedo is linear;
//    every other role is data; normals decode as n = 2c − 1 (float files that hold negative
//    values in their first band are taken as already signed);
//  - memory: each map is streamed in bands of `band_rows` rows on its own reader thread; the
//    maps a joint statistic needs are read in lockstep (albedo with metalness and opacity on the
//    albedo's grid; normal with height on the normal's grid), resampled by nearest neighbour
//    when sizes differ. The rules hold ≈ one band per map plus a few rows (tens of MB for an 8K
//    set); the peak is set by what the file's decoder holds (a PNG inflated whole, a progressive
//    JPEG's coefficients: docs/rules.md states the measured figures);
//  - output: findings sorted by catalog order (findings/catalog.hpp), then map order, at their
//    catalog severity; the RuleConfig's thresholds decide them, its switches (off, severity
//    overrides, suppressions) are the caller's to apply, once per set (apply_config).
#pragma once
#include <algorithm>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "findings/findings.hpp"
#include "findings/rules.hpp"
#include "image/image.hpp"
#include "material/roles.hpp"
#include "validate/color_tag.hpp"
#include "validate/normal_convention.hpp"

namespace mf::validate {

struct MapInput {
    Role role = Role::albedo;  // input role (orm, gloss, … allowed)
    InputFile file;
    std::string name;        // file as findings name it (relative to the set); empty: file.display
    ImageInfo info;          // header facts; width 0: read with mf::read_info
    ColorTagInfo color_tag;  // from read_color_tag(file); none: no tag check
    NormalConvention name_convention = NormalConvention::unknown;  // what the file name says
    // What the set's engine family implies (Unity gl, Unreal dx): taken when neither the name
    // nor the pixels decide, instead of assuming gl with NORMAL_CONVENTION_UNKNOWN.
    NormalConvention engine_convention = NormalConvention::unknown;
    std::vector<Role> unused;  // output roles this map must not feed (routing's `unused`)
    // Another candidate for a role whose chosen map comes first (a WebP copy beside the JPEG
    // original): checked by the rules of a map alone, never routed, never a joint statistic.
    bool alternate = false;
};

// Builds a MapInput reading the header and the color tag (the usual way to make one).
// Returns nullopt and sets `error` when the header cannot be read.
std::optional<MapInput> make_map_input(Role role, InputFile file, std::string name, NormalConvention name_convention,
                                       std::string& error);

// A band (or a row) of samples as a reader hands it: floats, or an 8-bit file's codes, code k
// standing for unorm8_values()[k] — the float mf::read_bands gives for it, bit for bit. The
// rules read codes through that table (or tables built from it), so a map held as codes
// validates to the same figures as its floats would, without a float copy of it.
struct Samples {
    const float* floats = nullptr;
    const uint8_t* codes = nullptr;
    bool empty() const { return !floats && !codes; }
    Samples operator+(size_t n) const { return codes ? Samples{nullptr, codes + n} : Samples{floats + n, nullptr}; }
    // One value (a branch per call: for the few reads outside the rules' per-type loops).
    float operator[](size_t i) const { return codes ? unorm8_values()[codes[i]] : floats[i]; }
};

// mf::read_bands's contract with Samples for the band: tests substitute in-memory images, ingest
// its decoded maps (codes where it holds codes).
using BandReader = std::function<bool(const InputFile&, int band_rows, ImageInfo&, std::string&,
                                      const std::function<void(int, int, Samples)>&)>;
// mf::read_bands as a BandReader: codes where matforge's own readers decode an 8-bit file.
bool read_file_bands(const InputFile& in, int band_rows, ImageInfo& info, std::string& error,
                     const std::function<void(int, int, Samples)>& fn);

struct ValidateOptions {
    std::string material;  // name the suppressions match
    int band_rows = 64;
    BandReader reader;         // empty: read_file_bands
    DetectorOptions detector;  // GL/DX detector settings
};

// The content verdict on the set's normal map (for the manifest's normal_convention_source).
struct NormalCheck {
    std::string file;
    NormalConvention name = NormalConvention::unknown;  // from the name
    NormalVerdict content;                              // from the pixels
    // The convention to use: the name's when it has one, else the content's when its confidence
    // reaches the rule threshold, else unknown.
    NormalConvention resolved = NormalConvention::unknown;
    std::string source = "none";  // "name" | "content" | "none"
};

struct SetValidation {
    std::vector<Finding> findings;
    std::optional<NormalCheck> normal;
    // The smallest finite value of the albedo's alpha channel, when the albedo has one and no
    // opacity map exists (routing's opacity-from-alpha); nullopt otherwise.
    std::optional<double> albedo_alpha_min;
    // The set's opacity (its opacity map, or the albedo's alpha standing in) would make the whole
    // surface invisible (OPACITY_ALL_TRANSPARENT): the plan does not apply it.
    bool opacity_invisible = false;
    // The routed normal map stores X and Y only (two channels, or an empty blue): ingest
    // rebuilds Z from them, as the rules did (NORMAL_Z_RECONSTRUCTED).
    bool normal_z_rebuilt = false;
    // The routed normal map is no tangent-space normal map (NORMAL_INVALID): the plan does not
    // write it into the normal slot; the material gets a flat normal.
    bool normal_invalid = false;
    // The maps that could not be read (a truncated file reads its header, not its pixels):
    // MapInput::name (the file, when unnamed) -> the reader's error. Each has its UNREADABLE_FILE.
    std::map<std::string, std::string> unreadable;
};

// The nearest-neighbour index of destination coordinate i (of n) in a source of size m (pixel
// centres matched): how the rules sample a mask of another size on a map's grid, and the
// report's overlays as they do.
inline int nearest_index(int i, int n, int m) {
    return std::min(m - 1, static_cast<int>((static_cast<int64_t>(2 * i + 1) * m) / (2 * int64_t{n})));
}

SetValidation validate_set(const std::vector<MapInput>& maps, const rules::RuleConfig& cfg,
                           const ValidateOptions& opt = {});

// Whether `file`'s pixels are a tangent-space normal map as NORMAL_INVALID judges one (three
// channels, X/Y centred, pointing up, not grey; gamma-encoded ones too): discovery asks it of a
// map whose name gives it a scalar role in a set without a normal map (ROLE_FROM_PIXELS).
// nullopt when the file cannot be read.
std::optional<bool> is_tangent_normal_map(const InputFile& file, const rules::Thresholds& t);

}  // namespace mf::validate
