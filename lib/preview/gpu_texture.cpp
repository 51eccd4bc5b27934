// GPU texture files (DDS, KTX2) -> renderer textures: the preview renders what ingest wrote, the
// same blocks and mip chain an engine samples, not the PNG they came from. Where the device
// cannot sample the format (ASTC on a desktop GPU, BCn on a mobile one), level 0 is decoded
// here with the codec that wrote it and uploaded as 8-bit codes (the renderer builds its mips).
#include "core/files.hpp"
#include "preview/preview.hpp"
#include "texture/texture.hpp"

namespace mf::preview {

std::optional<render::Texture> read_gpu_texture(const std::filesystem::path& file, const BlockSupport& samples,
                                                std::vector<std::string>& notes, std::string& error) {
    std::vector<uint8_t> bytes;
    if (!read_file(file, bytes, error)) return std::nullopt;
    texture::GpuTexture gt;
    if (!texture::read_gpu_texture(bytes, gt, error)) {
        error = file.string() + ": " + error;
        return std::nullopt;
    }
    render::Texture t;
    t.width = static_cast<uint32_t>(gt.levels[0].width);
    t.height = static_cast<uint32_t>(gt.levels[0].height);
    t.channels = static_cast<uint32_t>(gt.format->channels);
    const uint32_t vk = texture::vk_format(gt);
    if (samples && samples(vk)) {
        t.block_format = vk;
        for (auto& l : gt.levels) t.block_levels.push_back(std::move(l.data));
        return t;
    }
    Image8 rgba;
    if (!texture::decode_top_level(gt, 4, false, rgba, error)) {
        error = file.string() + ": " + error;
        return std::nullopt;
    }
    notes.push_back(file.filename().string() + ": this device does not sample " + std::string(gt.format->name) +
                    "; decoded on the CPU and its mips averaged again");
    t.channels = static_cast<uint32_t>(rgba.channels);
    t.type = render::TexelType::u8;
    t.data = std::move(rgba.pixels);
    return t;
}

}  // namespace mf::preview
