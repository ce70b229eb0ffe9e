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

namespace {

// Limb i of y shifted left by 64 words + s bits (s < 64), formed as it is read.
struct Shifted {
    const Limbs& y;
    std::size_t words;
    unsigned s;
    std::size_t size() const { return y.size() + words + (s != 0); }
    std::uint64_t operator[](std::size_t i) const {
        if (i < words) return 0;
        std::size_t j = i - words;
        std::uint64_t lo = j < y.size() ? y[j] << s : 0;
        std::uint64_t hi = s != 0 && j >= 1 && j - 1 < y.size() ? y[j - 1] >> (64 - s) : 0;
        return lo | hi;
    }
};

} // namespace

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
LINEQUAD_LIMB_LOOP BigFloat BigFloat::sum(const BigFloat& a, const BigFloat& b, int b_sign) {
    if (b_sign == 0) return a;
    if (a.sign_ == 0) {
        BigFloat r = b;
        r.sign_ = b_sign;
        return r;
    }
    bool a_lower = a.exp_ <= b.exp_;
    const BigFloat& x = a_lower ? a : b;
    const BigFloat& y = a_lower ? b : a;
    int x_sign = a_lower ? a.sign_ : b_sign, y_sign = a_lower ? b_sign : a.sign_;
    unsigned long d = static_cast<unsigned long>(y.exp_ - x.exp_);
    Shifted ys{y.mag, d / 64, unsigned(d % 64)};
    std::size_t n = std::max(x.mag.size(), ys.size());
    BigFloat r;
    r.exp_ = x.exp_;
    r.sign_ = x_sign;
    r.mag.resize(n + 1);
    std::uint64_t carry = 0; // or borrow
    if (x_sign == y_sign) {
        for (std::size_t i = 0; i < n; ++i) {
            std::uint64_t xi = i < x.mag.size() ? x.mag[i] : 0, s = xi + ys[i];
            std::uint64_t c1 = s < xi;
            r.mag[i] = s + carry;
            carry = c1 | (r.mag[i] < s);
        }
        r.mag[n] = carry;
    } else {
        for (std::size_t i = 0; i < n; ++i) {
            std::uint64_t xi = i < x.mag.size() ? x.mag[i] : 0, yi = ys[i], t = xi - yi;
            std::uint64_t b1 = xi < yi;
            r.mag[i] = t - carry;
            carry = b1 | (t < carry);
        }
        r.mag[n] = 0;
        if (carry != 0) {
            std::uint64_t c = 1;
            for (std::size_t i = 0; i < n; ++i) {
                r.mag[i] = ~r.mag[i] + c;
                c = c != 0 && r.mag[i] == 0;
            }
            r.sign_ = y_sign;
        }
    }
    while (!r.mag.empty() && r.mag.back() == 0)
        r.mag.pop_back();
    r.normalize();
    return r;
}

LINEQUAD_LIMB_LOOP BigFloat operator*(const BigFloat& a, const BigFloat& b) {
    if (a.sign_ == 0 || b.sign_ == 0) return BigFloat();
    BigFloat r;
    r.sign_ = a.sign_ * b.sign_;
    r.exp_ = a.exp_ + b.exp_;
    r.mag.assign(a.mag.size() + b.mag.size(), 0);
    for (std::size_t i = 0; i < a.mag.size(); ++i) {
        unsigned __int128 carry = 0;
        for (std::size_t j = 0; j < b.mag.size(); ++j) {
            unsigned __int128 t = (unsigned __int128)a.mag[i] * b.mag[j] + r.mag[i + j] + carry;
            r.mag[i + j] = std::uint64_t(t);
            carry = t >> 64;
        }
        r.mag[i + b.mag.size()] = std::uint64_t(carry);
    }
    while (r.mag.back() == 0)
        r.mag.pop_back();
    return r; // odd times odd is odd: already normal
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
    __int128 R =
        (__int128(t1) - __int128(static_cast<unsigned __int128>(hi))) * (__int128(1) << 64) +
        __int128(t2);
    double lo = double(R);
    __int128 off = R - __int128(lo);
    double err = double(off < 0 ? -off : off) + (rest ? 1 : 0); // exact: at most 2^22 + 1
    // Scaled by powers of two that are normal doubles (F in [-900, 860]), into results that are
    // normal too (hi in [2^63, 2^64], lo and err integers below 2^75): exact products, as ldexp
    // would give, without its library call.
    double s = sign_ < 0 ? -1 : 1, at_F = detail::Binary64::pow2(int(F));
    return {s * (hi * detail::Binary64::pow2(int(F + 64))), s * (lo * at_F), err * at_F};
}

} // namespace linequad
