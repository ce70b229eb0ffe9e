// OpenMC's geometry.xml (docs.openmc.org, "Geometry Specification"), read with pugixml.
#include "cli/openmc_geometry.hpp"

#include <pugixml.hpp>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

namespace linequad::cli {

namespace {

// A double computed without rounding, or the reason it is not one.
struct Exact {
    double v;
    bool ok;
};
Exact exactly(double x) {
    return {x, std::isfinite(x)};
}
// a b, where the product is a double (fma shows the residual; a product below 2^-969 may have
// lost bits fma cannot show, and is refused).
Exact operator*(Exact a, Exact b) {
    double p = a.v * b.v;
    bool tiny = p != 0 && std::fabs(p) < 0x1p-969;
    return {p, a.ok && b.ok && std::isfinite(p) && !tiny && std::fma(a.v, b.v, -p) == 0};
}
Exact operator+(Exact a, Exact b) {
    double s = a.v + b.v, bb = s - a.v, err = (a.v - (s - bb)) + (b.v - bb); // two_sum
    return {s, a.ok && b.ok && std::isfinite(s) && err == 0};
}
Exact operator-(Exact a) {
    return {-a.v, a.ok};
}

class Reader {
  public:
    Reader(std::string_view xml, std::string* why) : xml_(xml), why_(why) {}

    // "line 12: surface 3 (x-torus): ..." with the element's line.
    bool fail(const pugi::xml_node& node, const std::string& what) {
        long line = 1;
        std::ptrdiff_t at = node.offset_debug();
        if (at >= 0)
            line += long(std::count(
                xml_.begin(), xml_.begin() + std::min<std::size_t>(std::size_t(at), xml_.size()),
                '\n'));
        *why_ = "line " + std::to_string(line) + ": " + what;
        return false;
    }

    // An id attribute: a positive integer.
    bool id(const pugi::xml_node& node, const char* what, std::int64_t* out) {
        const char* text = node.attribute("id").value();
        char* end = nullptr;
        errno = 0;
        long long v = std::strtoll(text, &end, 10);
        if (*text == 0 || *end != 0 || errno != 0 || v < 1)
            return fail(node, std::string(what) + " with id \"" + text +
                                  "\": expected a positive integer id");
        *out = v;
        return true;
    }

    // The coefficients: whitespace-separated numbers, exactly `count` of them, each read
    // correctly rounded.
    bool coeffs(const pugi::xml_node& node, const std::string& where, std::size_t count,
                std::vector<double>* out) {
        std::string text = node.attribute("coeffs").value();
        out->clear();
        const char* p = text.c_str();
        for (;;) {
            while (*p == ' ' || *p == '\t' || *p == '\n' || *p == '\r')
                ++p;
            if (*p == 0) break;
            char* end = nullptr;
            double x = std::strtod(p, &end);
            if (end == p ||
                !(*end == 0 || *end == ' ' || *end == '\t' || *end == '\n' || *end == '\r') ||
                !std::isfinite(x))
                return fail(node, where + ": coeffs \"" + text + "\": not finite numbers");
            out->push_back(x);
            p = end;
        }
        if (out->size() != count)
            return fail(node, where + ": coeffs \"" + text + "\": expected " +
                                  std::to_string(count) +
                                  (count == 1 ? " coefficient" : " coefficients"));
        return true;
    }

