// The families of the solids that are images of the unit ball, P = O + M x with |x| <= 1: the
// sphere (M = r times a rotation) and the ellipsoid (any frame M = [a b c]). Exact constructions
// use integer frames and points x on the unit sphere with coordinates 0 and +-1, so that every
// coordinate is computed without rounding; the nominal 2^-k offsets are applied in double and the
// oracle decides what the resulting doubles really are.
#pragma once

#include "cases/case_maker.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>

namespace linequad::solids {

struct BallFrame {
    Vec3 O, a, b, c;
    Vec3 at(Vec3 x) const { return O + along(x); }
    Vec3 along(Vec3 x) const { return x.x * a + x.y * b + x.z * c; }
    double size() const { return std::max({norm(a), norm(b), norm(c)}); }
};

// A unit vector, rounded; and one of the six exact ones (+-e_i).
inline Vec3 unit_vector(Rng& r) {
    Vec3 u = r.vec(1);
    while (norm(u) < 0.25)
        u = r.vec(1);
    return (1 / norm(u)) * u;
}
inline Vec3 axis_vector(Rng& r, int* axis = nullptr) {
    int i = r.integer(0, 2);
    if (axis) *axis = i;
    Vec3 e{};
    (i == 0 ? e.x : i == 1 ? e.y : e.z) = r.coin() ? 1 : -1;
    return e;
}
// A vector orthogonal to the unit axis e (+-e_i): dyadic combinations of the other two.
inline Vec3 across_axis(Rng& r, int axis) {
    Vec3 d{};
    double p = (r.integer(1, 8) * (r.coin() ? 1 : -1)) * 0.125;
    double q = (r.integer(0, 8) * (r.coin() ? 1 : -1)) * 0.125;
    (axis == 0 ? d.y : d.x) = p;
    (axis == 2 ? d.y : d.z) = q;
    return d;
}

// The frames a shape is built on. round: a sphere's (three orthogonal axes of one length); exact:
// integer coordinates, so that the constructions above stay exact.
inline BallFrame ball_frame(Rng& r, bool round, bool exact, Frames frames) {
    bool axis_aligned = frames == Frames::axis || frames == Frames::aligned;
    if (frames == Frames::aligned && !round) {
        // Semi-axes of three distinct lengths along the coordinate axes.
        double x = exact ? r.integer(1, 6) : r.real(0.25, 3);
        double y = exact ? r.integer(1, 5) : x * r.real(0.3, 0.8);
        if (exact && y >= x) y += 1;
        double z = exact ? r.integer(1, 7) : r.real(0.25, 3);
        if (exact)
            while (z == x || z == y)
                z = r.integer(1, 7);
        return {exact ? r.ivec(6) : r.vec(4), {x, 0, 0}, {0, y, 0}, {0, 0, z}};
    }
    if (round || frames != Frames::any) {
        if (exact) {
            double radius = r.integer(1, 6);
            Vec3 O = r.ivec(6);
            if (axis_aligned || r.coin())
                return {O, {radius, 0, 0}, {0, radius, 0}, {0, 0, radius}};
            IntegerRotation q = integer_rotation(r);
            radius = r.integer(1, 3);
            return {O, radius * q.col[0], radius * q.col[1], radius * q.col[2]};
        }
        double radius = r.real(0.25, 3);
        Vec3 O = r.vec(4);
        if (axis_aligned) return {O, {radius, 0, 0}, {0, radius, 0}, {0, 0, radius}};
        Vec3 c = unit_vector(r), t = std::fabs(c.x) < 0.5 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
        Vec3 a = cross(c, t);
        a = (1 / norm(a)) * a;
        Vec3 b = cross(c, a);
        // An ellipsoid on a circular frame keeps an axis of its own length.
        double length = round ? radius : r.real(0.25, 3);
        return {O, radius * a, radius * b, length * c};
    }
    for (;;) {
        BallFrame f = exact ? BallFrame{r.ivec(6), r.ivec(4), r.ivec(4), r.ivec(4)}
                            : BallFrame{r.vec(4), r.vec(2), r.vec(2), r.vec(2)};
        double n = norm(f.a) * norm(f.b) * norm(f.c);
        if (n > 0 && std::fabs(dot(f.a, cross(f.b, f.c))) >= 0.2 * n) return f;
    }
}

// What a family's frame and line are drawn from: the random source, the case's k, whether it is an
// exact construction, whether the solid is round (a sphere), its frames and the case's format.
struct BallDraw {
    Rng& r;
    int k;
    bool exact, round;
    Frames frames;
    Precision p;
};
struct BallLine {
    BallFrame f;
    Line line;
};

inline BallLine generic_ball(const BallDraw& draw) {
    auto& [r, k, exact, round, frames, p] = draw;
    BallFrame f = ball_frame(r, round, r.integer(0, 9) == 0, frames);
    Vec3 target = f.at(r.real(0, 0.95) * unit_vector(r)), from = target + f.size() * r.vec(4);
    return {f, r.integer(0, 4) == 0 ? Line{from, r.vec(2)} : Line{from, target - from}};
}

inline BallLine near_tangent_ball(const BallDraw& draw) {
    auto& [r, k, exact, round, frames, p] = draw;
    // Touching at x on the unit sphere along a direction in its tangent plane, or 2^-k
    // inside or outside of that.
    BallFrame f = ball_frame(r, round, exact, frames);
    Vec3 x, t;
    if (exact) {
        int axis;
        x = axis_vector(r, &axis), t = across_axis(r, axis);
    } else {
        x = unit_vector(r), t = cross(x, unit_vector(r));
        while (norm(t) == 0)
            t = cross(x, unit_vector(r));
        x = (1 + (r.coin() ? 1 : -1) * std::ldexp(1.0, -k)) * x;
    }
    Vec3 P = f.at(x), d = f.along(t);
    return {f, {P - (exact ? 2.0 : r.real(0.5, 3)) * d, d}};
}

// One axis 2^-k of the others (the ellipsoid's).
inline BallLine thin_ball(const BallDraw& draw) {
    auto& [r, k, exact, round, frames, p] = draw;
    BallFrame f = ball_frame(r, round, false, frames);
    double e = std::ldexp(1.0, -k);
    switch (r.integer(0, 2)) {
    case 0:
        f.a = e * f.a;
        break;
    case 1:
        f.b = e * f.b;
        break;
    default:
        f.c = e * f.c;
    }
    Vec3 target = f.at(r.real(0, 0.95) * unit_vector(r));
    Vec3 from = target + f.size() * r.vec(4);
    return {f, {from, target - from}};
}

inline BallLine scale_ball(const BallDraw& draw) {
    auto& [r, k, exact, round, frames, p] = draw;
    BallFrame f = ball_frame(r, round, false, frames);
    Vec3 target = f.at(r.real(0, 0.95) * unit_vector(r)), from = target + f.size() * r.vec(4);
    Line l{from, target - from};
    double s = std::ldexp(1.0, r.coin() ? k : -k);
    if (r.coin()) {
        f = {s * f.O, s * f.a, s * f.b, s * f.c};
        l = {s * l.L0, s * l.v};
    } else {
        Vec3 far = std::ldexp(1.0, std::min(k, p == Precision::binary32 ? 24 : 50)) * r.vec(1);
        f.O = f.O + far, l.L0 = l.L0 + far;
    }
    return {f, l};
}

inline BallLine far_origin_ball(const BallDraw& draw) {
    auto& [r, k, exact, round, frames, p] = draw;
    BallFrame f = ball_frame(r, round, false, frames);
    Vec3 target, d;
    if (r.coin()) { // aimed through the solid
        target = f.at(r.real(0, 0.7) * unit_vector(r)), d = r.vec(1);
    } else { // along a tangent plane, 2^-m inside it or just past it
        Vec3 x = unit_vector(r), t = cross(x, unit_vector(r));
        double side = r.coin() ? 1 + r.real(0.001, 0.1) : 1 - std::ldexp(1.0, -r.integer(1, 30));
        target = f.at(side * x), d = f.along(t);
    }
    while (norm(d) == 0)
        d = r.vec(1);
    Vec3 from = target - (std::ldexp(f.size(), k) / norm(d)) * d;
    if (r.coin()) { // the scene far from the world origin too
        int j = r.integer(10, std::max(10, std::min(k, p == Precision::binary32 ? 20 : 40)));
        Vec3 far = std::ldexp(f.size(), j) * r.vec(1);
        f.O = f.O + far, target = target + far, from = from + far;
    }
    return {f, {from, 1.5 * (target - from)}};
}

// From inside, on the surface, or 2^-k outside it.
inline BallLine inside_start_ball(const BallDraw& draw) {
    auto& [r, k, exact, round, frames, p] = draw;
    BallFrame f = ball_frame(r, round, exact, frames);
    int kind = r.integer(0, 2);
    Vec3 x = kind == 0 ? 0.5 * (exact ? axis_vector(r) : unit_vector(r)) : axis_vector(r);
    if (kind == 2 && k > 0) x = (1 + std::ldexp(1.0, -k)) * x;
    return {f, {f.at(x), r.vec(2)}};
}

// Through O, or 2^-k of the size beside it.
inline BallLine through_centre_ball(const BallDraw& draw) {
    auto& [r, k, exact, round, frames, p] = draw;
    BallFrame f = ball_frame(r, round, exact, frames);
    Vec3 d = exact ? r.ivec(3) : r.vec(2);
    while (norm(d) == 0)
        d = exact ? r.ivec(3) : r.vec(2);
    Vec3 P = f.O;
    if (!exact) P = P + std::ldexp(f.size(), -k) * cross(d, unit_vector(r));
    return {f, {P - 0.25 * r.integer(2, 12) * d, d}};
}

inline std::optional<BallLine> ball_line(Family fam, const BallDraw& draw) {
    switch (fam) {
    case Family::generic:
        return generic_ball(draw);
    case Family::near_tangent:
        return near_tangent_ball(draw);
    case Family::thin:
        return thin_ball(draw);
    case Family::scale:
        return scale_ball(draw);
    case Family::far_origin:
        return far_origin_ball(draw);
    case Family::inside_start:
        return inside_start_ball(draw);
    case Family::through_centre:
        return through_centre_ball(draw);
    default:
        return std::nullopt;
    }
}

// The families, for a solid made from a frame by make(frame) (a Shape).
template <class Make>
Case ball_case(Family fam, Rng& r, int k, Frames frames, Precision p, bool round, Make make) {
    Case c;
    c.k = k;
    if (std::optional<BallLine> b = ball_line(fam, BallDraw{r, k, k == 0, round, frames, p}))
        c.shape = make(b->f), c.line = b->line;
    return c;
}

// The families a ball-like solid has.
inline bool ball_applies(Family f, bool round) {
    switch (f) {
    case Family::generic:
    case Family::near_tangent:
    case Family::scale:
    case Family::far_origin:
    case Family::inside_start:
    case Family::through_centre:
        return true;
    case Family::thin:
        return !round;
    default:
        return false;
    }
}

} // namespace linequad::solids
