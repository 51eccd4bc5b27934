// One material's card and contact-sheet tile on the report page, as HTML, from its manifest
// entry and the pictures report.cpp wrote for it; and the page's fixed style and script. Pure:
// nothing here reads or writes a file. Internal to lib/report.
#pragma once
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "manifest/manifest.hpp"
#include "report/images.hpp"
#include "report/viewer.hpp"

namespace mf::report {

// One picture written beside index.html.
struct Pic {
    std::string rel;  // relative to index.html
    int width = 0, height = 0;
};

// An output's pictures: the whole, each channel as grey, or why it is not shown.
struct OutputPics {
    Pic main;
    std::vector<std::pair<std::string, Pic>> channels;  // key -> grey picture
    std::string problem;
};

// Everything a card shows that is not in the manifest.
struct MaterialPictures {
    std::optional<Pic> preview, compare_preview;  // `matforge preview`'s images (--previews, --compare-previews)
    std::optional<Pic> sheet;                     // the contact sheet's tile when there is no preview: the albedo
    std::optional<Pic> albedo, metalness;         // the overlays
    std::vector<OutputPics> outputs, compare;     // per manifest output (and --compare's)
    std::vector<Pic> sources;                     // per input; rel empty: not shown
    std::optional<ViewerCard> viewer;             // the interactive view (--viewer)
    AlbedoStats albedo_stats;
    MetalnessStats metal_stats;
};

struct CardInput {
    const manifest::Material& material;
    const MaterialPictures& pictures;
    const rules::Thresholds& thresholds;  // the overlays' (the run's)
    const std::string& stem;              // the material's folder (material_stems)
    size_t index;                         // its place on the page
    const manifest::Material* other;      // --compare's entry of the same name, or null
    const std::string& other_preset;
};

struct CardHtml {
    std::string card, tile;
};
CardHtml write_card(const CardInput& in);

// <img> of a picture (lazy, its size given, `alt` escaped).
std::string img(const Pic& p, const std::string& alt, const std::string& cls = "");
// 0 for R (and RGB), 1 G, 2 B, 3 A.
int channel_index(const std::string& key);

extern const char* const kStyle;   // the page's style sheet
extern const char* const kScript;  // paging and filtering; without it every card is shown
std::string pager_html();

}  // namespace mf::report
