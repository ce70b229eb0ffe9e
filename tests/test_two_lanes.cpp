// Two doubles side by side (numeric/two_lanes.hpp): each operation is double's in each lane, bit
// for bit, and a quadric's two local quadratics at once are the two scalar calls'. Built twice
// (tests/CMakeLists.txt): with FMA, the SSE register form the library uses; without, the
// portable form a build with LINEQUAD_FMA off uses.
#include "numeric/two_lanes.hpp"
#include "shapes/quadric.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

using namespace linequad;
using namespace linequad::detail;

#if LINEQUAD_D2_REGISTER
#define D2_FORM "register"
#else
#define D2_FORM "portable"
#endif

namespace {

std::uint64_t bits_of(double x) {
    std::uint64_t b;
    std::memcpy(&b, &x, sizeof b);
    return b;
}
// The same double, or NaN for NaN (which NaN an operation of two NaNs keeps depends on the
// order of its operands, which the compiler may swap for a commutative one).
bool same(double a, double b) {
    return (std::isnan(a) && std::isnan(b)) || bits_of(a) == bits_of(b);
}

// Values that exercise every branch of the operations: signed zeros, subnormals, powers of two
// (is_power_of_two, half_ulp_of_normal), the extremes, infinities, NaN, and random doubles of
// every exponent.
std::vector<double> operands() {
    const double inf = std::numeric_limits<double>::infinity();
    std::vector<double> v = {0.0,       -0.0,        1.0,         -1.0,
                             0.5,       3.0,         0x1p-1074,   -0x1p-1074,
                             0x1p-1022, 0x1.8p-1030, 0x1p+1023,   -0x1.fffffffffffffp+1023,
                             inf,       -inf,        std::nan("")};
    std::mt19937_64 rng(20261202);
    std::uniform_int_distribution<int> exponent(-1080, 1030);
    std::uniform_real_distribution<double> mantissa(1.0, 2.0);
    for (int i = 0; i < 60; ++i) {
        double x = std::ldexp(mantissa(rng), exponent(rng));
        v.push_back(i % 2 ? -x : x);
    }
    return v;
}

void check_lanes(D2 got, double lane0, double lane1) {
    INFO("lanes " << got[0] << ", " << got[1] << "; expected " << lane0 << ", " << lane1);
    CHECK(same(got[0], lane0));
    CHECK(same(got[1], lane1));
}
void check_mask(M2 got, bool lane0, bool lane1) {
    CHECK(lane(got, 0) == lane0);
    CHECK(lane(got, 1) == lane1);
}

} // namespace

TEST_CASE("two lanes (" D2_FORM "): each operation gives double's bits in each lane",
          "[two_lanes]") {
    std::vector<double> x = operands();
    std::size_t n = x.size();
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = 0; j < n; ++j) {
            // Lane 0 takes (a, b), lane 1 (b', a'): different values in each lane, every pair.
            double a0 = x[i], b0 = x[j], a1 = x[(i + 7) % n], b1 = x[(j + 3) % n];
            double c0 = x[(i + j) % n], c1 = x[(i * 5 + j) % n];
            D2 a(a0, a1), b(b0, b1), c(c0, c1);
            INFO("a = " << a0 << ", " << a1 << "; b = " << b0 << ", " << b1);
            check_lanes(a + b, a0 + b0, a1 + b1);
            check_lanes(a - b, a0 - b0, a1 - b1);
            check_lanes(a * b, a0 * b0, a1 * b1);
            check_lanes(a / b, a0 / b0, a1 / b1);
            check_lanes(-a, -a0, -a1);
            check_lanes(fma(a, b, c), std::fma(a0, b0, c0), std::fma(a1, b1, c1));
            check_lanes(maximum(a, b), maximum(a0, b0), maximum(a1, b1));
            check_lanes(copysign(a, b), std::copysign(a0, b0), std::copysign(a1, b1));
            check_mask(a < b, a0 < b0, a1 < b1);
            check_mask(a <= b, a0 <= b0, a1 <= b1);
            check_mask(a >= b, a0 >= b0, a1 >= b1);
            check_mask(a != b, a0 != b0, a1 != b1);
            M2 lt = a < b, ge = a >= c;
            check_mask(lt & ge, (a0 < b0) && (a0 >= c0), (a1 < b1) && (a1 >= c1));
            check_mask(lt | ge, (a0 < b0) || (a0 >= c0), (a1 < b1) || (a1 >= c1));
            check_mask(!lt, !(a0 < b0), !(a1 < b1));
            check_lanes(select(lt, a, b), a0 < b0 ? a0 : b0, a1 < b1 ? a1 : b1);
        }
    for (double a0 : x) {
        double a1 = -a0 * 3;
        D2 a(a0, a1);
        check_lanes(sqrt(a), std::sqrt(a0), std::sqrt(a1));
        check_lanes(fabs(a), std::fabs(a0), std::fabs(a1));
        check_lanes(D2(a0), a0, a0);
        if (std::isfinite(a0) && std::fabs(a0) >= 0x1p-1022) { // their contract: finite, normal
            check_lanes(half_ulp_of_normal(a), Binary64::half_ulp_of_normal(a0),
                        Binary64::half_ulp_of_normal(a1));
            check_mask(is_power_of_two(a), Binary64::is_power_of_two(a0),
                       Binary64::is_power_of_two(a1));
        }
    }
}

TEST_CASE("two lanes (" D2_FORM "): a quadric's two local quadratics at once are two calls'",
          "[two_lanes]") {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> coefficient(-4, 4), position(-50, 50);
    std::uniform_int_distribution<int> scale(-40, 40);
    auto same_local = [](const newton::Local<double>& a, const newton::Local<double>& b) {
        return same(a.G, b.G) && same(a.e_G, b.e_G) && same(a.Gp, b.Gp) && same(a.e_Gp, b.e_Gp);
    };
    for (int i = 0; i < 3000; ++i) {
        QuadricCoefficients<double> q;
        int k = scale(rng);
        for (double& c : q)
            c = i % 5 == 0 && rng() % 3 == 0 ? 0.0 : std::ldexp(coefficient(rng), k);
        Line l{{position(rng), position(rng), position(rng)},
               {coefficient(rng), coefficient(rng), coefficient(rng)},
               Range::line};
        std::optional<QuadricNewtonForm> form = QuadricNewtonForm::of(q, false, l);
        REQUIRE(form);
        double c0 = std::ldexp(coefficient(rng), scale(rng) / 4), c1 = position(rng);
        newton::Local<D2> both = form->local_at(D2(c0, c1));
        newton::Local<double> lane0{lane(both.G, 0), lane(both.e_G, 0), lane(both.Gp, 0),
                                    lane(both.e_Gp, 0)};
        newton::Local<double> lane1{lane(both.G, 1), lane(both.e_G, 1), lane(both.Gp, 1),
                                    lane(both.e_Gp, 1)};
        INFO("case " << i);
        CHECK(same_local(lane0, form->local_at(c0)));
        CHECK(same_local(lane1, form->local_at(c1)));
    }
}
