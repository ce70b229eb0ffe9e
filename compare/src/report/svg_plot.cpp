#include "report/svg_plot.hpp"

#include "io/jsonl.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace linequad::plot {

namespace {

const char* const palette[] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd",
                               "#8c564b", "#e377c2", "#17becf", "#7f7f7f", "#bcbd22"};

std::string text(const std::string& s) {
    return jsonl::markup_text(s);
}

std::string num(double x) {
    char b[32];
    std::snprintf(b, sizeof b, "%.2f", x);
    return b;
}

// A tick's label: short, exact for whole numbers.
std::string tick_label(double v) {
    char b[32];
    if (v == 0) return "0";
    double a = std::fabs(v);
    if (a >= 1e5 || a < 1e-3)
        std::snprintf(b, sizeof b, "%.0e", v);
    else
        std::snprintf(b, sizeof b, "%g", v);
    return b;
}

// [lo, hi] with room, and ticks at a "nice" step (1, 2 or 5 times a power of ten).
struct Axis {
    double lo = 0, hi = 1;
    bool log = false;
    std::vector<double> ticks;

    void fit(double min, double max, bool logarithmic) {
        log = logarithmic;
        if (!(min <= max)) min = log ? 1 : 0, max = log ? 10 : 1;
        if (log) {
            lo = std::floor(std::log10(min));
            hi = std::ceil(std::log10(max));
            if (hi <= lo) hi = lo + 1;
            int step = std::max(1, int(std::ceil((hi - lo) / 10)));
            for (double e = lo; e <= hi + 1e-9; e += step)
                ticks.push_back(std::pow(10.0, e));
            return;
        }
        if (max == min) min -= 0.5, max += 0.5;
        double raw = (max - min) / 8, p = std::pow(10.0, std::floor(std::log10(raw)));
        double step = raw / p <= 1 ? p : raw / p <= 2 ? 2 * p : raw / p <= 5 ? 5 * p : 10 * p;
        lo = std::floor(min / step) * step;
        hi = std::ceil(max / step) * step;
        for (double t = lo; t <= hi + step * 1e-9; t += step)
            ticks.push_back(std::fabs(t) < step * 1e-9 ? 0 : t);
    }
    // Where v falls, from 0 (lo) to 1 (hi); NaN where it cannot be drawn.
    double at(double v) const {
        if (!std::isfinite(v)) return NAN;
        if (log) {
            if (!(v > 0)) return NAN;
            v = std::log10(v);
        }
        return (v - lo) / (hi - lo);
    }
};

// Where a chart's plot area is, and its axes.
struct Frame {
    double x0, width, height, left, right, top, bottom;
    int per_row, rows; // the legend's entries per row, and its rows
    Axis ax, ay, ay2;
    double px(double x) const { return left + ax.at(x) * (right - left); }
    double py(const Axis& a, double y) const { return bottom - a.at(y) * (bottom - top); }
};

Frame frame_of(const Chart& c, double x0, int width, int height) {
    Frame f;
    bool right_axis = !c.y2_label.empty();
    f.x0 = x0, f.width = width, f.height = height;
    f.left = x0 + 80, f.right = x0 + width - (right_axis ? 80 : 30), f.top = 40;
    // The legend below the plot: entries of 190 px, as many rows as they need.
    f.per_row = std::max(1, int((width - 40) / 190));
    f.rows = int((c.series.size() + std::size_t(f.per_row) - 1) / std::size_t(f.per_row));
    f.bottom = height - 72 - 18 * f.rows; // the x label clear of the legend
    double xmin = INFINITY, xmax = -INFINITY, ymin = INFINITY, ymax = -INFINITY;
    for (const Series& s : c.series)
        for (auto [x, y] : s.points) {
            if (!std::isfinite(x)) continue;
            xmin = std::min(xmin, x), xmax = std::max(xmax, x);
            if (s.right || !std::isfinite(y) || (c.log_y && !(y > 0))) continue;
            ymin = std::min(ymin, y), ymax = std::max(ymax, y);
        }
    for (const auto& [x, name] : c.x_names)
        xmin = std::min(xmin, x), xmax = std::max(xmax, x);
    f.ax.fit(xmin, xmax, false);
    if (!c.x_names.empty()) f.ax.lo = xmin - 0.5, f.ax.hi = xmax + 0.5;
    f.ay.fit(ymin, ymax, c.log_y);
    f.ay2.fit(c.y2_min, c.y2_max, false);
    return f;
}

