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

void draw_chart(std::ostringstream& out, const Chart& c, double x0, int width, int height) {
    bool right_axis = !c.y2_label.empty();
    double left = x0 + 80, right = x0 + width - (right_axis ? 80 : 30), top = 40;
    // The legend below the plot: entries of 190 px, as many rows as they need.
    int per_row = std::max(1, int((width - 40) / 190));
    int rows = int((c.series.size() + std::size_t(per_row) - 1) / std::size_t(per_row));
    double bottom = height - 55 - 18 * rows;

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
    Axis ax, ay, ay2;
    ax.fit(xmin, xmax, false);
    if (!c.x_names.empty()) ax.lo = xmin - 0.5, ax.hi = xmax + 0.5;
    ay.fit(ymin, ymax, c.log_y);
    ay2.fit(c.y2_min, c.y2_max, false);
    auto px = [&](double x) { return left + ax.at(x) * (right - left); };
    auto py = [&](const Axis& a, double y) { return bottom - a.at(y) * (bottom - top); };

    out << "<g font-family=\"sans-serif\" font-size=\"11\">\n";
    out << "<text x=\"" << num(x0 + width / 2.0) << "\" y=\"22\" text-anchor=\"middle\" "
        << "font-size=\"14\">" << text(c.title) << "</text>\n";
    out << "<rect x=\"" << num(left) << "\" y=\"" << num(top) << "\" width=\"" << num(right - left)
        << "\" height=\"" << num(bottom - top) << "\" fill=\"none\" stroke=\"#444\"/>\n";
    // Grid and ticks.
    if (c.x_names.empty()) {
        for (double t : ax.ticks) {
            double x = px(t);
            out << "<line x1=\"" << num(x) << "\" y1=\"" << num(top) << "\" x2=\"" << num(x)
                << "\" y2=\"" << num(bottom) << "\" stroke=\"#e4e4e4\"/>\n";
            out << "<text x=\"" << num(x) << "\" y=\"" << num(bottom + 15)
                << "\" text-anchor=\"middle\">" << text(tick_label(t)) << "</text>\n";
        }
    } else {
        for (const auto& [x, name] : c.x_names)
            out << "<text transform=\"translate(" << num(px(x)) << "," << num(bottom + 12)
                << ") rotate(30)\" text-anchor=\"start\" font-size=\"10\">" << text(name)
                << "</text>\n";
    }
    for (double t : ay.ticks) {
        double y = py(ay, t);
        out << "<line x1=\"" << num(left) << "\" y1=\"" << num(y) << "\" x2=\"" << num(right)
            << "\" y2=\"" << num(y) << "\" stroke=\"#e4e4e4\"/>\n";
        out << "<text x=\"" << num(left - 6) << "\" y=\"" << num(y + 4) << "\" text-anchor=\"end\">"
            << text(tick_label(t)) << "</text>\n";
    }
    if (right_axis)
        for (double t : ay2.ticks)
            out << "<text x=\"" << num(right + 6) << "\" y=\"" << num(py(ay2, t) + 4) << "\">"
                << text(tick_label(t)) << "</text>\n";
    out << "<text x=\"" << num((left + right) / 2) << "\" y=\"" << num(bottom + 38)
        << "\" text-anchor=\"middle\">" << text(c.x_label) << "</text>\n";
    out << "<text transform=\"translate(" << num(x0 + 18) << "," << num((top + bottom) / 2)
        << ") rotate(-90)\" text-anchor=\"middle\">" << text(c.y_label) << "</text>\n";
    if (right_axis)
        out << "<text transform=\"translate(" << num(x0 + width - 14) << ","
            << num((top + bottom) / 2) << ") rotate(90)\" text-anchor=\"middle\">"
            << text(c.y2_label) << "</text>\n";

    // The series: lines through runs of drawable points, and markers.
    for (std::size_t i = 0; i < c.series.size(); ++i) {
        const Series& s = c.series[i];
        const Axis& a = s.right ? ay2 : ay;
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
            double X = px(x), Y = py(a, y);
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
        // Its legend entry.
        int row = int(i) / per_row, col = int(i) % per_row;
        double lx = x0 + 20 + 190 * col, ly = height - 30 - 18 * (rows - 1 - row);
        out << "<line x1=\"" << num(lx) << "\" y1=\"" << num(ly - 4) << "\" x2=\"" << num(lx + 22)
            << "\" y2=\"" << num(ly - 4) << "\" stroke=\"" << color << "\" stroke-width=\"2\""
            << (s.dashed ? " stroke-dasharray=\"6,4\"" : "") << "/>\n";
        out << "<text x=\"" << num(lx + 28) << "\" y=\"" << num(ly) << "\">" << text(s.name)
            << "</text>\n";
    }
    for (const Chart::Label& l : c.labels) {
        double X = px(l.x), Y = py(ay, l.y);
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
