// Text helpers for names that come from the file system: bytes, not necessarily UTF-8.
#pragma once
#include <string>
#include <string_view>

namespace mf {

// `s` with every ill-formed UTF-8 sequence replaced by U+FFFD (one per maximal invalid
// subpart, Unicode 15 §3.9 "U+FFFD Substitution of Maximal Subparts"); valid text is unchanged.
// XML and JSON writers call it so a Latin-1 file name cannot make the whole report unreadable.
std::string utf8_or_replacement(std::string_view s);

}  // namespace mf
