// What the arithmetic knows of a floating-point format, once per format: its precision and
// range, the floors that bounds add for what underflow can hide, and the tricks played on its
// bits. Binary64 here; binary32 is a second specialisation of the same names.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

// Small helpers inlined always: out of line, a call passes its vectors through memory, which
// costs more than their arithmetic (the batch solvers' lanes, the bounded types).
#if defined(__GNUC__)
#define LINEQUAD_INLINE inline __attribute__((always_inline))
#define LINEQUAD_INLINE_LAMBDA __attribute__((always_inline))
#else
#define LINEQUAD_INLINE inline
#define LINEQUAD_INLINE_LAMBDA
#endif

namespace linequad::detail {

template <class F>
struct Format;

template <>
struct Format<double> {
    using Bits = std::uint64_t;
    using Ordinal = std::int64_t;

    static constexpr int precision = 53; // significand bits, the hidden one included
    static constexpr double u = 0x1p-53; // unit roundoff: |fl(x) - x| <= u |x| in the normal range
    static constexpr double denorm_min = 0x1p-1074; // the spacing of the subnormals
    static constexpr double max = std::numeric_limits<double>::max();
    static constexpr double inf = std::numeric_limits<double>::infinity();

    // The absolute floor a running bound adds for what underflow may have hidden: each
    // operation that rounds in the subnormal range errs by up to denorm_min, and 2^14 of them
    // fit under it (no chain in this library is a hundredth as long).
    static constexpr double underflow_floor = 0x1p-1060;
    // Below this a rounding may have been absolute (subnormal) rather than relative: 2^-1070
    // covers one such rounding of a quantity with its own bound's rounding.
    static constexpr double subnormal_slack = 0x1p-1070;
    // A bound computed in k roundings of nonnegative terms, each at most u relatively, is
    // covered by inflating it by 1 + k u for k much less than 1/u; a lower bound is covered by
    // shrinking it by 1 - k u. (k is a power of two: both factors are exact.)
    static constexpr double cover(double k) { return 1 + k * u; }
    static constexpr double shrink(double k) { return 1 - k * u; }
    // Exponents well inside the normal range, where scaling by 2^e is exact and pow2 works.
    static constexpr int moderate_exponent = 1000;
    // A product at least this large keeps its exact fma error (no bit of it is subnormal).
    static constexpr double exact_product_min = 0x1p-960;

    LINEQUAD_INLINE static Bits bits(double x) {
        Bits b;
        std::memcpy(&b, &x, sizeof b);
        return b;
    }
    LINEQUAD_INLINE static double from_bits(Bits b) {
        double x;
        std::memcpy(&x, &b, sizeof x);
        return x;
    }
    static constexpr Bits exponent_mask = Bits(0x7ff) << 52;
    static constexpr Bits significand_mask = (Bits(1) << 52) - 1;

    // 2^e for a normal exponent e (-1022 <= e <= 1023), built from its bits.
    LINEQUAD_INLINE static double pow2(int e) { return from_bits(Bits(e + 1023) << 52); }
    // The binary exponent of x (|x| in [2^e, 2^(e+1))), read from its bits; for subnormals
    // from libm, 0 for zero.
    LINEQUAD_INLINE static int exponent(double x) {
        int biased = int((bits(x) & exponent_mask) >> 52);
        return biased == 0 ? (x == 0 ? 0 : std::ilogb(x)) : biased - 1023;
    }
    // 2^E for |x| in [2^E, 2^(E+1)), exactly; 0 when x is zero or subnormal.
    LINEQUAD_INLINE static double power_of_two_floor(double x) {
        return from_bits(bits(x) & exponent_mask);
    }
    // Half an ulp of a normal |x| >= 2^-969: 2^(E - 53), its exponent bits less 53.
    LINEQUAD_INLINE static double half_ulp_of_normal(double x) {
        return from_bits((bits(x) & exponent_mask) - (Bits(precision) << 52));
    }
    LINEQUAD_INLINE static bool is_power_of_two(double x) {
        return (bits(x) & significand_mask) == 0;
    }
    // Half an ulp of any x: the distance to the next double away from zero, halved.
    static double half_ulp(double x) {
        if (!std::isfinite(x)) return inf;
        double a = std::fabs(x);
        return (from_bits(bits(a) + 1) - a) / 2;
    }

    // Doubles in order as integers: adjacent doubles have adjacent ordinals; +0 and -0 share 0.
    LINEQUAD_INLINE static Ordinal ordinal(double x) {
        Ordinal b = Ordinal(bits(x));
        return b >= 0 ? b : -(b & std::numeric_limits<Ordinal>::max());
    }
    LINEQUAD_INLINE static double from_ordinal(Ordinal k) {
        double x = from_bits(Bits(k >= 0 ? k : -k));
        return k >= 0 ? x : -x;
    }
    // The distance in doubles between a and b (0 when equal, +0 and -0 included).
    static std::uint64_t ulps_between(double a, double b) {
        Ordinal x = ordinal(a), y = ordinal(b);
        return x > y ? std::uint64_t(x) - std::uint64_t(y) : std::uint64_t(y) - std::uint64_t(x);
    }
};

using Binary64 = Format<double>;

} // namespace linequad::detail
