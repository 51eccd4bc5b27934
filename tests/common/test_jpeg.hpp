// JPEGs made by libjpeg(-turbo) for the tests: the library every JPEG reader matforge uses
// calls, writing with its own defaults. Tests that include this link JPEG::JPEG.
#pragma once
#include <cstdio>  // before jpeglib.h, which uses FILE

#include <jpeglib.h>

#include <cstdlib>
#include <random>
#include <vector>

namespace mf::testjpeg {

struct Marker {
    int code;  // JPEG_APP0 + n
    std::vector<unsigned char> data;
};

// A w x h JPEG of `components` (1 grey, 3 RGB as YCbCr, 4 CMYK) of smooth noise, with `markers`
// written after the JFIF header.
inline std::vector<unsigned char> make_jpeg(int w, int h, int components, bool progressive,
                                            const std::vector<Marker>& markers = {}) {
    jpeg_compress_struct c{};
    jpeg_error_mgr err{};
    c.err = jpeg_std_error(&err);
    jpeg_create_compress(&c);
    unsigned char* out = nullptr;
    unsigned long size = 0;
    jpeg_mem_dest(&c, &out, &size);
    c.image_width = static_cast<JDIMENSION>(w);
    c.image_height = static_cast<JDIMENSION>(h);
    c.input_components = components;
    c.in_color_space = components == 1 ? JCS_GRAYSCALE : components == 3 ? JCS_RGB : JCS_CMYK;
    jpeg_set_defaults(&c);
    jpeg_set_quality(&c, 90, TRUE);
    if (progressive) jpeg_simple_progression(&c);
    jpeg_start_compress(&c, TRUE);
    for (const Marker& m : markers)
        jpeg_write_marker(&c, m.code, m.data.data(), static_cast<unsigned int>(m.data.size()));
    std::mt19937 rng(static_cast<unsigned>(w * 31 + h * 7 + components));
    std::vector<unsigned char> row(static_cast<size_t>(w) * static_cast<size_t>(components));
    while (c.next_scanline < c.image_height) {
        for (size_t i = 0; i < row.size(); ++i)
            row[i] = static_cast<unsigned char>((i * 3 + c.next_scanline * 5 + (rng() & 15)) & 0xFF);
        JSAMPROW r[1] = {row.data()};
        jpeg_write_scanlines(&c, r, 1);
    }
    jpeg_finish_compress(&c);
    std::vector<unsigned char> bytes(out, out + size);
    jpeg_destroy_compress(&c);
    std::free(out);
    return bytes;
}

}  // namespace mf::testjpeg
