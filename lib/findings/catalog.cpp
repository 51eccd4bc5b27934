#include "findings/catalog.hpp"

#include <stdexcept>

namespace mf {

const std::vector<CodeInfo>& finding_catalog() {
    // Order: set-level, per-file value checks, PBR plausibility, normal maps, tags (what the
    // rules raise, in the order their findings are sorted), then the codes of the other stages.
    static const std::vector<CodeInfo> c{
        {code::unreadable_file, Severity::error, "File is corrupt, truncated, empty or not an image",
         "finding sets, decoding", "unreadable_file"},
        {code::resolution_mismatch, Severity::warning, "A map is resampled to the set's size", "planning",
         "resolution_mismatch"},
        {code::nonfinite_values, Severity::error, "NaN or Inf values in a map", "rules", "nonfinite_values"},
        {code::out_of_range_values, Severity::warning, "Float data outside [0, 1] where the role allows none", "rules",
         "out_of_range_values"},
        {code::not_grayscale, Severity::warning, "Scalar map stored with differing channels", "rules", "not_grayscale"},
        {code::packed_channels_identical, Severity::warning, "A packed (ORM-style) map whose R, G and B hold one image",
         "rules", "packed_channels_identical"},
        {code::constant_map, Severity::info, "Map holds one value (replaceable by a constant)", "rules",
         "constant_map"},
        {code::metalness_not_binary, Severity::warning, "Too much metalness strictly between 0 and 1", "rules",
         "metalness_not_binary"},
        {code::albedo_too_dark, Severity::warning, "Dielectric albedo darker than any real material", "rules",
         "albedo_too_dark"},
        {code::albedo_too_bright, Severity::warning, "Dielectric albedo brighter than any real material", "rules",
         "albedo_too_bright"},
        {code::metal_albedo_too_dark, Severity::warning, "Metallic areas darker than any real metal", "rules",
         "metal_albedo_too_dark"},
        {code::opacity_all_transparent, Severity::error, "Opacity makes the whole material invisible", "rules",
         "opacity_all_transparent"},
        {code::normal_invalid, Severity::error,
         "Not a tangent-space normal map (height, color or object-space map; one channel)", "rules", "normal_invalid"},
        {code::normal_gamma_encoded, Severity::error,
         "Normal map stored sRGB/gamma-encoded (X/Y centred near 0.74, not 0.5)", "rules", "normal_gamma_encoded"},
        {code::normal_not_unit_length, Severity::info, "Normal vectors not unit length (renormalized on ingest)",
         "rules", "normal_not_unit_length"},
        {code::normal_z_reconstructed, Severity::info, "Two-channel normal map: Z reconstructed from X and Y", "rules",
         "normal_z_reconstructed"},
        {code::normal_convention_mismatch, Severity::warning,
         "Normal map content contradicts the GL/DX convention its name states", "rules", "normal_convention_mismatch"},
        {code::normal_convention_unknown, Severity::warning, "Neither name nor content decides GL vs DX", "rules",
         "normal_convention_unknown"},
        // info: maps are read by role, so a tag never changes what ingest makes of the pixels.
        {code::color_space_mismatch, Severity::info,
         "Data map tagged as color, or color map tagged as data (the tag is ignored)", "rules", "color_space_mismatch"},
        // Emitted by discovery / ingest, not by validate_set().
        {code::missing_map, Severity::info, "A role the preset needs has no map", "planning", "missing_map"},
        {code::ambiguous_map, Severity::info, "Several files could be one role", "discovery", "ambiguous_map"},
        {code::unrecognized_file, Severity::info, "An image in the set matches no role", "discovery",
         "unrecognized_file"},
        // warning: the name says otherwise, and a look at the map decides what the outputs hold.
        {code::role_from_pixels, Severity::warning,
         "A map named for a scalar role holds a tangent-space normal map: read as the normal map", "discovery",
         "role_from_pixels"},
        {code::gloss_inverted, Severity::info, "A gloss map became roughness", "planning", "gloss_inverted"},
        {code::height_stored_as_depth, Severity::info,
         "A height map stored as depth (white = deep) is read inverted and written white = high", "planning",
         "height_stored_as_depth"},
        {code::packed_input_unpacked, Severity::info, "A packed input was split into roles", "planning",
         "packed_input_unpacked"},
        {code::normal_convention_converted, Severity::info, "Green channel flipped to the preset's convention",
         "planning", "normal_convention_converted"},
        {code::map_not_written, Severity::info,
         "A shading map (occlusion, emissive, opacity) the preset has no output for: read, not written", "planning",
         "map_not_written"},
        {code::licence_unknown, Severity::info,
         "No licence for the set: no licence file, sidecar field or vendor naming with a known licence", "discovery",
         "licence_unknown"},
        {code::names_merged, Severity::warning,
         "Two spellings of a material name were grouped as one material (info when only tags differ)", "finding sets",
         "names_merged"},
        {code::duplicate_input, Severity::info, "A folder or archive reached through two inputs was read once",
         "finding sets", "duplicate_input"},
        {code::duplicate_entry, Severity::warning, "An archive holds two entries of one name; the first is used",
         "finding sets", "duplicate_entry"},
        {code::multipart_image, Severity::warning,
         "A file holds several images (EXR parts, TIFF pages); the first is used", "decoding", "multipart_image"},
        {code::orientation_ignored, Severity::warning,
         "An EXIF/TIFF orientation is not applied: the map is used as stored", "decoding", "orientation_ignored"},
        {code::aspect_mismatch, Severity::error,
         "A map's aspect ratio is more than 2x off the set's: not stretched, not used", "planning", "aspect_mismatch"},
        {code::output_too_large, Severity::warning,
         "An output is wider or taller than engines and GPUs import (its figures give the limit)", "writing",
         "output_too_large"},
        {code::encoding_error_exceeded, Severity::warning,
         "A block-compressed level decodes with more error than the preset's bound", "encoding",
         "encoding_error_exceeded"},
        {code::material_file_skipped, Severity::info,
         "The preset's material file was not written: this run's normal maps are not the convention its engine reads",
         "writing", "material_file_skipped"},
        {code::resized, Severity::info,
         "Maps downsampled to the preset's max_size, or a dds top level resampled to a multiple of 4",
         "planning, encoding", "resized"},
        {code::output_write_failed, Severity::error, "An output or material file could not be written", "writing",
         "output_write_failed"},
        {code::input_not_found, Severity::error, "An input is neither a folder nor a .zip file", "finding sets",
         "input_not_found"},
        {code::unsafe_path, Severity::error, "An archive entry names a path outside the archive; it is skipped",
         "finding sets", "unsafe_path"},
    };
    return c;
}

const CodeInfo* find_code(std::string_view c) {
    for (const auto& r : finding_catalog())
        if (r.code == c) return &r;
    return nullptr;
}

Finding finding(std::string_view code, std::string role, std::string file, std::string message, Figures figures) {
    const CodeInfo* info = find_code(code);
    // A code outside the catalog would reach reports with no severity, title or docs: a bug here.
    if (!info) throw std::logic_error("finding code " + std::string(code) + " is not in the catalog");
    return {std::string(code), info->severity,     std::move(role),
            std::move(file),   std::move(message), std::move(figures)};
}

}  // namespace mf
