#include "pack/pack.hpp"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <algorithm>
#include <cmath>

namespace mf {

namespace {

template <class T>
BasicImage<T> extract_channel_t(const BasicImage<T>& src, int channel) {
    BasicImage<T> out(src.width, src.height, 1);
    const int c = std::min(channel, src.channels - 1);
    for (size_t i = 0, n = out.pixels.size(); i < n; ++i) out.pixels[i] = src.pixels[i * src.channels + c];
    return out;
}

template <class T>
BasicImage<T> to_rgb_t(const BasicImage<T>& src) {
    if (src.channels == 3) return src;
    BasicImage<T> out(src.width, src.height, 3);
    const size_t n = static_cast<size_t>(src.width) * src.height;
    for (size_t i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c)
            out.pixels[i * 3 + c] = src.pixels[i * src.channels + (src.channels >= 3 ? c : 0)];
    return out;
}

// One normal texel, shared by the float path (decode_normal, encode_normal) and the codes path
// (pack_output8), so both run the same float operations in the same order and write the same
// codes.
struct Texel {
    float x, y, z;
};

// Stored color (2 to 4 channels; 2: Z rebuilt from unit length) -> unit vector, Y times ysign;
// zero-length or non-finite -> (0,0,1). `bad`: the stored length was far from 1, or Z < 0.
inline Texel decode_texel(const float* e, int channels, float ysign, bool& bad) {
    float x = e[0] * 2.f - 1.f;
    float y = (channels > 1 ? e[1] : 0.5f) * 2.f - 1.f;
    float z;
    if (channels >= 3) {
        z = e[2] * 2.f - 1.f;
    } else {  // two-channel (BC5-style) normals: Z from unit length
        z = std::sqrt(std::max(0.f, 1.f - x * x - y * y));
    }
    const float len = std::sqrt(x * x + y * y + z * z);
    bad = !(std::abs(len - 1.f) <= 0.2f) || z < 0.f;
    if (!(len > 1e-6f) || !std::isfinite(len)) {
        x = 0.f, y = 0.f, z = 1.f;
    } else {
        x /= len, y /= len, z /= len;
    }
    return {x, y * ysign, z};
}

// Unit vector (renormalized first: resampling shortens vectors) -> stored color, Y times ysign.
inline Texel encode_texel(Texel n, float ysign) {
    float x = n.x, y = n.y, z = n.z;
    const float len = std::sqrt(x * x + y * y + z * z);
    if (len > 1e-6f && std::isfinite(len)) {
        x /= len, y /= len, z /= len;
    } else {
        x = 0.f, y = 0.f, z = 1.f;
    }
    return {x * 0.5f + 0.5f, y * ysign * 0.5f + 0.5f, z * 0.5f + 0.5f};
}

float ysign_of(NormalConvention c) { return c == NormalConvention::dx ? -1.f : 1.f; }

}  // namespace

Image extract_channel(const Image& src, int channel) { return extract_channel_t(src, channel); }
Image8 extract_channel(const Image8& src, int channel) { return extract_channel_t(src, channel); }
Image to_rgb(const Image& src) { return to_rgb_t(src); }
Image8 to_rgb(const Image8& src) { return to_rgb_t(src); }

void invert(Image& img) {
    for (float& v : img.pixels) v = 1.f - v;
}
void invert(Image8& codes) {
    for (uint8_t& k : codes.pixels) k = static_cast<uint8_t>(255 - k);
}

double decode_normal(const Image& enc, NormalConvention from, Image& out) {
    out = Image(enc.width, enc.height, 3);
    const size_t n = static_cast<size_t>(enc.width) * enc.height;
    const float ysign = ysign_of(from);
    size_t bad = 0;
    for (size_t i = 0; i < n; ++i) {
        bool b = false;
        const Texel t = decode_texel(&enc.pixels[i * enc.channels], enc.channels, ysign, b);
        bad += b ? 1 : 0;
        out.pixels[i * 3 + 0] = t.x;
        out.pixels[i * 3 + 1] = t.y;
        out.pixels[i * 3 + 2] = t.z;
    }
    return n ? static_cast<double>(bad) / static_cast<double>(n) : 0.0;
}

void renormalize(Image& n) {
    for (size_t i = 0, c = static_cast<size_t>(n.width) * n.height; i < c; ++i) {
        float* v = &n.pixels[i * 3];
        const float len = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        if (len > 1e-6f && std::isfinite(len)) {
            v[0] /= len, v[1] /= len, v[2] /= len;
        } else {
            v[0] = 0.f, v[1] = 0.f, v[2] = 1.f;
        }
    }
}

Image encode_normal(const Image& n, NormalConvention to) {
    Image out(n.width, n.height, 3);
    const float ysign = ysign_of(to);
    for (size_t i = 0, count = static_cast<size_t>(n.width) * n.height; i < count; ++i) {
        const Texel t = encode_texel({n.pixels[i * 3], n.pixels[i * 3 + 1], n.pixels[i * 3 + 2]}, ysign);
        out.pixels[i * 3 + 0] = t.x;
        out.pixels[i * 3 + 1] = t.y;
        out.pixels[i * 3 + 2] = t.z;
    }
    return out;
}

Image plane_floats(Role role, const RolePlane& plane) {
    if (!plane.is_codes()) return plane.image;
    if (role != Role::normal) return to_float(plane.codes);
    Image n;
    decode_normal(to_float(plane.codes), plane.codes_convention, n);
    return n;
}

void make_floats(Role role, RolePlane& plane) {
    if (!plane.is_codes()) return;
    plane.image = plane_floats(role, plane);
    plane.codes = Image8{};
}

Image resample(const Image& src, int w, int h) {
    if (src.width == w && src.height == h) return src;
    OIIO::ImageSpec in_spec(src.width, src.height, src.channels, OIIO::TypeDesc::FLOAT);
    OIIO::ImageBuf in(in_spec, const_cast<float*>(src.pixels.data()));  // read-only use
    Image out(w, h, src.channels);
    OIIO::ImageSpec out_spec(w, h, src.channels, OIIO::TypeDesc::FLOAT);
    OIIO::ImageBuf dst(out_spec, out.pixels.data());
    OIIO::ImageBufAlgo::resize(dst, in, "lanczos3", 0.f, OIIO::ROI::All(), 1);
    return out;
}

void fit_plane(Role role, RolePlane& plane, int w, int h, const ColorContext& color) {
    if (plane.width() == w && plane.height() == h) return;
    make_floats(role, plane);
    if (plane.encoding == ColorEncoding::srgb) {  // filter in linear light, never on encoded values
        color.convert(plane.image, ColorEncoding::srgb, ColorEncoding::linear);
        plane.encoding = ColorEncoding::linear;
    }
    plane.image = resample(plane.image, w, h);
    if (role == Role::normal) renormalize(plane.image);  // filtering shortens unit vectors
}

bool output_needed(const OutputSpec& o, const Planes& planes) {
    if (o.always) return true;
    for (Role r : o.roles())
        if (planes.count(r)) return true;
    return false;
}

std::vector<ChannelSpec> effective_channels(const OutputSpec& o, const Planes& planes) {
    std::vector<ChannelSpec> out;
    for (const auto& c : o.channels)
        if (!c.optional || planes.count(c.role)) out.push_back(c);
    return out;
}

Size output_size(const OutputSpec& o, const Planes& planes, const Preset& preset) {
    Size s;
    for (const auto& c : effective_channels(o, planes)) {
        if (c.kind != ChannelSpec::Kind::role && c.kind != ChannelSpec::Kind::smoothness) continue;
        auto it = planes.find(c.role);
        if (it == planes.end()) continue;
        s.width = std::max(s.width, it->second.width());
        s.height = std::max(s.height, it->second.height());
    }
    if (s.width == 0) return {preset.constant_size, preset.constant_size};
    if (preset.max_size > 0 && std::max(s.width, s.height) > preset.max_size) {
        const double k = static_cast<double>(preset.max_size) / std::max(s.width, s.height);
        s.width = std::max(1, static_cast<int>(std::lround(s.width * k)));
        s.height = std::max(1, static_cast<int>(std::lround(s.height * k)));
    }
    return s;
}

namespace {

// Channel k of the default color of a missing RGB role, in the output's encoding.
float default_rgb(const ChannelSpec& c, int k, const OutputSpec& o, const Preset& preset, const ColorContext& color) {
    const std::array<float, 3> def = c.role == Role::normal   ? std::array<float, 3>{0.5f, 0.5f, 1.f}
                                     : c.role == Role::albedo ? preset.default_albedo
                                                              : std::array<float, 3>{0.f, 0.f, 0.f};
    float v = def[static_cast<size_t>(k)];
    if (o.srgb && c.role != Role::normal) {
        float rgb[3] = {v, v, v};
        color.convert(rgb, 1, ColorEncoding::linear, ColorEncoding::srgb);
        v = rgb[0];
    }
    return v;
}

// The value of a missing scalar role (inverted for a smoothness channel).
float default_scalar(const ChannelSpec& c, const Preset& preset) {
    const float v = preset.default_value(c.role);
    return c.kind == ChannelSpec::Kind::smoothness ? 1.f - v : v;
}

int channel_count(const std::vector<ChannelSpec>& channels) {
    int n = 0;
    for (const auto& c : channels) n += c.key == "RGB" ? 3 : 1;
    return n;
}

}  // namespace

Image pack_output(const OutputSpec& o, const Planes& planes, const Preset& preset, Size size,
                  const ColorContext& color) {
    const auto channels = effective_channels(o, planes);
    const int nch = channel_count(channels);
    Image out(size.width, size.height, nch);
    const size_t n = static_cast<size_t>(size.width) * size.height;
    int dst = 0;
    for (const auto& c : channels) {
        auto fill = [&](int ch, float v) {
            for (size_t i = 0; i < n; ++i) out.pixels[i * nch + ch] = v;
        };
        auto copy = [&](int ch, const Image& src, int sc, bool inv) {
            for (size_t i = 0; i < n; ++i) {
                const float v = src.pixels[i * src.channels + sc];
                out.pixels[i * nch + ch] = inv ? 1.f - v : v;
            }
        };
        if (c.kind == ChannelSpec::Kind::constant || c.kind == ChannelSpec::Kind::unused) {
            fill(dst++, c.kind == ChannelSpec::Kind::constant ? c.value : 0.f);
            continue;
        }
        const auto it = planes.find(c.role);
        if (c.key == "RGB") {
            if (it == planes.end()) {  // default color or flat normal
                for (int k = 0; k < 3; ++k) fill(dst + k, default_rgb(c, k, o, preset, color));
            } else if (c.role == Role::normal) {
                const Image enc = encode_normal(plane_floats(c.role, it->second), preset.normal_convention);
                for (int k = 0; k < 3; ++k) copy(dst + k, enc, k, false);
            } else {
                Image rgb = plane_floats(c.role, it->second);
                color.convert(rgb, it->second.encoding, o.srgb ? ColorEncoding::srgb : ColorEncoding::linear);
                for (int k = 0; k < 3; ++k) copy(dst + k, rgb, k, false);
            }
            dst += 3;
            continue;
        }
        if (it == planes.end()) {
            fill(dst++, default_scalar(c, preset));
        } else if (it->second.is_codes()) {
            copy(dst++, to_float(it->second.codes), 0, c.kind == ChannelSpec::Kind::smoothness);
        } else {
            copy(dst++, it->second.image, 0, c.kind == ChannelSpec::Kind::smoothness);
        }
    }
    return out;
}

std::optional<Image8> pack_output8(const OutputSpec& o, const Planes& planes, const Preset& preset, Size size,
                                   const ColorContext& color) {
    if (o.bit_depth != 8) return std::nullopt;
    const auto channels = effective_channels(o, planes);
    for (const auto& c : channels) {
        const auto it = planes.find(c.role);
        if (c.kind == ChannelSpec::Kind::constant || c.kind == ChannelSpec::Kind::unused || it == planes.end()) continue;
        const RolePlane& p = it->second;
        if (!p.is_codes() || p.width() != size.width || p.height() != size.height) return std::nullopt;
        // Color codes are sRGB-encoded: only an sRGB output takes them as they are.
        if (c.key == "RGB" && c.role != Role::normal && p.encoding != (o.srgb ? ColorEncoding::srgb : ColorEncoding::linear))
            return std::nullopt;
    }
    const int nch = channel_count(channels);
    Image8 out(size.width, size.height, nch);
    const size_t n = static_cast<size_t>(size.width) * size.height;
    int dst = 0;
    for (const auto& c : channels) {
        auto fill = [&](int ch, float v) {
            const uint8_t k = quantize8(v);
            for (size_t i = 0; i < n; ++i) out.pixels[i * nch + ch] = k;
        };
        auto copy = [&](int ch, const Image8& src, int sc, bool inv) {
            const uint8_t x = inv ? 255 : 0;  // 255 - k == 255 ^ k for a byte
            for (size_t i = 0; i < n; ++i) out.pixels[i * nch + ch] = src.pixels[i * src.channels + sc] ^ x;
        };
        if (c.kind == ChannelSpec::Kind::constant || c.kind == ChannelSpec::Kind::unused) {
            fill(dst++, c.kind == ChannelSpec::Kind::constant ? c.value : 0.f);
            continue;
        }
        const auto it = planes.find(c.role);
        if (c.key == "RGB") {
            if (it == planes.end()) {
                for (int k = 0; k < 3; ++k) fill(dst + k, default_rgb(c, k, o, preset, color));
            } else if (c.role == Role::normal) {
                // Decode, convert the convention and encode each texel as the float path does.
                const Image8& enc = it->second.codes;
                const std::array<float, 256>& unorm = unorm8_values();
                const float from = ysign_of(it->second.codes_convention), to = ysign_of(preset.normal_convention);
                const int ec = enc.channels;
                for (size_t i = 0; i < n; ++i) {
                    float e[3] = {0.f, 0.f, 0.f};
                    for (int k = 0; k < std::min(ec, 3); ++k) e[k] = unorm[enc.pixels[i * ec + static_cast<size_t>(k)]];
                    bool bad = false;
                    const Texel t = encode_texel(decode_texel(e, ec, from, bad), to);
                    uint8_t* px = &out.pixels[i * nch + dst];
                    px[0] = quantize8(t.x), px[1] = quantize8(t.y), px[2] = quantize8(t.z);
                }
            } else {
                for (int k = 0; k < 3; ++k) copy(dst + k, it->second.codes, k, false);
            }
            dst += 3;
            continue;
        }
        if (it == planes.end()) fill(dst++, default_scalar(c, preset));
        else copy(dst++, it->second.codes, 0, c.kind == ChannelSpec::Kind::smoothness);
    }
    return out;
}

}  // namespace mf
