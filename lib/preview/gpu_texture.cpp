// GPU texture files (DDS, KTX2) -> renderer textures: the preview renders what ingest wrote, the
// same blocks and mip chain an engine samples, not the PNG they came from. Where the blocks are
// decoded here (a CPU device, a device without the format: BlockUse), every level is decoded with
// the codec that wrote it, so the chain sampled is still the file's.
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
    const BlockUse use = samples ? samples(vk) : BlockUse::as_written;
    if (use == BlockUse::as_written) {
        t.block_format = vk;
        for (auto& l : gt.levels) t.block_levels.push_back(std::move(l.data));
        return t;
    }
    if (use == BlockUse::top_level) {
        Image8 rgba;
        if (!texture::decode_top_level(gt, 4, false, rgba, error)) {
            error = file.string() + ": " + error;
            return std::nullopt;
        }
        t.channels = static_cast<uint32_t>(rgba.channels);
        t.type = render::TexelType::u8;
        t.data = std::move(rgba.pixels);
        return t;
    }
    texture::CodecOptions co;
    co.format = gt.format;
    co.srgb = gt.srgb;
    for (texture::Level& l : gt.levels) {
        Image8 rgba;
        if (!texture::decode_level(l.data, l.width, l.height, co, rgba, error)) {
            error = file.string() + ": " + error;
            return std::nullopt;
        }
        l.data.clear();
        l.data.shrink_to_fit();
        t.block_levels.push_back(std::move(rgba.pixels));
    }
    t.block_format = render::kDecodedLevels;
    if (use == BlockUse::decoded_absent)
        notes.push_back(file.filename().string() + ": this device does not sample " + std::string(gt.format->name) +
                        "; decoded on the CPU, every level as written");
    return t;
}

}  // namespace mf::preview
