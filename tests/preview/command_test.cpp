// The contact sheet (the command end to end is tests/cli/preview_cli_test.cpp).
#include <gtest/gtest.h>

#include "preview/preview.hpp"

namespace mf::preview {
namespace {

TEST(ContactSheet, TilesAndLabels) {
    std::vector<SheetTile> tiles;
    for (const char* name : {"Bricks059", "MetalPlates013", "a_very_long_material_name_that_overflows"})
        tiles.push_back({name, 64, 64, std::vector<uint8_t>(64 * 64 * 4, 255)});
    uint32_t w = 0, h = 0;
    std::vector<uint8_t> sheet;
    compose_contact_sheet(tiles, w, h, sheet);
    EXPECT_EQ(w, 2 * 64 + 3 * 8u);  // 2 columns for 3 tiles
    EXPECT_EQ(h % 2, 0u);
    // Some label pixels are lit below the first tile.
    size_t lit = 0;
    for (uint32_t y = 8 + 64; y < 8 + 64 + 16; ++y)
        for (uint32_t x = 8; x < 8 + 64; ++x) lit += sheet[(size_t{y} * w + x) * 4] > 200;
    EXPECT_GT(lit, 20u);
    EXPECT_EQ(text_width("abc", 2), 36);
}

}  // namespace
}  // namespace mf::preview
