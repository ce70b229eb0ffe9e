// Exact classification of the line quadratics of exact_derivation.hpp, and their rounding.
//
// Every root is t = (N + S sqrt(D)) / Den with N, Den, D exact and S in {-1, 0, +1}:
//   A != 0, D > 0:  N = -B, S = -1 and +1, Den = A   (two crossings)
//   A != 0, D = 0:  N = -B, S = 0,         Den = A   (tangent: double root)
//   A = 0, B != 0:  N = -C0, S = 0,        Den = 2B  (one crossing: parallel to a generator)
//   A = B = 0:      on the surface if C0 = 0, else no hit
// Each test on a root (inside the extent, inside the range) is the sign of some X + Y sqrt(D),
// decided exactly: when X and Y differ in sign, by comparing X^2 with Y^2 D.
#include "linequad/exact.hpp"

#include "linequad/exact_derivation.hpp"
#include "linequad/validate.hpp"
#include "rounding.hpp"

#include <CGAL/Gmpq.h>
#include <CGAL/Mpzf.h>
#include <CGAL/Simple_cartesian.h>

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

// sgn(X + Y sqrt(D)), D >= 0.
template <class NT>
int sign_surd(const NT& X, const NT& Y, const NT& D) {
    int sx = sgn(X), sy = CGAL::is_zero(D) ? 0 : sgn(Y);
    if (sy == 0) return sx;
    if (sx == 0 || sx == sy) return sy;
    int cmp = CGAL::compare(X * X, Y * Y * D); // |X| against |Y| sqrt(D)
    return cmp == CGAL::LARGER ? sx : cmp == CGAL::SMALLER ? sy : 0;
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

template <class NT>
struct ExactRoot {
    NT N, Den;
    int S = 0;
    HitKind kind = HitKind::cross;
};

// One rounder per thread: MPFR and GMP state are costly to create per call.
SurdRounder& rounder() {
    thread_local SurdRounder r;
    return r;
}

template <class NT>
bool in_range(const ExactRoot<NT>& r, const NT& D, Range range) {
    if (range == Range::line) return true;
    NT S(r.S);
    int sden = sgn(r.Den);
    if (sign_surd(r.N, S, D) * sden < 0) return false; // t < 0
    if (range == Range::segment && sign_surd(NT(r.Den - r.N), NT(-S), D) * sden < 0) return false;
    return true;
}

template <class NT>
bool in_extent(const ExactRoot<NT>& r, const NT& D, const LineQuadratic<NT>& q) {
    NT S(r.S);
    int sden = sgn(r.Den);
    // Z(t) - lo = (Den (Z0 - lo) + dZ N + S dZ sqrt(D)) / Den
    if (q.lo_bounded &&
        sign_surd(NT(r.Den * (q.Z0 - q.lo) + q.dZ * r.N), NT(S * q.dZ), D) * sden < 0)
        return false;
    if (q.hi_bounded &&
        sign_surd(NT(r.Den * (q.hi - q.Z0) - q.dZ * r.N), NT(-S * q.dZ), D) * sden < 0)
        return false;
    return true;
}

// The line on the surface: Z(t) = Z0 + t dZ within the extent and t within the range, as an
// interval with rational ends (num / den, den > 0), rounded at the end.
template <class NT>
Result on_surface(const LineQuadratic<NT>& q, const Line& l) {
    struct End {
        bool bounded;
        NT num, den;
    };
    auto frac = [](NT num, NT den) {
        if (sgn(den) < 0) num = -num, den = -den;
        return End{true, num, den};
    };
    End a = q.lo_bounded ? frac(q.lo - q.Z0, q.dZ) : End{false, NT(0), NT(1)};
    End b = q.hi_bounded ? frac(q.hi - q.Z0, q.dZ) : End{false, NT(0), NT(1)};
    // Which bound of Z limits t from below depends on the direction dZ.
    bool below_is_a = sgn(q.dZ) > 0;
    End lo = below_is_a ? a : b, hi = below_is_a ? b : a;
    auto less = [](const End& x, const End& y) { return x.num * y.den < y.num * x.den; };
    if (l.range != Range::line) {
        End zero{true, NT(0), NT(1)};
        if (!lo.bounded || less(lo, zero)) lo = zero;
    }
    if (l.range == Range::segment) {
        End one{true, NT(1), NT(1)};
        if (!hi.bounded || less(one, hi)) hi = one;
    }
    Result r;
    if (lo.bounded && hi.bounded && less(hi, lo)) return r;
    r.on_surface = true;
    SurdRounder& rd = rounder();
    rd.clear();
    mpz_set_ui(rd.D().m, 0);
    NT zero(0);
    if (lo.bounded) queue(rd, lo.num, zero, lo.den, zero);
    if (hi.bounded) queue(rd, hi.num, zero, hi.den, zero);
    rd.run();
    r.s0 = lo.bounded ? rd.result(0) : -INFINITY;
    r.s1 = hi.bounded ? rd.result(lo.bounded ? 1 : 0) : INFINITY;
    return r;
}

template <class K, class ShapeT>
Result solve(const ShapeT& shape, const Line& l, Query query) {
    using NT = typename K::FT;
    if (Error e = validate(shape, l); e.code != ErrorCode::none) return Result::failure(e);
    LineQuadratic<NT> q = line_quadratic<K>(shape, l);

    NT D = q.B * q.B - q.A * q.C0;
    ExactRoot<NT> roots[2];
    int n = 0;
    if (CGAL::is_zero(q.A)) {
        if (CGAL::is_zero(q.B)) {
            if (CGAL::is_zero(q.C0)) return on_surface(q, l);
            return Result{};
        }
        D = NT(0);
        roots[n++] = {-q.C0, NT(2) * q.B, 0, HitKind::cross};
    } else if (sgn(D) > 0) {
        int first = sgn(q.A) > 0 ? -1 : 1; // the smaller root first
        roots[n++] = {-q.B, q.A, first, HitKind::cross};
        roots[n++] = {-q.B, q.A, -first, HitKind::cross};
    } else if (CGAL::is_zero(D)) {
        roots[n++] = {-q.B, q.A, 0, HitKind::tangent};
    } else {
        return Result{};
    }

    int kept[2], m = 0;
    for (int i = 0; i < n; ++i) {
        if (!in_extent(roots[i], D, q) || !in_range(roots[i], D, l.range)) continue;
        kept[m++] = i;
        if (query.need != Need::all) break;
    }
    Result r;
    if (m == 0) return r;

    // Round t and, if asked, each coordinate of L0 + t v = (L0 Den + v N + v S sqrt(D)) / Den.
    SurdRounder& rd = rounder();
    rd.clear();
    to_dyadic(D, rd.D());
    for (int j = 0; j < m; ++j) {
        const ExactRoot<NT>& rt = roots[kept[j]];
        NT S(rt.S);
        queue(rd, rt.N, S, rt.Den, D);
        if (!query.points) continue;
        for (int c = 0; c < 3; ++c) {
            NT L0(l.L0[c]), v(l.v[c]);
            queue(rd, NT(L0 * rt.Den + v * rt.N), NT(v * S), rt.Den, D);
        }
    }
    rd.run();
    std::size_t per_root = query.points ? 4 : 1;
    for (int j = 0; j < m; ++j) {
        Hit& h = r.hits[r.count++];
        h.kind = roots[kept[j]].kind;
        h.t = rd.result(j * per_root);
        if (query.points)
            h.p = {rd.result(j * per_root + 1), rd.result(j * per_root + 2),
                   rd.result(j * per_root + 3)};
    }
    return r;
}

using MpzfKernel = CGAL::Simple_cartesian<CGAL::Mpzf>;
using GmpqKernel = CGAL::Simple_cartesian<CGAL::Gmpq>;

} // namespace

