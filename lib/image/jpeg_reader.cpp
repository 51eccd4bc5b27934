#include "image/jpeg_reader.hpp"

#include "image/exif.hpp"

#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <string_view>

#include <jerror.h>  // libjpeg's message codes (JWRN_JPEG_EOF)
#include <jpeglib.h>

namespace mf::jpeg {
namespace {

// libjpeg's errors end in a longjmp back to read_plain; warnings are counted, and the one that
// matters remembered: libjpeg answers a file that ends early with grey rows and a warning
// (JWRN_JPEG_EOF), which OpenImageIO turns into a failed read (oiio_module.cpp ended_early).
struct ErrorManager {
    jpeg_error_mgr pub{};
    std::jmp_buf jump{};
    bool ended_early = false;
};

[[noreturn]] void error_exit(j_common_ptr cinfo) {
    auto* err = reinterpret_cast<ErrorManager*>(cinfo->err);
    std::longjmp(err->jump, 1);
}

void emit_message(j_common_ptr cinfo, int level) {
    auto* err = reinterpret_cast<ErrorManager*>(cinfo->err);
    if (level < 0) {
        ++err->pub.num_warnings;
        if (err->pub.msg_code == JWRN_JPEG_EOF) err->ended_early = true;
    }
}

// What the saved APP1 markers state: the orientation, or false for any this reader leaves to
// OpenImageIO (two EXIF blocks, one it cannot walk, an XMP packet naming an orientation, which
// OpenImageIO's XMP decoder would read as well).
bool marker_facts(const jpeg_decompress_struct& cinfo, int& orientation) {
    static constexpr std::string_view kExif("Exif\0", 5), kXmp("http://ns.adobe.com/xap/1.0/\0", 29);
    int exif_blocks = 0;
    orientation = 1;
    for (jpeg_saved_marker_ptr m = cinfo.marker_list; m; m = m->next) {
        if (m->marker != JPEG_APP0 + 1) continue;
        const std::string_view data(reinterpret_cast<const char*>(m->data), m->data_length);
        if (data.substr(0, kExif.size()) == kExif) {
            if (++exif_blocks > 1 || data.size() < 6 ||
                !exif::orientation(m->data + 6, m->data_length - 6, orientation))
                return false;
        } else if (data.substr(0, kXmp.size()) == kXmp && data.find("Orientation") != std::string_view::npos) {
            return false;
        }
    }
    return true;
}

}  // namespace

bool read_plain(const unsigned char* data, size_t size, bool header_only, uint64_t max_samples, Plain& out) {
    out = Plain{};
    if (size < 4) return false;
    jpeg_decompress_struct cinfo{};
    ErrorManager err;
    cinfo.err = jpeg_std_error(&err.pub);
    err.pub.error_exit = error_exit;
    err.pub.emit_message = emit_message;
    // Only trivially destructible locals live across setjmp; the pixels are written into `out`.
    if (setjmp(err.jump)) {
        jpeg_destroy_decompress(&cinfo);
        out = Plain{};
        return false;
    }
    jpeg_create_decompress(&cinfo);
    jpeg_mem_src(&cinfo, data, static_cast<unsigned long>(size));
    jpeg_save_markers(&cinfo, JPEG_APP0 + 1, 0xFFFF);
    bool plain = jpeg_read_header(&cinfo, TRUE) == JPEG_HEADER_OK && !err.ended_early;
    plain = plain && cinfo.data_precision == 8 &&
            ((cinfo.num_components == 1 && cinfo.jpeg_color_space == JCS_GRAYSCALE) ||
             (cinfo.num_components == 3 && (cinfo.jpeg_color_space == JCS_YCbCr || cinfo.jpeg_color_space == JCS_RGB)));
    plain = plain && cinfo.image_width > 0 && cinfo.image_height > 0 &&
            uint64_t{cinfo.image_width} * cinfo.image_height * static_cast<uint64_t>(cinfo.num_components) <=
                max_samples;
    plain = plain && marker_facts(cinfo, out.orientation);
    if (!plain) {
        jpeg_destroy_decompress(&cinfo);
        out = Plain{};
        return false;
    }
    out.width = static_cast<int>(cinfo.image_width);
    out.height = static_cast<int>(cinfo.image_height);
    out.channels = cinfo.num_components;
    if (header_only) {
        jpeg_destroy_decompress(&cinfo);
        return true;
    }
    // libjpeg's defaults (islow DCT, fancy upsampling), as OpenImageIO leaves them.
    jpeg_start_decompress(&cinfo);
    const size_t row = size_t{cinfo.output_width} * static_cast<size_t>(cinfo.output_components);
    if (static_cast<int>(cinfo.output_width) != out.width || static_cast<int>(cinfo.output_height) != out.height ||
        cinfo.output_components != out.channels) {
        jpeg_destroy_decompress(&cinfo);
        out = Plain{};
        return false;
    }
    out.pixels.resize(row * cinfo.output_height);
    while (cinfo.output_scanline < cinfo.output_height) {
        JSAMPROW rows[1] = {out.pixels.data() + row * cinfo.output_scanline};
        if (jpeg_read_scanlines(&cinfo, rows, 1) != 1) break;
    }
    const bool whole = cinfo.output_scanline == cinfo.output_height && !err.ended_early;
    if (whole) jpeg_finish_decompress(&cinfo);
    jpeg_destroy_decompress(&cinfo);
    if (!whole || err.ended_early) {
        out = Plain{};
        return false;
    }
    return true;
}

}  // namespace mf::jpeg