// The title, the plot's box, the grid, the ticks and the axes' labels.
void draw_axes(std::ostringstream& out, const Chart& c, const Frame& f) {
    out << "<text x=\"" << num(f.x0 + f.width / 2.0) << "\" y=\"22\" text-anchor=\"middle\" "
        << "font-size=\"14\">" << text(c.title) << "</text>\n";
    out << "<rect x=\"" << num(f.left) << "\" y=\"" << num(f.top) << "\" width=\""
        << num(f.right - f.left) << "\" height=\"" << num(f.bottom - f.top)
        << "\" fill=\"none\" stroke=\"#444\"/>\n";
    if (c.x_names.empty()) {
        for (double t : f.ax.ticks) {
            double x = f.px(t);
            out << "<line x1=\"" << num(x) << "\" y1=\"" << num(f.top) << "\" x2=\"" << num(x)
                << "\" y2=\"" << num(f.bottom) << "\" stroke=\"#e4e4e4\"/>\n";
            out << "<text x=\"" << num(x) << "\" y=\"" << num(f.bottom + 15)
                << "\" text-anchor=\"middle\">" << text(tick_label(t)) << "</text>\n";
        }
    } else {
        for (const auto& [x, name] : c.x_names)
            out << "<text transform=\"translate(" << num(f.px(x)) << "," << num(f.bottom + 12)
                << ") rotate(30)\" text-anchor=\"start\" font-size=\"10\">" << text(name)
                << "</text>\n";
    }
    for (double t : f.ay.ticks) {
        double y = f.py(f.ay, t);
        out << "<line x1=\"" << num(f.left) << "\" y1=\"" << num(y) << "\" x2=\"" << num(f.right)
            << "\" y2=\"" << num(y) << "\" stroke=\"#e4e4e4\"/>\n";
        out << "<text x=\"" << num(f.left - 6) << "\" y=\"" << num(y + 4)
            << "\" text-anchor=\"end\">" << text(tick_label(t)) << "</text>\n";
    }
    bool right_axis = !c.y2_label.empty();
    if (right_axis)
        for (double t : f.ay2.ticks)
            out << "<text x=\"" << num(f.right + 6) << "\" y=\"" << num(f.py(f.ay2, t) + 4) << "\">"
                << text(tick_label(t)) << "</text>\n";
    out << "<text x=\"" << num((f.left + f.right) / 2) << "\" y=\"" << num(f.bottom + 38)
        << "\" text-anchor=\"middle\">" << text(c.x_label) << "</text>\n";
    out << "<text transform=\"translate(" << num(f.x0 + 18) << "," << num((f.top + f.bottom) / 2)
        << ") rotate(-90)\" text-anchor=\"middle\">" << text(c.y_label) << "</text>\n";
    if (right_axis)
        out << "<text transform=\"translate(" << num(f.x0 + f.width - 14) << ","
            << num((f.top + f.bottom) / 2) << ") rotate(90)\" text-anchor=\"middle\">"
            << text(c.y2_label) << "</text>\n";
}

// A series: lines through its runs of drawable points, its markers, and its legend entry.
void draw_series(std::ostringstream& out, const Series& s, std::size_t i, const Frame& f) {
    const Axis& a = s.right ? f.ay2 : f.ay;
    std::string color = palette[std::size_t(s.color >= 0 ? s.color : int(i)) % 10];
    std::vector<std::pair<double, double>> run;
    auto flush = [&] {
        if (s.lines && run.size() > 1) {
            out << "<polyline fill=\"none\" stroke=\"" << color << "\" stroke-width=\"1.8\""
                << (s.dashed ? " stroke-dasharray=\"6,4\"" : "") << " points=\"";
            for (auto [x, y] : run)
                out << num(x) << "," << num(y) << " ";
            out << "\"/>\n";
        }
        run.clear();
    };
    for (auto [x, y] : s.points) {
        double X = f.px(x), Y = f.py(a, y);
        if (!std::isfinite(X) || !std::isfinite(Y)) {
            flush();
            continue;
        }
        run.emplace_back(X, Y);
        if (!s.markers) continue;
        if (s.square)
            out << "<rect x=\"" << num(X - 3.5) << "\" y=\"" << num(Y - 3.5)
                << "\" width=\"7\" height=\"7\" fill=\"" << color << "\"/>\n";
        else
            out << "<circle cx=\"" << num(X) << "\" cy=\"" << num(Y) << "\" r=\"3.5\" fill=\""
                << color << "\"/>\n";
    }
    flush();
    int row = int(i) / f.per_row, col = int(i) % f.per_row;
    double lx = f.x0 + 20 + 190 * col, ly = f.height - 30 - 18 * (f.rows - 1 - row);
    out << "<line x1=\"" << num(lx) << "\" y1=\"" << num(ly - 4) << "\" x2=\"" << num(lx + 22)
        << "\" y2=\"" << num(ly - 4) << "\" stroke=\"" << color << "\" stroke-width=\"2\""
        << (s.dashed ? " stroke-dasharray=\"6,4\"" : "") << "/>\n";
    out << "<text x=\"" << num(lx + 28) << "\" y=\"" << num(ly) << "\">" << text(s.name)
        << "</text>\n";
}

void draw_chart(std::ostringstream& out, const Chart& c, double x0, int width, int height) {
    Frame f = frame_of(c, x0, width, height);
    out << "<g font-family=\"sans-serif\" font-size=\"11\">\n";
    draw_axes(out, c, f);
    for (std::size_t i = 0; i < c.series.size(); ++i)
        draw_series(out, c.series[i], i, f);
    for (const Chart::Label& l : c.labels) {
        double X = f.px(l.x), Y = f.py(f.ay, l.y);
        if (!std::isfinite(X) || !std::isfinite(Y)) continue;
        out << "<text x=\"" << num(X) << "\" y=\"" << num(Y - 8) << "\" text-anchor=\"middle\">"
            << text(l.text) << "</text>\n";
    }
    out << "</g>\n";
}

} // namespace

std::string svg(const std::vector<Chart>& charts, int width, int height) {
    std::ostringstream out;
    int total = width * int(std::max<std::size_t>(1, charts.size()));
    out << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
        << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << total << "\" height=\"" << height
        << "\" viewBox=\"0 0 " << total << " " << height << "\">\n"
        << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
    for (std::size_t i = 0; i < charts.size(); ++i)
        draw_chart(out, charts[i], double(width) * double(i), width, height);
    out << "</svg>\n";
    return out.str();
}

} // namespace linequad::plot
