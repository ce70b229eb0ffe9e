// The oracle: each shape's exact form (fast/src/shapes/: derivation and classification) in
// CGAL::Mpzf, every decision exact; then each output rounded to the nearest double, or float for
// a binary32 answer, by MPFR.
#include "linequad/exact.hpp"

#include "rounding.hpp"
#include "shapes/all.hpp"

#include <CGAL/Gmpq.h>
#include <CGAL/Mpzf.h>
#include <CGAL/number_utils.h>

#include <limits>
#include <stdexcept>

namespace linequad::exact {

namespace {

// Every value here is dyadic (see rounding.hpp); m 2^e from a canonical rational p / 2^k.
void dyadic_from_mpq(mpq_srcptr q, Dyadic& d) {
    std::size_t k = mpz_sizeinbase(mpq_denref(q), 2) - 1;
    if (mpz_scan1(mpq_denref(q), 0) != k) throw std::logic_error("oracle value is not dyadic");
    mpz_set(d.m, mpq_numref(q));
    d.e = -long(k);
}

void to_dyadic(const CGAL::Gmpq& x, Dyadic& d) {
    dyadic_from_mpq(x.mpq(), d);
}

void to_dyadic(const CGAL::Mpzf& x, Dyadic& d) {
    thread_local struct Q {
        mpq_t q;
        Q() { mpq_init(q); }
        ~Q() { mpq_clear(q); }
    } scratch;
    mpq_set_ui(scratch.q, 0, 1); // export_to_mpq_t requires 0 on entry and writes nothing for 0
    x.export_to_mpq_t(scratch.q);
    dyadic_from_mpq(scratch.q, d);
}

template <class NT>
int sgn(const NT& x) {
    return CGAL::sign(x);
}

// Queues (X + Y sqrt(D)) / Den for rounding, in the form that has no cancellation.
template <class NT>
void queue(SurdRounder& r, const NT& X, const NT& Y, const NT& Den, const NT& D) {
    SurdRounder::Value& v = r.next();
    int sx = sgn(X), sy = CGAL::is_zero(D) ? 0 : sgn(Y);
    to_dyadic(X, v.X);
    to_dyadic(Den, v.Den);
    if (sy == 0) {
        v.form = SurdRounder::Form::rational;
        return;
    }
    to_dyadic(Y, v.Y);
    if (sx * sy >= 0) {
        v.form = SurdRounder::Form::sum;
    } else {
        v.form = SurdRounder::Form::conjugate;
        to_dyadic(NT(X * X - Y * Y * D), v.N2);
    }
}

// One rounder per thread: MPFR and GMP state are costly to create per call.
SurdRounder& rounder() {
    thread_local SurdRounder r;
    return r;
}

// The on-surface interval's ends are rational: num / den.
template <class NT>
Result round_on_surface(const exact_form::Classification<NT>& c, Precision target) {
    Result r;
    r.on_surface = true;
    r.surface_part = c.surface_part;
    SurdRounder& rd = rounder();
    rd.clear();
    // The ends of a disc's chord are (num + S sqrt(D)) / den; every other end is rational.
    bool chord = c.s0.S != 0 || c.s1.S != 0;
    NT D = chord ? c.D : NT(0);
    to_dyadic(D, rd.D());
    if (c.s0.bounded) queue(rd, c.s0.num, NT(c.s0.S), c.s0.den, D);
    if (c.s1.bounded) queue(rd, c.s1.num, NT(c.s1.S), c.s1.den, D);
    rd.run(target);
    r.s0 = c.s0.bounded ? rd.result(0) : -INFINITY;
    r.s1 = c.s1.bounded ? rd.result(c.s0.bounded ? 1 : 0) : INFINITY;
    return r;
}

template <class NT, class ShapeT>
Result solve(const ShapeT& shape, const Line& l, Query query, Precision target) {
    if (Error e = validate(shape, l); !e.ok()) return Result::failure(e);
    if (target == Precision::binary32)
        if (Error e = detail::binary32_error(shape, l); !e.ok()) return Result::failure(e);
    // The frame's orientation folds into the extent; the oracle decides it in NT itself.
    using Traits = detail::ShapeTraits<ShapeT>;
    int orientation = Traits::template exact_orientation<NT>(shape);
    exact_form::Classification<NT> c =
        exact_form::classify(Traits::template exact_quadratic<NT>(shape, l, orientation),
                             exact_form::parameter_range<NT>(l.range), query.need);
    if (c.outcome == exact_form::Outcome::on_surface) return round_on_surface(c, target);
    if (c.outcome != exact_form::Outcome::hits) return Result{}; // exact: never undecided
    bool points = query.points && query.need != Need::any;       // a hit test computes no point

    // Round t and, if asked, each coordinate of L0 + t v = (L0 Den + v N + v S sqrt(D)) / Den.
    SurdRounder& rd = rounder();
    rd.clear();
    to_dyadic(c.D, rd.D());
    for (int j = 0; j < c.count; ++j) {
        const exact_form::SurdRoot<NT>& rt = c.roots[j];
        NT S(rt.S);
        queue(rd, rt.N, S, rt.Den, c.D);
        if (!points) continue;
        for (int k = 0; k < 3; ++k) {
            NT L0(l.L0[k]), v(l.v[k]);
            queue(rd, NT(L0 * rt.Den + v * rt.N), NT(v * S), rt.Den, c.D);
        }
    }
    rd.run(target);
    Result r;
    std::size_t per_root = points ? 4 : 1;
    for (int j = 0; j < c.count; ++j) {
        Hit& h = r.hits[r.count++];
        h.kind = c.roots[j].kind;
        h.part = c.roots[j].part;
        h.t = rd.result(j * per_root);
        h.p = points ? Vec3{rd.result(j * per_root + 1), rd.result(j * per_root + 2),
                            rd.result(j * per_root + 3)}
                     : Vec3{};
        h.bound = std::numeric_limits<double>::quiet_NaN(), h.certain = false;
    }
    return r;
}

} // namespace

template <class S, if_solvable<S>>
Result intersect(const S& shape, const Line& l, Query q, Precision p) {
    if constexpr (detail::is_prepared<S>::value)
        return solve<CGAL::Mpzf>(shape.shape(), l, q, p);
    else
        return solve<CGAL::Mpzf>(shape, l, q, p);
}
Result intersect(const Shape& s, const Line& l, Query q, Precision p) {
    return std::visit([&](const auto& shape) { return solve<CGAL::Mpzf>(shape, l, q, p); }, s);
}
Result intersect_gmpq(const Shape& s, const Line& l, Query q, Precision p) {
    return std::visit([&](const auto& shape) { return solve<CGAL::Gmpq>(shape, l, q, p); }, s);
}

#define LINEQUAD_INSTANTIATE_EXACT(S)                                                              \
    template Result intersect(const S&, const Line&, Query, Precision);                            \
    template Result intersect(const Prepared<S>&, const Line&, Query, Precision);
LINEQUAD_FOR_EACH_SHAPE(LINEQUAD_INSTANTIATE_EXACT)

double round_surd(const char* X, const char* Y, const char* D, const char* Den, Precision p) {
    CGAL::Gmpq x(X), y(Y), d(D), den(Den);
    SurdRounder& rd = rounder();
    rd.clear();
    to_dyadic(d, rd.D());
    queue(rd, x, y, den, d);
    rd.run(p);
    return rd.result(0);
}

const Solver& solver(Precision p) {
    static const Solver exact_solver = {
        "exact", "exact rational oracle (CGAL kernel over Mpzf), correctly rounded t and points",
        [](const Shape& s, const Line& l, Query q) { return intersect(s, l, q); }};
    static const Solver exact_binary32 = {
        "exact", "exact rational oracle (CGAL kernel over Mpzf), t and points rounded to float",
        [](const Shape& s, const Line& l, Query q) {
            return intersect(s, l, q, Precision::binary32);
        },
        Precision::binary32};
    return p == Precision::binary32 ? exact_binary32 : exact_solver;
}

} // namespace linequad::exact
