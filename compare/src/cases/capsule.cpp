// The capsule's cases. A frame: the base centre C, the axis h = H - C and two radial vectors a, b
// orthogonal to it, of the radius's length. Exact constructions use integer frames along a
// coordinate axis or turned by an integer quaternion, with |h| a power of two times the rotation's
// scale, so that the poles C - r h / |h| and H + r h / |h|, the seam circles and the lateral
// surface's points at dyadic heights are exact; the 2^-k offsets are applied in double and the
// oracle decides what the resulting doubles really are.
#include "cases/solids.hpp"

#include <algorithm>
#include <cmath>

namespace linequad {

namespace {

struct CapsuleFrame {
    Vec3 C, a, b, h;
    double r; // |a| = |b|
    // The point at height z along the axis (0 at C, 1 at H), (x, y) across it in units of r.
    Vec3 at(double x, double y, double z) const { return C + x * a + y * b + z * h; }
    Vec3 along(double x, double y, double z) const { return x * a + y * b + z * h; }
    // The height of r along the axis: the poles are at -pole and 1 + pole.
    double pole() const { return r / norm(h); }
    double size() const { return std::max(norm(h), r); }
};

CapsuleFrame capsule_frame(Rng& r, bool exact, Frames frames) {
    bool axis_aligned = frames == Frames::axis || frames == Frames::aligned;
    if (exact) {
        double radius = r.integer(1, 4), length = std::ldexp(1.0, r.integer(0, 2));
        Vec3 C = r.ivec(6);
        if (axis_aligned || r.coin()) {
            int i = r.integer(0, 2);
            Vec3 e[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
            double sign = r.coin() ? 1 : -1;
            return {C, radius * e[(i + 1) % 3], radius * e[(i + 2) % 3], sign * length * e[i],
                    radius};
        }
        IntegerRotation q = integer_rotation(r);
        return {C, radius * q.col[0], radius * q.col[1], length * q.col[2], radius * q.N};
    }
    double radius = r.real(0.25, 2), length = r.real(0.5, 4);
    Vec3 C = r.vec(4);
    Vec3 c = axis_aligned ? Vec3{0, 0, r.coin() ? 1.0 : -1.0} : solids::unit_vector(r);
    Vec3 t = std::fabs(c.x) < 0.5 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
    Vec3 a = cross(c, t);
    a = (1 / norm(a)) * a;
    Vec3 b = cross(c, a);
    return {C, radius * a, radius * b, length * c, radius};
}

Vec3 in_format(Vec3 x, Precision p) {
    if (p == Precision::binary64) return x;
    return {double(float(x.x)), double(float(x.y)), double(float(x.z))};
}

Shape capsule_of(const CapsuleFrame& f) {
    return Capsule{f.C, f.C + f.h, f.r};
}

// A point inside the solid: within 0.9 r of the axis segment, on either round end or between.
Vec3 inside(Rng& r, const CapsuleFrame& f) {
    double z = r.real(-0.8 * f.pole(), 1 + 0.8 * f.pole());
    double reach = z < 0   ? std::sqrt(std::max(0.0, 1 - std::pow(z / f.pole(), 2)))
                   : z > 1 ? std::sqrt(std::max(0.0, 1 - std::pow((z - 1) / f.pole(), 2)))
                           : 1.0;
    double rho = 0.9 * reach * r.real(0, 1), phi = r.real(0, 2 * M_PI);
    return f.at(rho * std::cos(phi), rho * std::sin(phi), z);
}

// What a family's line is drawn from: the random source, the frame (which a family may reshape),
// the case's k, whether it is an exact construction, a quarter-turn direction (cs, sn) across the
// axis, and the case's format.
struct Draw {
    Rng& r;
    CapsuleFrame& f;
    int k;
    bool exact;
    double cs, sn;
    Precision p;
};

Line generic_line(const Draw& draw) {
    auto& [r, f, k, exact, cs, sn, p] = draw;
    Vec3 target = inside(r, f), from = target + f.size() * r.vec(4);
    return r.integer(0, 4) == 0 ? Line{from, r.vec(2)} : Line{from, target - from};
}

Line near_tangent_line(const Draw& draw) {
    auto& [r, f, k, exact, cs, sn, p] = draw;
    // Touching the side (along its tangent plane, not along the axis) or a pole (across the
    // axis), or 2^-k inside or outside that.
    double side = exact ? 1 : 1 + (r.coin() ? 1 : -1) * std::ldexp(1.0, -k);
    Vec3 P, d;
    if (r.coin()) {
        double z = exact ? 0.125 + 0.75 * r.dyadic(3) : r.real(0.1, 0.9);
        P = f.at(side * cs, side * sn, z);
        d = f.along(-sn, cs, 0) + (exact ? 0.25 * r.integer(-4, 4) : r.real(-1, 1)) * f.h;
    } else {
        bool top = r.coin();
        double z = top ? 1 + side * f.pole() : -side * f.pole();
        P = f.at(0, 0, z);
        d = f.along(cs + 0.5 * sn, sn - 0.5 * cs, 0);
    }
    return {P - (exact ? 2.0 : r.real(0.5, 3)) * d, d};
}

// The radius 2^-k of the length, or the length 2^-k of the radius.
Line thin_line(const Draw& draw) {
    auto& [r, f, k, exact, cs, sn, p] = draw;
    double e = std::ldexp(1.0, -k);
    if (r.coin()) {
        f.a = e * f.a, f.b = e * f.b, f.r = e * f.r;
    } else {
        // No shorter than the case's format holds apart from C: H = C is no capsule.
        while (e < 1 && in_format(f.C + e * f.h, p) == in_format(f.C, p))
            e *= 2;
        f.h = e * f.h;
    }
    Vec3 target = inside(r, f), from = target + f.size() * r.vec(4);
    return {from, target - from};
}

Line scale_line(const Draw& draw) {
    auto& [r, f, k, exact, cs, sn, p] = draw;
    Vec3 target = inside(r, f), from = target + f.size() * r.vec(4);
    Line l{from, target - from};
    double s = std::ldexp(1.0, r.coin() ? k : -k);
    if (r.coin()) {
        f = {s * f.C, s * f.a, s * f.b, s * f.h, s * f.r};
        l = {s * l.L0, s * l.v};
    } else {
        Vec3 far = std::ldexp(1.0, std::min(k, p == Precision::binary32 ? 24 : 50)) * r.vec(1);
        f.C = f.C + far, l.L0 = l.L0 + far;
    }
    return l;
}

Line far_origin_line(const Draw& draw) {
    auto& [r, f, k, exact, cs, sn, p] = draw;
    Vec3 target, d;
    if (r.coin()) {
        target = inside(r, f), d = r.vec(1);
    } else { // along the side's tangent plane, just inside it or just past it
        double side = r.coin() ? 1 + r.real(0.001, 0.1) : 1 - std::ldexp(1.0, -r.integer(1, 30));
        target = f.at(side * cs, side * sn, r.real(0.1, 0.9));
        d = f.along(-sn, cs, 0) + r.real(-1, 1) * f.h;
    }
    while (norm(d) == 0)
        d = r.vec(1);
    Vec3 from = target - (std::ldexp(f.size(), k) / norm(d)) * d;
    if (r.coin()) {
        int j = r.integer(10, std::max(10, std::min(k, p == Precision::binary32 ? 20 : 40)));
        Vec3 far = std::ldexp(f.size(), j) * r.vec(1);
        f.C = f.C + far, target = target + far, from = from + far;
    }
    return {from, 1.5 * (target - from)};
}

// From inside, on the side or a pole, or 2^-k outside them.
Line inside_start_line(const Draw& draw) {
    auto& [r, f, k, exact, cs, sn, p] = draw;
    Vec3 P;
    switch (r.integer(0, 2)) {
    case 0:
        P = f.at(0.5 * cs, 0.5 * sn, 0.125 * r.integer(0, 8));
        break;
    case 1:
        P = f.at(cs, sn, 0.125 * r.integer(1, 7));
        if (k > 0) P = P + std::ldexp(1.0, -k) * f.along(cs, sn, 0);
        break;
    default: {
        bool top = r.coin();
        P = f.at(0, 0, top ? 1 + f.pole() : -f.pole());
        if (k > 0) P = P + (top ? 1 : -1) * std::ldexp(1.0, -k) * f.h;
    }
    }
    return {P, r.vec(2)};
}

// Through the axis' middle, or 2^-k of the size beside it.
Line through_centre_line(const Draw& draw) {
    auto& [r, f, k, exact, cs, sn, p] = draw;
    Vec3 d = exact ? r.ivec(3) : r.vec(2);
    while (norm(d) == 0)
        d = exact ? r.ivec(3) : r.vec(2);
    Vec3 P = f.at(0, 0, 0.5);
    if (!exact) P = P + std::ldexp(f.size(), -k) * cross(d, solids::unit_vector(r));
    return {P - 0.25 * r.integer(2, 12) * d, d};
}

Line seam_line(const Draw& draw) {
    auto& [r, f, k, exact, cs, sn, p] = draw;
    // Through a point of a seam circle exactly (k = 0) or moved k ulps: into the solid through
    // its middle, across the other seam, grazing the seam along its circle, or along the
    // axis (on the side's generator).
    bool top = r.coin();
    double z = top ? 1 : 0;
    Vec3 P = f.at(cs, sn, z), d;
    switch (r.integer(0, 3)) {
    case 0:
        d = f.at(0.25 * sn, -0.25 * cs, 0.5) - P;
        break;
    case 1:
        d = f.at(-cs, -sn, 1 - z) - P;
        break;
    case 2:
        d = f.along(-sn, cs, r.coin() ? 0.25 : -0.25);
        break;
    default:
        d = f.h;
    }
    if (k > 0) {
        int i = std::fabs(P.x) >= std::fabs(P.y) ? 0 : 1;
        if (std::fabs(P.z) > std::fabs(P[i])) i = 2;
        double moved = ulps_moved(P[i], k, r.coin(), p);
        (i == 0 ? P.x : i == 1 ? P.y : P.z) = moved;
    }
    return {P - 0.5 * d, d};
}

// Along the axis through both poles; tilted or moved by 2^-k.
Line poles_line(const Draw& draw) {
    auto& [r, f, k, exact, cs, sn, p] = draw;
    Vec3 P = f.at(0, 0, 0.5), d = f.h;
    if (k > 0) {
        Vec3 across = std::ldexp(1.0, -k) * f.along(r.real(-1, 1), r.real(-1, 1), 0);
        if (r.coin())
            d = d + across;
        else
            P = P + across;
    }
    return {P + 0.25 * r.integer(-8, 8) * d, (r.coin() ? 1.0 : -1.0) * d};
}

// Parallel to the axis inside, on the side, or outside.
Line axis_parallel_line(const Draw& draw) {
    auto& [r, f, k, exact, cs, sn, p] = draw;
    int kind = r.integer(0, 2);
    double rho = kind == 0 ? 0.5 : kind == 1 ? 1 : 2;
    Vec3 P = f.at(rho * cs, rho * sn, 0.125 * r.integer(0, 8)), d = f.h;
    if (k > 0) d = d + std::ldexp(1.0, -k) * f.along(r.real(-1, 1), r.real(-1, 1), 0);
    return {P - (exact ? 1.0 : r.real(0.5, 2)) * d, d};
}

Line line_of(Family fam, const Draw& draw) {
    switch (fam) {
    case Family::generic:
        return generic_line(draw);
    case Family::near_tangent:
        return near_tangent_line(draw);
    case Family::thin:
        return thin_line(draw);
    case Family::scale:
        return scale_line(draw);
    case Family::far_origin:
        return far_origin_line(draw);
    case Family::inside_start:
        return inside_start_line(draw);
    case Family::through_centre:
        return through_centre_line(draw);
    case Family::seam:
        return seam_line(draw);
    case Family::poles:
        return poles_line(draw);
    case Family::axis_parallel:
        return axis_parallel_line(draw);
    default:
        return {};
    }
}

Case make(Family fam, Rng& r, int k, Frames frames, Precision p) {
    bool exact = k == 0;
    Case c;
    c.k = k;
    CapsuleFrame f = capsule_frame(r, exact && fam != Family::generic, frames);
    auto [cs, sn] = quarter(r);
    c.line = line_of(fam, Draw{r, f, k, exact, cs, sn, p});
    c.shape = capsule_of(f);
    return c;
}

} // namespace

template <>
bool CaseMaker<Capsule>::applies(Family f) {
    switch (f) {
    case Family::generic:
    case Family::near_tangent:
    case Family::thin:
    case Family::scale:
    case Family::far_origin:
    case Family::inside_start:
    case Family::through_centre:
    case Family::seam:
    case Family::poles:
    case Family::axis_parallel:
        return true;
    default:
        return false;
    }
}

template <>
Case CaseMaker<Capsule>::make(Family f, Rng& r, int k, Frames frames, Precision p) {
    return linequad::make(f, r, k, frames, p);
}

} // namespace linequad
