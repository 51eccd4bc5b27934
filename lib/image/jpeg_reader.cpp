#include "image/jpeg_reader.hpp"

#include "base/limits.hpp"
#include "image/exif.hpp"

#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <string>
#include <string_view>

#include <jpeglib.h>

// After jpeglib.h: its jconfig.h says which codes exist (JWRN_ARITH_BAD_CODE with arithmetic
// decoding, in libjpeg-turbo's 6.2 API).
#include <jerror.h>

namespace mf::jpeg {
namespace {

// Bytes an encoder may leave before the end-of-image marker after the last block (padding: a
// few zero bytes from some encoders). More is the entropy decoder finishing out of step: 256
// garbled bytes in the middle of a real 1024² file (sample_materials' Net004A colour map) leave
// 40; no corpus JPEG leaves any.
constexpr int kMaxPaddingBeforeEoi = 4;

// libjpeg's errors end in a longjmp back to the caller; every warning is seen here (libjpeg's
// own emit_message passes only the first to output_message, which is all OpenImageIO hears),
// and the first that means lost data is kept with its text and the count of such warnings.
struct ErrorManager {
    jpeg_error_mgr pub{};
    std::jmp_buf jump{};
    int lost = 0;            // warnings that mean pixels were not decoded from the file's data
    bool decoding = false;   // past jpeg_start_decompress: the entropy-coded data is being read
    std::string first_lost;  // libjpeg's text of the first
};

[[noreturn]] void error_exit(j_common_ptr cinfo) {
    auto* err = reinterpret_cast<ErrorManager*>(cinfo->err);
    std::longjmp(err->jump, 1);
}

// Whether libjpeg's warning means decoded rows that are not the file's pixels: a segment cut
// short or garbled (libjpeg then fills with zeros or carries on out of step), the file ending
// early (grey rows). Not: an unknown JFIF revision or Adobe transform, a bad ICC marker (a
// profile, not pixels), and a few extraneous bytes before the end-of-image marker once every
// row is decoded (encoders' padding), nor stray bytes between header segments before any pixel
// is decoded (some writers leave them; the image data after them is whole).
bool loses_data(const ErrorManager& err, const jpeg_decompress_struct& cinfo) {
    const jpeg_error_mgr& e = err.pub;
    switch (e.msg_code) {
        case JWRN_ARITH_BAD_CODE:
        case JWRN_BOGUS_PROGRESSION:
        case JWRN_HIT_MARKER:
        case JWRN_HUFF_BAD_CODE:
        case JWRN_JPEG_EOF:
        case JWRN_MUST_RESYNC:
        case JWRN_NOT_SEQUENTIAL: return true;
        case JWRN_EXTRANEOUS_DATA:
            // msg_parm.i: {count, marker}. Bytes left over before EOI after the last MCU are
            // padding when few; many mean the entropy decoder finished out of step.
            return err.decoding && (e.msg_parm.i[1] != 0xD9 || e.msg_parm.i[0] > kMaxPaddingBeforeEoi ||
                                    cinfo.output_scanline < cinfo.output_height);
        default: return false;
    }
}

void emit_message(j_common_ptr cinfo, int level) {
    auto* err = reinterpret_cast<ErrorManager*>(cinfo->err);
    if (level >= 0) return;
    ++err->pub.num_warnings;
    if (cinfo->is_decompressor && loses_data(*err, *reinterpret_cast<const jpeg_decompress_struct*>(cinfo)) &&
        err->lost++ == 0) {
        char text[JMSG_LENGTH_MAX];
        (*cinfo->err->format_message)(cinfo, text);
        err->first_lost = text;
    }
}

// `cinfo` reporting to `err` (called before setjmp; jpeg_create_decompress after it).
void attach(jpeg_decompress_struct& cinfo, ErrorManager& err) {
    cinfo.err = jpeg_std_error(&err.pub);
    err.pub.error_exit = error_exit;
    err.pub.emit_message = emit_message;
}

// Why the frame header cannot be the file's: more blocks than its data can code. Huffman coding
// spends at least one bit on every block's DC coefficient (a sequential scan at least two: DC
// and end-of-block), so a file of N bytes holds at most 8 N blocks; arithmetic coding can code a
// flat block in far less, so it gets 64 blocks a bit. Empty when it fits. Checked after
// jpeg_read_header (which sets each component's size in blocks) and before any pixel buffer.
std::string size_refusal(const jpeg_decompress_struct& cinfo, uint64_t file_size) {
    // Beyond kMaxImageSide² pixels the decoders' own limit refuses the file, in its words.
    if (uint64_t{cinfo.image_width} * cinfo.image_height > uint64_t{kMaxImageSide} * uint64_t{kMaxImageSide}) return {};
    uint64_t blocks = 0;
    for (int c = 0; c < cinfo.num_components; ++c)
        blocks += uint64_t{cinfo.comp_info[c].width_in_blocks} * cinfo.comp_info[c].height_in_blocks;
    const uint64_t most = file_size * 8 * (cinfo.arith_code ? 64 : 1);
    if (blocks <= most) return {};
    return "its frame header declares " + std::to_string(cinfo.image_width) + "x" + std::to_string(cinfo.image_height) +
           " pixels (" + std::to_string(blocks) + " blocks of 8x8), more than its " + std::to_string(file_size) +
           " bytes can code (at most " + std::to_string(most) +
           "): the file is cut short or its header is damaged; not decoded";
}

std::string damage_text(const ErrorManager& err) {
    return "libjpeg reports lost data (" + err.first_lost +
           (err.lost > 1 ? "; " + std::to_string(err.lost) + " such warnings" : std::string()) +
           "): the file is cut short or its data corrupt, and those rows would be grey or garbage";
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

bool read_plain(const unsigned char* data, size_t size, bool header_only, uint64_t max_samples, Plain& out,
                uint64_t file_size) {
    out = Plain{};
    if (size < 4) return false;
    jpeg_decompress_struct cinfo{};
    ErrorManager err;
    attach(cinfo, err);
    // Only trivially destructible locals live across setjmp (err's string is set only after a
    // warning, never across the jump's return); the pixels are written into `out`.
    if (setjmp(err.jump)) {
        jpeg_destroy_decompress(&cinfo);
        out = Plain{};
        return false;
    }
    jpeg_create_decompress(&cinfo);
    jpeg_mem_src(&cinfo, data, static_cast<unsigned long>(size));
    jpeg_save_markers(&cinfo, JPEG_APP0 + 1, 0xFFFF);
    bool plain = jpeg_read_header(&cinfo, TRUE) == JPEG_HEADER_OK;
    if (plain) out.refusal = size_refusal(cinfo, file_size);
    if (plain && err.lost) out.refusal = damage_text(err);
    plain = plain && out.refusal.empty() && cinfo.data_precision == 8 &&
            ((cinfo.num_components == 1 && cinfo.jpeg_color_space == JCS_GRAYSCALE) ||
             (cinfo.num_components == 3 && (cinfo.jpeg_color_space == JCS_YCbCr || cinfo.jpeg_color_space == JCS_RGB)));
    plain = plain && cinfo.image_width > 0 && cinfo.image_height > 0 &&
            uint64_t{cinfo.image_width} * cinfo.image_height * static_cast<uint64_t>(cinfo.num_components) <=
                max_samples;
    plain = plain && marker_facts(cinfo, out.orientation);
    if (!plain) {
        jpeg_destroy_decompress(&cinfo);
        std::string refusal = std::move(out.refusal);
        out = Plain{};
        out.refusal = std::move(refusal);
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
    err.decoding = true;
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
    bool whole = cinfo.output_scanline == cinfo.output_height;
    if (whole) jpeg_finish_decompress(&cinfo);  // reads to EOI: warnings of the file's tail too
    whole = whole && err.lost == 0;
    const std::string damage = err.lost ? damage_text(err) : std::string();
    jpeg_destroy_decompress(&cinfo);
    if (!whole) {
        out = Plain{};
        out.refusal = damage;
        return false;
    }
    return true;
}

std::string check(const unsigned char* data, size_t size, bool header_only, uint64_t max_samples, uint64_t file_size) {
    if (size < 4) return {};
    jpeg_decompress_struct cinfo{};
    ErrorManager err;
    attach(cinfo, err);
    // No C++ object is made between here and a libjpeg call that may jump back: every string
    // below is made once libjpeg is done (but for jpeg_destroy_decompress, which never jumps).
    if (setjmp(err.jump)) {
        jpeg_destroy_decompress(&cinfo);
        return {};  // libjpeg cannot read it: the module's reader says why
    }
    jpeg_create_decompress(&cinfo);
    jpeg_mem_src(&cinfo, data, static_cast<unsigned long>(size));
    if (jpeg_read_header(&cinfo, TRUE) != JPEG_HEADER_OK) {
        jpeg_destroy_decompress(&cinfo);
        return {};
    }
    if (std::string why = size_refusal(cinfo, file_size); !why.empty() || err.lost) {
        jpeg_destroy_decompress(&cinfo);
        return why.empty() ? damage_text(err) : why;
    }
    if (header_only ||
        uint64_t{cinfo.image_width} * cinfo.image_height * static_cast<uint64_t>(cinfo.num_components) > max_samples) {
        jpeg_destroy_decompress(&cinfo);
        return {};
    }
    // Every row decoded into one row of libjpeg's own memory and dropped: what is wanted is
    // libjpeg's warnings (the fast DCT: warnings come from the entropy decoder, not the IDCT).
    cinfo.dct_method = JDCT_IFAST;
    cinfo.do_fancy_upsampling = FALSE;
    err.decoding = true;
    jpeg_start_decompress(&cinfo);
    JSAMPARRAY row = (*cinfo.mem->alloc_sarray)(reinterpret_cast<j_common_ptr>(&cinfo), JPOOL_IMAGE,
                                                cinfo.output_width * static_cast<JDIMENSION>(cinfo.output_components),
                                                1);
    while (cinfo.output_scanline < cinfo.output_height)
        if (jpeg_read_scanlines(&cinfo, row, 1) != 1) break;
    if (cinfo.output_scanline == cinfo.output_height) jpeg_finish_decompress(&cinfo);
    const bool lost = err.lost > 0;
    jpeg_destroy_decompress(&cinfo);
    return lost ? damage_text(err) : std::string();
}

}  // namespace mf::jpeg
