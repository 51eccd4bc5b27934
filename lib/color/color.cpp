#include "color/color.hpp"

#include <OpenColorIO/OpenColorIO.h>

#include <array>
#include <cstdlib>
#include <sstream>

namespace OCIO = OCIO_NAMESPACE;

namespace mf {
namespace {

// Generated from ocio/config.ocio by CMake.
#include "ocio_config_embedded.inc"

class OcioContext final : public ColorContext {
public:
    OcioContext(OCIO::ConstConfigRcPtr config, std::string origin, std::string linear, std::string srgb)
        : config_(std::move(config)), origin_(std::move(origin)), linear_(std::move(linear)), srgb_(std::move(srgb)) {
        // Lossless optimization: the default bakes a LUT for 8-bit inputs; we run float inputs
        // and want the analytic curve (error vs speed is measured in bench/).
        to_linear_ = config_->getProcessor(srgb_.c_str(), linear_.c_str())
                         ->getOptimizedCPUProcessor(OCIO::BIT_DEPTH_F32, OCIO::BIT_DEPTH_F32,
                                                    OCIO::OPTIMIZATION_LOSSLESS);
        to_srgb_ = config_->getProcessor(linear_.c_str(), srgb_.c_str())
                       ->getOptimizedCPUProcessor(OCIO::BIT_DEPTH_F32, OCIO::BIT_DEPTH_F32,
                                                  OCIO::OPTIMIZATION_LOSSLESS);
        if (!to_linear_->hasChannelCrosstalk()) {
            // Code k as a grey pixel (R = G = B): with no crosstalk each channel's result is
            // that of its own value, whatever the others hold.
            const std::array<float, 256>& unorm = unorm8_values();
            std::vector<float> rgb(256 * 3);
            for (size_t k = 0; k < 256; ++k) rgb[k * 3] = rgb[k * 3 + 1] = rgb[k * 3 + 2] = unorm[k];
            OCIO::PackedImageDesc desc(rgb.data(), 256, 1, 3);
            to_linear_->apply(desc);
            codes_to_linear_.resize(256);
            for (size_t k = 0; k < 256; ++k) codes_to_linear_[k] = rgb[k * 3];
        }
    }

    const std::vector<float>& srgb_codes_to_linear() const override { return codes_to_linear_; }

    void convert(Image& img, ColorEncoding from, ColorEncoding to) const override {
        if (from == to || img.empty()) return;
        const auto& proc = to == ColorEncoding::linear ? to_linear_ : to_srgb_;
        if (img.channels >= 3) {
            OCIO::PackedImageDesc desc(img.pixels.data(), img.width, img.height, img.channels);
            proc->apply(desc);
            return;
        }
        // Grey: run each sample as an R=G=B triple, keep R.
        for (size_t i = 0; i < img.pixels.size(); i += static_cast<size_t>(img.channels)) {
            float rgb[3] = {img.pixels[i], img.pixels[i], img.pixels[i]};
            proc->applyRGB(rgb);
            img.pixels[i] = rgb[0];
        }
    }

    void convert(float* rgb, size_t pixels, ColorEncoding from, ColorEncoding to) const override {
        if (from == to || pixels == 0) return;
        const auto& proc = to == ColorEncoding::linear ? to_linear_ : to_srgb_;
        OCIO::PackedImageDesc desc(rgb, static_cast<long>(pixels), 1, 3);
        proc->apply(desc);
    }

    std::string cache_id() const override {
        return std::string("OpenColorIO ") + OCIO::GetVersion() + "|" + config_->getCacheID() + "|" + linear_ + "|" +
               srgb_;
    }
    std::string description() const override { return origin_ + " (linear: " + linear_ + ", sRGB: " + srgb_ + ")"; }

private:
    OCIO::ConstConfigRcPtr config_;
    std::string origin_, linear_, srgb_;
    OCIO::ConstCPUProcessorRcPtr to_linear_, to_srgb_;
    std::vector<float> codes_to_linear_;  // 256 entries, or empty (crosstalk)
};

// The sRGB texture space in a user's config: our alias, then names common configs use.
std::string find_srgb_space(const OCIO::ConstConfigRcPtr& config) {
    for (const char* name :
         {"srgb_texture", "sRGB - Texture", "Utility - sRGB - Texture", "sRGB Encoded Rec.709 (sRGB)", "sRGB"}) {
        if (config->getColorSpace(name)) return name;
    }
    return {};
}

}  // namespace

std::shared_ptr<const ColorContext> ColorContext::create(std::string& error) {
    std::string origin = "built-in config";
    try {
        OCIO::ConstConfigRcPtr config;
        const char* env = std::getenv("OCIO");
        if (env && *env) {
            config = OCIO::Config::CreateFromFile(env);
            origin = std::string("$OCIO=") + env;
        } else {
            std::istringstream in(kEmbeddedOcioConfig);
            config = OCIO::Config::CreateFromStream(in);
        }
        config->validate();
        const char* linear = config->getColorSpace(OCIO::ROLE_SCENE_LINEAR)
                                 ? config->getColorSpace(OCIO::ROLE_SCENE_LINEAR)->getName()
                                 : nullptr;
        const std::string srgb = find_srgb_space(config);
        if (!linear || srgb.empty()) {
            error = "OpenColorIO config " + origin +
                    " lacks a scene_linear role or an sRGB texture color space (srgb_texture)";
            return nullptr;
        }
        return std::make_shared<OcioContext>(config, origin, linear, srgb);
    } catch (const OCIO::Exception& e) {
        error = "OpenColorIO config " + origin + ": " + e.what();
        return nullptr;
    }
}

std::string color_library_version() { return std::string("OpenColorIO ") + OCIO::GetVersion(); }

}  // namespace mf
