// Case generators. Exact constructions (tangents, lines on the surface, hits at the extent's
// ends) use small-integer frames and dyadic parameters so that every coordinate is computed
// without rounding; the nominal 2^-k perturbations are then applied in double, and the oracle
// decides what the resulting doubles really are.
#include "linequad/families.hpp"

#include "shape_types.hpp"

#include <cmath>
#include <random>
#include <utility>
#include <variant>

namespace linequad {

namespace {

const char* const names[family_count] = {
    "generic",          "near_tangent", "axis_parallel", "apex", "generator",
    "degenerate_frame", "scale",        "extent_edge",   "rim",  "cap_plane",
    "cap_axis",         "inside_start", "two_nappes"};

std::uint64_t splitmix(std::uint64_t x) {
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

struct Rng {
    std::mt19937_64 g;
    double real(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(g); }
    int integer(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(g); }
    bool coin() { return g() & 1; }
    Vec3 vec(double s) { return {real(-s, s), real(-s, s), real(-s, s)}; }
    Vec3 ivec(int s) {
        return {double(integer(-s, s)), double(integer(-s, s)), double(integer(-s, s))};
    }
    double dyadic(int bits) {
        return std::ldexp(double(integer(0, (1 << bits) - 1)), -bits);
    } // [0, 1)
};

// A frame: origin, a, b, c. Every shape is described by one: the cylinder's a, b are
// orthogonal to c = H - C with length r (approximately, when not integer).
struct Frame {
    Vec3 O, a, b, c;
};

bool well_shaped(Vec3 a, Vec3 b, Vec3 c, double ratio) {
    double n = norm(a) * norm(b) * norm(c);
    return n > 0 && std::fabs(dot(a, cross(b, c))) >= ratio * n;
}

Frame random_frame(Rng& r, double scale = 2) {
    for (;;) {
        Frame f{r.vec(4), r.vec(scale), r.vec(scale), r.vec(scale)};
        if (well_shaped(f.a, f.b, f.c, 0.2)) return f;
    }
}

// Small-integer frames: every dyadic combination of them is exact.
Frame integer_frame(Rng& r) {
    for (;;) {
        Frame f{r.ivec(6), r.ivec(4), r.ivec(4), r.ivec(4)};
        if (well_shaped(f.a, f.b, f.c, 0.2)) return f;
    }
}

// An integer frame for the circular cylinder: the axis along a coordinate axis (permuted and
// signed), a and b the other two axes times the integer radius.
Frame integer_circular_frame(Rng& r) {
    int axis = r.integer(0, 2);
    double len = r.integer(1, 12) * (r.coin() ? 1 : -1), radius = r.integer(1, 6);
    Vec3 e[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    Frame f;
    f.O = r.ivec(6);
    f.c = len * e[axis];
    f.a = radius * e[(axis + 1) % 3];
    f.b = radius * e[(axis + 2) % 3];
    return f;
}

// A cylinder frame with a, b orthogonal to c and of equal length (rounded).
Frame circular_from(Vec3 O, Vec3 c, double radius) {
    Vec3 t = std::fabs(c.x) < std::fabs(c.y) ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
    Vec3 a = cross(c, t);
    a = (radius / norm(a)) * a;
    Vec3 b = cross(c, a);
    b = (radius / norm(b)) * b;
    return {O, a, b, c};
}

// What the families need to know of each shape: whether its cross-section is round (its frame
// then has orthogonal a, b of one length, the radius) and whether it is a cone (its local extent
// is -1 <= z <= 0, its radius there |z|, and it has an apex and generators); and how to build it
// on a frame.
template <class S>
struct Sampling;
template <>
struct Sampling<Cylinder> {
    static constexpr bool circular = true, conical = false;
    static Cylinder make(const Frame& f, bool finite) {
        return Cylinder{f.O, f.O + f.c, norm(f.a), finite};
    }
};
template <>
struct Sampling<EllipticCylinder> {
    static constexpr bool circular = false, conical = false;
    static EllipticCylinder make(const Frame& f, bool finite) {
        return EllipticCylinder{f.O, f.a, f.b, f.c, finite};
    }
};
template <>
struct Sampling<EllipticCone> {
    static constexpr bool circular = false, conical = true;
    static EllipticCone make(const Frame& f, bool finite) {
        return EllipticCone{f.O - f.c, f.O, f.a, f.b, finite}; // apex at O, base at O - c
    }
};

template <class S>
Frame frame_for(Rng& r, bool integer) {
    if constexpr (Sampling<S>::circular) {
        if (integer) return integer_circular_frame(r);
        Vec3 c = r.vec(4);
        while (norm(c) < 0.5)
            c = r.vec(4);
        return circular_from(r.vec(4), c, r.real(0.25, 3));
    }
    return integer ? integer_frame(r) : random_frame(r);
}

template <class S>
Shape shape_from(const Frame& f, bool finite = true) {
    return Sampling<S>::make(f, finite);
}

// The cylinder's radius must be a double: integer frames have integer radii, random frames
// use norm(a) rounded, and the surface is then the oracle's business.

// A world point from local coordinates: O + x a + y b + z c (apex frame for the cone).
Vec3 world(const Frame& f, double x, double y, double z) {
    return f.O + x * f.a + y * f.b + z * f.c;
}
Vec3 world_vec(const Frame& f, double x, double y, double z) {
    return x * f.a + y * f.b + z * f.c;
}

// The local extent: cylinders z in [0, 1], the cone z in [-1, 0].
template <class S>
double z_inside(Rng& r) {
    return Sampling<S>::conical ? -r.real(0.1, 0.9) : r.real(0.1, 0.9);
}
template <class S>
double z_dyadic(Rng& r) {
    double z = 0.125 + 0.75 * r.dyadic(6);
    return Sampling<S>::conical ? -z : z;
}
// Radius of the surface at local height z: 1 for cylinders, |z| for the cone.
template <class S>
double radius_at(double z) {
    return Sampling<S>::conical ? std::fabs(z) : 1.0;
}

template <class S>
Line generic_line(Rng& r, const Frame& f) {
    double z = z_inside<S>(r);
    Vec3 target = world(f, r.real(-1, 1) * radius_at<S>(z), r.real(-1, 1) * radius_at<S>(z), z);
    Vec3 from = target + r.vec(8);
    if (r.integer(0, 4) == 0) return {from, r.vec(2)}; // a fifth aim anywhere
    return {from, target - from};
}

template <class S>
Case near_tangent(Rng& r, int k) {
    bool exact = k == 0;
    Frame f = frame_for<S>(r, exact);
    double z = exact ? z_dyadic<S>(r) : z_inside<S>(r);
    double rho = radius_at<S>(z);
    // Touch at local (rho, 0, z) (exact) or at angle theta; the tangent direction lies in the
    // tangent plane: along the circle, plus some of the generator (or the axis).
    double theta = exact ? 0.5 * M_PI * r.integer(0, 3) : r.real(0, 2 * M_PI);
    double cs = std::cos(theta), sn = std::sin(theta);
    if (exact) cs = std::round(cs), sn = std::round(sn);
    double mu = exact ? r.dyadic(3) * (r.coin() ? 1 : -1) : r.real(-1, 1);
    double side = k == 0 ? 1 : 1 + (r.coin() ? 1 : -1) * std::ldexp(1.0, -k);
    Vec3 P = world(f, side * rho * cs, side * rho * sn, z);
    Vec3 d = world_vec(f, -sn, cs, 0);
    if (Sampling<S>::conical)
        d = d + mu * world_vec(f, cs, sn, z < 0 ? -1 : 1); // generator through P
    else
        d = d + mu * f.c;
    Case c;
    c.shape = shape_from<S>(f);
    double back = exact ? 2 : r.real(0.5, 3);
    c.line = {P - back * d, d};
    c.k = k;
    return c;
}

template <class S>
Case axis_parallel(Rng& r, int k) {
    bool on_surface = k == 0 && r.coin();
    Frame f = frame_for<S>(r, on_surface || k == 0);
    double z = k == 0 ? z_dyadic<S>(r) : z_inside<S>(r);
    // k = 0: exactly parallel, inside (radius 1/2), outside (2) or on the surface (1).
    double radius = on_surface ? 1 : (r.coin() ? 0.5 : 2);
    if (Sampling<S>::conical) radius *= std::fabs(z);
    Vec3 P = world(f, radius, 0, z);
    Vec3 d = f.c;
    if (k > 0) d = d + std::ldexp(1.0, -k) * world_vec(f, r.real(-1, 1), r.real(-1, 1), 0);
    Case c;
    c.shape = shape_from<S>(f, r.integer(0, 3) != 0);
    c.line = {P - (on_surface ? 1.0 : r.real(0.5, 2)) * d, d};
    c.k = k;
    return c;
}

template <class S>
Case apex(Rng& r, int k) {
    bool exact = k == 0;
    Frame f = frame_for<S>(r, exact);
    Vec3 d = exact ? world_vec(f, r.integer(-3, 3) * 0.25, r.integer(-3, 3) * 0.25, -1)
                   : world_vec(f, r.real(-2, 2), r.real(-2, 2), -1);
    Vec3 P = f.O;
    if (!exact) P = P + std::ldexp(1.0, -k) * cross(d, r.vec(1)); // 2^-k from the apex
    Case c;
    c.shape = shape_from<S>(f, r.integer(0, 3) != 0);
    c.line = {P - d, d};
    c.k = k;
    return c;
}

template <class S>
Case generator(Rng& r, int k) {
    Frame f = frame_for<S>(r, k == 0);
    // (3/8, 1/2, -5/8) and its sign/axis variants: x^2 + y^2 = z^2 exactly.
    double x = 0.375, y = 0.5;
    if (r.coin()) std::swap(x, y);
    if (r.coin()) x = -x;
    if (r.coin()) y = -y;
    Vec3 d = world_vec(f, x, y, -0.625);
    if (k > 0)
        d = d + std::ldexp(1.0, -k) * world_vec(f, r.real(-1, 1), r.real(-1, 1), r.real(-1, 1));
    Vec3 from =
        world(f, r.real(-0.5, 0.5), r.real(-0.5, 0.5), -r.real(0.2, 0.8)) - r.real(0, 2) * d;
    Case c;
    c.shape = shape_from<S>(f, r.integer(0, 3) != 0);
    c.line = {from, d};
    c.k = k;
    return c;
}

template <class S>
Case degenerate_frame(Rng& r, int k) {
    Frame f = frame_for<S>(r, false);
    double e = std::ldexp(1.0, -k);
    int kind = r.integer(0, 3);
    if (Sampling<S>::circular) kind = kind % 2 + 2; // only thin and flat for a round section
    switch (kind) {
    case 0:
        f.c = f.a + f.b + (e / norm(f.a)) * cross(f.a, f.b);
        break; // nearly singular
    case 1:
        f.c = f.a + e * norm(f.a) * (f.c - (dot(f.c, f.a) / dot(f.a, f.a)) * f.a);
        break;
    case 2:
        f.a = e * f.a, f.b = e * f.b;
        break; // very thin
    default:
        f.c = e * f.c, f.O = e * f.O;
        break; // very flat, near the origin so H - C survives
    }
    if (Sampling<S>::circular) f = circular_from(f.O, f.c, norm(f.a));
    Case c;
    c.shape = shape_from<S>(f);
    c.line = generic_line<S>(r, f);
    c.k = k;
    return c;
}

template <class S>
Case scale(Rng& r, int k) {
    Frame f = frame_for<S>(r, false);
    int exponent = r.coin() ? k : -k;
    double s = std::ldexp(1.0, exponent);
    Line l = generic_line<S>(r, f);
    // Half of the cases: the whole scene scaled by 2^+-k (exact). The other half: a unit
    // shape moved up to 2^50 from the origin, the line's origin with it.
    if (r.coin()) {
        f = {s * f.O, s * f.a, s * f.b, s * f.c};
        l = {s * l.L0, s * l.v};
    } else {
        Vec3 far = std::ldexp(1.0, std::min(k, 50)) * r.vec(1);
        f.O = f.O + far;
        l.L0 = l.L0 + far;
    }
    Case c;
    c.shape = shape_from<S>(f);
    c.line = l;
    c.k = k;
    return c;
}

template <class S>
Case extent_edge(Rng& r, int k) {
    Frame f = frame_for<S>(r, true);
    // A line through a point exactly on the rim (z = 0 or 1, -1 or 0 for the cone's base
    // and... the apex rim is a point) and another surface point, then moved by 2^-k along the
    // axis (k = 0: not moved).
    double z_end = Sampling<S>::conical ? -1 : (r.coin() ? 0 : 1);
    Vec3 P = world(f, 1, 0, z_end);
    double z2 = z_dyadic<S>(r);
    Vec3 Q = world(f, 0, radius_at<S>(z2), z2);
    Vec3 d = Q - P;
    if (k > 0) P = P + (r.coin() ? 1 : -1) * std::ldexp(1.0, -k) * f.c;
    Case c;
    c.shape = shape_from<S>(f);
    c.line = {P - 0.5 * d, d};
    c.k = k;
    return c;
}

// ---- Closed shapes ----

// The shape on f, closed by its discs; the cone with `nappes` nappes.
template <class S>
Shape closed_from(const Frame& f, int nappes) {
    S s = Sampling<S>::make(f, true);
    s.caps = true;
    if constexpr (Sampling<S>::conical) s.nappes = nappes;
    return s;
}

// A closed shape's discs in local z: the cylinders' at 0 and 1, the cone's at -1 (and at 1 with
// two nappes). Both are radius 1.
struct Closed {
    int nappes;
    double base, top;
    bool has_top;
    double middle; // a local z inside the (first) solid
};
template <class S>
Closed closed_kind(Rng& r) {
    if constexpr (Sampling<S>::conical) {
        int n = r.integer(1, 2);
        return {n, -1, 1, n == 2, -0.5};
    }
    return {1, 0, 1, true, 0.5};
}
template <class S>
double end_z(Rng& r, const Closed& k) {
    return k.has_top && r.coin() ? k.top : k.base;
}

// One of the four exact quarter turns: (cos, sin) of 0, 90, 180, 270 degrees.
std::pair<double, double> quarter(Rng& r) {
    static const double c[4] = {1, 0, -1, 0};
    int q = r.integer(0, 3);
    return {c[q], c[(q + 3) % 4]};
}

// x moved by k ulps, up or down (0 by k ulps of 1).
double ulps_moved(double x, int k, bool up) {
    if (x == 0) return (up ? k : -k) * 0x1p-52;
    for (int i = 0; i < k; ++i)
        x = std::nextafter(x, up ? INFINITY : -INFINITY);
    return x;
}

template <class S>
Case rim(Rng& r, int k) {
    Frame f = frame_for<S>(r, true);
    Closed kind = closed_kind<S>(r);
    double z = end_z<S>(r, kind);
    auto [cs, sn] = quarter(r);
    Vec3 P = world(f, cs, sn, z);
    Vec3 d;
    switch (r.integer(0, 2)) {
    case 0: // into the solid, through its middle
        d = world(f, 0.25 * sn, -0.25 * cs, kind.middle) - P;
        break;
    case 1: // across the disc to another point of it
        d = world(f, -0.5 * cs + 0.25 * sn, -0.5 * sn - 0.25 * cs, z) - P;
        break;
    default: // grazing the rim: along the circle, tilted out of the disc's plane
        d = world_vec(f, -sn, cs, r.coin() ? 0.5 : -0.5);
        break;
    }
    if (k > 0) { // the largest coordinate moved (at the origin: by k ulps of 1, not subnormals)
        int i = std::fabs(P.x) >= std::fabs(P.y) ? 0 : 1;
        if (std::fabs(P.z) > std::fabs(P[i])) i = 2;
        double moved = ulps_moved(P[i], k, r.coin());
        (i == 0 ? P.x : i == 1 ? P.y : P.z) = moved;
    }
    Case c;
    c.shape = closed_from<S>(f, kind.nappes);
    c.line = {P - 0.5 * d, d};
    c.k = k;
    return c;
}

template <class S>
Case cap_plane(Rng& r, int k) {
    Frame f = frame_for<S>(r, true);
    Closed kind = closed_kind<S>(r);
    double z = end_z<S>(r, kind);
    auto [cs, sn] = quarter(r);
    // At distance 1/2 (across the disc), 1 (grazing the rim) or 2 (beside it) from the centre,
    // along the circle's tangent there.
    static const double distance[3] = {0.5, 1, 2};
    double rho = distance[r.integer(0, 2)];
    Vec3 P = world(f, rho * cs, rho * sn, z), d = world_vec(f, -sn, cs, 0);
    if (k > 0) {
        double e = (r.coin() ? 1 : -1) * std::ldexp(1.0, -k);
        if (r.coin())
            d = d + e * f.c; // tilted through P
        else
            P = P + e * f.c; // lifted
    }
    Case c;
    c.shape = closed_from<S>(f, kind.nappes);
    c.line = {P - r.real(0.5, 2) * d, d};
    c.k = k;
    return c;
}

template <class S>
Case cap_axis(Rng& r, int k) {
    Frame f = frame_for<S>(r, k == 0);
    Closed kind = closed_kind<S>(r);
    Vec3 P = world(f, 0, 0, kind.middle), d = f.c;
    if (k > 0) {
        Vec3 side = std::ldexp(1.0, -k) * world_vec(f, r.real(-1, 1), r.real(-1, 1), 0);
        if (r.coin())
            d = d + side;
        else
            P = P + side;
    }
    Case c;
    c.shape = closed_from<S>(f, kind.nappes);
    // From inside (s < 1/2 of the way), on a disc or outside, either way along the axis.
    double s = 0.25 * r.integer(-8, 8);
    c.line = {P + s * d, (r.coin() ? 1.0 : -1.0) * d};
    c.k = k;
    return c;
}

template <class S>
Case inside_start(Rng& r, int k) {
    Frame f = frame_for<S>(r, k == 0);
    Closed kind = closed_kind<S>(r);
    double z = z_dyadic<S>(r), rho = radius_at<S>(z);
    auto [cs, sn] = quarter(r);
    Vec3 P;
    switch (r.integer(0, 2)) {
    case 0: // inside
        P = world(f, 0.5 * rho * cs, 0.5 * rho * sn, z);
        break;
    case 1: // on the lateral surface, and 2^-k outside it
        P = world(f, rho * cs, rho * sn, z);
        if (k > 0) P = P + std::ldexp(1.0, -k) * world_vec(f, cs, sn, 0);
        break;
    default: { // on a disc, and 2^-k beyond it
        double e = end_z<S>(r, kind);
        P = world(f, 0.5 * cs, 0.5 * sn, e);
        if (k > 0) P = P + (e == kind.base ? -1 : 1) * std::ldexp(1.0, -k) * f.c;
        break;
    }
    }
    Case c;
    c.shape = closed_from<S>(f, kind.nappes);
    c.line = {P, r.vec(2)};
    c.k = k;
    return c;
}

template <class S>
Case two_nappes(Rng& r, int k) {
    Frame f = frame_for<S>(r, k == 0);
    bool exact = k == 0;
    Shape shape = closed_from<S>(f, 2);
    if (r.coin()) std::visit([](auto& s) { s.caps = false; }, shape);
    Vec3 P, d;
    if (r.coin()) {
        // Through the apex (inside both nappes, outside both, or along a generator), or 2^-k
        // beside it.
        static const double slope[3] = {0.5, 2, 1};
        double m = slope[r.integer(0, 2)];
        auto [cs, sn] = quarter(r);
        d = world_vec(f, m * cs, m * sn, 1);
        P = f.O;
        if (!exact) P = P + std::ldexp(1.0, -k) * world_vec(f, -sn, cs, 0);
    } else {
        // Parallel to the axis at a dyadic distance from it (through both solids: four hits
        // closed), tilted by 2^-k.
        double rho = 0.125 * r.integer(1, 7);
        P = world(f, rho, 0, 0);
        d = f.c;
        if (!exact) d = d + std::ldexp(1.0, -k) * world_vec(f, r.real(-1, 1), r.real(-1, 1), 0);
    }
    Case c;
    c.shape = shape;
    c.line = {P - r.real(0.5, 2) * d, d};
    c.k = k;
    return c;
}

template <class S>
Case make(Family fam, Rng& r, std::uint64_t index) {
    switch (fam) {
    case Family::generic: {
        bool integer = r.integer(0, 9) == 0;
        Frame f = frame_for<S>(r, integer);
        Case c;
        c.shape = shape_from<S>(f, r.integer(0, 4) != 0);
        c.line = generic_line<S>(r, f);
        return c;
    }
    case Family::near_tangent:
        return near_tangent<S>(r, int(index % 61));
    case Family::axis_parallel:
        return axis_parallel<S>(r, int(index % 61));
    case Family::apex:
        return apex<S>(r, int(index % 61));
    case Family::generator:
        return generator<S>(r, int(index % 61));
    case Family::degenerate_frame:
        return degenerate_frame<S>(r, 1 + int(index % 60));
    case Family::scale:
        return scale<S>(r, int(index % 64) * 8);
    case Family::extent_edge:
        return extent_edge<S>(r, index % 3 == 0 ? 0 : 40 + int(index % 14));
    case Family::rim:
        return rim<S>(r, int(index % 17));
    case Family::cap_plane:
        return cap_plane<S>(r, int(index % 61));
    case Family::cap_axis:
        return cap_axis<S>(r, int(index % 61));
    case Family::inside_start:
        return inside_start<S>(r, int(index % 61));
    case Family::two_nappes:
        return two_nappes<S>(r, int(index % 61));
    }
    return {};
}

} // namespace

const char* family_name(Family f) {
    return names[int(f)];
}

bool parse_family(std::string_view name, Family* f) {
    for (int i = 0; i < family_count; ++i)
        if (name == names[i]) return *f = Family(i), true;
    return false;
}

bool family_applies(Family f, int shape) {
    bool conical = with_shape_type(std::size_t(shape), [](auto tag) {
        return Sampling<typename decltype(tag)::type>::conical;
    });
    return (f != Family::apex && f != Family::generator && f != Family::two_nappes) || conical;
}

Case make_case(Family fam, int shape, Range range, std::uint64_t seed, std::uint64_t index) {
    std::uint64_t key =
        splitmix(seed) ^
        splitmix(std::uint64_t(fam) * 1000003 + std::uint64_t(shape) * 101 + std::uint64_t(range));
    Rng r{std::mt19937_64(splitmix(key ^ splitmix(index)))};
    Case c = with_shape_type(std::size_t(shape), [&](auto tag) {
        return make<typename decltype(tag)::type>(fam, r, index);
    });
    c.line.range = range;
    c.family = family_name(fam);
    c.id = "\"" + std::string(family_name(fam)) + "/" + std::to_string(shape) + "/" +
           range_name(range) + "/" + std::to_string(seed) + "/" + std::to_string(index) + "\"";
    return c;
}

} // namespace linequad
