// The interactive view on each card (`matforge report --viewer`): the material on a sphere, a
// plane or the shaderball under the look-dev lighting of `matforge preview`, turned by dragging,
// in WebGL2, from the page on disk with no network and no external script. Drawn by the
// renderer's own shaders: shade.vert, shade.frag and the output transform (output.glsl), compiled
// to SPIR-V by glslc and translated to ESSL 3.00 by spirv-cross when matforge is built
// (cmake/WebglShader.cmake); with the renderer's own variant and uniform block of each material,
// its BRDF table and prefiltered studio environment and its meshes, read from look-dev renderers
// on this machine (render.hpp, "Export"): nothing of the shading is written twice.
//
// Files beside index.html (loaded by a <script> element when a card's view is opened: a page
// from file:// may not fetch):
//   viewer/lookdev.js   once: the viewer's script (viewer/viewer.js), the shaders, the lighting
//                       (half floats) and the meshes
//   <stem>/viewer.js    per material: its textures as PNG, at most kViewerTextureSize on a side,
//                       and its variant and uniform block for each shape
// Internal to lib/report.
#pragma once
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "manifest/manifest.hpp"

namespace mf::report {

struct Options;

// The longest side of a texture in a view: the renderer's mip of a map that fits.
inline constexpr int kViewerTextureSize = 512;

// What a card says of its view.
struct ViewerCard {
    std::string script;  // <stem>/viewer.js, relative to index.html
    uint64_t bytes = 0;  // its size
};

class Viewer {
public:
    // The look-dev renderers (a GPU, else lavapipe) and viewer/lookdev.js under options.out. The
    // view is as large as the first preview found in options.previews (the still it turns), else
    // 512². nullptr + `error` when there is no Vulkan device or a file cannot be written.
    static std::unique_ptr<Viewer> create(const Options& options, const manifest::Manifest& m, std::string& error);
    ~Viewer();
    Viewer(const Viewer&) = delete;
    Viewer& operator=(const Viewer&) = delete;

    // Writes <stem>/viewer.js for one material (its outputs read as `matforge preview` reads
    // them). Safe to call from several threads. nullopt, and "name: why" in `problems`, when it
    // cannot be shown.
    std::optional<ViewerCard> material(const manifest::Material& m, const std::filesystem::path& manifest_dir,
                                       const std::string& stem, std::vector<std::string>& problems) const;

    // The card's part: a button (shown by the page's script) that opens the view in place.
    static std::string card_html(const ViewerCard& card, const std::string& stem);
    // Says in the page, after <main>, how large index.html and the views' data are (index.html's
    // own size included: the note is counted in it).
    void state_sizes(std::string& html) const;

private:
    struct Impl;
    explicit Viewer(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
};

}  // namespace mf::report
