#include "support.hpp"

#include "big_float.hpp"
#include "roots.hpp"

#include "linequad/expansion.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <initializer_list>

namespace linequad {

const char* shape_name(const Shape& s) {
    switch (s.index()) {
    case 0:
        return "cylinder";
    case 1:
        return "elliptic_cylinder";
    default:
        return "elliptic_cone";
    }
}

const char* range_name(Range r) {
    switch (r) {
    case Range::line:
        return "line";
    case Range::ray:
        return "ray";
    case Range::segment:
        return "segment";
    }
    return "?";
}

const char* code_name(ErrorCode c) {
    switch (c) {
    case ErrorCode::none:
        return "none";
    case ErrorCode::not_a_number:
        return "not_a_number";
    case ErrorCode::infinite:
        return "infinite";
    case ErrorCode::zero_direction:
        return "zero_direction";
    case ErrorCode::bad_radius:
        return "bad_radius";
    case ErrorCode::degenerate_axis:
        return "degenerate_axis";
    case ErrorCode::singular_frame:
        return "singular_frame";
    case ErrorCode::out_of_range:
        return "out_of_range";
    case ErrorCode::unknown_solver:
        return "unknown_solver";
    }
    return "?";
}

std::string message(const Error& e) {
    std::string f = e.field;
    switch (e.code) {
    case ErrorCode::none:
        return "";
    case ErrorCode::not_a_number:
        return f + " has a NaN coordinate";
    case ErrorCode::infinite:
        return f + " has an infinite coordinate";
    case ErrorCode::zero_direction:
        return "the direction " + f + " is the zero vector";
    case ErrorCode::bad_radius:
        return "the radius " + f + " is not positive";
    case ErrorCode::degenerate_axis:
        return f + ": the axis has zero length (H = C)";
    case ErrorCode::singular_frame:
        return "the frame " + f + " is singular (linearly dependent)";
    case ErrorCode::out_of_range:
        return f + ": magnitudes too far apart for double evaluation (overflow or underflow)";
    case ErrorCode::unknown_solver:
        return "no solver named " + f + " for this shape";
    }
    return "?";
}

namespace {

// |a| . (|b| x |c|): Shewchuk's bound on the rounding error of a . (b x c) is (7u + 56u^2)
// times it; 2^-49 (16u) covers that and, for the cone, the rounding of c = H - C (at most
// u (|H| + |C|) per component, accounted for by passing |H| + |C| for |c|).
double permanent3(Vec3 a, Vec3 b, Vec3 c) {
    return std::fabs(a.x) * (std::fabs(b.y * c.z) + std::fabs(b.z * c.y)) +
           std::fabs(a.y) * (std::fabs(b.z * c.x) + std::fabs(b.x * c.z)) +
           std::fabs(a.z) * (std::fabs(b.x * c.y) + std::fabs(b.y * c.x));
}

// The sign of a . (b x c) when its floating-point value is certain, else 0. Products of two
// may underflow even when the determinant is large: b.y c.x = 2^-1452 becomes 0, and a.z =
// 2^954 then loses 2^-498 (nor does the permanent see it). Each underflow costs at most
// eta = 2^-1075 before the multiplication by a component of a, so (2 |a|_1 + 3) eta bounds
// what underflow can hide, in the value and in the permanent; (|a|_1 + 2) 2^-1072 covers it.
// Near overflow nothing is certain.
int filtered_sign(double det, double permanent, Vec3 a) {
    if (!(permanent < 0x1p+900)) return 0; // NaN too
    double norm1 = std::fabs(a.x) + std::fabs(a.y) + std::fabs(a.z);
    double bound = 0x1p-49 * permanent + (norm1 + 2) * 0x1p-1072;
    if (std::fabs(det) > bound) return det > 0 ? 1 : -1;
    return 0;
}

// Expansions of three-fold products are exact only while nothing underflows. Each vector is
// scaled by its own power of two, which cannot change the determinant's sign; that is enough
// when every nonzero component of a vector is within 2^300 of its largest, so that products of
// three keep their lowest bits above 2^-1074. Wider vectors (a frame spanning a thousand
// binades) go to BigFloat, which has no range limits.
Vec3 unit_scaled(Vec3 u, double m) {
    return m == 0 ? u : ldexp(u, -std::ilogb(m));
}

bool narrow(std::initializer_list<Vec3> vectors) {
    double big = 0, small = INFINITY;
    for (Vec3 u : vectors)
        for (double x : {u.x, u.y, u.z})
            if (x != 0) big = std::fmax(big, std::fabs(x)), small = std::fmin(small, std::fabs(x));
    return big == 0 || std::ilogb(big) - std::ilogb(small) <= 300;
}

void add_det_terms(Expansion<128>& e, double s, Vec3 a, Vec3 b, Vec3 c) {
    e.add_product(s * a.x, b.y, c.z), e.add_product(-s * a.x, b.z, c.y);
    e.add_product(s * a.y, b.z, c.x), e.add_product(-s * a.y, b.x, c.z);
    e.add_product(s * a.z, b.x, c.y), e.add_product(-s * a.z, b.y, c.x);
}

Vec3T<BigFloat> big(Vec3 u) {
    return {BigFloat(u.x), BigFloat(u.y), BigFloat(u.z)};
}

} // namespace

// The cone's frame uses c = H - C, which is not a double. det is linear in c, so
// det[a b H-C] = det[a b H] - det[a b C]: both scaled by one power of two, then summed exactly.
int cone_det_sign_exact(Vec3 a, Vec3 b, Vec3 C, Vec3 H) {
    Vec3 habs{std::fabs(H.x) + std::fabs(C.x), std::fabs(H.y) + std::fabs(C.y),
              std::fabs(H.z) + std::fabs(C.z)};
    Vec3 c = H - C;
    if (int s = filtered_sign(dot(a, cross(b, c)), permanent3(a, b, habs), a)) return s;
    if (a == Vec3{} || b == Vec3{}) return 0;
    if (!narrow({a}) || !narrow({b}) || !narrow({C, H}))
        return sign(dot(big(a), cross(big(b), big(H) - big(C))));
    double m = std::fmax(max_abs(C), max_abs(H));
    C = unit_scaled(C, m), H = unit_scaled(H, m);
    a = unit_scaled(a, max_abs(a)), b = unit_scaled(b, max_abs(b));
    Expansion<128> e;
    add_det_terms(e, 1, a, b, H);
    add_det_terms(e, -1, a, b, C);
    return e.sign();
}

int det3_sign_exact(Vec3 a, Vec3 b, Vec3 c) {
    if (int s = filtered_sign(dot(a, cross(b, c)), permanent3(a, b, c), a)) return s;
    if (!narrow({a}) || !narrow({b}) || !narrow({c}))
        return sign(dot(big(a), cross(big(b), big(c))));
    a = unit_scaled(a, max_abs(a)), b = unit_scaled(b, max_abs(b)), c = unit_scaled(c, max_abs(c));
    Expansion<128> e;
    add_det_terms(e, 1, a, b, c);
    return e.sign();
}

namespace {

Error check_point(Vec3 p, const char* field) {
    if (std::isnan(p.x) || std::isnan(p.y) || std::isnan(p.z))
        return {ErrorCode::not_a_number, field};
    if (!is_finite(p)) return {ErrorCode::infinite, field};
    return {};
}

Error check_line(const Line& l) {
    if (Error e = check_point(l.L0, "L0"); e.code != ErrorCode::none) return e;
    if (Error e = check_point(l.v, "v"); e.code != ErrorCode::none) return e;
    if (l.v == Vec3{}) return {ErrorCode::zero_direction, "v"};
    return {};
}

struct Named {
    Vec3 p;
    const char* field;
};

Error check_all(const Line& l, std::initializer_list<Named> points) {
    // 0 * (sum of every coordinate) is NaN iff one is NaN or infinite: one test for the usual
    // case, the field by field checks (which name the culprit) only when it fails.
    double sum = l.L0.x + l.L0.y + l.L0.z + l.v.x + l.v.y + l.v.z;
    for (const Named& n : points)
        sum += n.p.x + n.p.y + n.p.z;
    if (0 * sum == 0) return l.v == Vec3{} ? Error{ErrorCode::zero_direction, "v"} : Error{};
    Error e = check_line(l);
    for (const Named& n : points)
        if (e.code == ErrorCode::none) e = check_point(n.p, n.field);
    return e;
}

} // namespace

namespace detail {

void assemble(FinishedCandidate* c, int n, Query q, Result& r) {
    // Field by field: r may be a caller's buffer, and a whole Result is large to write twice.
    r.error = {};
    r.count = 0;
    r.on_surface = false;
    r.s0 = r.s1 = 0;
    r.certainty = Certainty::unknown;
    for (int i = 0; i < n; ++i)
        if (c[i].bad) return void(r.error = {ErrorCode::out_of_range, "t"});
    if (n == 2 && c[1].t < c[0].t) std::swap(c[0], c[1]);
    for (int i = 0; i < n; ++i) {
        if (!c[i].keep) continue;
        // A hit whose point lies beyond double's range is refused, not returned as inf.
        if (q.points && !is_finite(c[i].p))
            return void(r = Result::failure(ErrorCode::out_of_range, "p"));
        r.hits[r.count++] = Hit{c[i].t, c[i].kind, q.points ? c[i].p : Vec3{}};
        if (q.need != Need::all) break; // sorted, so the first kept is also the nearest
    }
}

Result finish(Candidate* c, int n, Extent e, const Line& l, Query q) {
    FinishedCandidate f[2];
    for (int i = 0; i < n; ++i) {
        double t = c[i].t;
        f[i] = {t,
                c[i].kind,
                !std::isfinite(t) || std::isnan(c[i].z),
                c[i].z >= e.lo && c[i].z <= e.hi && in_range(t, l.range),
                {}};
        if (q.points)
            f[i].p = {std::fma(t, l.v.x, l.L0.x), std::fma(t, l.v.y, l.L0.y),
                      std::fma(t, l.v.z, l.L0.z)};
    }
    Result r;
    assemble(f, n, q, r);
    return r;
}

template <class BT>
Result finish_certified(CertifiedCandidate<BT>* c, int n, bool classification_certain, Extent e,
                        const Line& l, Query q) {
    // Every return is of r (so it is built in place): a failure replaces it.
    Result r;
    for (int i = 0; i < n; ++i)
        if (!std::isfinite(c[i].t.v)) {
            r = Result::failure(ErrorCode::out_of_range, "t");
            return r;
        }
    if (n == 2 && c[1].t.v < c[0].t.v) std::swap(c[0], c[1]);
    bool all_certain = classification_certain;
    for (int i = 0; i < n; ++i) {
        // Each test is a sign: certain when the bound excludes zero (or the value is exactly 0).
        BT above_lo = std::isfinite(e.lo) ? c[i].z - BT::exact(e.lo) : BT{};
        BT below_hi = std::isfinite(e.hi) ? BT::exact(e.hi) - c[i].z : BT{};
        bool certain = c[i].certain;
        bool inside = true;
        auto test = [&](BT x, bool bounded) {
            if (!bounded) return;
            inside = inside && x.v >= 0;
            certain = certain && (x.certain_sign() != 0 || exactly_zero(x));
        };
        test(above_lo, std::isfinite(e.lo));
        test(below_hi, std::isfinite(e.hi));
        test(c[i].t, l.range != Range::line);
        test(BT::exact(1) - c[i].t, l.range == Range::segment);
        all_certain = all_certain && certain;
        if (!inside) continue;
        if (r.count > 0 && q.need != Need::all) continue;
        Hit& h = r.hits[r.count++];
        h.t = c[i].t.v;
        h.bound = c[i].t.bound();
        h.kind = c[i].kind;
        h.certain = certain;
        if (q.points) {
            h.p = {std::fma(h.t, l.v.x, l.L0.x), std::fma(h.t, l.v.y, l.L0.y),
                   std::fma(h.t, l.v.z, l.L0.z)};
            if (!is_finite(h.p)) {
                r = Result::failure(ErrorCode::out_of_range, "p");
                return r;
            }
        }
    }
    r.certainty = all_certain ? Certainty::certain : Certainty::uncertain;
    return r;
}

template Result finish_certified(CertifiedCandidate<QuickBounded>*, int, bool, Extent, const Line&,
                                 Query);
template Result finish_certified(CertifiedCandidate<Bounded>*, int, bool, Extent, const Line&,
                                 Query);

Result finish_on_surface(double z0, double dz, double t_scale, Extent e, const Line& l) {
    // dz != 0 on every surface line: it runs along the axis (cylinders) or a generator (cone).
    // The interval is cut to the range in the prescaled parameter, where neither end has
    // underflowed, and only then scaled back (an end may then round to +-0 or overflow).
    double a = (e.lo - z0) / dz, b = (e.hi - z0) / dz;
    if (std::isnan(a)) a = -inf; // guards (-inf) / 0-like cases for unbounded extents
    if (std::isnan(b)) b = inf;
    double s0 = std::min(a, b), s1 = std::max(a, b);
    if (l.range != Range::line) s0 = std::max(s0, 0.0);
    if (l.range == Range::segment) s1 = std::min(s1, 1 / t_scale);
    Result r;
    if (!(s0 <= s1)) return r;
    r.on_surface = true;
    // An unbounded end stays unbounded, even if t_scale underflowed (inf * 0 would be NaN).
    auto to_caller = [&](double x) { return std::isinf(x) ? x : x * t_scale; };
    r.s0 = to_caller(s0), r.s1 = to_caller(s1);
    if (l.range != Range::line) r.s0 = std::max(r.s0, 0.0) + 0.0; // +0, never -0, at a range start
    if (l.range == Range::segment) r.s1 = std::min(r.s1, 1.0);
    return r;
}

namespace {
// 2^e for |e| <= 1000 built from its bits, and the binary exponent of a normal number read
// from its bits: both exact, and inline (libm's ldexp and ilogb are calls).
double pow2(int e) {
    std::uint64_t bits = std::uint64_t(e + 1023) << 52;
    double x;
    std::memcpy(&x, &bits, sizeof x);
    return x;
}
int exponent_of(double m) {
    std::uint64_t bits;
    std::memcpy(&bits, &m, sizeof bits);
    int biased = int((bits >> 52) & 0x7ff);
    int e = biased == 0 ? (m == 0 ? 0 : std::ilogb(m)) : biased - 1023; // subnormals: libm
    return std::clamp(e, -1000, 1000);
}
} // namespace

bool fragile_scene(double extent, std::initializer_list<Vec3> positions, Vec3 v) {
    // 0 < |x| < below, as one unsigned comparison of magnitude bits minus one (0 wraps to the
    // largest): no branch per component, since this runs on every certified solve. The inputs
    // are finite (validated).
    auto tiny = [](Vec3 u, double scale) {
        auto magnitude = [](double x) {
            std::uint64_t bits;
            std::memcpy(&bits, &x, sizeof bits);
            return bits & 0x7fffffffffffffffu;
        };
        auto magnitude_less_one = [&](double x) { return magnitude(x) - 1; };
        // A threshold that underflowed to 0 has nothing below it.
        std::uint64_t b = magnitude(min_relative_size * scale), below = b == 0 ? 0 : b - 1;
        return (magnitude_less_one(u.x) < below) | (magnitude_less_one(u.y) < below) |
               (magnitude_less_one(u.z) < below);
    };
    bool fragile = tiny(v, max_abs(v));
    for (Vec3 p : positions)
        fragile |= tiny(p, extent);
    return fragile;
}

Prescale prescale_for(double max_position, Vec3 v) {
    int k = exponent_of(max_position), j = exponent_of(max_abs(v));
    Prescale p;
    p.to_unit = pow2(-k);
    p.dir_to_unit = pow2(-j);
    // k - j may leave double's range: ldexp then overflows to inf or underflows, and finish()
    // reports out_of_range for the non-finite t that follows.
    p.t_factor = k - j >= -1000 && k - j <= 1000 ? pow2(k - j) : std::ldexp(1.0, k - j);
    return p;
}

} // namespace detail

Error validate(const Cylinder& s, const Line& l) {
    Error e = check_all(l, {{s.C, "C"}, {s.H, "H"}});
    if (e.code != ErrorCode::none) return e;
    if (std::isnan(s.r)) return {ErrorCode::not_a_number, "r"};
    if (std::isinf(s.r)) return {ErrorCode::infinite, "r"};
    if (!(s.r > 0)) return {ErrorCode::bad_radius, "r"};
    if (s.H == s.C) return {ErrorCode::degenerate_axis, "H-C"};
    return {};
}

namespace detail {

ValidFrame validate_frame(const EllipticCylinder& s, const Line& l) {
    Error e = check_all(l, {{s.C, "C"}, {s.a, "a"}, {s.b, "b"}, {s.c, "c"}});
    if (e.code != ErrorCode::none) return {e};
    int orientation =
        s.a == Vec3{} || s.b == Vec3{} || s.c == Vec3{} ? 0 : det3_sign_exact(s.a, s.b, s.c);
    if (orientation == 0) return {{ErrorCode::singular_frame, "a,b,c"}};
    return {{}, orientation};
}

ValidFrame validate_frame(const EllipticCone& s, const Line& l) {
    Error e = check_all(l, {{s.C, "C"}, {s.H, "H"}, {s.a, "a"}, {s.b, "b"}});
    if (e.code != ErrorCode::none) return {e};
    if (s.H == s.C) return {{ErrorCode::degenerate_axis, "H-C"}};
    int orientation = cone_det_sign_exact(s.a, s.b, s.C, s.H);
    if (orientation == 0) return {{ErrorCode::singular_frame, "a,b,H-C"}};
    return {{}, orientation};
}

} // namespace detail

Error validate(const EllipticCylinder& s, const Line& l) {
    return detail::validate_frame(s, l).error;
}

Error validate(const EllipticCone& s, const Line& l) {
    return detail::validate_frame(s, l).error;
}

Error validate(const Shape& s, const Line& l) {
    return std::visit([&](const auto& shape) { return validate(shape, l); }, s);
}

} // namespace linequad
