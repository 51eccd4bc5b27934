// Text helpers for names that come from the file system: bytes, not necessarily UTF-8.
#pragma once
#include <string>
#include <string_view>

namespace mf {

// `s` with every ill-formed UTF-8 sequence replaced by U+FFFD (one per maximal invalid
// subpart, Unicode 15 §3.9 "U+FFFD Substitution of Maximal Subparts"); valid text is unchanged.
// XML and JSON writers call it so a Latin-1 file name cannot make the whole report unreadable.
std::string utf8_or_replacement(std::string_view s);

// A relative path as a URI reference (RFC 3986): unreserved characters and '/' kept, every
// other byte percent-encoded (upper-case hex). glTF's image URIs and the report's links use it,
// so a name with spaces, '#', '%' or non-ASCII bytes resolves to the file on disk.
std::string percent_encode_path(std::string_view path);

}  // namespace mf
