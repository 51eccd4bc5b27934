// Findings: the coded, stable results every stage reports (docs/interface.md "Finding codes").
// A code never changes meaning; new checks get new codes.
#pragma once
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
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
}  // namespace code

struct Finding {
    std::string code;
    Severity severity = Severity::info;
    std::string role;                                   // empty when no role applies
    std::string file;                                   // input file (relative to the set's source) when one applies
    std::string message;                                // a sentence a person can act on
    nlohmann::json figures = nlohmann::json::object();  // measured values behind the finding
};

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
