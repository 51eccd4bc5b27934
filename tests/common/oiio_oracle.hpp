// OpenImageIO read directly, as the oracle of matforge's own readers (lib/image/direct.hpp):
// the tests that link OpenImageIO compare every code and header fact with what it reads.
#pragma once
#include <gtest/gtest.h>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "image/image.hpp"

namespace mf::testenv {

struct OiioRead {
    bool ok = false;
    OIIO::ImageSpec spec;
    std::vector<unsigned char> pixels;  // in the type asked for
};

// `bytes` opened by the reader `format` names ("jpeg", "png"), as matforge's module opens a file
// (unassociated alpha), read whole in `type`; a failure is added to the calling test.
inline OiioRead oiio_read(const std::vector<unsigned char>& bytes, const std::string& format, OIIO::TypeDesc type) {
    OiioRead o;
    OIIO::Filesystem::IOMemReader mem(bytes.data(), bytes.size());
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    auto in = OIIO::ImageInput::create(format, false, &config);
    OIIO::ImageSpec spec;
    if (!in || !in->set_ioproxy(&mem) || !in->open("memory." + format, spec, config)) {
        ADD_FAILURE() << "OpenImageIO cannot open it: " << (in ? in->geterror() : OIIO::geterror());
        return o;
    }
    o.spec = in->spec();
    o.pixels.resize(o.spec.image_pixels() * static_cast<size_t>(o.spec.nchannels) * type.size());
    o.ok = in->read_image(0, 0, 0, o.spec.nchannels, type, o.pixels.data());
    if (!o.ok) ADD_FAILURE() << "OpenImageIO cannot read it: " << in->geterror();
    return o;
}

// An 8-bit PNG of `px` (interleaved, unassociated alpha) written by OpenImageIO (libpng): an
// encoder independent of matforge's, for inputs the tests build. Folders are made.
inline void oiio_write_png8(const std::filesystem::path& file, int w, int h, int channels,
                            const std::vector<uint8_t>& px) {
    std::filesystem::create_directories(file.parent_path());
    auto out = OIIO::ImageOutput::create(file.string());
    ASSERT_TRUE(out);
    OIIO::ImageSpec spec(w, h, channels, OIIO::TypeDesc::UINT8);
    if (channels == 4) spec.attribute("oiio:UnassociatedAlpha", 1);
    ASSERT_TRUE(out->open(file.string(), spec));
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, px.data()));
    ASSERT_TRUE(out->close());
}

// matforge's read_image of `in` (which holds `bytes`) gives every float OpenImageIO's reader
// `format` reads from them, bit for bit; returns the facts matforge's read stated.
inline mf::ImageInfo expect_floats_as_openimageio(const mf::InputFile& in, const std::vector<unsigned char>& bytes,
                                                  const std::string& format) {
    const OiioRead o = oiio_read(bytes, format, OIIO::TypeDesc::FLOAT);
    mf::Image got;
    mf::ImageInfo info;
    std::string err;
    EXPECT_TRUE(mf::read_image(in, got, info, err)) << err;
    EXPECT_EQ(got.pixels.size() * sizeof(float), o.pixels.size());
    if (o.ok && got.pixels.size() * sizeof(float) == o.pixels.size()) {
        EXPECT_EQ(std::memcmp(got.pixels.data(), o.pixels.data(), o.pixels.size()), 0) << "a float differs";
    }
    return info;
}

}  // namespace mf::testenv
