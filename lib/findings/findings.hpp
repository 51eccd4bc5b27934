// Findings: the coded, stable results every stage reports (docs/interface.md "Finding codes").
// A code never changes meaning; new checks get new codes.
#pragma once
#include <cstdint>
#include <functional>
#include <map>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <variant>
#include <vector>

namespace mf {

enum class Severity { info = 0, warning = 1, error = 2 };

std::string_view severity_name(Severity s);
std::optional<Severity> severity_from_name(std::string_view name);

// Stable finding codes. Documented with their thresholds and sources in docs/rules.md.
namespace code {
inline constexpr std::string_view unreadable_file = "UNREADABLE_FILE";
inline constexpr std::string_view missing_map = "MISSING_MAP";
inline constexpr std::string_view ambiguous_map = "AMBIGUOUS_MAP";
inline constexpr std::string_view unrecognized_file = "UNRECOGNIZED_FILE";
inline constexpr std::string_view resolution_mismatch = "RESOLUTION_MISMATCH";
inline constexpr std::string_view nonfinite_values = "NONFINITE_VALUES";
inline constexpr std::string_view out_of_range_values = "OUT_OF_RANGE_VALUES";
inline constexpr std::string_view not_grayscale = "NOT_GRAYSCALE";
inline constexpr std::string_view constant_map = "CONSTANT_MAP";
inline constexpr std::string_view metalness_not_binary = "METALNESS_NOT_BINARY";
inline constexpr std::string_view albedo_too_dark = "ALBEDO_TOO_DARK";
inline constexpr std::string_view albedo_too_bright = "ALBEDO_TOO_BRIGHT";
inline constexpr std::string_view metal_albedo_too_dark = "METAL_ALBEDO_TOO_DARK";
inline constexpr std::string_view normal_invalid = "NORMAL_INVALID";
inline constexpr std::string_view normal_convention_mismatch = "NORMAL_CONVENTION_MISMATCH";
inline constexpr std::string_view color_space_mismatch = "COLOR_SPACE_MISMATCH";
inline constexpr std::string_view gloss_inverted = "GLOSS_INVERTED";
inline constexpr std::string_view packed_input_unpacked = "PACKED_INPUT_UNPACKED";
inline constexpr std::string_view normal_convention_converted = "NORMAL_CONVENTION_CONVERTED";
inline constexpr std::string_view normal_convention_unknown = "NORMAL_CONVENTION_UNKNOWN";
// matforge extensions (never reused for another meaning)
inline constexpr std::string_view output_write_failed = "OUTPUT_WRITE_FAILED";
inline constexpr std::string_view resized = "RESIZED";
inline constexpr std::string_view input_not_found = "INPUT_NOT_FOUND";
inline constexpr std::string_view unsafe_path = "UNSAFE_PATH";  // an archive entry naming a path outside it
inline constexpr std::string_view normal_not_unit_length =
    "NORMAL_NOT_UNIT_LENGTH";                                                     // valid map, renormalized on ingest
inline constexpr std::string_view normal_gamma_encoded = "NORMAL_GAMMA_ENCODED";  // normal map stored sRGB-encoded
inline constexpr std::string_view normal_z_reconstructed =
    "NORMAL_Z_RECONSTRUCTED";  // two-channel (BC5-style) normal map
inline constexpr std::string_view opacity_all_transparent =
    "OPACITY_ALL_TRANSPARENT";  // the material would be invisible
// Choices matforge makes that a user should know of (hardening, round two)
inline constexpr std::string_view names_merged = "NAMES_MERGED";        // two file-name spellings made one material
inline constexpr std::string_view duplicate_input = "DUPLICATE_INPUT";  // a set reached through two inputs, read once
inline constexpr std::string_view duplicate_entry = "DUPLICATE_ENTRY";  // an archive holds one name twice
inline constexpr std::string_view multipart_image = "MULTIPART_IMAGE";  // a file with several images: the first is used
inline constexpr std::string_view orientation_ignored = "ORIENTATION_IGNORED";  // EXIF/TIFF orientation not applied
inline constexpr std::string_view aspect_mismatch =
    "ASPECT_MISMATCH";  // a map's shape does not fit the set's: not used
inline constexpr std::string_view output_too_large = "OUTPUT_TOO_LARGE";  // wider or taller than engines import
inline constexpr std::string_view encoding_error_exceeded =
    "ENCODING_ERROR_EXCEEDED";  // a decoded block-compressed level over the preset's bound
inline constexpr std::string_view material_file_skipped =
    "MATERIAL_FILE_SKIPPED";  // the preset's glTF not written (dx normals)
inline constexpr std::string_view map_not_written =
    "MAP_NOT_WRITTEN";  // a shading map the preset has no output for (d3d11: occlusion, emissive)
inline constexpr std::string_view packed_channels_identical =
    "PACKED_CHANNELS_IDENTICAL";  // an ORM-style map whose R, G, B are one image
inline constexpr std::string_view height_stored_as_depth =
    "HEIGHT_STORED_AS_DEPTH";  // white = deep: written white = high
inline constexpr std::string_view role_from_pixels =
    "ROLE_FROM_PIXELS";  // a name's scalar role on a normal map's pixels: read as the normal map
// Where a material comes from and under what licence (provenance.hpp)
inline constexpr std::string_view licence_unknown = "LICENCE_UNKNOWN";  // no licence found for the set
}  // namespace code

// A measured value behind a finding: a flag, a count, a measure, a word, or a list of counts,
// measures or words. Written to JSON as held (3, 3.0, "gl", [2048, 1024], [0.5, 0.5]) and read
// back the same.
using FigureValue = std::variant<bool, std::int64_t, double, std::string, std::vector<std::int64_t>,
                                 std::vector<double>, std::vector<std::string>>;

// A FigureValue made from what the rules measure in: any integer is a count, float a measure,
// characters a text, a braced list of integers {w, h} counts.
struct Figure : FigureValue {
    Figure() = default;
    Figure(bool b) : FigureValue(b) {}
    template <class T>
    requires(std::is_integral_v<T> && !std::is_same_v<T, bool>) Figure(T v)
        : FigureValue(static_cast<std::int64_t>(v)) {}
    Figure(double v) : FigureValue(v) {}
    Figure(float v) : FigureValue(double{v}) {}
    Figure(std::string s) : FigureValue(std::move(s)) {}
    Figure(std::string_view s) : FigureValue(std::string(s)) {}
    Figure(const char* s) : FigureValue(std::string(s)) {}
    Figure(std::initializer_list<std::int64_t> counts) : FigureValue(std::vector<std::int64_t>(counts)) {}
    Figure(std::vector<std::int64_t> counts) : FigureValue(std::move(counts)) {}
    Figure(std::vector<double> measures) : FigureValue(std::move(measures)) {}
    Figure(const std::vector<float>& measures) : FigureValue(std::vector<double>(measures.begin(), measures.end())) {}
    Figure(std::vector<std::string> words) : FigureValue(std::move(words)) {}
};
// A finding's figures by name, in name order (the order they are written in).
using Figures = std::map<std::string, Figure, std::less<>>;

// The number a figure holds (a count or a measure); nullopt when absent or not a number.
std::optional<double> figure_number(const Figures& figures, std::string_view name);
// The text a figure holds; nullopt when absent or not text.
std::optional<std::string> figure_string(const Figures& figures, std::string_view name);
// A figure as its JSON text (the report's figure tables).
std::string figure_text(const FigureValue& v);

struct Finding {
    std::string code;
    Severity severity = Severity::info;
    std::string role;     // empty when no role applies
    std::string file;     // input file (relative to the set's source) when one applies
    std::string message;  // a sentence a person can act on
    Figures figures;      // measured values behind the finding
};

nlohmann::json to_json(const Figures& figures);
nlohmann::json to_json(const Finding& f);
// nullopt + `error` naming the member when `j` is not a finding (a code and a known severity).
std::optional<Finding> finding_from_json(const nlohmann::json& j, std::string& error);

// An input that could not be processed at all (an unreadable archive, a set with no readable
// map, a folder that does not exist): the one shape for manifests, reports and the CLI.
struct InputFailure {
    std::string source;  // the input as the manifest/report names it
    std::string code;    // a finding code (UNREADABLE_FILE, INPUT_NOT_FOUND, UNSAFE_PATH, ...)
    std::string message;
};
nlohmann::json to_json(const InputFailure& f);
std::optional<InputFailure> input_failure_from_json(const nlohmann::json& j, std::string& error);

// Highest severity in a list, or nullopt when empty.
std::optional<Severity> worst(const std::vector<Finding>& findings);

}  // namespace mf
