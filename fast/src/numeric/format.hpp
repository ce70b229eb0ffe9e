// What the arithmetic knows of a floating-point format, once per format: its precision and
// range, the floors that bounds add for what underflow can hide, and the tricks played on its
// bits. Binary64 is what the solvers compute in; binary32 is what the float solvers compute in
// and what the correct ladder can round to (a float is held in a double exactly).
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

// A format's bits as an unsigned integer, and its values in order as signed integers: adjacent
// values have adjacent ordinals; +0 and -0 share 0.
template <class R, class B, class O>
struct FormatBits {
    using Real = R;
    using Bits = B;
    using Ordinal = O;
    LINEQUAD_INLINE static Bits bits(Real x) {
        Bits b;
        std::memcpy(&b, &x, sizeof b);
        return b;
    }
    LINEQUAD_INLINE static Real from_bits(Bits b) {
        Real x;
        std::memcpy(&x, &b, sizeof x);
        return x;
    }
    LINEQUAD_INLINE static Ordinal ordinal(Real x) {
        Ordinal b = Ordinal(bits(x));
        return b >= 0 ? b : -(b & std::numeric_limits<Ordinal>::max());
    }
    LINEQUAD_INLINE static Real from_ordinal(Ordinal k) {
        Real x = from_bits(Bits(k >= 0 ? k : -k));
        return k >= 0 ? x : -x;
    }
};

template <>
struct Format<double> : FormatBits<double, std::uint64_t, std::int64_t> {

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

    // The distance in doubles between a and b (0 when equal, +0 and -0 included).
    static std::uint64_t ulps_between(double a, double b) {
        Ordinal x = ordinal(a), y = ordinal(b);
        return x > y ? std::uint64_t(x) - std::uint64_t(y) : std::uint64_t(y) - std::uint64_t(x);
    }
};

using Binary64 = Format<double>;

// binary32: what the float solvers compute in (seed32, stable32), and the correct ladder's second
// rounding target. Its values are passed around in doubles (exactly): the rounding helpers take
// and return doubles.
template <>
struct Format<float> : FormatBits<float, std::uint32_t, std::int32_t> {

    static constexpr int precision = 24;
    static constexpr float u = 0x1p-24f;
    static constexpr float denorm_min = 0x1p-149f;
    static constexpr float max = std::numeric_limits<float>::max();
    static constexpr float inf = std::numeric_limits<float>::infinity();
    static constexpr int min_exponent = -126; // of the normal floats
    static constexpr int max_exponent = 127;
    // 2^k for |k| up to this is normal: the float solvers' prescaling stays there.
    static constexpr int moderate_exponent = 100;

    static constexpr Bits exponent_mask = Bits(0xff) << 23;
    LINEQUAD_INLINE static float pow2(int e) { return from_bits(Bits(e + 127) << 23); }
    LINEQUAD_INLINE static int exponent(float x) {
        int biased = int((bits(x) & exponent_mask) >> 23);
        return biased == 0 ? (x == 0 ? 0 : std::ilogb(x)) : biased - 127;
    }

    // 2^E for |x| in [2^E, 2^(E+1)), exactly; 0 when x is zero or subnormal.
    LINEQUAD_INLINE static float power_of_two_floor(float x) {
        return from_bits(bits(x) & exponent_mask);
    }
    // Whether the double x is a float: finite ones and the infinities (NaN is not asked).
    LINEQUAD_INLINE static bool holds(double x) { return double(float(x)) == x; }

    // Half the spacing of the floats around the float f (a double holding it), away from zero
    // and towards it: they differ at a normal power of two, where the spacing below halves.
    // Subnormal floats (and zero) are 2^-149 apart.
    // (From the double's bits: these run on the correct ladder's every rounding.)
    LINEQUAD_INLINE static double half_spacing_away(double f) {
        double a = std::fabs(f);
        if (a < 0x1p-126) return 0x1p-150;
        return Format<double>::power_of_two_floor(a) * 0x1p-24;
    }
    LINEQUAD_INLINE static double half_spacing_toward(double f) {
        double a = std::fabs(f), h = half_spacing_away(f);
        return a >= 0x1p-125 && Format<double>::is_power_of_two(a) ? 0.5 * h : h;
    }
    // Half an ulp of the float f: the distance to the next float away from zero, halved.
    static double half_ulp(double f) {
        if (!std::isfinite(f)) return std::numeric_limits<double>::infinity();
        return half_spacing_away(f);
    }

    // The distance in floats between two floats (held in doubles).
    static std::uint64_t ulps_between(double a, double b) {
        std::int64_t x = ordinal(float(a)), y = ordinal(float(b));
        return std::uint64_t(x > y ? x - y : y - x);
    }
};

using Binary32 = Format<float>;

} // namespace linequad::detail
