// Color conversion through OpenColorIO: decide once (context -> processor), then run tight loops.
//
// The context loads $OCIO when set, else matforge's own config (ocio/config.ocio, embedded).
// Processors for the two conversions texture sets need are built once and shared by threads.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "image/image.hpp"

namespace mf {

enum class ColorEncoding { linear, srgb };

class ColorContext {
public:
    // nullptr and `error` set when the config cannot be loaded or lacks the needed spaces
    // (a configuration error: exit code 2).
    static std::shared_ptr<const ColorContext> create(std::string& error);
    virtual ~ColorContext() = default;

    // Converts the first min(3, channels) channels of every pixel in place (alpha untouched).
    // Grey (1-2 channel) images are converted per channel as well.
    virtual void convert(Image& img, ColorEncoding from, ColorEncoding to) const = 0;
    virtual void convert(float* rgb, size_t pixels, ColorEncoding from, ColorEncoding to) const = 0;

    // 8-bit sRGB codes as linear floats: entry k is what convert() makes of code k's float
    // (unorm8_values), computed once through the same processor, so a lookup per sample replaces
    // the transfer curve (an 8-bit map resampled in linear light). Empty when the conversion
    // mixes channels (a user config whose linear space has other primaries): use convert().
    virtual const std::vector<float>& srgb_codes_to_linear() const = 0;

    // Where the config came from ("built-in" or the $OCIO path) and the spaces used.
    virtual std::string description() const = 0;
    // Identifies the config's content (OpenColorIO's cache id) and the spaces used: part of
    // every action key, so another config misses the cache.
    virtual std::string cache_id() const = 0;
};

// For `matforge --version`: the OpenColorIO library loaded at run time.
std::string color_library_version();

}  // namespace mf
