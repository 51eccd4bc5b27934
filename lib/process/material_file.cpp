#include "process/material_file.hpp"

#include <algorithm>

#include "core/files.hpp"
#include "engine/engine.hpp"
#include "engine/gltf.hpp"
#include "engine/mtlx.hpp"
#include "engine/usd.hpp"
#include "findings/catalog.hpp"
#include "manifest/attribution.hpp"
#include "texture/texture.hpp"

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

void decide_alpha(const Preset& preset, const Planes& planes, manifest::Material& m) {
    const auto it = planes.find(Role::opacity);
    const bool carried = std::any_of(m.outputs.begin(), m.outputs.end(), [](const manifest::Output& o) {
        return std::any_of(o.channels.begin(), o.channels.end(),
                           [](const Channel& c) { return c.kind == Channel::Kind::role && c.role == Role::opacity; });
    });
    if (it == planes.end() || !carried) return;
    using manifest::AlphaMode;
    switch (texture::classify_opacity(plane_floats(Role::opacity, it->second))) {
        case texture::AlphaUse::opaque: m.alpha_mode = AlphaMode::opaque; break;
        case texture::AlphaUse::cutout: m.alpha_mode = AlphaMode::mask; break;
        case texture::AlphaUse::blend: m.alpha_mode = AlphaMode::blend; break;
    }
    m.alpha_cutoff = preset.alpha_cutoff;
}

namespace {

// MATERIAL_FILE_SKIPPED when an output's normals are not `want` (--normal-convention): the
// textures as asked, but no material file that would read them upside down.
bool normals_fit(NormalConvention want, const std::string& file, std::string_view reader, manifest::Material& m) {
    for (const auto& o : m.outputs)
        if (o.normal_convention && *o.normal_convention != want) {
            const std::string got(convention_name(*o.normal_convention));
            m.findings.push_back(finding(code::material_file_skipped, "normal", "",
                                         file + " not written: " + std::string(reader) + " reads " +
                                             std::string(convention_name(want)) + " normals and this run writes " +
                                             got + " normals (--normal-convention)",
                                         {{"normal_convention", got}}));
            return false;
        }
    return true;
}

bool write_text(const WriteFile& write, const std::string& rel, const std::string& format, const std::string& text,
                manifest::Material& m) {
    std::string error;
    if (!write(rel, bytes_of(text), error)) {
        m.findings.push_back(finding(code::output_write_failed, "", "", rel + ": " + error));
        m.status = manifest::Status::partial;
        return false;
    }
    m.material_files.push_back({rel, format, sha256_hex(bytes_of(text))});
    return true;
}

}  // namespace

void write_material_files(const Preset& preset, const WriteFile& write, manifest::Material& m) {
    const EngineMaterial* e = engine_material(preset.material_file);
    if (!e) return;
    if (e->kind != MaterialFileKind::gltf) {
        const auto files = engine::material_files(*e, m);
        if (files.empty() || !normals_fit(e->normal, files.back().file, e->engine, m)) return;
        for (const engine::File& f : files)
            if (!write_text(write, f.file, f.format, f.text, m)) return;
        return;
    }
    const std::string gltf_rel = m.name + "/" + m.name + ".gltf", bin_rel = m.name + "/" + m.name + ".bin";
    if (!normals_fit(e->normal, gltf_rel, "glTF", m)) return;
    gltf::Files files;
    std::string error;
    if (!gltf::material_gltf(m, gltf_rel, m.name + ".bin", files, error) ||
        !write_pair(files, gltf_rel, bin_rel, write, m.material_files, error)) {
        m.findings.push_back(finding(code::output_write_failed, "", "", gltf_rel + ": " + error));
        m.status = manifest::Status::partial;
        return;
    }
    // The same material for DCCs: MaterialX (gltf_pbr, the glTF's own model) and USD
    // (UsdPreviewSurface), each beside the glTF.
    const std::string stem = m.name + "/" + m.name;
    if (write_text(write, stem + ".mtlx", "mtlx", mtlx::material_mtlx(m, stem + ".mtlx"), m))
        write_text(write, stem + ".usda", "usda", usd::material_usda(m, stem + ".usda"), m);
}

bool write_folder_files(const Preset& preset, const WriteFile& write, std::vector<manifest::MaterialFile>& library,
                        std::string& error) {
    const EngineMaterial* e = engine_material(preset.material_file);
    if (!e) return true;
    for (const engine::File& f : engine::folder_files(*e)) {
        if (!write(f.file, bytes_of(f.text), error)) {
            error = f.file + ": " + error;
            return false;
        }
        library.push_back({f.file, f.format, sha256_hex(bytes_of(f.text))});
    }
    return true;
}

bool write_library(const manifest::MaterialSpool& spool, const std::filesystem::path& out_dir, const WriteFile& write,
                   const WriteStream& write_stream, std::vector<manifest::MaterialFile>& library, std::string& error) {
    // Each library file made as it is written, hashed on the way, then listed.
    std::string read_error;  // a material that could not be read back from the spool
    const auto stream = [&](const std::string& rel, const char* format, const ByteProducer& produce) {
        Sha256 sha;
        const bool ok = write_stream(
            rel,
            [&](const ByteSink& sink) {
                return produce([&](std::string_view piece) {
                    sha.update(piece);
                    return sink(piece);
                });
            },
            error);
        if (!ok) {
            error = rel + ": " + (read_error.empty() ? error : read_error);
            return false;
        }
        library.push_back({rel, format, sha.hex()});
        return true;
    };
    // Every preset's folder: every material's source and licence (manifest/attribution.hpp).
    if (!stream(std::string(manifest::kAttributionFile), "md",
                [&](const ByteSink& sink) { return manifest::attribution_text(spool, sink, read_error); }))
        return false;
    std::vector<gltf::LibraryItem> items;
    for (const auto& m : spool.entries())
        if (!m.gltf.empty()) items.push_back({m.name, m.gltf});
    if (items.empty()) return true;
    const auto text = gltf::library_gltf(items, out_dir, error);
    if (!text) return false;
    // The buffer first: a .gltf is never there without the buffer it names.
    const std::vector<uint8_t>& bin = gltf::sphere_buffer();
    if (!write("library.bin", bin, error)) {
        error = "library.gltf: " + error;
        return false;
    }
    if (!stream("library.gltf", "gltf", *text)) return false;
    library.push_back({"library.bin", "bin", sha256_hex(bin)});
    // library.usda: every material's layer, which write_material_files writes beside its .gltf
    // under the same stem.
    std::vector<usd::LibraryItem> layers;
    layers.reserve(items.size());
    for (const auto& it : items)
        layers.push_back({it.name, std::filesystem::path(it.gltf_file).replace_extension(".usda").generic_string()});
    if (!stream("library.usda", "usda", [&](const ByteSink& sink) { return usd::library_usda(layers, sink); }))
        return false;
    // library.mtlx: every material's MaterialX elements again, read back from the spool one at a
    // time (those with a .gltf have a .mtlx beside it).
    const auto materials = [&](const mtlx::MaterialVisitor& visit) {
        return spool.for_each(
            [&](manifest::Material&& m) {
                const bool has = std::any_of(m.material_files.begin(), m.material_files.end(),
                                             [](const manifest::MaterialFile& f) { return f.format == "mtlx"; });
                return !has || visit(m);
            },
            read_error);
    };
    return stream("library.mtlx", "mtlx",
                  [&](const ByteSink& sink) { return mtlx::library_mtlx(materials, sink, read_error); });
}

}  // namespace mf
