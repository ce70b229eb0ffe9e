// spawn_ray: an origin off the surface, proven to leave it (the proof: linequad/spawn.hpp).
//
// The origin is searched for as pbrt-v4 does, then proven: from the hit point p along the
// normal, first by the point's own rounding error (an ulp of each coordinate, weighted by the
// normal's components), doubling until the exact test accepts. Each candidate is rounded away
// from p in every coordinate the normal moves, so that it is never p again. At a cone's apex the
// normal vanishes; the origin moves along the direction itself instead, where the double root
// at the apex falls behind it.
#include "linequad/spawn.hpp"

#include "numeric/big_float.hpp"
#include "numeric/bounded_dd.hpp"
#include "numeric/fp_environment.hpp"
#include "shapes/all.hpp"

#include <cmath>
#include <cstdlib>
#include <limits>
#include <optional>
#include <tuple>

namespace linequad {

namespace {

using detail::ShapeTraits;
using exact_form::undecided;

// The spacing of doubles at x (below the largest double, where there is none above).
double ulp(double x) {
    double a = std::fabs(x), up = std::nextafter(a, std::numeric_limits<double>::infinity());
    return std::isfinite(up) ? up - a : a - std::nextafter(a, 0.0);
}

// The surface a hit's part lies on, along x + t d in the exact form: its value at x and its rate
// along d, oriented so that + is outside the solid. The lateral surface: Q(0) = C0 and
// Q'(0) / 2 = B; a disc: the distance of x from its plane, Z0 - e, and dZ (negated for the base,
// whose outside is below it). The rate is affine in x.
template <class NT>
struct Oriented {
    NT value, rate;
};
template <class NT>
Oriented<NT> oriented(const exact_form::LineQuadratic<NT>& q, Part part) {
    if (part == Part::lateral) return {q.C0, q.B};
    if (part == Part::top) return {NT(q.Z0 - q.hi), q.dZ};
    return {NT(q.lo - q.Z0), NT(NT(0.0) - q.dZ)};
}
template <class NT, class S>
Oriented<NT> oriented_along(const S& shape, int orientation, Part part, Vec3 x, Vec3 d) {
    return oriented(
        ShapeTraits<S>::template exact_quadratic<NT>(shape, Line{x, d, Range::ray}, orientation),
        part);
}

// For a closed shape, whether o is strictly inside one of its solids: inside the lateral
// surface (C0 < 0), strictly between its bounded ends (a one-nappe cone's apex end included),
// off a two-solid cone's apex plane. 1, 0, or undecided.
template <class NT>
int strictly_inside(const exact_form::LineQuadratic<NT>& q) {
    int signs[4] = {sign(q.C0), q.lo_bounded ? sign(NT(q.lo - q.Z0)) : -1,
                    q.hi_bounded ? sign(NT(q.Z0 - q.hi)) : -1,
                    q.two_solids ? -std::abs(sign(q.Z0)) : -1};
    int result = 1;
    for (int s : signs) {
        if (s == undecided)
            result = undecided;
        else if (s >= 0)
            return 0;
    }
    return result;
}

struct Signs {
    int at_origin = 0, ahead = 0; // each +-1, 0 or undecided
    int inside = 0;               // strictly_inside, for a closed shape
};
template <class NT, class S>
Signs signs_along(const S& shape, int orientation, Part part, Vec3 o, Vec3 d, bool closed) {
    auto q =
        ShapeTraits<S>::template exact_quadratic<NT>(shape, Line{o, d, Range::ray}, orientation);
    Oriented<NT> f = oriented(q, part);
    return {sign(f.value), sign(f.rate), closed ? strictly_inside(q) : 0};
}

// The side the ray from o leaves the surface to, proven: +-1 when both signs are that, 0 when
// they are not one nonzero sign. Into a closed shape, o must moreover be strictly inside it:
// the line then leaves the (convex) solid once ahead, and never re-enters it through the
// crossing it left, or through the other part at a rim it left by.
template <class S>
int proven_side(const S& shape, int orientation, Part part, Vec3 o, Vec3 d, bool closed) {
    Signs f = signs_along<BoundedDD>(shape, orientation, part, o, d, closed);
    if (f.at_origin == undecided || f.ahead == undecided ||
        (closed && f.at_origin < 0 && f.inside == undecided))
        f = signs_along<BigFloat>(shape, orientation, part, o, d, closed);
    int a = f.at_origin;
    if (a == 0 || a != f.ahead) return 0;
    return a < 0 && closed && f.inside != 1 ? 0 : a;
}

// The side d points to from the crossing at p, and the same over the box of an ulp around p in
// every coordinate (where the exact hit of a correctly rounded point lies, with room to spare):
// the rate's sign at p, when its magnitude exceeds the most the affine rate can change over the
// box, sum_k |rate(e_k) - rate(0)| ulp(p_k). Else 0: within rounding of tangent, or of a point
// where the side changes (a cone's apex, a hit where an ulp is as wide as the shape). In NT:
// undecided when a filtered NT cannot tell.
template <class NT, class S>
int direction_side_in(const S& shape, int orientation, Part part, Vec3 p, Vec3 d) {
    NT at_p = oriented_along<NT>(shape, orientation, part, p, d).rate;
    NT at_origin = oriented_along<NT>(shape, orientation, part, Vec3{0, 0, 0}, d).rate;
    int side = sign(at_p);
    if (side == undecided || side == 0) return side;
    NT reach(0.0);
    for (int k = 0; k < 3; ++k) {
        Vec3 e{k == 0 ? 1.0 : 0.0, k == 1 ? 1.0 : 0.0, k == 2 ? 1.0 : 0.0};
        NT slope = oriented_along<NT>(shape, orientation, part, e, d).rate - at_origin;
        int s = sign(slope);
        if (s == undecided) return undecided;
        reach = reach + (s < 0 ? NT(NT(0.0) - slope) : slope) * NT(ulp(p[k]));
    }
    int margin = sign(NT(NT(double(side)) * at_p - reach));
    if (margin == undecided) return undecided;
    return margin > 0 ? side : 0;
}
template <class S>
int direction_side(const S& shape, int orientation, Part part, Vec3 p, Vec3 d) {
    int side = direction_side_in<BoundedDD>(shape, orientation, part, p, d);
    return side != undecided ? side : direction_side_in<BigFloat>(shape, orientation, part, p, d);
}

// The gradient of the surface at p, up to a positive factor, in double, outward (for the base
// disc, down the axis): its rate of change along each axis, from the same exact form, with shape
// and point scaled by one power of two to unit size first (the form's products of four would
// overflow or underflow for shapes far from it). Rounding only makes it approximate; the search
// uses it only to pick candidates.
template <class S>
Vec3 gradient(const S& shape, int orientation, Part part, Vec3 p) {
    double size = std::fmax(detail::shape_magnitude(shape), max_abs(p));
    double f = size > 0 ? std::ldexp(1.0, -std::ilogb(size)) : 1.0;
    std::optional<S> scaled = detail::scaled(shape, f);
    if (!scaled) scaled = shape, f = 1; // a shape that cannot be scaled exactly: as it is
    const S& unit = *scaled;
    Vec3 q = f * p;
    double g[3];
    for (int k = 0; k < 3; ++k) {
        Vec3 e{k == 0 ? 1.0 : 0.0, k == 1 ? 1.0 : 0.0, k == 2 ? 1.0 : 0.0};
        g[k] = oriented_along<double>(unit, orientation, part, q, e).rate;
    }
    return {g[0], g[1], g[2]};
}

// g / |g|, scaled first so that |g|^2 neither underflows nor overflows; zero for g = 0.
Vec3 unit(Vec3 g) {
    double m = max_abs(g);
    if (m == 0) return g;
    g = (1 / m) * g;
    return (1 / norm(g)) * g;
}

// p + delta n, each coordinate that n moves rounded one step further (away from p).
Vec3 moved(Vec3 p, double delta, Vec3 n) {
    double o[3];
    for (int k = 0; k < 3; ++k) {
        o[k] = p[k] + delta * n[k];
        if (n[k] != 0)
            o[k] = std::nextafter(o[k], n[k] > 0 ? std::numeric_limits<double>::infinity()
                                                 : -std::numeric_limits<double>::infinity());
    }
    return {o[0], o[1], o[2]};
}

bool finite(Vec3 x) {
    return std::isfinite(x.x) && std::isfinite(x.y) && std::isfinite(x.z);
}

Error field_error(Vec3 x, const char* field) {
    if (std::isnan(x.x) || std::isnan(x.y) || std::isnan(x.z))
        return {ErrorCode::not_a_number, field};
    if (!finite(x)) return {ErrorCode::infinite, field};
    return {};
}

// Doublings of the offset before giving up: from an ulp of the point to 2^60 of them, far more
// than any hit's rounding error, and a bounded number of exact tests.
constexpr int max_doublings = 60;

// f(surface, part on it): the patch of a shape made of patches that holds the hit's part, as a
// surface of its own (its one part, lateral); the shape itself otherwise.
template <class S, class F>
auto on_surface_of(const S& shape, Part part, F&& f) {
    if constexpr (detail::is_composite<S>)
        return detail::with_patch(shape, part, [&](const auto& p) { return f(p, Part::lateral); });
    else
        return f(shape, part);
}

template <class S>
SpawnedRay spawn_from(const S& shape, int orientation, Part part, const Hit& hit, Vec3 d);

template <class S>
SpawnedRay spawn(const detail::AsPrepared<S>& src, const Hit& hit, Vec3 d) {
    SpawnedRay out;
    detail::Validity valid = src.validity();
    if (!valid.error.ok()) {
        out.error = valid.error;
        return out;
    }
    return on_surface_of(src.shape, hit.part, [&](const auto& surface, Part part) {
        return spawn_from(surface, valid.orientation, part, hit, d);
    });
}

template <class S>
SpawnedRay spawn_from(const S& shape, int orientation, Part part, const Hit& hit, Vec3 d) {
    SpawnedRay out;
    auto refuse = [&](Error e) {
        out.error = e;
        return out;
    };
    if (Error e = field_error(hit.p, "p"); !e.ok()) return refuse(e);
    if (Error e = field_error(d, "direction"); !e.ok()) return refuse(e);
    if (d.x == 0 && d.y == 0 && d.z == 0) return refuse({ErrorCode::zero_direction, "direction"});
    Vec3 p = hit.p;
    // Which discs the shape has, as its exact form sets them (the form's values are not used).
    auto ends = ShapeTraits<S>::template exact_quadratic<double>(shape, Line{p, d}, orientation);
    bool closed = ends.lo_capped || ends.hi_capped;
    if (part != Part::lateral && !(part == Part::base ? ends.lo_capped : ends.hi_capped))
        return refuse({ErrorCode::bad_option, "part"}); // no such disc on this shape
    int sigma = direction_side(shape, orientation, part, p, d);
    Vec3 g = gradient(shape, orientation, part, p);
    if (!finite(g)) return refuse({ErrorCode::out_of_range, "p"});
    // A line through a cone's apex touches it there (a tangent hit, where the normal vanishes);
    // a crossing whose rounded point is the apex is within rounding of two crossings instead,
    // and no side is proven for it.
    bool singular = hit.kind == HitKind::tangent && g.x == 0 && g.y == 0 && g.z == 0;
    if (sigma == 0 && !singular) return refuse({ErrorCode::along_surface, "direction"});

    // Candidates along n, from the point's own rounding error on; true when one is proven.
    bool overflow = false;
    auto search = [&](Vec3 n) {
        if (n.x == 0 && n.y == 0 && n.z == 0) return false; // a gradient that underflowed
        double delta = 0;
        for (int k = 0; k < 3; ++k)
            delta += std::fabs(n[k]) * ulp(p[k]);
        for (int i = 0; i <= max_doublings; ++i, delta *= 2) {
            Vec3 o = moved(p, delta, n);
            if (!finite(o)) return !(overflow = true);
            int side = proven_side(shape, orientation, part, o, d, closed);
            if (side != 0 && (singular || side == sigma)) {
                out.line = Line{o, d, Range::ray};
                out.side = side;
                out.offset = std::fmax(std::fabs(o.x - p.x),
                                       std::fmax(std::fabs(o.y - p.y), std::fabs(o.z - p.z)));
                return true;
            }
        }
        return false;
    };
    // Along the normal towards side sigma. Then along d itself, where the crossing left falls
    // behind as the origin passes it: at a cone's apex (no normal; either side is then proven),
    // and where the surface is only a few ulps across (a small shape far from the origin),
    // which the normal's candidates can step over.
    if (!singular && search(double(sigma) * unit(g))) return out;
    if (search(unit(d))) return out;
    if (overflow) return refuse({ErrorCode::out_of_range, "p"});
    return refuse({ErrorCode::along_surface, "direction"});
}

template <class S>
Vec3 outward_normal(const detail::AsPrepared<S>& src, const Hit& hit) {
    detail::Validity valid = src.validity();
    if (!valid.error.ok() || !finite(hit.p)) return {};
    Vec3 g = on_surface_of(src.shape, hit.part, [&](const auto& surface, Part part) {
        return gradient(surface, valid.orientation, part, hit.p);
    });
    if (!finite(g)) return {};
    return unit(g);
}

} // namespace

template <class S>
Vec3 normal(const Prepared<S>& shape, const Hit& hit) {
    numeric::StandardEnvironment standard;
    return outward_normal(detail::AsPrepared<S>(shape), hit);
}

Vec3 normal(const Shape& shape, const Hit& hit) {
    return std::visit([&](const auto& s) { return normal(prepare(s), hit); }, shape);
}

template <class S>
SpawnedRay spawn_ray(const Prepared<S>& shape, const Hit& hit, Vec3 direction) {
    numeric::StandardEnvironment standard;
    return spawn(detail::AsPrepared<S>(shape), hit, direction);
}

SpawnedRay spawn_ray(const Shape& shape, const Hit& hit, Vec3 direction) {
    return std::visit([&](const auto& s) { return spawn_ray(prepare(s), hit, direction); }, shape);
}

#define LINEQUAD_SPAWN(S)                                                                          \
    template SpawnedRay spawn_ray(const Prepared<S>&, const Hit&, Vec3);                           \
    template Vec3 normal(const Prepared<S>&, const Hit&);
LINEQUAD_FOR_EACH_SHAPE(LINEQUAD_SPAWN)
#undef LINEQUAD_SPAWN

} // namespace linequad
