// plot_csv: a log-log plot of a CSV (bench/scale/run.sh's results) as a PNG, with the plot code
// of the accuracy bench (bench/accuracy/plot.hpp), so a benchmark's figure needs no plotting
// package.
//
//   plot_csv IN.csv OUT.png --x COLUMN --y COLUMN --series COLUMN [--where COLUMN=VALUE]
//            [--title T] [--xlabel T] [--ylabel T]
//
// IN.csv: a header line, then comma-separated values (no quoting). One curve per distinct value
// of the --series column, its points sorted by x.
#include <algorithm>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "image/image.hpp"
#include "plot.hpp"

namespace {

std::vector<std::string> split(const std::string& line) {
    std::vector<std::string> cells;
    std::stringstream s(line);
    for (std::string c; std::getline(s, c, ',');) cells.push_back(c);
    return cells;
}

int usage() {
    std::cerr << "usage: plot_csv IN.csv OUT.png --x COL --y COL --series COL [--where COL=VALUE] [--title T] "
                 "[--xlabel T] [--ylabel T]\n";
    return 2;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 3) return usage();
    const std::string in = argv[1], out = argv[2];
    std::map<std::string, std::string> opt;
    for (int i = 3; i + 1 < argc; i += 2) opt[argv[i]] = argv[i + 1];
    for (const char* need : {"--x", "--y", "--series"})
        if (!opt.count(need)) return usage();
    std::ifstream f(in);
    std::string line;
    if (!std::getline(f, line)) {
        std::cerr << "plot_csv: " << in << ": empty\n";
        return 1;
    }
    const std::vector<std::string> header = split(line);
    auto column = [&](const std::string& name) {
        const auto it = std::find(header.begin(), header.end(), name);
        return it == header.end() ? -1 : static_cast<int>(it - header.begin());
    };
    const int cx = column(opt["--x"]), cy = column(opt["--y"]), cs = column(opt["--series"]);
    int cw = -1;
    std::string want;
    if (opt.count("--where")) {
        const std::string& w = opt["--where"];
        cw = column(w.substr(0, w.find('=')));
        want = w.substr(w.find('=') + 1);
    }
    if (cx < 0 || cy < 0 || cs < 0 || (opt.count("--where") && cw < 0)) {
        std::cerr << "plot_csv: " << in << ": a named column is not in the header\n";
        return 1;
    }
    std::vector<mf::bench::PlotSeries> series;
    std::map<std::string, size_t> index;
    while (std::getline(f, line)) {
        const auto c = split(line);
        if (c.size() != header.size() || (cw >= 0 && c[static_cast<size_t>(cw)] != want)) continue;
        const std::string& name = c[static_cast<size_t>(cs)];
        if (!index.count(name)) index[name] = series.size(), series.push_back({name, {}});
        series[index[name]].points.push_back({std::stod(c[static_cast<size_t>(cx)]),
                                              std::stod(c[static_cast<size_t>(cy)]), ""});
    }
    for (auto& s : series)
        std::sort(s.points.begin(), s.points.end(), [](const auto& a, const auto& b) { return a.x < b.x; });
    mf::bench::PlotSpec spec;
    spec.title = opt.count("--title") ? opt["--title"] : "";
    spec.x_label = opt.count("--xlabel") ? opt["--xlabel"] : opt["--x"];
    spec.y_label = opt.count("--ylabel") ? opt["--ylabel"] : opt["--y"];
    spec.legend = opt["--series"];
    spec.width = 1200;
    spec.height = 800;
    spec.y_floor = 1e-3;
    const mf::Image img = mf::bench::draw_plot(spec, series);
    std::vector<unsigned char> bytes;
    std::string err;
    if (!mf::encode_image(img, {mf::FileFormat::png, 8}, bytes, err)) {
        std::cerr << "plot_csv: " << out << ": " << err << "\n";
        return 1;
    }
    std::ofstream(out, std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    return 0;
}
