// Case generators. Exact constructions (tangents, lines on the surface, hits at the extent's
// ends) use small-integer frames and dyadic parameters so that every coordinate is computed
// without rounding; the nominal 2^-k perturbations are then applied in double, and the oracle
// decides what the resulting doubles really are.
#include "linequad/families.hpp"

#include "cases/case_maker.hpp"
#include "cases/rng.hpp"
#include "io/shape_types.hpp"

#include <charconv>
#include <cmath>
#include <random>
#include <type_traits>
#include <utility>
#include <variant>

namespace linequad {

namespace {

const char* const names[family_count] = {"generic",    "near_tangent", "axis_parallel",
                                         "apex",       "generator",    "degenerate_frame",
                                         "scale",      "extent_edge",  "rim",
                                         "cap_plane",  "cap_axis",     "inside_start",
                                         "two_nappes", "far_origin",   "through_centre",
                                         "thin",       "seam",         "poles"};
const char* const frame_names[4] = {"any", "circular", "axis", "aligned"};

// A frame: origin, a, b, c, and the shape's profile in it: points O + x a + y b + z c, the
// extent z0 <= z <= z0 + 1, and the surface's radius at z, |rho0 + (rho1 - rho0)(z - z0)| (the
// cylinders 1; the cone |z|, z0 = -1; a frustum rho0 at its base, rho1 at its top). `round`: a
// and b orthogonal to c and of one length (the circular shapes' radius unit).
struct Frame {
    Vec3 O, a, b, c;
    double z0 = 0, rho0 = 1, rho1 = 1;
    bool round = false;
    bool aligned = false; // a, b, c along coordinate axes (kept so by the families)
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

// A round frame along a coordinate axis (permuted and signed).
Frame axis_frame(Vec3 O, int axis, double length, double radius) {
    Vec3 e[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    return {O,   radius * e[(axis + 1) % 3], radius * e[(axis + 2) % 3], length * e[axis], 0, 1, 1,
            true};
}

// A round integer frame: along a coordinate axis, or turned by the rotation of an integer
// quaternion q, whose matrix times N = |q|^2 is an integer matrix with orthogonal columns of
// length N (so the radius N times an integer is exact too).
Frame integer_round_frame(Rng& r, bool axis_aligned) {
    double len = r.integer(1, 12) * (r.coin() ? 1 : -1), radius = r.integer(1, 6);
    Vec3 O = r.ivec(6);
    if (axis_aligned || r.coin()) return axis_frame(O, r.integer(0, 2), len, radius);
    IntegerRotation q = integer_rotation(r);
    len = std::copysign(r.integer(1, 3), len), radius = r.integer(1, 3);
    return {O, radius * q.col[0], radius * q.col[1], len * q.col[2], 0, 1, 1, true};
}

// A frame along the coordinate axes whose section is elliptic: semi-axes of distinct lengths
// (integers in an integer frame, so that the constructions stay exact).
Frame aligned_elliptic_frame(Rng& r, bool integer) {
    int axis = r.integer(0, 2);
    Vec3 e[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    double sign = r.coin() ? 1 : -1, ra, rb, len;
    Vec3 O;
    if (integer) {
        ra = r.integer(1, 6), rb = r.integer(1, 5), len = sign * r.integer(1, 12);
        if (rb >= ra) rb += 1; // distinct
        O = r.ivec(6);
    } else {
        ra = r.real(0.25, 3), rb = ra * r.real(0.3, 0.8), len = sign * r.real(0.5, 4);
        if (r.coin()) std::swap(ra, rb);
        O = r.vec(4);
    }
    Frame f{O, ra * e[(axis + 1) % 3], rb * e[(axis + 2) % 3], len * e[axis], 0, 1, 1, false};
    f.aligned = true;
    return f;
}

// A round frame on the axis c with a, b of length `radius` (rounded).
Frame circular_from(Vec3 O, Vec3 c, double radius) {
    Vec3 t = std::fabs(c.x) < std::fabs(c.y) ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
    Vec3 a = cross(c, t);
    a = (radius / norm(a)) * a;
    Vec3 b = cross(c, a);
    b = (radius / norm(b)) * b;
    return {O, a, b, c, 0, 1, 1, true};
}

Frame random_round_frame(Rng& r, bool axis_aligned) {
    if (axis_aligned)
        return axis_frame(r.vec(4), r.integer(0, 2), r.real(0.5, 4) * (r.coin() ? 1 : -1),
                          r.real(0.25, 3));
    Vec3 c = r.vec(4);
    while (norm(c) < 0.5)
        c = r.vec(4);
    return circular_from(r.vec(4), c, r.real(0.25, 3));
}

// The profile a family asks of a frustum: any, one with an apex (a zero radius), or one whose
// radii differ (it has generators).
enum class Profile { any, apex, slanted };

// A frustum's radii in units of the frame's radius: unequal, an apex at one end, nearly equal,
// equal (a cylinder) or one tiny; in integer frames, dyadics of two bits (so that every
// construction stays exact).
void frustum_profile(Rng& r, Frame& f, bool integer, Profile want) {
    double rho0, rho1;
    int kind = want == Profile::apex ? 1 : r.integer(0, want == Profile::slanted ? 3 : 4);
    if (integer) {
        rho0 = 0.25 * r.integer(2, 8);
        switch (kind) {
        case 1:
            rho1 = 0;
            break;
        case 4:
            rho1 = rho0;
            break;
        default:
            do
                rho1 = 0.25 * r.integer(1, 8);
            while (rho1 == rho0);
        }
    } else {
        rho0 = r.real(0.25, 2);
        switch (kind) {
        case 1:
            rho1 = 0;
            break;
        case 2:
            rho1 = rho0 * (1 + (r.coin() ? 1 : -1) * std::ldexp(1.0, -r.integer(1, 52)));
            break;
        case 3:
            rho1 = rho0 * std::ldexp(1.0, -r.integer(1, 60));
            break;
        case 4:
            rho1 = rho0;
            break;
        default:
            rho1 = r.real(0.25, 2);
        }
    }
    if (r.coin()) std::swap(rho0, rho1);
    f.z0 = 0, f.rho0 = rho0, f.rho1 = rho1;
}

// What the families need to know of each shape: whether its cross-section is round, whether it
// can have an apex and generators, its profile in a frame, and how to build it on a frame.
template <class S>
struct Sampling;
template <>
struct Sampling<Cylinder> {
    static constexpr bool round = true, conical = false;
    static void profile(Rng&, Frame&, bool, Profile) {}
    static Cylinder make(const Frame& f, bool finite) {
        return Cylinder{f.O, f.O + f.c, norm(f.a), finite};
    }
};
template <>
struct Sampling<EllipticCylinder> {
    static constexpr bool round = false, conical = false;
    static void profile(Rng&, Frame&, bool, Profile) {}
    static EllipticCylinder make(const Frame& f, bool finite) {
        return EllipticCylinder{f.O, f.a, f.b, f.c, finite};
    }
};
template <>
struct Sampling<EllipticCone> {
    static constexpr bool round = false, conical = true;
    static void profile(Rng&, Frame& f, bool, Profile) { f.z0 = -1, f.rho0 = 1, f.rho1 = 0; }
    static EllipticCone make(const Frame& f, bool finite) {
        return EllipticCone{f.O - f.c, f.O, f.a, f.b, finite}; // apex at O, base at O - c
    }
};
template <>
struct Sampling<Frustum> {
    static constexpr bool round = true, conical = true;
    static void profile(Rng& r, Frame& f, bool integer, Profile want) {
        frustum_profile(r, f, integer, want);
    }
    static Frustum make(const Frame& f, bool finite) {
        double radius = norm(f.a);
        return Frustum{f.O, f.rho0 * radius, f.O + f.c, f.rho1 * radius, finite};
    }
};

// A frame for the shape S: round when S or the frames asked for are, the shape's profile in it.
template <class S>
Frame frame_for(Rng& r, bool integer, Frames frames, Profile want = Profile::any) {
    Frame f;
    if (frames == Frames::aligned && !Sampling<S>::round) {
        f = aligned_elliptic_frame(r, integer);
    } else if (Sampling<S>::round || frames != Frames::any) {
        bool axis_aligned = frames == Frames::axis || frames == Frames::aligned;
        f = integer ? integer_round_frame(r, axis_aligned) : random_round_frame(r, axis_aligned);
    } else {
        f = integer ? integer_frame(r) : random_frame(r);
    }
    Sampling<S>::profile(r, f, integer, want);
    return f;
}

template <class S>
Shape shape_from(const Frame& f, bool finite = true) {
    return Sampling<S>::make(f, finite);
}

// The circular shapes' radii must be doubles: integer frames have integer radii, random frames
// use norm(a) rounded, and the surface is then the oracle's business.

// A world point from local coordinates: O + x a + y b + z c (apex frame for the cone).
Vec3 world(const Frame& f, double x, double y, double z) {
    return f.O + x * f.a + y * f.b + z * f.c;
}
Vec3 world_vec(const Frame& f, double x, double y, double z) {
    return x * f.a + y * f.b + z * f.c;
}

// Local heights inside the extent, and at dyadics there.
double z_inside(Rng& r, const Frame& f) {
    return f.z0 + r.real(0.1, 0.9);
}
double z_dyadic(Rng& r, const Frame& f) {
    return f.z0 + 0.125 + 0.75 * r.dyadic(6);
}
// The surface's radius at local height z, and its slope d rho / dz.
double slope(const Frame& f) {
    return f.rho1 - f.rho0;
}
double radius_at(const Frame& f, double z) {
    return std::fabs(f.rho0 + slope(f) * (z - f.z0));
}
// The local height of the apex (where the radius is 0); only for a slanted profile.
double apex_z(const Frame& f) {
    return f.z0 + f.rho0 / (f.rho0 - f.rho1);
}

Line generic_line(Rng& r, const Frame& f) {
    double z = z_inside(r, f), rho = radius_at(f, z);
    Vec3 target = world(f, r.real(-1, 1) * rho, r.real(-1, 1) * rho, z);
    Vec3 from = target + r.vec(8);
    if (r.integer(0, 4) == 0) return {from, r.vec(2)}; // a fifth aim anywhere
    return {from, target - from};
}

template <class S>
Case near_tangent(Rng& r, int k, Frames frames) {
    bool exact = k == 0;
    Frame f = frame_for<S>(r, exact, frames);
    double z = exact ? z_dyadic(r, f) : z_inside(r, f);
    double rho = radius_at(f, z);
    // Touch at local (rho, 0, z) (exact) or at angle theta; the tangent direction lies in the
    // tangent plane: along the circle, plus some of the generator (local (m cos, m sin, 1) for
    // the slope m; the axis for the cylinders).
    double theta = exact ? 0.5 * M_PI * r.integer(0, 3) : r.real(0, 2 * M_PI);
    double cs = std::cos(theta), sn = std::sin(theta);
    if (exact) cs = std::round(cs), sn = std::round(sn);
    double mu = exact ? r.dyadic(3) * (r.coin() ? 1 : -1) : r.real(-1, 1);
    double side = k == 0 ? 1 : 1 + (r.coin() ? 1 : -1) * std::ldexp(1.0, -k);
    Vec3 P = world(f, side * rho * cs, side * rho * sn, z);
    Vec3 d = world_vec(f, -sn, cs, 0) + mu * world_vec(f, slope(f) * cs, slope(f) * sn, 1);
    Case c;
    c.shape = shape_from<S>(f);
    double back = exact ? 2 : r.real(0.5, 3);
    c.line = {P - back * d, d};
    c.k = k;
    return c;
}

template <class S>
Case axis_parallel(Rng& r, int k, Frames frames) {
    bool on_surface = k == 0 && r.coin();
    Frame f = frame_for<S>(r, on_surface || k == 0, frames);
    double z = k == 0 ? z_dyadic(r, f) : z_inside(r, f);
    // k = 0: exactly parallel, inside (radius 1/2), outside (2) or on the surface (1).
    double radius = (on_surface ? 1 : (r.coin() ? 0.5 : 2)) * radius_at(f, z);
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
Case apex(Rng& r, int k, Frames frames) {
    bool exact = k == 0;
    Frame f = frame_for<S>(r, exact, frames, Profile::apex);
    // Towards the shape from its apex, inside the cone of its generators (slope m) or outside.
    double za = apex_z(f), m = std::fabs(slope(f)), into = za > f.z0 + 0.5 ? -1 : 1;
    Vec3 d = exact ? world_vec(f, m * r.integer(-3, 3) * 0.25, m * r.integer(-3, 3) * 0.25, into)
                   : world_vec(f, m * r.real(-2, 2), m * r.real(-2, 2), into);
    Vec3 P = world(f, 0, 0, za);
    if (!exact) P = P + std::ldexp(1.0, -k) * cross(d, r.vec(1)); // 2^-k from the apex
    Case c;
    c.shape = shape_from<S>(f, r.integer(0, 3) != 0);
    c.line = {P - d, d};
    c.k = k;
    return c;
}

template <class S>
Case generator(Rng& r, int k, Frames frames) {
    Frame f = frame_for<S>(r, k == 0, frames, Profile::slanted);
    // m (3/8, 1/2) and its sign/axis variants over -5/8: x^2 + y^2 = (m z)^2 exactly.
    double x = 0.375, y = 0.5, m = slope(f);
    if (r.coin()) std::swap(x, y);
    if (r.coin()) x = -x;
    if (r.coin()) y = -y;
    Vec3 d = world_vec(f, m * x, m * y, -0.625);
    if (k > 0)
        d = d + std::ldexp(1.0, -k) * world_vec(f, r.real(-1, 1), r.real(-1, 1), r.real(-1, 1));
    double z = f.z0 + r.real(0.2, 0.8), rho = radius_at(f, z);
    Vec3 from = world(f, rho * r.real(-0.5, 0.5), rho * r.real(-0.5, 0.5), z) - r.real(0, 2) * d;
    Case c;
    c.shape = shape_from<S>(f, r.integer(0, 3) != 0);
    c.line = {from, d};
    c.k = k;
    return c;
}

template <class S>
Case degenerate_frame(Rng& r, int k, Frames frames) {
    Frame f = frame_for<S>(r, false, frames);
    double e = std::ldexp(1.0, -k);
    int kind = r.integer(0, 3);
    // Only thin and flat for a round section, or one along the axes (what keeps it so).
    if (f.round || f.aligned) kind = kind % 2 + 2;
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
    if (f.round) {
        Frame g = circular_from(f.O, f.c, norm(f.a));
        f.a = g.a, f.b = g.b;
    }
    Case c;
    c.shape = shape_from<S>(f);
    c.line = generic_line(r, f);
    c.k = k;
    return c;
}

template <class S>
Case scale(Rng& r, int k, Frames frames, Precision p) {
    Frame f = frame_for<S>(r, false, frames);
    int exponent = r.coin() ? k : -k;
    double s = std::ldexp(1.0, exponent);
    Line l = generic_line(r, f);
    // Half of the cases: the whole scene scaled by 2^+-k (exact). The other half: a unit
    // shape moved up to 2^50 from the origin (2^24 in float, where its size is then an ulp), the
    // line's origin with it.
    if (r.coin()) {
        f.O = s * f.O, f.a = s * f.a, f.b = s * f.b, f.c = s * f.c;
        l = {s * l.L0, s * l.v};
    } else {
        Vec3 far = std::ldexp(1.0, std::min(k, p == Precision::binary32 ? 24 : 50)) * r.vec(1);
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
Case extent_edge(Rng& r, int k, Frames frames) {
    Frame f = frame_for<S>(r, true, frames);
    // A line through a point exactly on a rim (an end whose radius is not 0: an apex is a
    // point) and another surface point, then moved by 2^-k along the axis (k = 0: not moved).
    double z_end = f.z0 + (r.coin() ? 0 : 1);
    if (radius_at(f, z_end) == 0) z_end = 2 * f.z0 + 1 - z_end;
    Vec3 P = world(f, radius_at(f, z_end), 0, z_end);
    double z2 = z_dyadic(r, f);
    Vec3 Q = world(f, 0, radius_at(f, z2), z2);
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
    if constexpr (std::is_same_v<S, EllipticCone>) s.nappes = nappes;
    return s;
}

// A closed shape's discs in local z: its ends whose radius is not 0 (the cone's base at -1, and
// its top at 1 with two nappes; an apex has no disc), and a height inside its (first) solid.
struct Closed {
    int nappes = 1;
    double ends[2];
    int discs = 0;
    double middle;
    bool has_disc(double z) const {
        return (discs > 0 && ends[0] == z) || (discs > 1 && ends[1] == z);
    }
};
template <class S>
Closed closed_kind(Rng& r, const Frame& f) {
    Closed k;
    if constexpr (std::is_same_v<S, EllipticCone>) k.nappes = r.integer(1, 2);
    double top = k.nappes == 2 ? 1 : f.z0 + 1;
    for (double z : {f.z0, top})
        if (radius_at(f, z) != 0) k.ends[k.discs++] = z;
    k.middle = f.z0 + 0.5;
    return k;
}
// One of the discs, and its radius.
double end_z(Rng& r, const Closed& k) {
    return k.discs > 1 && r.coin() ? k.ends[1] : k.ends[0];
}
bool is_base(const Closed& k, double z) {
    return z == k.ends[0] && z < k.middle;
}

template <class S>
Case rim(Rng& r, int k, Frames frames, Precision p) {
    Frame f = frame_for<S>(r, true, frames);
    Closed kind = closed_kind<S>(r, f);
    double z = end_z(r, kind), rho = radius_at(f, z), mid = radius_at(f, kind.middle);
    auto [cs, sn] = quarter(r);
    Vec3 P = world(f, rho * cs, rho * sn, z);
    Vec3 d;
    switch (r.integer(0, 2)) {
    case 0: // into the solid, through its middle
        d = world(f, 0.25 * mid * sn, -0.25 * mid * cs, kind.middle) - P;
        break;
    case 1: // across the disc to another point of it
        d = world(f, rho * (-0.5 * cs + 0.25 * sn), rho * (-0.5 * sn - 0.25 * cs), z) - P;
        break;
    default: // grazing the rim: along the circle, tilted out of the disc's plane
        d = world_vec(f, -sn, cs, r.coin() ? 0.5 : -0.5);
        break;
    }
    if (k > 0) { // the largest coordinate moved (at the origin: by k ulps of 1, not subnormals)
        int i = std::fabs(P.x) >= std::fabs(P.y) ? 0 : 1;
        if (std::fabs(P.z) > std::fabs(P[i])) i = 2;
        double moved = ulps_moved(P[i], k, r.coin(), p);
        (i == 0 ? P.x : i == 1 ? P.y : P.z) = moved;
    }
    Case c;
    c.shape = closed_from<S>(f, kind.nappes);
    c.line = {P - 0.5 * d, d};
    c.k = k;
    return c;
}

template <class S>
Case cap_plane(Rng& r, int k, Frames frames) {
    Frame f = frame_for<S>(r, true, frames);
    Closed kind = closed_kind<S>(r, f);
    double z = end_z(r, kind);
    auto [cs, sn] = quarter(r);
    // At 1/2 the disc's radius (across the disc), its radius (grazing the rim) or twice it
    // (beside it) from the centre, along the circle's tangent there.
    static const double distance[3] = {0.5, 1, 2};
    double rho = distance[r.integer(0, 2)] * radius_at(f, z);
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
Case cap_axis(Rng& r, int k, Frames frames) {
    Frame f = frame_for<S>(r, k == 0, frames);
    Closed kind = closed_kind<S>(r, f);
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
Case inside_start(Rng& r, int k, Frames frames) {
    Frame f = frame_for<S>(r, k == 0, frames);
    Closed kind = closed_kind<S>(r, f);
    double z = z_dyadic(r, f), rho = radius_at(f, z);
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
        double e = end_z(r, kind), half = 0.5 * radius_at(f, e);
        P = world(f, half * cs, half * sn, e);
        if (k > 0) P = P + (is_base(kind, e) ? -1 : 1) * std::ldexp(1.0, -k) * f.c;
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
Case two_nappes(Rng& r, int k, Frames frames) {
    Frame f = frame_for<S>(r, k == 0, frames);
    bool exact = k == 0;
    Shape shape = closed_from<S>(f, 2);
    if (r.coin()) std::get<S>(shape).caps = false;
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
Case far_origin(Rng& r, int k, Frames frames, Precision p) {
    Frame f = frame_for<S>(r, false, frames);
    // The shape's size, which the ray's origin is 2^k of away: its frame's longest axis.
    double size = std::max({norm(f.a), norm(f.b), norm(f.c)});
    double z = z_inside(r, f), rho = radius_at(f, z);
    double theta = r.real(0, 2 * M_PI), cs = std::cos(theta), sn = std::sin(theta);
    Vec3 target, d;
    switch (r.integer(0, 2)) {
    case 0: { // aimed through the shape, from any direction
        target = world(f, r.real(-0.7, 0.7) * rho, r.real(-0.7, 0.7) * rho, z);
        d = r.vec(1);
        break;
    }
    default: { // along the surface's tangent plane: 2^-m of the radius inside, or just past it
        bool past = r.coin();
        double side = past ? 1 + r.real(0.001, 0.1) : 1 - std::ldexp(1.0, -r.integer(1, 30));
        target = world(f, side * rho * cs, side * rho * sn, z);
        d = world_vec(f, -sn, cs, 0) +
            r.real(-1, 1) * world_vec(f, slope(f) * cs, slope(f) * sn, 1);
        break;
    }
    }
    while (norm(d) == 0)
        d = r.vec(1);
    Vec3 from = target - (std::ldexp(size, k) / norm(d)) * d;
    // Half of the cases: the whole scene moved far from the world origin too (within float's
    // reach for a float case), by 2^j shape sizes, j from 10 to k.
    if (r.coin()) {
        int j = r.integer(10, std::max(10, std::min(k, p == Precision::binary32 ? 20 : 40)));
        Vec3 far = std::ldexp(size, j) * r.vec(1);
        f.O = f.O + far, target = target + far, from = from + far;
    }
    Case c;
    c.shape = shape_from<S>(f, r.integer(0, 3) != 0);
    // The shape at t = 2/3 of the segment: a segment (0 <= t <= 1) reaches past it.
    c.line = {from, 1.5 * (target - from)};
    c.k = k;
    return c;
}

// The family's difficulty for case `index`: 2^-k offsets up to 2^-60 in double, 2^-24 in float
// (beyond, a float offset is lost in the rounding of the case); the scale family's 2^+-k within
// each format's range; the rim's and the seam's k in ulps of the case's own format.
int difficulty(Family fam, std::uint64_t index, Precision p) {
    bool single = p == Precision::binary32;
    int steps = single ? 25 : 61; // k = 0 .. 24 or 0 .. 60
    switch (fam) {
    case Family::generic:
        return 0;
    case Family::degenerate_frame:
    case Family::thin:
        return 1 + int(index % std::uint64_t(steps - 1));
    case Family::scale:
        return int(index % (single ? 16 : 64)) * 8;
    case Family::extent_edge:
        if (index % 3 == 0) return 0;
        return single ? 14 + int(index % 11) : 40 + int(index % 14);
    case Family::rim:
    case Family::seam:
        return int(index % 17);
    case Family::far_origin: // the ray's origin 2^k shape sizes away
        return 10 + int(index % (single ? 15 : 31));
    default:
        return int(index % std::uint64_t(steps));
    }
}

// The shapes with an axis: every family on a frame and a profile.
template <class S>
Case axial_case(Family fam, Rng& r, int k, Frames frames, Precision p) {
    switch (fam) {
    case Family::generic: {
        bool integer = r.integer(0, 9) == 0;
        Frame f = frame_for<S>(r, integer, frames);
        Case c;
        c.shape = shape_from<S>(f, r.integer(0, 4) != 0);
        c.line = generic_line(r, f);
        return c;
    }
    case Family::near_tangent:
        return near_tangent<S>(r, k, frames);
    case Family::axis_parallel:
        return axis_parallel<S>(r, k, frames);
    case Family::apex:
        return apex<S>(r, k, frames);
    case Family::generator:
        return generator<S>(r, k, frames);
    case Family::degenerate_frame:
        return degenerate_frame<S>(r, k, frames);
    case Family::scale:
        return scale<S>(r, k, frames, p);
    case Family::extent_edge:
        return extent_edge<S>(r, k, frames);
    case Family::rim:
        return rim<S>(r, k, frames, p);
    case Family::cap_plane:
        return cap_plane<S>(r, k, frames);
    case Family::cap_axis:
        return cap_axis<S>(r, k, frames);
    case Family::inside_start:
        return inside_start<S>(r, k, frames);
    case Family::two_nappes:
        return two_nappes<S>(r, k, frames);
    case Family::far_origin:
        return far_origin<S>(r, k, frames, p);
    default:
        break;
    }
    return {};
}

// apex and generator: the shapes with generators; two_nappes: the cone; the closed solids'
// own families: none of them.
template <class S>
bool axial_applies(Family f) {
    switch (f) {
    case Family::apex:
    case Family::generator:
        return Sampling<S>::conical;
    case Family::two_nappes:
        return std::is_same_v<S, EllipticCone>;
    case Family::through_centre:
    case Family::thin:
    case Family::seam:
    case Family::poles:
        return false;
    default:
        return true;
    }
}

} // namespace

double ulps_moved(double x, int k, bool up, Precision p) {
    bool single = p == Precision::binary32;
    if (x == 0) return (up ? k : -k) * (single ? 0x1p-23 : 0x1p-52);
    for (int i = 0; i < k; ++i)
        x = single ? std::nextafter(float(x), up ? INFINITY : -INFINITY)
                   : std::nextafter(x, up ? INFINITY : -INFINITY);
    return x;
}

#define LINEQUAD_AXIAL_CASES(S)                                                                    \
    template <>                                                                                    \
    bool CaseMaker<S>::applies(Family f) {                                                         \
        return axial_applies<S>(f);                                                                \
    }                                                                                              \
    template <>                                                                                    \
    Case CaseMaker<S>::make(Family f, Rng& r, int k, Frames frames, Precision p) {                 \
        return axial_case<S>(f, r, k, frames, p);                                                  \
    }
LINEQUAD_AXIAL_CASES(Cylinder)
LINEQUAD_AXIAL_CASES(EllipticCylinder)
LINEQUAD_AXIAL_CASES(EllipticCone)
LINEQUAD_AXIAL_CASES(Frustum)
#undef LINEQUAD_AXIAL_CASES

const char* family_name(Family f) {
    return names[int(f)];
}

bool parse_family(std::string_view name, Family* f) {
    for (int i = 0; i < family_count; ++i)
        if (name == names[i]) return *f = Family(i), true;
    return false;
}

const char* frames_name(Frames f) {
    return frame_names[int(f)];
}

bool parse_frames(std::string_view name, Frames* f) {
    for (int i = 0; i < 4; ++i)
        if (name == frame_names[i]) return *f = Frames(i), true;
    return false;
}

std::vector<std::string> family_names() {
    std::vector<std::string> out;
    for (int f = 0; f < family_count; ++f)
        out.emplace_back(family_name(Family(f)));
    return out;
}

std::vector<std::string> shape_names() {
    std::vector<std::string> out;
    for (std::size_t s = 0; s < shape_count; ++s)
        out.emplace_back(shape_name_at(s));
    return out;
}

int shape_named(std::string_view name) {
    std::size_t i = shape_index(name);
    return i < shape_count ? int(i) : -1;
}

bool family_applies(Family f, int shape) {
    return with_shape_type(std::size_t(shape), [&](auto tag) {
        return CaseMaker<typename decltype(tag)::type>::applies(f);
    });
}

Case make_case(Family fam, int shape, Range range, std::uint64_t seed, std::uint64_t index,
               Frames frames, Precision precision) {
    std::uint64_t key =
        splitmix(seed) ^
        splitmix(std::uint64_t(fam) * 1000003 + std::uint64_t(shape) * 101 + std::uint64_t(range));
    Rng r{SplitMix64{splitmix(key ^ splitmix(index))}};
    int k = difficulty(fam, index, precision);
    Case c = with_shape_type(std::size_t(shape), [&](auto tag) {
        return CaseMaker<typename decltype(tag)::type>::make(fam, r, k, frames, precision);
    });
    c.k = k;
    c.line.range = range;
    // A binary32 case: every input rounded to the nearest float. The exact constructions (small
    // integers, dyadics of a few bits) are floats already and stay exact; the rest is a float
    // case near the double one, which the oracle decides as it is.
    if (precision == Precision::binary32) {
        c.shape = rounded_to_binary32(c.shape);
        c.line = rounded_to_binary32(c.line);
        c.precision = precision;
    }
    c.family = family_name(fam);
    // "family/shape/range/seed/index[/frames][/binary32]", built in place: one allocation per
    // case, not one per piece (the audit makes a case for every one it grades).
    std::string& id = c.id;
    id.clear();
    id.reserve(80);
    auto number = [&id](std::uint64_t v) {
        char digits[24];
        id.append(digits, std::to_chars(digits, digits + sizeof digits, v).ptr);
    };
    id.append("\"").append(family_name(fam)).append("/");
    number(std::uint64_t(shape));
    id.append("/").append(range_name(range)).append("/");
    number(seed);
    id.append("/");
    number(index);
    if (frames != Frames::any) id.append("/").append(frames_name(frames));
    if (precision == Precision::binary32) id.append("/binary32");
    id.append("\"");
    return c;
}

} // namespace linequad
