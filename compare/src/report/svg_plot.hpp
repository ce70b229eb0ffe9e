// The report's figures, written as SVG by linequad itself: no plotting program is started and no
// script is written, so a name in a figure is only ever text (escaped by jsonl::markup_text).
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace linequad::plot {

struct Series {
    std::string name;
    std::vector<std::pair<double, double>> points; // (x, y); a y that cannot be drawn: a gap
    bool right = false;                            // on the right axis (linear, y2_min..y2_max)
    bool lines = true, markers = true, dashed = false;
    bool square = false; // square markers instead of round ones
    int color = -1;      // an index in the palette; -1: the series' own position
};

struct Chart {
    std::string title, x_label, y_label, y2_label; // no y2_label: no right axis
    bool log_y = false;                            // the left axis logarithmic (y > 0 drawn)
    double y2_min = 0, y2_max = 1;
    std::vector<Series> series;
    // Named ticks on the x axis (a history's commits); empty: numbers.
    std::vector<std::pair<double, std::string>> x_names;
    struct Label {
        double x, y;
        std::string text;
    };
    std::vector<Label> labels; // text above a point of the left axis
};

// One SVG document of the charts side by side, each `width` by `height` pixels.
std::string svg(const std::vector<Chart>& charts, int width = 800, int height = 500);

} // namespace linequad::plot
