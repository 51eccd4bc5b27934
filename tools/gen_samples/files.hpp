// Writing files so that their bytes depend on the content only: images through OpenImageIO
// (quantised here, EXR with a fixed DateTime), text, and zip archives (sorted entries, fixed
// times and modes).
#pragma once

#include <filesystem>
#include <string>

#include "maps.hpp"

namespace gen {

bool write_image(const std::filesystem::path& path, const Pixels& px, Enc enc, bool srgb_tag, std::string& err);
bool write_text(const std::filesystem::path& path, const std::string& text, std::string& err);
// Zips the files under `staged` (names relative to it) into `zip_path`.
bool write_zip(const std::filesystem::path& staged, const std::filesystem::path& zip_path, std::string& err);

}  // namespace gen
