// What binutils (an independent ELF reader) says of a file: the build-id lib/core reads in
// memory (core/version.hpp code_identity) checked against `readelf -n`.
#pragma once
#include <cctype>
#include <cstdio>
#include <string>

namespace mf::testelf {

// `s` as one shell word.
inline std::string shell_word(const std::string& s) {
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

// What a shell command prints (stdout and stderr).
inline std::string output_of(const std::string& command) {
    std::string out;
    FILE* p = ::popen((command + " 2>&1").c_str(), "r");
    if (p == nullptr) return out;
    char buf[4096];
    for (size_t n; (n = std::fread(buf, 1, sizeof buf, p)) > 0;) out.append(buf, n);
    ::pclose(p);
    return out;
}

// The build ID `readelf -n` prints for `file` (lowercase hex); "" when it prints none.
inline std::string readelf_build_id(const std::string& file) {
    const std::string out = output_of("readelf -n " + shell_word(file));
    const std::string label = "Build ID: ";
    const auto at = out.find(label);
    if (at == std::string::npos) return {};
    size_t end = at + label.size();
    while (end < out.size() && std::isxdigit(static_cast<unsigned char>(out[end]))) ++end;
    return out.substr(at + label.size(), end - at - label.size());
}

}  // namespace mf::testelf
