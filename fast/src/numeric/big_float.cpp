#include "numeric/big_float.hpp"

#include "numeric/format.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

// The limb loops are plain arithmetic: coverage feedback from them tells a fuzzer nothing, and
// instrumenting every comparison in them made the fuzzer ten times slower.
#if defined(__clang__)
#define LINEQUAD_LIMB_LOOP __attribute__((no_sanitize("coverage")))
#else
#define LINEQUAD_LIMB_LOOP
#endif

namespace linequad {

// From the encoding: the significand (with its hidden bit, unless subnormal) times 2^(e - 1075),
// its trailing zero bits moved into the exponent. x is finite.
BigFloat::BigFloat(double x) {
    if (x == 0) return;
    std::uint64_t bits;
    std::memcpy(&bits, &x, sizeof bits);
    long biased = long((bits >> 52) & 0x7ff);
    std::uint64_t m = bits & ((std::uint64_t(1) << 52) - 1);
    if (biased != 0) m |= std::uint64_t(1) << 52;
    unsigned zeros = unsigned(__builtin_ctzll(m));
    mag.push_back(m >> zeros);
    exp_ = (biased != 0 ? biased - 1075 : -1074) + long(zeros);
    sign_ = bits >> 63 ? -1 : 1;
}

BigFloat BigFloat::pow2(long e) {
    BigFloat r;
    r.sign_ = 1;
    r.exp_ = e;
    r.mag.push_back(1);
    return r;
}

// Shifts out the trailing zero bits into the exponent, so that every value has one form.
LINEQUAD_LIMB_LOOP void BigFloat::normalize() {
    if (mag.empty()) {
        sign_ = 0, exp_ = 0;
        return;
    }
    std::size_t words = 0;
    while (mag[words] == 0)
        ++words;
    unsigned s = unsigned(__builtin_ctzll(mag[words]));
    if (words == 0 && s == 0) return;
    std::size_t n = mag.size() - words;
    for (std::size_t i = 0; i < n; ++i) {
        std::uint64_t lo = mag[i + words] >> s;
        std::uint64_t hi =
            (s != 0 && i + words + 1 < mag.size()) ? mag[i + words + 1] << (64 - s) : 0;
        mag[i] = lo | hi;
    }
    mag.resize(n);
    while (!mag.empty() && mag.back() == 0)
        mag.pop_back();
    exp_ += long(words) * 64 + s;
}

// In one pass: x, the operand of the smaller exponent, as it is; y shifted onto it as it is read;
// their sum or difference limb by limb. A difference that borrows out of the top was y - x:
// negated (two's complement) and given y's sign.
LINEQUAD_LIMB_LOOP void BigFloat::sum_of_limbs(const BigFloat& x, int x_sign, const BigFloat& y,
                                               int y_sign, unsigned long d, BigFloat& r) {
    std::size_t nx = x.mag.size(), ny = y.mag.size();
    std::size_t words = d / 64;
    unsigned s = unsigned(d % 64);
    std::size_t n = std::max(nx, ny + words + (s != 0));
    r.exp_ = x.exp_;
    r.sign_ = x_sign;
    r.mag.resize_for_writing(n + 1);
    // Distinct objects (r is new): the loops need not reload the limbs after every store.
    const std::uint64_t* __restrict xp = x.mag.data();
    const std::uint64_t* __restrict yp = y.mag.data();
    std::uint64_t* __restrict rp = r.mag.data();
    // Below y's lowest limb: x's limbs, or zeros past them.
    std::size_t i = 0;
    for (; i < words; ++i)
        rp[i] = i < nx ? xp[i] : 0;
    bool add = x_sign == y_sign;
    std::uint64_t carry = 0, below = 0; // carry or borrow; the y limb below the current one
    for (std::size_t j = 0; i < n; ++i, ++j) {
        std::uint64_t yj = j < ny ? yp[j] : 0;
        std::uint64_t yi = s == 0 ? yj : (yj << s) | (below >> (64 - s));
        below = yj;
        std::uint64_t xi = i < nx ? xp[i] : 0;
        if (add) {
            std::uint64_t t = xi + yi, c1 = t < xi;
            rp[i] = t + carry;
            carry = c1 | (rp[i] < t);
        } else {
            std::uint64_t t = xi - yi, b1 = xi < yi;
            rp[i] = t - carry;
            carry = b1 | (t < carry);
        }
    }
    rp[n] = add ? carry : 0;
    if (!add && carry != 0) {
        std::uint64_t c = 1;
        for (i = 0; i < n; ++i) {
            rp[i] = ~rp[i] + c;
            c = c != 0 && rp[i] == 0;
        }
        r.sign_ = y_sign;
    }
    while (!r.mag.empty() && r.mag.back() == 0)
        r.mag.pop_back();
    // x is odd and y 2^d even for d > 0: only equal exponents leave trailing zero bits.
    if (d == 0 || r.mag.empty()) r.normalize();
}

// Schoolbook, the first row writing the limbs the others add to.
LINEQUAD_LIMB_LOOP void BigFloat::product_of_limbs(const BigFloat& a, const BigFloat& b,
                                                   BigFloat& r) {
    using U = unsigned __int128;
    std::size_t na = a.mag.size(), nb = b.mag.size();
    r.mag.resize_for_writing(na + nb);
    const std::uint64_t* __restrict ap = a.mag.data();
    const std::uint64_t* __restrict bp = b.mag.data();
    std::uint64_t* __restrict rp = r.mag.data();
    U carry = 0;
    for (std::size_t j = 0; j < nb; ++j) {
        U t = U(ap[0]) * bp[j] + carry;
        rp[j] = std::uint64_t(t);
        carry = t >> 64;
    }
    rp[nb] = std::uint64_t(carry);
    for (std::size_t i = 1; i < na; ++i) {
        carry = 0;
        for (std::size_t j = 0; j < nb; ++j) {
            U t = U(ap[i]) * bp[j] + rp[i + j] + carry;
            rp[i + j] = std::uint64_t(t);
            carry = t >> 64;
        }
        rp[i + nb] = std::uint64_t(carry);
    }
    while (r.mag.back() == 0)
        r.mag.pop_back();
}

BigFloat::Approx BigFloat::approx() const {
    if (sign_ == 0) return {};
    // The top 64 bits (rounded to a double), scaled into [1, 2).
    std::size_t n = mag.size();
    unsigned lead = 63 - unsigned(__builtin_clzll(mag[n - 1])); // bit index of the top bit
    std::uint64_t top = mag[n - 1] << (63 - lead);
    if (n >= 2 && lead != 63) top |= mag[n - 2] >> (lead + 1);
    double m = std::ldexp(double(top), -63); // in [1, 2]
    long e = exp_ + long(n - 1) * 64 + long(lead);
    if (m >= 2) m /= 2, ++e;
    return {sign_ * m, e};
}

namespace {

// The double nearest an integer |R| < 2^75 (ties to even), without libgcc's 128-bit conversion:
// the bits below the top 64 folded into a sticky bit, far below the rounding position.
double nearest_double(__int128 R) {
    bool negative = R < 0;
    auto m = static_cast<unsigned __int128>(negative ? -R : R);
    auto high = std::uint64_t(m >> 64), low = std::uint64_t(m);
    double d;
    if (high == 0) {
        d = double(low);
    } else {
        int shift = 64 - __builtin_clzll(high); // 1 to 11
        std::uint64_t sticky = (low & ((std::uint64_t(1) << shift) - 1)) != 0;
        d = double(std::uint64_t(m >> shift) | sticky) * double(std::uint64_t(1) << shift);
    }
    return negative ? -d : d;
}

// An integer-valued double |x| < 2^76 as a 128-bit integer, exactly.
__int128 integer_of(double x) {
    if (std::fabs(x) < 0x1p63) return std::int64_t(x);
    std::uint64_t bits;
    std::memcpy(&bits, &x, sizeof bits);
    int e = int((bits >> 52) & 0x7ff) - 1075; // 11 to 23 here
    __int128 m = __int128((bits & ((std::uint64_t(1) << 52) - 1)) | (std::uint64_t(1) << 52)) << e;
    return x < 0 ? -m : m;
}

} // namespace

// |x| = (t1 2^64 + t2 + rho) 2^F, t1's top bit set, 0 <= rho < 1 (rho > 0 when any bit lies
// below t2). hi = RN(t1), within 2^10 of it; R = (t1 - hi) 2^64 + t2 (|R| < 2^75) and its
// rounding lo = RN(R) are exact in 128-bit integers, and so is R - lo.
BigFloat::Leading BigFloat::leading() const {
    if (sign_ == 0) return {};
    long n = long(mag.size());
    auto limb = [&](long i) -> std::uint64_t { return i >= 0 && i < n ? mag[std::size_t(i)] : 0; };
    unsigned lead = 63 - unsigned(__builtin_clzll(mag[std::size_t(n - 1)]));
    unsigned sh = 63 - lead;
    std::uint64_t t1 = limb(n - 1) << sh, t2 = limb(n - 2) << sh, below = limb(n - 3) << sh;
    if (sh != 0) t1 |= limb(n - 2) >> (64 - sh), t2 |= limb(n - 3) >> (64 - sh);
    bool rest = below != 0 || n >= 4; // normalized: the lowest limb is not zero
    long F = exp_ + 64 * (n - 1) + long(lead) - 127;
    if (F < -900 || F > 860) return {0, 0, INFINITY};
    double hi = double(t1);
    // t1 - hi is within 2^10 of zero: exact modulo 2^64 (hi = 2^64 is 0 there).
    auto t1_minus_hi = std::int64_t(t1 - (hi == 0x1p64 ? 0 : std::uint64_t(hi)));
    __int128 R = __int128(t1_minus_hi) * (__int128(1) << 64) + __int128(t2);
    double lo = nearest_double(R);
    __int128 off = R - integer_of(lo);
    double err = double(std::uint64_t(off < 0 ? -off : off)) + (rest ? 1 : 0); // exact: <= 2^22 + 1
    // Scaled by powers of two that are normal doubles (F in [-900, 860]), into results that are
    // normal too (hi in [2^63, 2^64], lo and err integers below 2^75): exact products, as ldexp
    // would give, without its library call.
    double s = sign_ < 0 ? -1 : 1, at_F = detail::Binary64::pow2(int(F));
    return {s * (hi * detail::Binary64::pow2(int(F + 64))), s * (lo * at_F), err * at_F};
}

} // namespace linequad
