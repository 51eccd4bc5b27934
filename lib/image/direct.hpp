// Internal to lib/image: the files read without OpenImageIO. image.cpp asks here first and
// loads the OpenImageIO module (image/oiio_module.hpp) only for what these decline, so a run of
// JPEG sets with plain PNG heights never loads it (261 libraries, 0.2-0.3 s in which no other
// work could start; a run that loads it stalls the threads it starts meanwhile). What they read they read as
// OpenImageIO does (the same codes, sizes and notes: DirectCodecs.* hold them against it on the corpus and on made
// files):
//  - JPEG: libjpeg-turbo, the library OpenImageIO's reader calls, with its defaults
//    (image/jpeg_reader.hpp), for a file named as a JPEG;
//  - PNG: plain 8/16-bit files (image/png_reader.hpp), libdeflate's inflate;
//  - WebP: still, opaque files without metadata (image/webp_reader.hpp), libwebp, for a file
//    named as a WebP.
// Each returns false, having changed nothing, for anything else, and never an exception (a
// decode without the memory for it declines too): the module then reads the file as before and
// says what is wrong with it. The exceptions: a JPEG, whatever its name, that libjpeg finds
// damaged (jpeg_reader.hpp's check: a declared size its data cannot hold, a warning of lost
// data), and a PNG whose header declares more rows than its data can inflate to
// (png_reader.hpp's size_refusal) — `refusal` then says why, and the caller reports it instead
// of reading it another way (OpenImageIO would first allocate what the header declares).
#pragma once
#include <optional>

#include "image/image.hpp"

namespace mf::direct {

// A header read. `stated`: what stated_color_space gives for the file (JPEG, WebP: "sRGB", as
// OpenImageIO states it for every such file), left empty where the module would have to say it.
bool read_info(const InputFile& in, ImageInfo& info, std::optional<StatedColorSpace>& stated, std::string& refusal);

// A whole decode: an 8-bit file into out.codes when keep_codes, else into out.floats (a 16-bit
// PNG's code k as k / 65535, an 8-bit code as unorm8_values()).
bool read_image(const InputFile& in, Decoded& out, ImageInfo& info, bool keep_codes, std::string& refusal);

// read_bands' contract over a whole decode (the files read here are at most kMaxSampleBytes).
// Declines only before the first band: `fn` is called for every band or for none. With `codes`,
// an 8-bit file's bands go there as its codes instead.
bool read_bands(const InputFile& in, int band_rows, ImageInfo& info, std::string& refusal,
                const std::function<void(int, int, const float*)>& fn,
                const std::function<void(int, int, const uint8_t*)>& codes = {});

// The largest decode read here: a 4K RGB map's 48 MiB of samples; the module streams larger
// files in bands (read_bands).
inline constexpr size_t kMaxSampleBytes = size_t{48} << 20;

}  // namespace mf::direct
