// The certified solver's two bounded types and its guards, checked against 4096-bit MPFR and
// against their definitions.
#include "support.hpp"

#include "forms/certified.hpp"
#include "forms/prescale.hpp"
#include "numeric/bounded.hpp"

#include <mpfr.h>

#include <cstdint>
#include <vector>

using namespace linequad;
using namespace linequad::test;

namespace {

// A value in MPFR that follows a QuickBounded through a chain of operations: the exact result
// of the exact operands, never the rounded one.
struct Tracked {
    QuickBounded q;
    mpfr_t exact;
    explicit Tracked(double x) : q(QuickBounded::exact(x)) {
        mpfr_init2(exact, 4096);
        mpfr_set_d(exact, x, MPFR_RNDN);
    }
    ~Tracked() { mpfr_clear(exact); }
    Tracked(const Tracked&) = delete;
};

// |q.v - exact|, rounded up.
double distance(const Tracked& t) {
    mpfr_t d;
    mpfr_init2(d, 4096);
    mpfr_sub_d(d, t.exact, t.q.v, MPFR_RNDN); // exact at 4096 bits for these magnitudes
    mpfr_abs(d, d, MPFR_RNDN);
    double r = mpfr_get_d(d, MPFR_RNDU);
    mpfr_clear(d);
    return r;
}

} // namespace

TEST_CASE("QuickBounded bounds hold along chains of every operation") {
    // Chains of 40 operations on values near unit size (as prescaling makes them), each operand
    // an earlier result: the bound must cover the distance to the exact value of the whole
    // chain, which is what deferring the bound's own rounding to bound() has to get right.
    std::mt19937_64 rng(21);
    auto unit = [&] {
        double x =
            std::ldexp(std::uniform_real_distribution<double>(1, 2)(rng), int(rng() % 8) - 4);
        return rng() % 2 ? -x : x;
    };
    long checked = 0;
    for (int chain = 0; chain < 2000; ++chain) {
        std::vector<std::unique_ptr<Tracked>> values;
        for (int i = 0; i < 4; ++i)
            values.push_back(std::make_unique<Tracked>(unit()));
        for (int step = 0; step < 40; ++step) {
            const Tracked& a = *values[rng() % values.size()];
            const Tracked& b = *values[rng() % values.size()];
            auto r = std::make_unique<Tracked>(0.0);
            int op = int(rng() % 5);
            if (op == 3 && b.q.certain_sign() == 0) op = 2; // a divisor of unknown sign: no bound
            switch (op) {
            case 0:
                r->q = a.q + b.q, mpfr_add(r->exact, a.exact, b.exact, MPFR_RNDN);
                break;
            case 1:
                r->q = a.q - b.q, mpfr_sub(r->exact, a.exact, b.exact, MPFR_RNDN);
                break;
            case 2:
                r->q = a.q * b.q, mpfr_mul(r->exact, a.exact, b.exact, MPFR_RNDN);
                break;
            case 3:
                r->q = a.q / b.q, mpfr_div(r->exact, a.exact, b.exact, MPFR_RNDN);
                break;
            default: // sqrt of a value whose exact value is >= 0: a^2
                r->q = sqrt(a.q * a.q);
                mpfr_abs(r->exact, a.exact, MPFR_RNDN);
            }
            // Keep magnitudes in the prescaled range the solvers use; 4096 bits hold every
            // exact value of such a chain (products and sums of 53-bit numbers, rounded
            // quotients and roots: MPFR's rounding at 4096 bits is far below any bound here).
            double m = std::fabs(r->q.v);
            if (!(m > 0x1p-200 && m < 0x1p+200)) continue;
            INFO("chain " << chain << " step " << step << " op " << op);
            REQUIRE(distance(*r) <= r->q.bound());
            ++checked;
            values.push_back(std::move(r));
        }
    }
    CHECK(checked > 40000);
}

TEST_CASE("QuickBounded never calls a zero certain, so exact zeros go to Bounded") {
    QuickBounded a = QuickBounded::exact(0.5), b = QuickBounded::exact(0.25);
    CHECK((a - a).certain_sign() == 0);
    CHECK((a * b - b * a).certain_sign() == 0);
    CHECK((a * b).certain_sign() == 1);
    CHECK((b - a).certain_sign() == -1);
    // Bounded keeps the same exact zero exact: it decides.
    Bounded x = Bounded::exact(0.5), y = Bounded::exact(0.25);
    CHECK(detail::exactly_zero(x * y - y * x));
}

TEST_CASE("certified settles with Bounded what QuickBounded leaves uncertain") {
    // A line on the surface of a cylinder, along the axis: A, B and C0 are exact zeros, which
    // only Bounded can prove; the result must still be certain.
    Shape s = Cylinder{{0, 0, 0}, {0, 0, 4}, 1, true};
    Line on_surface{{1, 0, -1}, {0, 0, 1}, Range::line};
    Result r = run("certified", s, on_surface);
    CHECK(r.on_surface);
    CHECK(r.certainty == Certainty::certain);
    // A generic crossing is certain from the quick pass, and its bounds hold against the
    // oracle's correctly rounded roots: |t - exact| <= bound, where the oracle's t is itself
    // within half an ulp of exact.
    Line across{{-3, 0.25, 2}, {1, 0, 0}, Range::line};
    Result c = run("certified", s, across), oracle = run("exact", s, across);
    REQUIRE(c.count == 2);
    REQUIRE(oracle.count == 2);
    CHECK(c.certainty == Certainty::certain);
    for (int i = 0; i < 2; ++i) {
        double t = oracle.hits[i].t;
        double half_ulp = (std::nextafter(std::fabs(t), INFINITY) - std::fabs(t)) / 2;
        CHECK(std::fabs(c.hits[i].t - t) <= c.hits[i].bound + half_ulp);
    }
}

TEST_CASE("fragile_scene finds exactly the components below 2^-240 of their scale") {
    // Against its definition: some component x != 0 with |x| < 2^-240 scale, for positions (the
    // shape's, given by its smallest nonzero component, and L0) against the extent and for v
    // against its own largest component.
    std::mt19937_64 rng(5);
    auto component = [&] {
        switch (rng() % 5) {
        case 0:
            return 0.0;
        case 1:
            return std::ldexp(1.0, -240) * (rng() % 2 ? 1 : -1); // the threshold itself
        case 2:
            return std::ldexp(std::uniform_real_distribution<double>(1, 2)(rng),
                              int(rng() % 300) - 290); // below and above it
        default:
            return std::uniform_real_distribution<double>(-1, 1)(rng);
        }
    };
    auto vec = [&] { return Vec3{component(), component(), component()}; };
    auto tiny = [](Vec3 u, double scale) {
        for (int i = 0; i < 3; ++i)
            if (u[i] != 0 && std::fabs(u[i]) < 0x1p-240 * scale) return true;
        return false;
    };
    for (int i = 0; i < 20000; ++i) {
        Vec3 p = vec(), L0 = vec(), v = vec();
        if (v == Vec3{}) v.x = 1;
        // Extents from 1 down to where 2^-240 extent underflows to 0 (nothing is below it).
        double extent = std::ldexp(1.0, -int(rng() % 1100));
        double v_scale = max_abs(v);
        bool want = tiny(p, extent) || tiny(L0, extent) || tiny(v, v_scale);
        INFO("extent " << extent);
        REQUIRE(detail::fragile_scene(extent, detail::min_nonzero(p), L0, v) == want);
    }
}
