// ASCII case, header-only: lib/image (and its OpenImageIO module, which links no library of ours)
// compares file extensions with it through InputFile.
#pragma once
#include <string>

namespace mf {

// `s` with ASCII letters in lower case, other bytes unchanged: names compared as case-insensitive
// file systems compare them (file names are bytes, not text in a locale).
inline std::string ascii_lower(std::string s) {
    for (char& c : s)
        if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
    return s;
}

}  // namespace mf