Result intersect(const Cylinder& s, const Line& l, Query q) {
    return solve<MpzfKernel>(s, l, q);
}
Result intersect(const EllipticCylinder& s, const Line& l, Query q) {
    return solve<MpzfKernel>(s, l, q);
}
Result intersect(const EllipticCone& s, const Line& l, Query q) {
    return solve<MpzfKernel>(s, l, q);
}
Result intersect(const Shape& s, const Line& l, Query q) {
    return std::visit([&](const auto& shape) { return solve<MpzfKernel>(shape, l, q); }, s);
}
Result intersect_gmpq(const Shape& s, const Line& l, Query q) {
    return std::visit([&](const auto& shape) { return solve<GmpqKernel>(shape, l, q); }, s);
}

double round_surd(const char* X, const char* Y, const char* D, const char* Den) {
    CGAL::Gmpq x(X), y(Y), d(D), den(Den);
    SurdRounder& rd = rounder();
    rd.clear();
    to_dyadic(d, rd.D());
    queue(rd, x, y, den, d);
    rd.run();
    return rd.result(0);
}

const Solver& solver() {
    static const Solver exact_solver = {
        "exact", "exact rational oracle (CGAL kernel over Mpzf), correctly rounded t and points",
        [](const Cylinder& s, const Line& l, Query q) { return intersect(s, l, q); },
        [](const EllipticCylinder& s, const Line& l, Query q) { return intersect(s, l, q); },
        [](const EllipticCone& s, const Line& l, Query q) { return intersect(s, l, q); }};
    return exact_solver;
}

} // namespace linequad::exact
