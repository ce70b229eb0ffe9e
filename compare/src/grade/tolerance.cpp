// Declared tolerances: brackets of a solid by exact shapes, and the chords a solid between them
// may have. See tolerance.hpp for what is proved.
#include "grade/tolerance.hpp"

#include "linequad/exact.hpp"

#include "shapes/all.hpp"

#include <algorithm>
#include <cmath>

namespace linequad::audit {

namespace {

// Every bound below is scaled by this much less than 1, so that the few roundings of a bound's
// own arithmetic (a product, a square root) never carry it past what it bounds.
constexpr double margin = 1 - 0x1p-40;

// x + d, rounded toward x: never farther from x than the exact sum.
double toward(double x, double d) {
    double s = x + d;
    if (!std::isfinite(s)) return x;
    double bb = s - x, e = (x - (s - bb)) + (d - bb); // TwoSum: x + d = s + e exactly
    if ((d > 0 && e < 0) || (d < 0 && e > 0)) s = std::nextafter(s, x);
    return s;
}

// w scaled by 1 + eps, coordinate by coordinate, each rounded toward w: w' - w = diag(e) w with
// every |e_k| <= |eps|.
Vec3 scaled(Vec3 w, double eps) {
    return {toward(w.x, eps * w.x), toward(w.y, eps * w.y), toward(w.z, eps * w.z)};
}
// p moved by eps w, each coordinate rounded toward p: |p' - p| <= |eps| |w| (1 + 2^-52).
Vec3 moved(Vec3 p, double eps, Vec3 w) {
    return {toward(p.x, eps * w.x), toward(p.y, eps * w.y), toward(p.z, eps * w.z)};
}

// |w|, rounded up past the roundings of computing it.
double length_above(Vec3 w) {
    return std::hypot(std::hypot(w.x, w.y), w.z) / margin;
}

// The coordinate w lies along, if it has exactly one nonzero coordinate; else -1.
int axis_of(Vec3 w) {
    int n = (w.x != 0) + (w.y != 0) + (w.z != 0);
    if (n != 1) return -1;
    return w.x != 0 ? 0 : w.y != 0 ? 1 : 2;
}

// What an offset made: the shape, or the proof that the shrunk solid is empty (every point of S
// lies within d of its surface), or neither (an edge case not worth a proof: no bracket).
enum class Made { shape, empty, none };

// The section vectors of an elliptic shape grown (sign +1) or shrunk (-1) so that the section's
// support moves by at most d: each vector by d along itself when they lie along distinct
// coordinate axes (orthogonal, so the moves add in quadrature), else all scaled by d / rho with
// rho^2 the sum of their squared lengths (Cauchy-Schwarz bounds the move).
Made sections(std::initializer_list<Vec3*> vectors, double d, int sign) {
    bool aligned = true;
    int used = 0;
    for (Vec3* w : vectors) {
        int k = axis_of(*w);
        aligned = aligned && k >= 0 && !(used & (1 << k));
        if (k >= 0) used |= 1 << k;
    }
    double rho = 0;
    for (Vec3* w : vectors)
        rho = std::hypot(rho, length_above(*w));
    rho /= margin;
    if (!(rho > 0) || !std::isfinite(rho)) return Made::none;
    for (Vec3* w : vectors) {
        // A section no wider than 2 d in some direction: S shrunk by d is empty (its inscribed
        // radius is at most its smallest semi-axis).
        if (sign < 0 && d * margin * margin > length_above(*w)) return Made::empty;
        double length = aligned ? max_abs(*w) : rho; // exact for an aligned vector
        double eps = sign * d * margin / length;
        if (!(eps > -1) || !std::isfinite(eps)) return Made::none;
        *w = scaled(*w, eps);
    }
    return Made::shape;
}

// The shape grown (sign +1) or shrunk (-1) by `radial` across its axis and `axial` along it, as
// each shape's support function allows (see each case). Every new parameter is rounded toward
// the old one, so the moves are never larger than the bounds say.
Made offset(Shape& shape, double radial, double axial, int sign) {
    double rd = radial * margin, ad = sign * axial * margin;
    // A radius r +- rd; a shrunk radius below rd proves the shrunk solid empty.
    auto radius = [&](double& r) {
        if (sign > 0) return r = toward(r, rd), Made::shape;
        if (r < rd) return Made::empty;
        r = toward(r, -rd);
        return r > 0 ? Made::shape : Made::none;
    };
    return std::visit(
        [&](auto& x) -> Made {
            using S = std::decay_t<decltype(x)>;
            if constexpr (std::is_same_v<S, Sphere> || std::is_same_v<S, Capsule>) {
                // S grown or shrunk by d is the same solid with r +- d: exactly.
                if (axial != 0) return Made::none;
                return radius(x.r);
            } else if constexpr (std::is_same_v<S, Cylinder> || std::is_same_v<S, Frustum>) {
                // A hull of discs: radii +- d move its support by at most d; its end discs moved
                // d along the axis, by at most d. Along the axis only when it lies along a
                // coordinate (no rounding turns the discs).
                Vec3& P0 = [&]() -> Vec3& {
                    if constexpr (std::is_same_v<S, Cylinder>)
                        return x.C;
                    else
                        return x.C0;
                }();
                Vec3& P1 = [&]() -> Vec3& {
                    if constexpr (std::is_same_v<S, Cylinder>)
                        return x.H;
                    else
                        return x.C1;
                }();
                if (radial != 0) {
                    if constexpr (std::is_same_v<S, Cylinder>) {
                        if (Made m = radius(x.r); m != Made::shape) return m;
                    } else {
                        // Radii clamped at 0 (an apex) still contain S shrunk; both below rd:
                        // S lies in the cylinder of its larger radius, whose shrunk solid is empty.
                        if (sign < 0 && std::max(x.r0, x.r1) < rd) return Made::empty;
                        auto clamped = [&](double r) {
                            return sign > 0 ? toward(r, rd) : std::max(toward(r, -rd), 0.0);
                        };
                        x.r0 = clamped(x.r0), x.r1 = clamped(x.r1);
                        if (!(x.r0 > 0 || x.r1 > 0)) return Made::none;
                    }
                }
                if (axial != 0) {
                    int k = axis_of(P1 - P0);
                    if (k < 0) return Made::none;
                    double& lo = k == 0 ? P0.x : k == 1 ? P0.y : P0.z;
                    double& hi = k == 0 ? P1.x : k == 1 ? P1.y : P1.z;
                    double up = hi > lo ? ad : -ad;
                    double new_lo = toward(lo, -up), new_hi = toward(hi, up);
                    // Ends that crossed: the height is below 2 d, and S shrunk by d is empty.
                    bool ordered = hi > lo ? new_lo < new_hi : new_hi < new_lo;
                    bool crossed = hi > lo ? new_lo > new_hi : new_hi > new_lo;
                    if (!ordered) return crossed ? Made::empty : Made::none;
                    lo = new_lo, hi = new_hi;
                }
                return Made::shape;
            } else if constexpr (std::is_same_v<S, EllipticCylinder>) {
                // C + {x a + y b + z c}: the section's support by sections(); the ends moved by
                // eps c and the axis grown by 2 eps c move it by at most 3 eps |c|.
                if (radial != 0)
                    if (Made m = sections({&x.a, &x.b}, radial, sign); m != Made::shape) return m;
                if (axial != 0) {
                    double eps = ad / (3 * length_above(x.c));
                    if (!std::isfinite(eps)) return Made::none;
                    // d >= |c|: at least the height, so S shrunk by d is empty.
                    if (!(eps > -1.0 / 3)) return Made::empty;
                    x.C = moved(x.C, -eps, x.c);
                    x.c = scaled(x.c, 2 * eps);
                }
                return Made::shape;
            } else if constexpr (std::is_same_v<S, EllipticCone>) {
                // The hull of the apex H and the base section at C: the section by sections(), the
                // apex and the base moved eps (H - C) apart, each by at most eps |H - C|.
                if (radial != 0)
                    if (Made m = sections({&x.a, &x.b}, radial, sign); m != Made::shape) return m;
                if (axial != 0) {
                    Vec3 c = x.H - x.C;
                    double eps = ad / length_above(c);
                    if (!std::isfinite(eps)) return Made::none;
                    // d >= |H - C| / 2: a cone's inscribed radius is below half its height.
                    if (!(eps > -0.5)) return Made::empty;
                    x.H = moved(x.H, eps, c), x.C = moved(x.C, -eps, c);
                }
                return Made::shape;
            } else if constexpr (is_unbounded_surface<S>) {
                return Made::none; // an unbounded surface: no bracket (convex_solid says so)
            } else {
                static_assert(std::is_same_v<S, Ellipsoid>);
                if (axial != 0) return Made::none;
                return sections({&x.a, &x.b, &x.c}, radial, sign);
            }
        },
        shape);
}

// Whether the shape is a closed convex solid (the brackets' argument needs convexity).
bool convex_solid(const Shape& s) {
    return std::visit(
        [](const auto& x) { return is_closed(x) && has_finite_extent(x) && nappes_of(x) == 1; }, s);
}

// The solid's chord along the whole line, from the oracle: none, or [lo, hi] (a touch: lo = hi).
struct Chord {
    bool exists = false;
    double lo = 0, hi = 0;
};
std::optional<Chord> chord(const Shape& s, const Line& l, Precision p) {
    Line whole = l;
    whole.range = Interval{};
    Result r = exact::intersect(s, whole, {Need::all, false}, p);
    if (!r.ok() || r.on_surface) return std::nullopt;
    if (r.count == 0) return Chord{};
    if (r.count == 1 && r.hits[0].kind != HitKind::tangent) return std::nullopt;
    return Chord{true, r.hits[0].t, r.hits[r.count - 1].t};
}

double next_up(double t, Precision p) {
    return p == Precision::binary32 ? double(std::nextafter(float(t), INFINITY))
                                    : std::nextafter(t, INFINITY);
}
double next_down(double t, Precision p) {
    return p == Precision::binary32 ? double(std::nextafter(float(t), -INFINITY))
                                    : std::nextafter(t, -INFINITY);
}

// Where the chord J = [j0, j1] of a solid between the bracket's may lie: j0 in first, j1 in
// second, or no chord at all when `may_miss`. The oracle's ends are correctly rounded: one ulp
// inward each is certainly inside the exact bounds.
struct Room {
    double lo0, hi0, lo1, hi1;
    bool may_miss;
};
std::optional<Room> room(const Chord& outer, const Chord& inner, Precision p) {
    if (!outer.exists) {
        if (inner.exists) return std::nullopt;
        return Room{1, 0, 1, 0, true};
    }
    double lo = next_up(outer.lo, p), hi = next_down(outer.hi, p);
    if (!inner.exists) return Room{lo, hi, lo, hi, true};
    return Room{lo, next_down(inner.lo, p), next_up(inner.hi, p), hi, false};
}

// The answer, under s's conventions, of a solid whose chord is J (none: `miss`), on the range of
// l; `any` when the conventions leave it undefined.
struct Expected {
    bool any = false, convention = false;
    int count = 0;
    double t[2] = {0, 0};
    HitKind kind[2] = {HitKind::cross, HitKind::cross};
};
Expected expected(const ExternalSolver& s, const Line& l, bool miss, double j0, double j1) {
    Expected all;
    auto add = [&](double t, HitKind k) {
        if (l.range.contains(t)) all.t[all.count] = t, all.kind[all.count++] = k;
    };
    if (!miss && j0 == j1) add(j0, HitKind::tangent);
    if (!miss && j0 < j1) add(j0, HitKind::cross), add(j1, HitKind::cross);
    double t0 = l.range.t0;
    bool has_t0 = l.range.has_t0() && !miss;
    bool inside = has_t0 && j0 < t0 && t0 < j1;
    bool on_surface = has_t0 && (t0 == j0 || t0 == j1);
    if (s.answers == Answers::first_exit) {
        // A first exit from outside is not in the contract (VecGeom's DistanceToOut: undefined):
        // for such a solid, any answer is its answer.
        if (!inside && !on_surface) return Expected{true};
    } else if (s.inside != StartInside::as_answers) {
        bool applies = inside || (on_surface && s.inside != StartInside::no_hit &&
                                  s.on_surface == StartOnSurface::as_inside);
        if (applies) {
            Expected e;
            e.convention = true;
            if (s.inside == StartInside::undefined) e.any = true;
            if (s.inside == StartInside::at_t0) e.t[e.count++] = t0;
            if (s.inside == StartInside::at_zero) e.t[e.count++] = 0;
            return e;
        }
    }
    if (s.tangent == TangentRule::no_hit && all.count == 1 && all.kind[0] == HitKind::tangent)
        all.count = 0;
    switch (s.answers) {
    case Answers::all:
        return all;
    case Answers::nearest:
        all.count = std::min(all.count, 1);
        return all;
    case Answers::first_entry: {
        // Inside just before t0 (a crossing before it): the solid is ignored until left.
        bool inside_before = !miss && j0 < j1 && j0 < t0 && t0 <= j1 && l.range.has_t0();
        if (inside_before) all.count = 0;
        all.count = std::min(all.count, 1);
        return all;
    }
    case Answers::first_exit: {
        Expected e;
        if (j0 < j1 && l.range.contains(j1)) e.t[e.count++] = j1;
        return e;
    }
    }
    return all;
}

bool same(const ExternalSolver& s, const Expected& e, const Result& got) {
    if (e.any) return true;
    if (got.count != e.count) return false;
    for (int i = 0; i < e.count; ++i) {
        if (got.hits[i].t != e.t[i]) return false;
        if (s.kinds && !e.convention && got.hits[i].kind != e.kind[i]) return false;
    }
    return true;
}

// A solid between the bracket's whose answer is got: J's ends tried at got's t, at the ends of
// their room and at the range's ends (where the conventions change), which covers every way an
// answer of at most two hits can come out.
bool some_solid_answers(const ExternalSolver& s, const Line& l, const Room& room,
                        const Result& got) {
    if (room.may_miss && same(s, expected(s, l, true, 0, 0), got)) return true;
    std::vector<double> at = {room.lo0, room.hi0, room.lo1, room.hi1};
    for (int i = 0; i < got.count; ++i)
        at.push_back(got.hits[i].t);
    if (l.range.has_t0()) at.push_back(l.range.t0);
    if (l.range.has_t1()) at.push_back(l.range.t1);
    for (double j0 : at) {
        if (!(j0 >= room.lo0 && j0 <= room.hi0)) continue;
        for (double j1 : at)
            if (j1 >= room.lo1 && j1 <= room.hi1 && j0 <= j1 &&
                same(s, expected(s, l, false, j0, j1), got))
                return true;
    }
    return false;
}

// The hit points a solver carries must be on the line within delta (and the rounding of L(t)).
bool points_on_line(const Result& got, const Line& l, double delta) {
    for (int i = 0; i < got.count; ++i) {
        const Hit& h = got.hits[i];
        Vec3 at = l.L0 + h.t * l.v;
        double m = std::max({max_abs(l.L0), max_abs(h.t * l.v), max_abs(h.p)});
        double slack = 4 * (std::nextafter(m, INFINITY) - m);
        if (!(max_abs(h.p - at) <= delta + slack)) return false;
    }
    return true;
}

} // namespace

std::vector<Bracket> brackets(const Shape& s, double delta) {
    std::vector<Bracket> out;
    double d = delta * margin;
    if (!(d > 0) || !std::isfinite(d) || !convex_solid(s)) return out;
    // Across the axis, along it, and both at once (d/sqrt(2) each: their moves add in
    // quadrature for the round shapes; for the elliptic ones, d/2 each, as they add at most).
    bool round = std::holds_alternative<Cylinder>(s) || std::holds_alternative<Frustum>(s);
    double both = round ? d * 0.70710678118654746 : d * 0.5; // 1/sqrt(2) rounded down
    for (auto [radial, axial] : {std::pair{d, 0.0}, {0.0, d}, {both, both}}) {
        Shape outer = s, inner = s;
        if (offset(outer, radial, axial, +1) != Made::shape) continue;
        Made shrunk = offset(inner, radial, axial, -1);
        if (shrunk == Made::none) continue;
        out.push_back({outer, shrunk == Made::shape ? std::optional(inner) : std::nullopt});
    }
    return out;
}

bool within_tolerance(const ExternalSolver& s, const Case& posed, const Result& got) {
    if (!got.ok() || got.on_surface || got.count > 2) return false;
    for (int i = 0; i < got.count; ++i)
        if (!std::isfinite(got.hits[i].t)) return false;
    double magnitude =
        std::max(std::visit([](const auto& x) { return detail::shape_magnitude(x); }, posed.shape),
                 max_abs(posed.line.L0));
    double delta = s.tolerance.at(magnitude);
    if (!(delta > 0) || !std::isfinite(delta)) return false;
    if (s.points && !points_on_line(got, posed.line, delta)) return false;
    for (const Bracket& b : brackets(posed.shape, delta)) {
        std::optional<Chord> outer = chord(b.outer, posed.line, posed.precision);
        std::optional<Chord> inner =
            b.inner ? chord(*b.inner, posed.line, posed.precision) : std::optional(Chord{});
        if (!outer || !inner) continue;
        std::optional<Room> r = room(*outer, *inner, posed.precision);
        if (r && some_solid_answers(s, posed.line, *r, got)) return true;
    }
    return false;
}

} // namespace linequad::audit