  private:
    std::string_view xml_;
    std::string* why_;
};

// The ten coefficients of a centred type, each a double exactly, or the first that is not.
struct Expanded {
    std::array<Exact, 10> q;
    const char* names[10] = {"A", "B", "C", "D", "E", "F", "G", "H", "J", "K"};
};

// x0, y0, z0 the centre (one of them unused for a cylinder), s the scale of each squared
// coordinate (1, or -R2 for a cone's axis), K0 the constant beyond the centre's terms (-R^2).
// f = sum_i s_i (x_i - c_i)^2 + K0 = sum s_i x_i^2 - 2 s_i c_i x_i + (sum s_i c_i^2 + K0).
Expanded centred(const std::array<Exact, 3>& s, const std::array<Exact, 3>& c, Exact K0) {
    Expanded e;
    Exact zero = exactly(0), two = exactly(2);
    for (int i = 0; i < 3; ++i) {
        e.q[std::size_t(i)] = s[std::size_t(i)];
        e.q[std::size_t(3 + i)] = zero;
        e.q[std::size_t(6 + i)] = -(two * s[std::size_t(i)] * c[std::size_t(i)]);
    }
    Exact K = K0;
    for (int i = 0; i < 3; ++i)
        K = K + s[std::size_t(i)] * c[std::size_t(i)] * c[std::size_t(i)];
    e.q[9] = K;
    return e;
}

bool surface(Reader& r, const pugi::xml_node& node, Model::Surface* out) {
    if (!r.id(node, "surface", &out->id)) return false;
    std::string type = node.attribute("type").value();
    std::string where = "surface " + std::to_string(out->id) + " (" + type + ")";
    std::vector<double> c;
    auto planes = [&](int axis) {
        if (!r.coeffs(node, where, 1, &c)) return false;
        Vec3 n{double(axis == 0), double(axis == 1), double(axis == 2)};
        out->shape = Plane{n, c[0]};
        return true;
    };
    if (type == "x-plane") return planes(0);
    if (type == "y-plane") return planes(1);
    if (type == "z-plane") return planes(2);
    if (type == "plane") {
        if (!r.coeffs(node, where, 4, &c)) return false;
        out->shape = Plane{{c[0], c[1], c[2]}, c[3]};
        return true;
    }
    if (type == "quadric") {
        if (!r.coeffs(node, where, 10, &c)) return false;
        Quadric q;
        std::copy(c.begin(), c.end(), q.q.begin());
        out->shape = q;
        return true;
    }
    // The sphere and the cylinders as OpenMC defines them, from their centre and radius: exact
    // whatever the doubles (linequad/cells.hpp's Sphere and Cylinder surfaces).
    auto radius = [&](double R) {
        return R > 0 || r.fail(node, where + ": coeffs \"" + node.attribute("coeffs").value() +
                                         "\": the radius is not positive");
    };
    if (type == "sphere") {
        if (!r.coeffs(node, where, 4, &c) || !radius(c[3])) return false;
        out->shape = Sphere{{c[0], c[1], c[2]}, c[3]};
        return true;
    }
    if (type == "x-cylinder" || type == "y-cylinder" || type == "z-cylinder") {
        if (!r.coeffs(node, where, 3, &c) || !radius(c[2])) return false;
        int axis = type[0] - 'x';
        double centre[3], along[3];
        for (int i = 0, k = 0; i < 3; ++i) {
            centre[i] = i == axis ? 0.0 : c[std::size_t(k++)];
            along[i] = i == axis ? 1.0 : centre[i];
        }
        Cylinder cylinder{{centre[0], centre[1], centre[2]}, {along[0], along[1], along[2]}, c[2]};
        cylinder.finite = false;
        out->shape = cylinder;
        return true;
    }
    Exact one = exactly(1), zero = exactly(0);
    Expanded e;
    if (type == "x-cone" || type == "y-cone" || type == "z-cone") {
        // (x_i - c_i)^2 summed over the other axes, less R2 (x_axis - c_axis)^2: R2 is OpenMC's
        // coefficient itself (the squared tangent), not a square to round.
        if (!r.coeffs(node, where, 4, &c)) return false;
        int axis = type[0] - 'x';
        std::array<Exact, 3> s{one, one, one};
        s[std::size_t(axis)] = -exactly(c[3]);
        e = centred(s, {exactly(c[0]), exactly(c[1]), exactly(c[2])}, zero);
    } else {
        return r.fail(node, where + ": a surface type linequad does not pose (it poses plane, "
                                    "x-/y-/z-plane, sphere, x-/y-/z-cylinder, x-/y-/z-cone and "
                                    "quadric)");
    }
    Quadric q;
    for (int i = 0; i < 10; ++i) {
        if (!e.q[std::size_t(i)].ok)
            return r.fail(node, where + ": coeffs \"" + node.attribute("coeffs").value() +
                                    "\": its general-quadric coefficient " + e.names[i] +
                                    " is not a double, and linequad poses a surface exactly, "
                                    "never rounded (such cones are not taken yet)");
        q.q[std::size_t(i)] = e.q[std::size_t(i)].v;
    }
    out->shape = q;
    return true;
}

// A cell as geometry.xml writes it: its universe, and what fills it (a material, or another
// universe's cells).
struct XmlCell {
    Model::CellSource source; // id, name, region ("" for a universe's infinite cell)
    std::string universe = "0", fill;
    pugi::xml_node node;
};

bool cell(Reader& r, const pugi::xml_node& node, XmlCell* out) {
    out->node = node;
    if (!r.id(node, "cell", &out->source.id)) return false;
    std::string where = "cell " + std::to_string(out->source.id);
    for (const char* refused : {"rotation", "translation"})
        if (node.attribute(refused))
            return r.fail(node, where + ": " + refused +
                                    " is not taken yet (a universe fills a cell as it is)");
    if (pugi::xml_attribute u = node.attribute("universe")) out->universe = u.value();
    if (pugi::xml_attribute f = node.attribute("fill")) out->fill = f.value();
    pugi::xml_attribute region = node.attribute("region");
    bool infinite =
        !region || std::string(region.value()).find_first_not_of(" \t\r\n") == std::string::npos;
    if (infinite && out->universe == "0")
        return r.fail(node, where + ": has no region (an infinite cell is not taken in the root "
                                    "universe)");
    out->source.region = infinite ? "" : region.value();
    out->source.name = node.attribute("name").value();
    return true;
}

constexpr std::size_t max_universe_depth = 64;

// The root universe's cells, each cell filled with a universe replaced by that universe's cells
// (each one's region within the filling cell's), down to cells of materials. A universe fills
// one cell at most (its cells keep their ids), and no universe contains itself.
bool flatten(Reader& r, const std::vector<XmlCell>& cells, std::vector<Model::CellSource>* out) {
    std::vector<std::string> filled; // universes already placed
    struct Place {
        const XmlCell* cell;
        std::string region, name;      // within the cells that hold it
        std::vector<std::string> path; // the universes it is placed through
    };
    std::vector<Place> todo;
    for (auto it = cells.rbegin(); it != cells.rend(); ++it)
        if (it->universe == "0") todo.push_back({&*it, "", "", {"0"}});
    if (todo.empty() && !cells.empty())
        return r.fail(cells.front().node, "no cell is in the root universe (0)");
    std::vector<Model::CellSource> placed;
    while (!todo.empty()) {
        Place p = todo.back();
        todo.pop_back();
        const XmlCell& c = *p.cell;
        std::string region = c.source.region.empty() ? p.region
                             : p.region.empty()      ? c.source.region
                                                     : p.region + " (" + c.source.region + ")";
        std::string name = p.name.empty() ? c.source.name : p.name + " / " + c.source.name;
        if (c.fill.empty()) {
            placed.push_back({c.source.id, name, region});
            continue;
        }
        std::string where = "cell " + std::to_string(c.source.id) + ": fill " + c.fill;
        if (std::find(p.path.begin(), p.path.end(), c.fill) != p.path.end())
            return r.fail(c.node, where + ": the universe contains itself");
        // Each level wraps the regions within once more: bounded, so that hostile text cannot
        // make them grow as the square of its length.
        if (p.path.size() > max_universe_depth)
            return r.fail(c.node, where + ": universes nested more than " +
                                      std::to_string(max_universe_depth) + " deep");
        if (std::find(filled.begin(), filled.end(), c.fill) != filled.end())
            return r.fail(c.node, where + ": the universe fills another cell too (a universe "
                                          "placed more than once is not taken yet: its cells "
                                          "would need ids of their own)");
        filled.push_back(c.fill);
        std::vector<Place> inner;
        for (const XmlCell& d : cells)
            if (d.universe == c.fill) {
                std::vector<std::string> path = p.path;
                path.push_back(c.fill);
                inner.push_back({&d, "(" + region + ")", name, path});
            }
        if (inner.empty()) return r.fail(c.node, where + ": no cell is in that universe");
        todo.insert(todo.end(), inner.rbegin(), inner.rend());
    }
    *out = std::move(placed);
    return true;
}

} // namespace

bool openmc_geometry_available() {
    return true;
}

bool parse_openmc_geometry(std::string_view xml, ModelFile* out, std::string* why) {
    *out = ModelFile{};
    pugi::xml_document doc;
    pugi::xml_parse_result parsed = doc.load_buffer(xml.data(), xml.size());
    if (!parsed) {
        long line = 1 + long(std::count(xml.begin(),
                                        xml.begin() + std::min<std::size_t>(
                                                          std::size_t(parsed.offset), xml.size()),
                                        '\n'));
        *why = "line " + std::to_string(line) + ": not well-formed XML: " + parsed.description();
        return false;
    }
    pugi::xml_node geometry = doc.child("geometry");
    Reader r(xml, why);
    if (!geometry) return r.fail(doc.first_child(), "expected a <geometry> element");
    std::vector<XmlCell> cells;
    for (pugi::xml_node node : geometry.children()) {
        if (node.type() != pugi::node_element) continue;
        std::string name = node.name();
        if (name == "surface") {
            Model::Surface s{};
            if (!surface(r, node, &s)) return false;
            out->surfaces.push_back(s);
        } else if (name == "cell") {
            XmlCell c;
            if (!cell(r, node, &c)) return false;
            cells.push_back(std::move(c));
        } else {
            return r.fail(node, "<" + name +
                                    "> is not taken yet (linequad reads surfaces, cells and "
                                    "the universes that fill them)");
        }
    }
    return flatten(r, cells, &out->cells);
}

} // namespace linequad::cli
