#include "process/material_file.hpp"

#include <algorithm>

#include "core/files.hpp"
#include "findings/catalog.hpp"
#include "gltf/gltf.hpp"
#include "mtlx/mtlx.hpp"
#include "texture/texture.hpp"
#include "usd/usd.hpp"

namespace mf {
namespace {

std::span<const unsigned char> bytes_of(const std::string& s) {
    return {reinterpret_cast<const unsigned char*>(s.data()), s.size()};
}

bool write_pair(const gltf::Files& files, const std::string& gltf_rel, const std::string& bin_rel,
                const WriteFile& write, std::vector<manifest::MaterialFile>& recorded, std::string& error) {
    // The buffer first: a .gltf is never there without the buffer it names.
    if (!write(bin_rel, files.bin, error) || !write(gltf_rel, bytes_of(files.gltf), error)) return false;
    recorded.push_back({gltf_rel, "gltf", sha256_hex(bytes_of(files.gltf))});
    recorded.push_back({bin_rel, "bin", sha256_hex(files.bin)});
    return true;
}

}  // namespace

void write_material_files(const Preset& preset, const Planes& planes, const WriteFile& write, manifest::Material& m) {
    if (preset.material_file != MaterialFileKind::gltf) return;
    const std::string gltf_rel = m.name + "/" + m.name + ".gltf", bin_rel = m.name + "/" + m.name + ".bin";
    // --normal-convention dx: the PNGs as asked, but no glTF (its normal textures are +Y).
    for (const auto& o : m.outputs)
        if (o.normal_convention && *o.normal_convention != NormalConvention::gl) {
            m.findings.push_back(finding(code::material_file_skipped, "normal", "",
                                         gltf_rel +
                                             " not written: glTF normal textures are +Y (gl) and this run writes " +
                                             std::string(convention_name(*o.normal_convention)) +
                                             " normals (--normal-convention)",
                                         {{"normal_convention", std::string(convention_name(*o.normal_convention))}}));
            return;
        }
    gltf::MaterialOptions opt;
    opt.alpha_cutoff = preset.alpha_cutoff;
    opt.emissive_strength = m.emissive_strength;
    if (const auto it = planes.find(Role::opacity); it != planes.end()) {
        switch (texture::classify_opacity(plane_floats(Role::opacity, it->second))) {
            case texture::AlphaUse::opaque: opt.alpha_mode = gltf::AlphaMode::opaque; break;
            case texture::AlphaUse::cutout: opt.alpha_mode = gltf::AlphaMode::mask; break;
            case texture::AlphaUse::blend: opt.alpha_mode = gltf::AlphaMode::blend; break;
        }
    }
    gltf::Files files;
    std::string error;
    if (!gltf::material_gltf(m, gltf_rel, m.name + ".bin", opt, files, error) ||
        !write_pair(files, gltf_rel, bin_rel, write, m.material_files, error)) {
        m.findings.push_back(finding(code::output_write_failed, "", "", gltf_rel + ": " + error));
        m.status = manifest::Status::partial;
        return;
    }
    // The same material for DCCs: MaterialX (gltf_pbr, the glTF's own model) and USD
    // (UsdPreviewSurface), each beside the glTF.
    const std::string stem = m.name + "/" + m.name;
    const std::pair<std::string, std::string> more[] = {
        {"mtlx", mtlx::material_mtlx(m, stem + ".mtlx", opt)},
        {"usda", usd::material_usda(m, stem + ".usda", opt)},
    };
    for (const auto& [format, text] : more) {
        const std::string rel = stem + "." + format;
        if (!write(rel, bytes_of(text), error)) {
            m.findings.push_back(finding(code::output_write_failed, "", "", rel + ": " + error));
            m.status = manifest::Status::partial;
            return;
        }
        m.material_files.push_back({rel, format, sha256_hex(bytes_of(text))});
    }
}

bool write_library(const std::vector<manifest::MaterialSpool::Entry>& materials, const std::filesystem::path& out_dir,
                   const WriteFile& write, const WriteStream& write_stream,
                   std::vector<manifest::MaterialFile>& library, std::string& error) {
    std::vector<gltf::LibraryItem> items;
    for (const auto& m : materials)
        if (!m.gltf.empty()) items.push_back({m.name, m.gltf});
    if (items.empty()) return true;
    const auto text = gltf::library_gltf(items, out_dir, error);
    if (!text) return false;
    // The buffer first: a .gltf is never there without the buffer it names.
    const std::vector<uint8_t>& bin = gltf::sphere_buffer();
    Sha256 sha;
    const bool ok = write("library.bin", bin, error) && write_stream(
                                                            "library.gltf",
                                                            [&](const ByteSink& sink) {
                                                                return (*text)([&](std::string_view piece) {
                                                                    sha.update(piece);
                                                                    return sink(piece);
                                                                });
                                                            },
                                                            error);
    if (!ok) {
        error = "library.gltf: " + error;
        return false;
    }
    library.push_back({"library.gltf", "gltf", sha.hex()});
    library.push_back({"library.bin", "bin", sha256_hex(bin)});
    // library.usda: every material's layer, which write_material_files writes beside its .gltf
    // under the same stem.
    std::vector<usd::LibraryItem> layers;
    layers.reserve(items.size());
    for (const auto& it : items)
        layers.push_back({it.name, std::filesystem::path(it.gltf_file).replace_extension(".usda").generic_string()});
    Sha256 usda_sha;
    if (!write_stream(
            "library.usda",
            [&](const ByteSink& sink) {
                return usd::library_usda(layers, [&](std::string_view piece) {
                    usda_sha.update(piece);
                    return sink(piece);
                });
            },
            error)) {
        error = "library.usda: " + error;
        return false;
    }
    library.push_back({"library.usda", "usda", usda_sha.hex()});
    return true;
}

}  // namespace mf
