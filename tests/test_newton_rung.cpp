// The correct solver's Newton rung: its arithmetic (CompensatedSum), the line forms it builds, and
// its answers, run without scaling at sizes from 2^-600 to 2^600, against exact GMP rationals and
// the oracle.
#include "mpfr_reference.hpp"
#include "rational.hpp"
#include "support.hpp"

#include "correct/correct.hpp"
#include "correct/newton_rung.hpp"
#include "numeric/compensated_sum.hpp"
#include "shapes/all.hpp"

#include "linequad/case_io.hpp"
#include "linequad/exact.hpp"
#include "linequad/families.hpp"

#include <mpfr.h>

#include <vector>

using namespace linequad;
using namespace linequad::test;

namespace {

struct QVec {
    Q x, y, z;
};
QVec qvec(Vec3 a) {
    return {Q(a.x), Q(a.y), Q(a.z)};
}
QVec operator-(const QVec& a, const QVec& b) {
    return {a.x - b.x, a.y - b.y, a.z - b.z};
}
QVec cross(const QVec& a, const QVec& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
Q dot(const QVec& a, const QVec& b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
const Q& at(const QVec& a, int k) {
    return k == 0 ? a.x : k == 1 ? a.y : a.z;
}

// det[a b c] < 0, decided exactly (the frame's orientation, which validation gives the solver).
bool negative_frame(Vec3 a, Vec3 b, const QVec& c) {
    return mpq_sgn(dot(qvec(a), cross(qvec(b), c)).q) < 0;
}
bool negative_frame(const EllipticCylinder& s) {
    return negative_frame(s.a, s.b, qvec(s.c));
}
bool negative_frame(const Ellipsoid& s) {
    return negative_frame(s.a, s.b, qvec(s.c));
}
bool negative_frame(const EllipticCone& s) {
    return negative_frame(s.a, s.b, qvec(s.H) - qvec(s.C));
}

// |value - exact| <= bound, decided exactly.
bool within(const Q& value, const Q& exact, double bound) {
    Q d = value - exact;
    mpq_abs(d.q, d.q);
    return mpq_cmp(d.q, Q(bound).q) <= 0;
}
bool within(const BoundedDD& x, const Q& exact) {
    return within(Q(x.hi) + Q(x.lo), exact, x.e);
}
bool within(double x, double e, const Q& exact) {
    return within(Q(x), exact, e);
}

// Doubles with random mantissas and exponents around `e`, either sign.
double around(std::mt19937_64& rng, int e, int spread) {
    double m = std::uniform_real_distribution<double>(1, 2)(rng);
    double x = std::ldexp(m, e + int(rng() % (2 * spread + 1)) - spread);
    return rng() % 2 ? -x : x;
}

} // namespace

TEST_CASE("CompensatedSum's bound holds for products and small terms at every magnitude") {
    // Sums of up to 5 exact products, some made to cancel, and up to 6 small terms, each a product
    // rounded once (as the rung forms them), at magnitudes from 2^-1000 to 2^900 (small terms down
    // to the subnormal range): the bound must cover the distance from hi + lo to the exact sum of
    // the exact products, whether normalized, left unnormalized or rounded to one double.
    std::mt19937_64 rng(5);
    for (int trial = 0; trial < 20000; ++trial) {
        int e = int(rng() % 1900) - 1000; // the sum's magnitude
        detail::CompensatedSum s;
        Q exact;
        int products = 1 + int(rng() % 5), smalls = int(rng() % 7);
        double last = 0;
        for (int i = 0; i < products; ++i) {
            double a = around(rng, e / 2, 3), b = around(rng, e - e / 2, 3);
            if (i > 0 && rng() % 2) b = -last / a; // cancels the previous product, but for rounding
            last = a * b;
            s.add_product(a, b);
            exact = exact + Q(a) * Q(b);
        }
        for (int i = 0; i < smalls; ++i) {
            double c = around(rng, e / 2 - 26, 3), d = around(rng, e - e / 2 - 27, 3);
            s.add_small(c * d); // stands for the exact c d
            exact = exact + Q(c) * Q(d);
        }
        BoundedDD normalized = s.result(), raw = s.unnormalized(), one = s.rounded();
        INFO("trial " << trial << " magnitude 2^" << e);
        REQUIRE(within(normalized, exact));
        REQUIRE(within(raw, exact));
        REQUIRE(one.lo == 0);
        REQUIRE(within(one, exact));
        CHECK(std::fabs(normalized.lo) <= std::fabs(normalized.hi) * 0x1p-53);
    }
}

TEST_CASE("round_proven returns a double only when every value within the bound rounds to it") {
    // hi + lo +- e times 2^k: lo anywhere up to an ulp either way (near and at the midpoints
    // too), e from 0 to half an ulp, hi sometimes a power of two (whose cell is narrower below),
    // scales that reach the subnormal range. Where round_proven answers v, both ends of the
    // interval must round to v (then every value between does); 4096-bit MPFR is exact here.
    std::mt19937_64 rng(3);
    auto rounds_to = [&](double hi, double lo, double e, int k, double v) {
        return same_bits(mpfr_rounded(hi, lo, e, k, Precision::binary64), v);
    };
    long answered = 0;
    for (int i = 0; i < 200000; ++i) {
        double hi = around(rng, int(rng() % 200) - 100, 0);
        if (rng() % 8 == 0) hi = std::copysign(std::ldexp(1.0, std::ilogb(hi)), hi);
        double ulp = std::ldexp(1.0, std::ilogb(hi) - 52);
        double fraction[] = {0.5,
                             0.25,
                             -0.25,
                             -0.5,
                             0.5 - 0x1p-30,
                             0.25 - 0x1p-30,
                             std::uniform_real_distribution<double>(-1, 1)(rng)};
        double lo = ulp * fraction[rng() % 7];
        double e = rng() % 4 == 0 ? 0 : ulp * std::ldexp(1.0, -int(rng() % 60));
        int k = int(rng() % 121) - 60 - (rng() % 16 == 0 ? 900 : 0);
        std::optional<double> v =
            detail::round_proven<detail::Binary64>({hi, lo, e}, std::ldexp(1.0, k));
        if (!v) continue;
        ++answered;
        INFO("hi " << hi << " lo " << lo << " e " << e << " k " << k);
        REQUIRE(rounds_to(hi, lo, -e, k, *v));
        REQUIRE(rounds_to(hi, lo, e, k, *v));
    }
    CHECK(answered > 50000);
}

TEST_CASE("certain_sign_of_difference decides only what the bounds prove") {
    using detail::certain_sign_of_difference;
    CHECK(certain_sign_of_difference(1, 0x1p-60, 0.5, 0x1p-60) == 1);
    CHECK(certain_sign_of_difference(0.5, 0, 1, 0) == -1);
    // within the bounds of each other: undecided
    CHECK(certain_sign_of_difference(1 + 0x1p-40, 0x1p-40, 1, 0) == 0);
    CHECK(certain_sign_of_difference(std::nan(""), 0, 1, 0) == 0);
    // subnormal neighbours: the difference's rounding is covered below the normal range too
    CHECK(certain_sign_of_difference(0x1p-1073, 0, 0x1p-1074, 0) == 0);
}

namespace {

// The exact U0, U1, K, Z0, dZ and extent end of each shape's line form (newton_rung.hpp).
struct ExactForm {
    QVec U0, U1;
    Q K, Z0, dZ, end; // end: h.h or |det|, the finite extent's nonzero end
};

// The sphere: U0 = w, U1 = v, K = r^2; no extent (its ends 0).
ExactForm exact_form_of(const Sphere& s, const Line& l) {
    Q r(s.r);
    return {qvec(l.L0) - qvec(s.C), qvec(l.v), r * r, Q(), Q(), Q()};
}

ExactForm exact_form_of(const Cylinder& s, const Line& l) {
    QVec h = qvec(s.H) - qvec(s.C), w = qvec(l.L0) - qvec(s.C), v = qvec(l.v);
    Q hh = dot(h, h), r(s.r);
    return {cross(w, h), cross(v, h), r * r * hh, dot(w, h), dot(v, h), hh};
}

// The elliptic shapes: U0 = adj(M) w, U1 = adj(M) v with the rows b x c, c x a, a x b.
ExactForm exact_elliptic(const QVec& a, const QVec& b, const QVec& c, const QVec& w, const QVec& v,
                         bool negative, bool cone) {
    QVec nx = cross(b, c), ny = cross(c, a), nz = cross(a, b);
    Q det = dot(a, nx), sign(negative ? -1.0 : 1.0);
    ExactForm f{{dot(nx, w), dot(ny, w), dot(nz, w)},
                {dot(nx, v), dot(ny, v), dot(nz, v)},
                Q(),
                Q(),
                Q(),
                sign * det};
    f.K = cone ? Q() : det * det;
    f.Z0 = sign * f.U0.z, f.dZ = sign * f.U1.z;
    return f;
}

// line_form's every value within its bound of the exact one.
void check_form(const detail::LineForm& f, const ExactForm& x, bool cone) {
    for (int k = 0; k < 3; ++k) {
        INFO("component " << k);
        CHECK(within(f.U0[k], at(x.U0, k)));
        CHECK(within(f.U1[k], at(x.U1, k)));
    }
    CHECK(within(f.K, x.K));
    CHECK(within(f.Z0, f.e_Z0, x.Z0));
    CHECK(within(f.dZ, f.e_dZ, x.dZ));
    if (cone) // -|det| <= Z <= 0
        CHECK(within(f.lo, f.e_lo, Q() - x.end));
    else
        CHECK(within(f.hi, f.e_hi, x.end));
}

} // namespace

TEST_CASE("line_form's values are within their bounds of the exact ones, at every size") {
    // Family cases (generic, near-tangent, thin and oblique frames, ...) moved to sizes 2^k,
    // k from -150 to 150 (the forms' values, of degree up to 6, stay finite and their low parts
    // reach the subnormal range): U0, U1, K, Z0, dZ and the extent against GMP rationals.
    int checked = 0;
    for (Family fam : {Family::generic, Family::near_tangent, Family::axis_parallel,
                       Family::degenerate_frame, Family::generator})
        for (int shape = 0; shape < shape_kinds; ++shape) {
            if (!family_applies(fam, shape)) continue;
            for (int i = 0; i < 40; ++i) {
                Case c = make_case(fam, shape, Range::line, 9, std::uint64_t(i));
                double f = std::ldexp(1.0, (i * 37) % 301 - 150);
                Line l{f * c.line.L0, c.line.v, Range::line};
                INFO(format_case(c) << "\nscaled by " << f);
                using detail::AsGiven;
                using detail::ShapeTraits;
                if (std::holds_alternative<Frustum>(c.shape) ||
                    std::holds_alternative<Capsule>(c.shape) ||
                    std::holds_alternative<Plane>(c.shape) ||
                    std::holds_alternative<Quadric>(c.shape))
                    continue; // no Newton form (the capsule's patches have theirs)
                if (const auto* p = std::get_if<Cylinder>(&c.shape)) {
                    Cylinder s{f * p->C, f * p->H, f * p->r, true};
                    check_form(ShapeTraits<Cylinder>::line_form(AsGiven<Cylinder>{s}, l.L0, l.v, 0),
                               exact_form_of(s, l), false);
                } else if (const auto* p = std::get_if<Sphere>(&c.shape)) {
                    Sphere s{f * p->C, f * p->r};
                    auto as_given = AsGiven<Sphere>{s};
                    check_form(ShapeTraits<Sphere>::line_form(as_given, l.L0, l.v, 0),
                               exact_form_of(s, l), false);
                    check_form(ShapeTraits<Sphere>::quick_line_form(as_given, l.L0, l.v, 0),
                               exact_form_of(s, l), false);
                } else if (const auto* p = std::get_if<Ellipsoid>(&c.shape)) {
                    Ellipsoid s{f * p->C, f * p->a, f * p->b, f * p->c};
                    if (validate(s, l).code != ErrorCode::none) continue;
                    bool negative = negative_frame(s);
                    ExactForm x =
                        exact_elliptic(qvec(s.a), qvec(s.b), qvec(s.c), qvec(l.L0) - qvec(s.C),
                                       qvec(l.v), negative, false);
                    x.end = Q(); // no extent
                    check_form(ShapeTraits<Ellipsoid>::line_form(AsGiven<Ellipsoid>{s}, l.L0, l.v,
                                                                 negative ? -1 : 1),
                               x, false);
                } else if (const auto* p = std::get_if<EllipticCylinder>(&c.shape)) {
                    EllipticCylinder s{f * p->C, f * p->a, f * p->b, f * p->c, true};
                    if (validate(s, l).code != ErrorCode::none) continue;
                    bool negative = negative_frame(s);
                    ExactForm x =
                        exact_elliptic(qvec(s.a), qvec(s.b), qvec(s.c), qvec(l.L0) - qvec(s.C),
                                       qvec(l.v), negative, false);
                    check_form(ShapeTraits<EllipticCylinder>::line_form(
                                   AsGiven<EllipticCylinder>{s}, l.L0, l.v, negative ? -1 : 1),
                               x, false);
                } else {
                    const auto& q = std::get<EllipticCone>(c.shape);
                    EllipticCone s{f * q.C, f * q.H, f * q.a, f * q.b, true};
                    if (validate(s, l).code != ErrorCode::none) continue;
                    bool negative = negative_frame(s);
                    ExactForm x = exact_elliptic(qvec(s.a), qvec(s.b), qvec(s.H) - qvec(s.C),
                                                 qvec(l.L0) - qvec(s.H), qvec(l.v), negative, true);
                    check_form(ShapeTraits<EllipticCone>::line_form(AsGiven<EllipticCone>{s}, l.L0,
                                                                    l.v, negative ? -1 : 1),
                               x, true);
                }
                ++checked;
            }
        }
    CHECK(checked > 500);
}

namespace {

// The rung on one case as given (no scaling: the bounds must hold at any size), with the form
// built as the ladder builds it; false when the case is invalid.
bool run_rung(const Shape& shape, const Line& l, Query q, Result& r, bool& answered) {
    if (validate(shape, l).code != ErrorCode::none) return false;
    // The orientation as the ladder has it: what validation decided; shapes without a Newton
    // form (the frustum) never reach the rung.
    return std::visit(
        [&](const auto& s) {
            using Traits = detail::ShapeTraits<std::decay_t<decltype(s)>>;
            if constexpr (detail::has_newton_form<std::decay_t<decltype(s)>>) {
                // A surface without extent (a plane, a quadric): its own local quadratic.
                auto form = Traits::newton_form(s, l);
                if (!form) return false; // coincident: the exact form's rungs
                answered = detail::surface_newton_rung<detail::Binary64>(
                    *form, detail::Unit{1, 1, l}, l, q, r, nullptr);
                return true;
            } else if constexpr (Traits::has_line_form) {
                detail::Validity valid = detail::validity_of(s);
                detail::LineForm form = Traits::line_form(
                    detail::AsGiven<std::decay_t<decltype(s)>>{s}, l.L0, l.v, valid.orientation);
                answered =
                    detail::newton_rung<detail::Binary64>(form, detail::Unit{1, 1, l}, l, q, r);
                return true;
            }
            return false;
        },
        shape);
}

// None where the shape cannot be scaled exactly (a quadric's coefficient would lose bits).
std::optional<Shape> scaled_shape(const Shape& s, double f) {
    return std::visit(
        [&](const auto& shape) -> std::optional<Shape> {
            if (auto scaled = detail::scaled(shape, f)) return Shape(*scaled);
            return std::nullopt;
        },
        s);
}

} // namespace

TEST_CASE("the Newton rung, run as given at sizes 2^-600 to 2^600, answers only as the oracle") {
    // Every family, shape and range; scenes scaled by 2^k and directions by 2^(-k/2) (so that
    // t is far from 1 too). Where the rung answers, its classification, t and points must be the
    // oracle's bit for bit; where it cannot prove them, it must not answer (the ladder goes on).
    const Query queries[] = {{Need::all, true}, {Need::nearest, false}};
    long answered = 0, generic_moderate = 0, generic_moderate_answered = 0;
    long surface_moderate = 0, surface_moderate_answered = 0; // planes and quadrics
    for (int f = 0; f < family_count; ++f)
        for (int shape = 0; shape < shape_kinds; ++shape) {
            if (!family_applies(Family(f), shape)) continue;
            for (Range range : {Range::line, Range::ray, Range::segment})
                for (int i = 0; i < 120; ++i) {
                    Case c = make_case(Family(f), shape, range, 17, std::uint64_t(i));
                    // The ladder gives the rung no closed shape: its proof is the lateral
                    // surface's alone.
                    if (std::visit([](const auto& x) { return has_caps(x); }, c.shape)) continue;
                    int k = (i * 83) % 1201 - 600;
                    double size = std::ldexp(1.0, k);
                    Line l{size * c.line.L0, std::ldexp(1.0, -k / 2) * c.line.v, range};
                    std::optional<Shape> scaled = scaled_shape(c.shape, size);
                    if (!scaled) continue;
                    const Shape& s = *scaled;
                    for (Query q : queries) {
                        Result r;
                        bool ok = false;
                        if (!run_rung(s, l, q, r, ok)) continue;
                        bool moderate = std::abs(k) <= 64 && Family(f) == Family::generic;
                        // A plane's or a quadric's generic family mixes in exact zeros (lines
                        // on the surface, tangents, starts on it), which no bound proves: the
                        // rung is counted on the lines whose every hit is a simple root off the
                        // range's ends.
                        bool surface = moderate && (std::holds_alternative<Plane>(s) ||
                                                    std::holds_alternative<Quadric>(s));
                        if (surface) {
                            Result want = exact::intersect(s, l, q);
                            bool simple = want.ok() && !want.on_surface;
                            for (int h = 0; h < want.count; ++h)
                                simple = simple && want.hits[h].kind == HitKind::cross &&
                                         want.hits[h].t != 0 && want.hits[h].t != l.range.t1;
                            surface = simple;
                        }
                        generic_moderate += moderate;
                        surface_moderate += surface;
                        if (!ok) continue;
                        ++answered, generic_moderate_answered += moderate;
                        surface_moderate_answered += surface;
                        Result want = exact::intersect(s, l, q);
                        INFO(format_case(c) << "\nscaled by 2^" << k << "\nrung   " << describe(r)
                                            << "\noracle " << describe(want));
                        REQUIRE(want.ok());
                        REQUIRE(!want.on_surface);
                        REQUIRE(r.count == want.count);
                        for (int h = 0; h < r.count; ++h) {
                            CHECK(r.hits[h].kind == want.hits[h].kind);
                            CHECK(same_bits(r.hits[h].t, want.hits[h].t));
                            if (!q.points) continue;
                            CHECK(same_bits(r.hits[h].p.x, want.hits[h].p.x));
                            CHECK(same_bits(r.hits[h].p.y, want.hits[h].p.y));
                            CHECK(same_bits(r.hits[h].p.z, want.hits[h].p.z));
                        }
                    }
                }
        }
    // Not vacuous: the rung answers most generic cases of moderate size (all of them, in the
    // audit), and many others.
    INFO("answered " << answered << "; generic of moderate size " << generic_moderate_answered
                     << " of " << generic_moderate);
    CHECK(generic_moderate_answered * 10 >= generic_moderate * 9);
    INFO("planes and quadrics, simple roots only: " << surface_moderate_answered << " of "
                                                    << surface_moderate);
    CHECK(surface_moderate > 100);
    CHECK(surface_moderate_answered * 10 >= surface_moderate * 9);
    CHECK(answered > 2000);
}

TEST_CASE("the Newton rung proves a miss, and leaves tangency to the next rungs") {
    Cylinder s{{0, 0, 0}, {0, 0, 4}, 1, true};
    Result r;
    bool answered = false;
    SECTION("a line that passes at distance 2 from the axis: no hit, proven") {
        Line l{{-3, 2, 1}, {1, 0, 0.25}, Range::line};
        REQUIRE(run_rung(s, l, {}, r, answered));
        CHECK(answered);
        CHECK(r.count == 0);
        CHECK(correct::intersect(s, l, {}).rung == Rung::newton);
    }
    SECTION("a tangent line: a double root, which only an exact zero can prove") {
        // The rung's bounds alone never show it; the ladder's exact forms do (here the exact form
        // in double, every input a small integer), and the rung then answers with them.
        Line l{{-3, 1, 1}, {1, 0, 0}, Range::line};
        REQUIRE(run_rung(s, l, {}, r, answered));
        CHECK(!answered);
        Result c = correct::intersect(s, l, {});
        CHECK(c.rung == Rung::newton);
        REQUIRE(c.count == 1);
        CHECK(c.hits[0].kind == HitKind::tangent);
        CHECK(c.hits[0].t == 3);
    }
    SECTION("two crossings: t and points correctly rounded") {
        Line l{{-3, 0.5, 1}, {1, 0, 0.1}, Range::line};
        REQUIRE(run_rung(s, l, {}, r, answered));
        CHECK(answered);
        Result want = exact::intersect(s, l, {});
        REQUIRE(r.count == 2);
        REQUIRE(want.count == 2);
        for (int h = 0; h < 2; ++h) {
            CHECK(same_bits(r.hits[h].t, want.hits[h].t));
            CHECK(same_bits(r.hits[h].p.z, want.hits[h].p.z));
        }
    }
}
