#include "files.hpp"

#include <OpenImageIO/imageio.h>
#include <zip.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <utility>
#include <vector>

namespace gen {

namespace fs = std::filesystem;

namespace {

std::vector<unsigned char> read_bytes(const fs::path& path) {
    std::ifstream f(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

}  // namespace

// Writes with OpenImageIO. Integer formats are quantised here (round half up) so the bytes do
// not depend on library conversion details; EXR gets a fixed DateTime (else it stamps "now").
bool write_image(const fs::path& path, const Pixels& px, Enc enc, bool srgb_tag, std::string& err) {
    auto out = OIIO::ImageOutput::create(path.string());
    if (!out) {
        err = "no writer for " + path.string();
        return false;
    }
    const OIIO::TypeDesc fmt = enc == Enc::png16      ? OIIO::TypeDesc::UINT16
                               : enc == Enc::exr_half ? OIIO::TypeDesc::HALF
                                                      : OIIO::TypeDesc::UINT8;
    OIIO::ImageSpec spec(px.w, px.h, px.c, fmt);
    if (enc == Enc::exr_half) {
        spec.attribute("DateTime", "2024:01:01 00:00:00");
        spec.attribute("compression", "zip");
        if (px.c == 1) spec.channelnames = {"Y"};
    }
    if (enc == Enc::jpg) spec.attribute("Compression", "jpeg:90");
    if (srgb_tag) spec.attribute("oiio:ColorSpace", "sRGB");
    bool ok = out->open(path.string(), spec);
    if (ok && enc == Enc::exr_half) {
        ok = out->write_image(OIIO::TypeDesc::FLOAT, px.v.data());
    } else if (ok && enc == Enc::png16) {
        std::vector<uint16_t> q(px.v.size());
        for (size_t i = 0; i < q.size(); ++i)
            q[i] = static_cast<uint16_t>(std::floor(clamp01(px.v[i]) * 65535.f + 0.5f));
        ok = out->write_image(OIIO::TypeDesc::UINT16, q.data());
    } else if (ok) {
        std::vector<uint8_t> q(px.v.size());
        for (size_t i = 0; i < q.size(); ++i) q[i] = static_cast<uint8_t>(std::floor(clamp01(px.v[i]) * 255.f + 0.5f));
        ok = out->write_image(OIIO::TypeDesc::UINT8, q.data());
    }
    ok = out->close() && ok;
    if (!ok) err = path.string() + ": " + out->geterror();
    return ok;
}

bool write_text(const fs::path& path, const std::string& text, std::string& err) {
    std::ofstream f(path, std::ios::binary);
    f << text;
    if (!f) err = "cannot write " + path.string();
    return static_cast<bool>(f);
}

// Zips a staged folder: entries sorted by name, fixed DOS time and Unix mode, deflate level 9,
// so the archive's bytes depend on the content only.
bool write_zip(const fs::path& staged, const fs::path& zip_path, std::string& err) {
    std::vector<std::pair<std::string, std::vector<unsigned char>>> entries;
    for (const auto& e : fs::recursive_directory_iterator(staged))
        if (e.is_regular_file())
            entries.emplace_back(fs::relative(e.path(), staged).generic_string(), read_bytes(e.path()));
    std::sort(entries.begin(), entries.end());
    int zerr = 0;
    zip_t* za = zip_open(zip_path.string().c_str(), ZIP_CREATE | ZIP_TRUNCATE, &zerr);
    if (!za) {
        err = "cannot create " + zip_path.string();
        return false;
    }
    constexpr zip_uint16_t kDosDate = ((2024 - 1980) << 9) | (1 << 5) | 1;  // 2024-01-01
    constexpr zip_uint16_t kDosTime = 12 << 11;                             // 12:00:00
    bool ok = true;
    for (const auto& [name, bytes] : entries) {
        zip_source_t* src = zip_source_buffer(za, bytes.data(), bytes.size(), 0);
        const zip_int64_t idx = src ? zip_file_add(za, name.c_str(), src, ZIP_FL_ENC_UTF_8) : -1;
        if (idx < 0) {
            if (src) zip_source_free(src);
            ok = false;
            break;
        }
        const auto u = static_cast<zip_uint64_t>(idx);
        ok = zip_set_file_compression(za, u, ZIP_CM_DEFLATE, 9) == 0 &&
             zip_file_set_dostime(za, u, kDosTime, kDosDate, 0) == 0 &&
             zip_file_set_external_attributes(za, u, 0, ZIP_OPSYS_UNIX, 0100644U << 16) == 0;
        if (!ok) break;
    }
    if (!ok) {
        err = zip_path.string() + ": " + zip_strerror(za);
        zip_discard(za);
        return false;
    }
    if (zip_close(za) != 0) {
        err = zip_path.string() + ": " + zip_strerror(za);
        zip_discard(za);
        return false;
    }
    return true;
}

}  // namespace gen
