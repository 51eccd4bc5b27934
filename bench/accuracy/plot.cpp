#include "plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <map>

namespace mf::bench {
namespace {

// 5×7 glyphs, one byte per row, bit 4 = leftmost column (the classic HD44780 shapes).
const std::map<char, std::array<uint8_t, 7>>& font() {
    static const std::map<char, std::array<uint8_t, 7>> f = {
        {' ', {0, 0, 0, 0, 0, 0, 0}},
        {'0', {0x0E, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0E}},
        {'1', {0x04, 0x0C, 0x04, 0x04, 0x04, 0x04, 0x0E}},
        {'2', {0x0E, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1F}},
        {'3', {0x1F, 0x02, 0x04, 0x02, 0x01, 0x11, 0x0E}},
        {'4', {0x02, 0x06, 0x0A, 0x12, 0x1F, 0x02, 0x02}},
        {'5', {0x1F, 0x10, 0x1E, 0x01, 0x01, 0x11, 0x0E}},
        {'6', {0x06, 0x08, 0x10, 0x1E, 0x11, 0x11, 0x0E}},
        {'7', {0x1F, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08}},
        {'8', {0x0E, 0x11, 0x11, 0x0E, 0x11, 0x11, 0x0E}},
        {'9', {0x0E, 0x11, 0x11, 0x0F, 0x01, 0x02, 0x0C}},
        {'A', {0x0E, 0x11, 0x11, 0x11, 0x1F, 0x11, 0x11}},
        {'B', {0x1E, 0x11, 0x11, 0x1E, 0x11, 0x11, 0x1E}},
        {'C', {0x0E, 0x11, 0x10, 0x10, 0x10, 0x11, 0x0E}},
        {'D', {0x1C, 0x12, 0x11, 0x11, 0x11, 0x12, 0x1C}},
        {'E', {0x1F, 0x10, 0x10, 0x1E, 0x10, 0x10, 0x1F}},
        {'F', {0x1F, 0x10, 0x10, 0x1E, 0x10, 0x10, 0x10}},
        {'G', {0x0E, 0x11, 0x10, 0x17, 0x11, 0x11, 0x0F}},
        {'H', {0x11, 0x11, 0x11, 0x1F, 0x11, 0x11, 0x11}},
        {'I', {0x0E, 0x04, 0x04, 0x04, 0x04, 0x04, 0x0E}},
        {'J', {0x07, 0x02, 0x02, 0x02, 0x02, 0x12, 0x0C}},
        {'K', {0x11, 0x12, 0x14, 0x18, 0x14, 0x12, 0x11}},
        {'L', {0x10, 0x10, 0x10, 0x10, 0x10, 0x10, 0x1F}},
        {'M', {0x11, 0x1B, 0x15, 0x15, 0x11, 0x11, 0x11}},
        {'N', {0x11, 0x11, 0x19, 0x15, 0x13, 0x11, 0x11}},
        {'O', {0x0E, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0E}},
        {'P', {0x1E, 0x11, 0x11, 0x1E, 0x10, 0x10, 0x10}},
        {'Q', {0x0E, 0x11, 0x11, 0x11, 0x15, 0x12, 0x0D}},
        {'R', {0x1E, 0x11, 0x11, 0x1E, 0x14, 0x12, 0x11}},
        {'S', {0x0F, 0x10, 0x10, 0x0E, 0x01, 0x01, 0x1E}},
        {'T', {0x1F, 0x04, 0x04, 0x04, 0x04, 0x04, 0x04}},
        {'U', {0x11, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0E}},
        {'V', {0x11, 0x11, 0x11, 0x11, 0x11, 0x0A, 0x04}},
        {'W', {0x11, 0x11, 0x11, 0x15, 0x15, 0x15, 0x0A}},
        {'X', {0x11, 0x11, 0x0A, 0x04, 0x0A, 0x11, 0x11}},
        {'Y', {0x11, 0x11, 0x11, 0x0A, 0x04, 0x04, 0x04}},
        {'Z', {0x1F, 0x01, 0x02, 0x04, 0x08, 0x10, 0x1F}},
        {'.', {0, 0, 0, 0, 0, 0x0C, 0x0C}},
        {',', {0, 0, 0, 0, 0x0C, 0x04, 0x08}},
        {'-', {0, 0, 0, 0x1F, 0, 0, 0}},
        {'+', {0, 0x04, 0x04, 0x1F, 0x04, 0x04, 0}},
        {'/', {0, 0x01, 0x02, 0x04, 0x08, 0x10, 0}},
        {'(', {0x02, 0x04, 0x08, 0x08, 0x08, 0x04, 0x02}},
        {')', {0x08, 0x04, 0x02, 0x02, 0x02, 0x04, 0x08}},
        {'%', {0x18, 0x19, 0x02, 0x04, 0x08, 0x13, 0x03}},
        {':', {0, 0x0C, 0x0C, 0, 0x0C, 0x0C, 0}},
        {'=', {0, 0, 0x1F, 0, 0x1F, 0, 0}},
        {'_', {0, 0, 0, 0, 0, 0, 0x1F}},
        {'^', {0x04, 0x0A, 0x11, 0, 0, 0, 0}},
        {'<', {0x02, 0x04, 0x08, 0x10, 0x08, 0x04, 0x02}},
        {'>', {0x08, 0x04, 0x02, 0x01, 0x02, 0x04, 0x08}},
        {'*', {0, 0x04, 0x15, 0x0E, 0x15, 0x04, 0}},
        {'#', {0x0A, 0x0A, 0x1F, 0x0A, 0x1F, 0x0A, 0x0A}},
        {'?', {0x0E, 0x11, 0x01, 0x02, 0x04, 0, 0x04}},
    };
    return f;
}

void put(Image& img, int x, int y, std::array<float, 3> c) {
    if (x < 0 || y < 0 || x >= img.width || y >= img.height) return;
    for (int k = 0; k < 3; ++k) img.at(x, y, k) = c[static_cast<size_t>(k)];
}

void rect(Image& img, int x0, int y0, int x1, int y1, std::array<float, 3> c) {
    for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) put(img, x, y, c);
}

// Bresenham with a square pen of side `w`.
void line(Image& img, int x0, int y0, int x1, int y1, std::array<float, 3> c, int w = 1, int dash = 0) {
    const int dx = std::abs(x1 - x0), dy = -std::abs(y1 - y0);
    const int sx = x0 < x1 ? 1 : -1, sy = y0 < y1 ? 1 : -1;
    int err = dx + dy, step = 0;
    while (true) {
        if (dash == 0 || (step / dash) % 2 == 0)
            rect(img, x0 - w / 2, y0 - w / 2, x0 + (w - 1) / 2, y0 + (w - 1) / 2, c);
        ++step;
        if (x0 == x1 && y0 == y1) break;
        const int e2 = 2 * err;
        if (e2 >= dy) err += dy, x0 += sx;
        if (e2 <= dx) err += dx, y0 += sy;
    }
}

// Marker shapes, one per series: square, circle, triangle, diamond, cross, ring, …
void marker(Image& img, int cx, int cy, int shape, std::array<float, 3> c) {
    const int r = 5;
    for (int y = -r; y <= r; ++y)
        for (int x = -r; x <= r; ++x) {
            bool on = false;
            switch (shape % 7) {
                case 0: on = std::abs(x) <= r - 1 && std::abs(y) <= r - 1; break;
                case 1: on = x * x + y * y <= r * r; break;
                case 2: on = y >= -r + 1 && 2 * std::abs(x) <= (y + r); break;
                case 3: on = std::abs(x) + std::abs(y) <= r; break;
                case 4: on = std::abs(x - y) <= 1 || std::abs(x + y) <= 1; break;
                case 5: on = x * x + y * y <= r * r && x * x + y * y >= (r - 2) * (r - 2); break;
                case 6: on = std::abs(x) <= 1 || std::abs(y) <= 1; break;
            }
            if (on) put(img, cx + x, cy + y, c);
        }
}

const std::array<float, 3> kPalette[] = {
    {0.12f, 0.47f, 0.71f}, {1.00f, 0.50f, 0.05f}, {0.17f, 0.63f, 0.17f}, {0.84f, 0.15f, 0.16f},
    {0.58f, 0.40f, 0.74f}, {0.55f, 0.34f, 0.29f}, {0.89f, 0.47f, 0.76f}, {0.50f, 0.50f, 0.50f},
    {0.74f, 0.74f, 0.13f}, {0.09f, 0.75f, 0.81f}, {0.00f, 0.00f, 0.00f}, {0.40f, 0.10f, 0.60f},
};

}  // namespace

