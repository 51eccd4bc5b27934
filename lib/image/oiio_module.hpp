// The table of functions the matforge_oiio module (lib/image/oiio/) exports, the one contract
// between it and lib/image/image.cpp, which loads it on first use. Both sides come from one
// build; the ABI number and the table's size refuse a module of another.
#pragma once
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "image/image.hpp"

namespace mf::oiio_module {

// Raised whenever a function's signature or a type the table passes changes.
inline constexpr int kAbi = 2;
// The module's file name and its one exported symbol, `const Table* matforge_oiio_table()`.
inline constexpr const char* kFileName = "matforge_oiio.so";
inline constexpr const char* kEntry = "matforge_oiio_table";

struct Table {
    int abi;
    size_t size;  // sizeof(Table) of the module's build
    // As read_info, read_image (keep_codes: an 8-bit file as its codes), read_bands and
    // encode_image of image.hpp, without the exception guard image.cpp puts around them.
    // `stated`: what stated_color_space would give, when this open used the reader the file's
    // name picks (that function opens by name), else left empty.
    std::optional<ImageInfo> (*read_info)(const InputFile& in, std::string& error,
                                          std::optional<StatedColorSpace>& stated);
    bool (*read_image)(const InputFile& in, Decoded& out, ImageInfo& info, std::string& error, bool keep_codes);
    bool (*read_bands)(const InputFile& in, int band_rows, ImageInfo& info, std::string& error,
                       const std::function<void(int, int, const float*)>& fn);
    bool (*encode_floats)(const Image& img, const EncodeOptions& opt, std::vector<unsigned char>& bytes,
                          std::string& error);
    bool (*encode_codes)(const Image8& img, const EncodeOptions& opt, std::vector<unsigned char>& bytes,
                         std::string& error);
    StatedColorSpace (*stated_color_space)(const InputFile& in);
    // `out` is allocated at the size wanted, with src's channels.
    void (*resize_lanczos3)(const Image& src, Image& out);
    int (*version)();                   // openimageio_version(): 20407 is 2.4.7
    std::string (*library_file)();      // the libOpenImageIO file loaded, as the loader opened it
    std::string (*format_libraries)();  // "png:libpng 1.6.39 jpeg:jpeg-turbo 2.1.5 ..."
};

// The module's table, loaded on the first call (image/oiio_loader.cpp: beside the executable,
// the install's library folder, then the build tree), or nullptr with `error` set to `prefix`
// and every place tried. Thread-safe; never unloaded.
const Table* table(std::string& error, const std::string& prefix = {});

}  // namespace mf::oiio_module
