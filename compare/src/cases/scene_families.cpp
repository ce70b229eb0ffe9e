// The scene families (linequad/scene_audit.hpp). Each scene stands on axes e0, e1, e2 that are
// the columns of an integer rotation (orthogonal, each of length N) at an integer origin, maybe
// moved 2^k away; radii are dyadic multiples of N and every named point (a contact, a rim, a
// disc's centre) a dyadic combination of the axes, so the contacts the family is about are
// exact (nested's gaps of 2^-k excepted: past 2^-40 they round, and the oracle says what they
// became). Lines go through those points along small dyadic directions, exactly too.
#include "linequad/scene_audit.hpp"

#include "cases/rng.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <string>

namespace linequad::audit {

namespace {

const char* const names[scene_family_count] = {"touching", "nested",  "coaxial", "shared_rim",
                                               "far_grid", "spawned", "from_hit"};

struct Axes {
    Vec3 O, e[3];
    double N = 1;
    // O + x e0 + y e1 + z e2
    Vec3 at(double x, double y, double z) const { return O + x * e[0] + y * e[1] + z * e[2]; }
    Vec3 dir(double x, double y, double z) const { return x * e[0] + y * e[1] + z * e[2]; }
};

// Axes along the coordinate axes, or an integer rotation's; the origin 2^offset out.
Axes axes(Rng& r, bool aligned, int offset) {
    Axes a;
    IntegerRotation q =
        aligned ? IntegerRotation{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, 1} : integer_rotation(r);
    for (int i = 0; i < 3; ++i)
        a.e[i] = q.col[i];
    a.N = q.N;
    Vec3 near = r.ivec(8), far = r.ivec(4); // drawn in order: each scene a pure function
    a.O = near + std::ldexp(1.0, offset) * far;
    return a;
}

// A radius in [1/2, 2), six bits.
double radius(Rng& r) {
    return double(r.integer(32, 127)) / 64;
}

// A height in (0, h), four bits.
double inside(Rng& r, double h) {
    return h * double(r.integer(1, 15)) / 16;
}

// A direction of small integers in the axes' frame, not zero.
Vec3 direction(Rng& r, const Axes& a, int s = 3) {
    for (;;) {
        Vec3 d = r.ivec(s);
        if (d != Vec3{}) return a.dir(d.x, d.y, d.z);
    }
}

// The line through P along v, P at t = s: a ray or a line; or a segment ending at P (s = 1).
Line through(Rng& r, Vec3 P, Vec3 v) {
    int kind = r.integer(0, 4);
    if (kind == 4) return {P - v, v, Range::segment};
    double s = r.integer(1, 4);
    return {P - s * v, v, kind < 3 ? Interval(Range::ray) : Interval(Range::line)};
}

Cylinder cylinder(const Axes& a, double x, double y, double z0, double z1, double rho, bool caps) {
    return {a.at(x, y, z0), a.at(x, y, z1), rho * a.N, true, caps};
}

struct Builder {
    SceneCase sc;
    Rng& r;
    void add(std::string id, Shape s) { sc.shapes.push_back({"\"" + id + "\"", s}); }
    void line(Line l) {
        sc.lines.push_back({sc.header.id.substr(0, sc.header.id.size() - 1) + "/" +
                                std::to_string(sc.lines.size()) + "\"",
                            l});
    }
    // A line across the scene's box lo..hi (in the axes' frame), any direction.
    void generic(const Axes& a, Vec3 lo, Vec3 hi) {
        double x = r.dyadic(6), y = r.dyadic(6), z = r.dyadic(6);
        Vec3 P = a.at(lo.x + (hi.x - lo.x) * x, lo.y + (hi.y - lo.y) * y, lo.z + (hi.z - lo.z) * z);
        line(through(r, P, direction(r, a)));
    }
};

// Three cylinders: B touches A along x = rhoA (y = 0), C (an elliptic cylinder) touches it along
// y = -rhoA. k: the origin's offset exponent.
void touching(Builder& b, int k, int lines) {
    Rng& r = b.r;
    Axes a = axes(r, r.integer(0, 2) == 0, k);
    double rA = radius(r), rB = radius(r), rC = radius(r), h = r.integer(2, 8);
    b.add("A", cylinder(a, 0, 0, 0, h, rA, r.coin()));
    b.add("B", cylinder(a, rA + rB, 0, 0, h, rB, r.coin()));
    b.add("C", EllipticCylinder{a.at(0, -(rA + rC), 0), rC * a.e[0], rC * a.e[1], h * a.e[2], true,
                                r.coin()});
    for (int j = 0; j < lines; ++j) {
        double z = inside(r, h);
        Vec3 d = r.ivec(3);
        switch (j % 5) {
        case 0: // across the contact with B
            d.x = d.x == 0 ? 1 : d.x;
            b.line(through(r, a.at(rA, 0, z), a.dir(d.x, d.y, d.z)));
            break;
        case 1: // tangent to A and B at their contact
            d.x = 0, d.y = d.y == 0 && d.z == 0 ? 1 : d.y;
            b.line(through(r, a.at(rA, 0, z), a.dir(0, d.y, d.z)));
            break;
        case 2: // across the contact with C
            d.y = d.y == 0 ? 1 : d.y;
            b.line(through(r, a.at(0, -rA, z), a.dir(d.x, d.y, d.z)));
            break;
        case 3: // tangent to A and C
            d.y = 0, d.x = d.x == 0 && d.z == 0 ? 1 : d.x;
            b.line(through(r, a.at(0, -rA, z), a.dir(d.x, 0, d.z)));
            break;
        default:
            b.generic(a, {-rA, -rA - 2 * rC, 0}, {rA + 2 * rB, rA, h});
        }
    }
}

// Closed coaxial cylinders of radius rho (1 + i g) over [-i g h, h + i g h], g = 2^-k, and a
// frustum that is the outermost of them again.
void nested(Builder& b, int k, int lines) {
    Rng& r = b.r;
    bool aligned = r.coin();
    Axes a = axes(r, aligned, r.integer(0, 8));
    double rho = radius(r), h = r.integer(2, 8), g = std::ldexp(1.0, -k);
    for (int i = 0; i < 3; ++i)
        b.add("shell-" + std::to_string(i),
              cylinder(a, 0, 0, -i * g * h, h + i * g * h, rho * (1 + i * g), true));
    double outer = rho * (1 + 2 * g) * a.N;
    b.add("frustum",
          Frustum{a.at(0, 0, -2 * g * h), outer, a.at(0, 0, h + 2 * g * h), outer, true, true});
    for (int j = 0; j < lines; ++j) {
        switch (j % 4) {
        case 0: { // across, near the axis
            Vec3 d = r.ivec(3);
            d.x = d.x == 0 ? 1 : d.x;
            double x = rho * (r.dyadic(4) - 0.5), y = rho * (r.dyadic(4) - 0.5);
            b.line(through(r, a.at(x, y, inside(r, h)), a.dir(d.x, d.y, d.z)));
            break;
        }
        case 1: { // through the caps, nearly along the axis
            double x = rho * (r.dyadic(4) - 0.5), y = rho * (r.dyadic(4) - 0.5), z = inside(r, h);
            double dx = r.integer(-1, 1), dy = r.integer(-1, 1), dz = r.coin() ? 16 : -16;
            b.line(through(r, a.at(x, y, z), a.dir(dx, dy, dz)));
            break;
        }
        case 2: { // through a rim of the innermost
            double z = r.coin() ? 0 : h;
            b.line(through(r, a.at(rho, 0, z), direction(r, a)));
            break;
        }
        default:
            b.generic(a, {-2 * rho, -2 * rho, -1}, {2 * rho, 2 * rho, h + 1});
        }
    }
}

// A cylinder, a frustum and a cone on one axis over [0, h], sharing the base rim (and, where
// capped, the base disc); the frustum narrows to sigma rho (sigma 0: it is the cone again).
void coaxial(Builder& b, int k, int lines) {
    Rng& r = b.r;
    Axes a = axes(r, k == 0, r.integer(0, 8));
    double rho = radius(r), h = r.integer(2, 8), sigma = 0.25 * r.integer(0, 3);
    b.add("cylinder", cylinder(a, 0, 0, 0, h, rho, r.coin()));
    b.add("frustum",
          Frustum{a.at(0, 0, 0), rho * a.N, a.at(0, 0, h), sigma * rho * a.N, true, r.coin()});
    b.add("cone",
          EllipticCone{a.at(0, 0, 0), a.at(0, 0, h), rho * a.e[0], rho * a.e[1], true, r.coin()});
    for (int j = 0; j < lines; ++j) {
        switch (j % 4) {
        case 0: { // through a point of the shared rim
            int q = r.integer(0, 3);
            double x = q == 0 ? rho : q == 1 ? -rho : 0, y = q == 2 ? rho : q == 3 ? -rho : 0;
            b.line(through(r, a.at(x, y, 0), direction(r, a)));
            break;
        }
        case 1: { // along the axis, or parallel to it
            double x = r.coin() ? 0 : rho * (r.dyadic(3) - 0.5), z = inside(r, h);
            double dz = r.coin() ? 1 : -1;
            b.line(through(r, a.at(x, 0, z), a.dir(0, 0, dz)));
            break;
        }
        case 2: // through the cone's apex
            b.line(through(r, a.at(0, 0, h), direction(r, a)));
            break;
        default:
            b.generic(a, {-rho, -rho, -1}, {rho, rho, h + 1});
        }
    }
}

// Closed cylinders A over [0, h1] and B over [h1, h1 + h2], and a closed frustum above B from its
// radius to sigma of it: two shared discs, two shared rims.
void shared_rim(Builder& b, int k, int lines) {
    Rng& r = b.r;
    Axes a = axes(r, k == 0, r.integer(0, 8));
    double rho = radius(r), h1 = r.integer(1, 4), h2 = r.integer(1, 4), h3 = r.integer(1, 4);
    double sigma = 0.25 * r.integer(1, 6);
    b.add("A", cylinder(a, 0, 0, 0, h1, rho, true));
    b.add("B", cylinder(a, 0, 0, h1, h1 + h2, rho, true));
    b.add("F", Frustum{a.at(0, 0, h1 + h2), rho * a.N, a.at(0, 0, h1 + h2 + h3), sigma * rho * a.N,
                       true, true});
    for (int j = 0; j < lines; ++j) {
        double z = r.coin() ? h1 : h1 + h2;
        switch (j % 4) {
        case 0: { // through a point of a shared rim
            int q = r.integer(0, 3);
            double x = q == 0 ? rho : q == 1 ? -rho : 0, y = q == 2 ? rho : q == 3 ? -rho : 0;
            b.line(through(r, a.at(x, y, z), direction(r, a)));
            break;
        }
        case 1: { // across a shared disc
            Vec3 d = r.ivec(3);
            d.z = d.z == 0 ? 1 : d.z;
            double x = rho * (r.dyadic(3) - 0.5), y = rho * (r.dyadic(3) - 0.5);
            b.line(through(r, a.at(x, y, z), a.dir(d.x, d.y, d.z)));
            break;
        }
        case 2: // along the axis
            b.line(through(r, a.at(0, 0, z), a.dir(0, 0, r.coin() ? 1 : -1)));
            break;
        default:
            b.generic(a, {-rho, -rho, -1}, {rho, rho, h1 + h2 + h3 + 1});
        }
    }
}

// An n by n grid of rods of radius 1/64 a unit apart, length 16, 2^k from the origin.
void far_grid(Builder& b, int k, int lines) {
    Rng& r = b.r;
    Axes a = axes(r, r.integer(0, 2) == 0, k);
    int n = r.integer(4, 8);
    double rho = 1.0 / 64, L = 16;
    bool caps = r.coin();
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            b.add("rod-" + std::to_string(i) + "-" + std::to_string(j),
                  cylinder(a, i, j, 0, L, rho, caps));
    for (int m = 0; m < lines; ++m) {
        double row = r.integer(0, n - 1), z = inside(r, L);
        switch (m % 4) {
        case 0: // along a row, through every rod's axis
            b.line(through(r, a.at(-1, row, z), a.dir(16, 0, r.integer(-2, 2))));
            break;
        case 1: // grazing a row: tangent to every rod in it
            b.line(through(r, a.at(-1, row + (r.coin() ? rho : -rho), z), a.dir(1, 0, 0)));
            break;
        case 2: // along the diagonal, through the axes of rods (i, i)
            b.line(through(r, a.at(0, 0, z), a.dir(1, 1, r.integer(-1, 1) * 0.0625)));
            break;
        default: {
            Vec3 d = r.ivec(8);
            d.x = d.x == 0 ? 8 : d.x;
            b.line(through(r, a.at(-1, row + r.dyadic(6), z), a.dir(d.x, d.y, d.z * 0.125)));
        }
        }
    }
}

} // namespace

const char* scene_family_name(SceneFamily f) {
    return names[int(f)];
}

bool parse_scene_family(const std::string& name, SceneFamily* f) {
    for (int i = 0; i < scene_family_count; ++i)
        if (name == names[i]) return *f = SceneFamily(i), true;
    return false;
}

std::vector<Shape> SceneCase::shape_list() const {
    std::vector<Shape> out;
    out.reserve(shapes.size());
    for (const SceneShape& s : shapes)
        out.push_back(s.shape);
    return out;
}

namespace {

// Each built family's difficulty k for scene `index`, and its builder.
struct Built {
    int (*k)(std::uint64_t index);
    void (*build)(Builder&, int k, int lines);
};
const Built built[] = {
    {[](std::uint64_t i) { return 3 * int(i % 14); }, touching}, // offsets to 2^39: still exact
    {[](std::uint64_t i) { return 1 + int(i % 52); }, nested},
    {[](std::uint64_t i) { return int(i % 2); }, coaxial},
    {[](std::uint64_t i) { return int(i % 2); }, shared_rim},
    {[](std::uint64_t i) { return 10 + int(i % 31); }, far_grid},
};
constexpr int built_count = int(std::size(built));

// Rays from the correct scene's nearest hit of a line of a built family's scene, on along the
// line: from spawn_ray's origin, or (from_hit) from the hit point itself. k: that family.
void leaving_hits(Builder& b, SceneFamily f, std::uint64_t seed, std::uint64_t index, int lines) {
    SceneFamily from = SceneFamily(index % built_count);
    SceneCase base = make_scene(from, seed ^ 0x5ca1ab1eull, index / built_count, 2 * lines);
    b.sc.shapes = base.shapes;
    b.sc.header.k = int(from);
    Scene scene(base.shape_list(), SceneSolver::correct);
    SceneAnswer hit;
    for (const SceneLine& l : base.lines) {
        if (int(b.sc.lines.size()) >= lines) break;
        scene.intersect(l.line, {Need::nearest, true}, hit);
        if (!hit.ok() || hit.hits.empty() || !std::isfinite(hit.hits[0].hit.t)) continue;
        if (f == SceneFamily::from_hit) {
            b.line({hit.hits[0].hit.p, l.line.v, Range::ray});
        } else if (SpawnedRay s = scene.spawn_ray(hit.hits[0], l.line.v); s.ok()) {
            b.line(s.line);
        }
    }
}

} // namespace

SceneCase make_scene(SceneFamily f, std::uint64_t seed, std::uint64_t index, int lines) {
    std::uint64_t key = splitmix(seed) ^ splitmix(std::uint64_t(f) * 1000003 + 17);
    Rng r{SplitMix64{splitmix(key ^ splitmix(index))}};
    Builder b{{}, r};
    b.sc.header.family = names[int(f)];
    b.sc.header.id = "\"" + std::string(names[int(f)]) + "/" + std::to_string(index) + "\"";
    if (int(f) < built_count) {
        b.sc.header.k = built[int(f)].k(index);
        built[int(f)].build(b, b.sc.header.k, lines);
    } else {
        leaving_hits(b, f, seed, index, lines);
    }
    return b.sc;
}

} // namespace linequad::audit
