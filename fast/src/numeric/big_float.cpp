#include "numeric/big_float.hpp"

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

LINEQUAD_LIMB_LOOP int compare_mag(const Limbs& a, const Limbs& b) {
    if (a.size() != b.size()) return a.size() < b.size() ? -1 : 1;
    for (std::size_t i = a.size(); i-- > 0;)
        if (a[i] != b[i]) return a[i] < b[i] ? -1 : 1;
    return 0;
}

// a << bits.
LINEQUAD_LIMB_LOOP Limbs shifted_left(const Limbs& a, unsigned long bits) {
    std::size_t words = bits / 64;
    unsigned s = bits % 64;
    Limbs r(a.size() + words + 1, 0);
    for (std::size_t i = 0; i < a.size(); ++i) {
        r[i + words] |= a[i] << s;
        if (s != 0) r[i + words + 1] |= a[i] >> (64 - s);
    }
    while (!r.empty() && r.back() == 0)
        r.pop_back();
    return r;
}

LINEQUAD_LIMB_LOOP void add_to(Limbs& a, const Limbs& b) {
    if (a.size() < b.size()) a.resize(b.size(), 0);
    unsigned carry = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        std::uint64_t bi = i < b.size() ? b[i] : 0;
        std::uint64_t s = a[i] + bi;
        unsigned c1 = s < a[i];
        std::uint64_t s2 = s + carry;
        unsigned c2 = s2 < s;
        a[i] = s2;
        carry = c1 | c2;
        if (i >= b.size() && carry == 0) break;
    }
    if (carry) a.push_back(1);
}

// a -= b, for |a| >= |b|.
LINEQUAD_LIMB_LOOP void subtract_from(Limbs& a, const Limbs& b) {
    unsigned borrow = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        std::uint64_t bi = i < b.size() ? b[i] : 0;
        std::uint64_t d = a[i] - bi;
        unsigned b1 = a[i] < bi;
        std::uint64_t d2 = d - borrow;
        unsigned b2 = d < std::uint64_t(borrow);
        a[i] = d2;
        borrow = b1 | b2;
        if (i >= b.size() && borrow == 0) break;
    }
    while (!a.empty() && a.back() == 0)
        a.pop_back();
}

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

BigFloat operator+(const BigFloat& a, const BigFloat& b) {
    if (a.sign_ == 0) return b;
    if (b.sign_ == 0) return a;
    // Both at the smaller exponent; the other one's magnitude shifted left.
    long e = std::min(a.exp_, b.exp_);
    Limbs x = a.exp_ == e ? a.mag : shifted_left(a.mag, static_cast<unsigned long>(a.exp_ - e));
    Limbs y = b.exp_ == e ? b.mag : shifted_left(b.mag, static_cast<unsigned long>(b.exp_ - e));
    BigFloat r;
    r.exp_ = e;
    if (a.sign_ == b.sign_) {
        add_to(x, y);
        r.mag = std::move(x);
        r.sign_ = a.sign_;
    } else {
        int c = compare_mag(x, y);
        if (c == 0) return BigFloat();
        if (c > 0) {
            subtract_from(x, y);
            r.mag = std::move(x);
            r.sign_ = a.sign_;
        } else {
            subtract_from(y, x);
            r.mag = std::move(y);
            r.sign_ = b.sign_;
        }
    }
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

} // namespace linequad