int text_width(const std::string& text, int scale) { return static_cast<int>(text.size()) * 6 * scale; }

void draw_text(Image& img, int x, int y, const std::string& text, std::array<float, 3> color, int scale) {
    const auto& f = font();
    for (char ch : text) {
        char u = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
        auto it = f.find(u);
        if (it == f.end()) it = f.find('?');
        for (int row = 0; row < 7; ++row)
            for (int col = 0; col < 5; ++col)
                if (it->second[static_cast<size_t>(row)] & (0x10 >> col))
                    rect(img, x + col * scale, y + row * scale, x + col * scale + scale - 1,
                         y + row * scale + scale - 1, color);
        x += 6 * scale;
    }
}

Image draw_plot(const PlotSpec& spec, const std::vector<PlotSeries>& series) {
    Image img(spec.width, spec.height, 3, 1.f);
    const std::array<float, 3> black{0, 0, 0}, grey{0.85f, 0.85f, 0.85f}, dark{0.3f, 0.3f, 0.3f};
    const int left = 110, right = spec.width - 450, top = 60, bottom = spec.height - 80;

    // Data range, in decades.
    double xmin = 1e300, xmax = 0, ymin = 1e300, ymax = 0;
    for (const auto& s : series)
        for (const auto& p : s.points) {
            if (p.x <= 0) continue;
            xmin = std::min(xmin, p.x), xmax = std::max(xmax, p.x);
            const double y = std::max(p.y, spec.y_floor);
            ymin = std::min(ymin, y), ymax = std::max(ymax, y);
        }
    if (xmax <= 0) xmin = 1, xmax = 10, ymin = 1, ymax = 10;
    const int dx0 = static_cast<int>(std::floor(std::log10(xmin))), dx1 = static_cast<int>(std::ceil(std::log10(xmax)));
    const int dy0 = static_cast<int>(std::floor(std::log10(ymin))), dy1 = static_cast<int>(std::ceil(std::log10(ymax)));
    const int nx = std::max(1, dx1 - dx0), ny = std::max(1, dy1 - dy0);
    auto px = [&](double x) {
        return left + static_cast<int>(std::lround((std::log10(x) - dx0) / nx * (right - left)));
    };
    auto py = [&](double y) {
        y = std::max(y, spec.y_floor);
        return bottom - static_cast<int>(std::lround((std::log10(y) - dy0) / ny * (bottom - top)));
    };

    // Grid: decades solid grey, 2…9 light.
    for (int d = dx0; d <= dx0 + nx; ++d) {
        for (int m = 1; m <= 9 && d < dx0 + nx + (m == 1); ++m) {
            const int x = px(m * std::pow(10.0, d));
            if (x > right) break;
            line(img, x, top, x, bottom, m == 1 ? grey : std::array<float, 3>{0.94f, 0.94f, 0.94f});
        }
        char buf[16];
        std::snprintf(buf, sizeof buf, "1E%d", d);
        const int x = px(std::pow(10.0, d));
        line(img, x, bottom, x, bottom + 6, black);
        draw_text(img, x - text_width(buf, 2) / 2, bottom + 12, buf, black, 2);
    }
    for (int d = dy0; d <= dy0 + ny; ++d) {
        for (int m = 1; m <= 9 && d < dy0 + ny + (m == 1); ++m) {
            const int y = py(m * std::pow(10.0, d));
            if (y < top) break;
            line(img, left, y, right, y, m == 1 ? grey : std::array<float, 3>{0.94f, 0.94f, 0.94f});
        }
        char buf[16];
        std::snprintf(buf, sizeof buf, "1E%d", d);
        const int y = py(std::pow(10.0, d));
        line(img, left - 6, y, left, y, black);
        draw_text(img, left - 10 - text_width(buf, 2), y - 7, buf, black, 2);
    }
    // Floor line: values at or below it (exact results) sit there.
    if (spec.y_floor >= std::pow(10.0, dy0)) {
        line(img, left, py(spec.y_floor), right, py(spec.y_floor), dark, 1, 6);
        draw_text(img, left + 6, py(spec.y_floor) - 12, "EXACT / BELOW FLOOR", dark, 1);
    }
    line(img, left, top, left, bottom, black, 2);
    line(img, left, bottom, right, bottom, black, 2);
    line(img, left, top, right, top, black, 1);
    line(img, right, top, right, bottom, black, 1);

    draw_text(img, left, 20, spec.title, black, 3);
    draw_text(img, (left + right) / 2 - text_width(spec.x_label, 2) / 2, spec.height - 36, spec.x_label, black, 2);
    // Y label, written vertically letter by letter at the left edge.
    for (size_t i = 0; i < spec.y_label.size(); ++i)
        draw_text(img, 8, top + 20 + static_cast<int>(i) * 16, std::string(1, spec.y_label[i]), black, 2);

    // Curves (each knob's variants joined from fastest to slowest, so a curve reads as "what
    // more time buys"), then markers and tags on top.
    for (size_t s = 0; s < series.size(); ++s) {
        const auto c = kPalette[s % std::size(kPalette)];
        auto pts = series[s].points;
        std::sort(pts.begin(), pts.end(), [](const PlotPoint& a, const PlotPoint& b) { return a.x < b.x; });
        for (size_t i = 1; i < pts.size(); ++i)
            line(img, px(pts[i - 1].x), py(pts[i - 1].y), px(pts[i].x), py(pts[i].y), c, 2);
    }
    for (size_t s = 0; s < series.size(); ++s) {
        const auto c = kPalette[s % std::size(kPalette)];
        for (const auto& p : series[s].points) {
            marker(img, px(p.x), py(p.y), static_cast<int>(s), c);
            if (!p.tag.empty()) draw_text(img, px(p.x) + 8, py(p.y) - 3, p.tag, c, 1);
        }
    }

    // Legend at the right.
    int ly = top;
    draw_text(img, right + 20, ly, spec.legend, black, 2);
    ly += 26;
    for (size_t s = 0; s < series.size(); ++s) {
        const auto c = kPalette[s % std::size(kPalette)];
        line(img, right + 20, ly + 6, right + 50, ly + 6, c, 2);
        marker(img, right + 35, ly + 6, static_cast<int>(s), c);
        draw_text(img, right + 58, ly, series[s].name, c, 2);
        ly += 24;
    }
    return img;
}

}  // namespace mf::bench
