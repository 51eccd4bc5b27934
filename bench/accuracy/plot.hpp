// A log-log scatter/line plot drawn into an mf::Image (no plotting package): axes with decade
// ticks, one coloured curve with its own marker per series, a legend, all text in a 5×7
// bitmap font of our own.
#pragma once
#include <array>
#include <string>
#include <vector>

#include "image/image.hpp"

namespace mf::bench {

struct PlotPoint {
    double x = 0, y = 0;  // > 0 (log axes); y ≤ 0 is drawn at the floor of the axis
    std::string tag;      // short label drawn beside the marker (may be empty)
};

struct PlotSeries {
    std::string name;
    std::vector<PlotPoint> points;  // joined in the given order
};

struct PlotSpec {
    std::string title, x_label, y_label;
    std::string legend = "KNOB";  // the legend's heading
    int width = 1700, height = 1000;
    double y_floor = 1e-4;  // smallest y shown; smaller values sit on this line
};

Image draw_plot(const PlotSpec& spec, const std::vector<PlotSeries>& series);

// Text in the built-in font (upper case; lower case is drawn as upper case). `scale` ≥ 1.
void draw_text(Image& img, int x, int y, const std::string& text, std::array<float, 3> color, int scale = 1);
int text_width(const std::string& text, int scale = 1);

}  // namespace mf::bench
