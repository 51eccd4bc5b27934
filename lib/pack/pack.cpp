#include "pack/pack.hpp"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <algorithm>
#include <cmath>

namespace mf {

Image extract_channel(const Image& src, int channel) {
    Image out(src.width, src.height, 1);
    const int c = std::min(channel, src.channels - 1);
    for (size_t i = 0, n = out.pixels.size(); i < n; ++i) out.pixels[i] = src.pixels[i * src.channels + c];
    return out;
}

Image to_rgb(const Image& src) {
    if (src.channels == 3) return src;
    Image out(src.width, src.height, 3);
    const size_t n = static_cast<size_t>(src.width) * src.height;
    for (size_t i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c)
            out.pixels[i * 3 + c] = src.pixels[i * src.channels + (src.channels >= 3 ? c : 0)];
    return out;
}

void invert(Image& img) {
    for (float& v : img.pixels) v = 1.f - v;
}

double decode_normal(const Image& enc, NormalConvention from, Image& out) {
    out = Image(enc.width, enc.height, 3);
    const size_t n = static_cast<size_t>(enc.width) * enc.height;
    const float ysign = from == NormalConvention::dx ? -1.f : 1.f;
    size_t bad = 0;
    for (size_t i = 0; i < n; ++i) {
        const float* e = &enc.pixels[i * enc.channels];
        float x = e[0] * 2.f - 1.f;
        float y = (enc.channels > 1 ? e[1] : 0.5f) * 2.f - 1.f;
        float z;
        if (enc.channels >= 3) {
            z = e[2] * 2.f - 1.f;
        } else {  // two-channel (BC5-style) normals: Z from unit length
            z = std::sqrt(std::max(0.f, 1.f - x * x - y * y));
        }
        const float len = std::sqrt(x * x + y * y + z * z);
        if (!(std::abs(len - 1.f) <= 0.2f) || z < 0.f) ++bad;
        if (!(len > 1e-6f) || !std::isfinite(len)) {
            x = 0.f, y = 0.f, z = 1.f;
        } else {
            x /= len, y /= len, z /= len;
        }
        out.pixels[i * 3 + 0] = x;
        out.pixels[i * 3 + 1] = y * ysign;
        out.pixels[i * 3 + 2] = z;
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
    const float ysign = to == NormalConvention::dx ? -1.f : 1.f;
    for (size_t i = 0, count = static_cast<size_t>(n.width) * n.height; i < count; ++i) {
        float x = n.pixels[i * 3], y = n.pixels[i * 3 + 1], z = n.pixels[i * 3 + 2];
        const float len = std::sqrt(x * x + y * y + z * z);
        if (len > 1e-6f && std::isfinite(len)) {
            x /= len, y /= len, z /= len;
        } else {
            x = 0.f, y = 0.f, z = 1.f;
        }
        out.pixels[i * 3 + 0] = x * 0.5f + 0.5f;
        out.pixels[i * 3 + 1] = y * ysign * 0.5f + 0.5f;
        out.pixels[i * 3 + 2] = z * 0.5f + 0.5f;
    }
    return out;
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
    if (plane.image.width == w && plane.image.height == h) return;
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
        s.width = std::max(s.width, it->second.image.width);
        s.height = std::max(s.height, it->second.image.height);
    }
    if (s.width == 0) return {preset.constant_size, preset.constant_size};
    if (preset.max_size > 0 && std::max(s.width, s.height) > preset.max_size) {
        const double k = static_cast<double>(preset.max_size) / std::max(s.width, s.height);
        s.width = std::max(1, static_cast<int>(std::lround(s.width * k)));
        s.height = std::max(1, static_cast<int>(std::lround(s.height * k)));
    }
    return s;
}

Image pack_output(const OutputSpec& o, const Planes& planes, const Preset& preset, Size size,
                  const ColorContext& color) {
    const auto channels = effective_channels(o, planes);
    int nch = 0;
    for (const auto& c : channels) nch += c.key == "RGB" ? 3 : 1;
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
                const std::array<float, 3> def = c.role == Role::normal ? std::array<float, 3>{0.5f, 0.5f, 1.f}
                                                 : c.role == Role::albedo ? preset.default_albedo
                                                                          : std::array<float, 3>{0.f, 0.f, 0.f};
                for (int k = 0; k < 3; ++k) {
                    float v = def[static_cast<size_t>(k)];
                    if (o.srgb && c.role != Role::normal) {
                        float rgb[3] = {v, v, v};
                        color.convert(rgb, 1, ColorEncoding::linear, ColorEncoding::srgb);
                        v = rgb[0];
                    }
                    fill(dst + k, v);
                }
            } else if (c.role == Role::normal) {
                const Image enc = encode_normal(it->second.image, preset.normal_convention);
                for (int k = 0; k < 3; ++k) copy(dst + k, enc, k, false);
            } else {
                Image rgb = it->second.image;
                color.convert(rgb, it->second.encoding, o.srgb ? ColorEncoding::srgb : ColorEncoding::linear);
                for (int k = 0; k < 3; ++k) copy(dst + k, rgb, k, false);
            }
            dst += 3;
            continue;
        }
        const bool inv = c.kind == ChannelSpec::Kind::smoothness;
        if (it == planes.end()) {
            const float v = preset.default_value(c.role);
            fill(dst++, inv ? 1.f - v : v);
        } else {
            copy(dst++, it->second.image, 0, inv);
        }
    }
    return out;
}

}  // namespace mf
