// Exact dyadic numbers m 2^e (m an integer of any length) for the correct solver's last rung:
// what CGAL::Mpzf is to the oracle, without GMP. Sums, differences and products of doubles are
// exact here at any magnitude, subnormals included, which Shewchuk expansions of doubles cannot
// promise once a product underflows. Only ring operations: the rung never divides.
#pragma once

#include "numeric/bounded_dd.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>

namespace linequad {

// A BigFloat's limbs: up to `local` of them in place, more on the heap. The exact rung builds
// and drops BigFloats by the million (an audit made nine million heap allocations from them),
// and almost all of its values are products of a few doubles: twelve limbs hold 768 bits, enough
// for the squares of a line from far away (with eight, its exact rung made 15 allocations a solve).
class Limbs {
  public:
    static constexpr std::size_t local = 12;

    Limbs() = default;
    Limbs(const Limbs& o) { copy_from(o); }
    Limbs(Limbs&& o) noexcept { take(o); }
    Limbs& operator=(const Limbs& o) {
        if (this != &o) size_ = 0, copy_from(o);
        return *this;
    }
    Limbs& operator=(Limbs&& o) noexcept {
        if (this != &o) release(), take(o);
        return *this;
    }
    ~Limbs() { release(); }

    std::size_t size() const { return size_; }
    bool empty() const { return size_ == 0; }
    std::uint64_t& operator[](std::size_t i) { return data_[i]; }
    std::uint64_t operator[](std::size_t i) const { return data_[i]; }
    std::uint64_t back() const { return data_[size_ - 1]; }
    std::uint64_t* data() { return data_; }
    const std::uint64_t* data() const { return data_; }
    void pop_back() { --size_; }
    void push_back(std::uint64_t x) {
        reserve(size_ + 1);
        data_[size_++] = x;
    }
    // The limbs past the old size are `fill`.
    void resize(std::size_t n, std::uint64_t fill = 0) {
        reserve(n);
        if (n > size_) std::fill(data_ + size_, data_ + n, fill);
        size_ = n;
    }
    // n limbs whose values the caller writes next: no fill.
    void resize_for_writing(std::size_t n) {
        reserve(n);
        size_ = n;
    }
    // The value hi 2^64 + lo (hi and lo not both zero), in one limb when hi is zero; in place.
    void set_two(std::uint64_t lo, std::uint64_t hi) {
        data_[0] = lo, data_[1] = hi;
        size_ = hi != 0 ? 2 : 1;
    }
    // The value of up to four limbs, the lowest nonzero, without the zero limbs on top; in place.
    void set_four(std::uint64_t l0, std::uint64_t l1, std::uint64_t l2, std::uint64_t l3) {
        data_[0] = l0, data_[1] = l1, data_[2] = l2, data_[3] = l3;
        size_ = l3 != 0 ? 4 : l2 != 0 ? 3 : l1 != 0 ? 2 : 1;
    }

  private:
    std::uint64_t* data_ = in_place_;
    std::size_t size_ = 0, capacity_ = local;
    std::uint64_t in_place_[local];

    bool on_heap() const { return data_ != in_place_; }
    void reserve(std::size_t n) {
        if (n <= capacity_) return;
        std::size_t grown = std::max(n, 2 * capacity_);
        auto* d = new std::uint64_t[grown];
        std::memcpy(d, data_, size_ * sizeof *d);
        release();
        data_ = d, capacity_ = grown;
    }
    void release() {
        if (on_heap()) delete[] data_;
        data_ = in_place_, capacity_ = local;
    }
    // Into an empty *this: up to four limbs (nearly every value the exact forms make) as a fixed
    // block the compiler moves inline, more by memcpy.
    void copy_from(const Limbs& o) {
        if (o.size_ <= 4) {
            std::memcpy(data_, o.data_, 4 * sizeof *data_); // capacity is at least 12
        } else {
            reserve(o.size_);
            std::memcpy(data_, o.data_, o.size_ * sizeof *data_);
        }
        size_ = o.size_;
    }
    void take(Limbs& o) {
        if (o.on_heap()) {
            data_ = o.data_, size_ = o.size_, capacity_ = o.capacity_;
            o.data_ = o.in_place_, o.size_ = 0, o.capacity_ = local;
        } else {
            size_ = 0;
            copy_from(o);
            o.size_ = 0;
        }
    }
};

class BigFloat {
  public:
    BigFloat() = default;
    explicit BigFloat(double x); // exact
    static BigFloat pow2(long e);

    friend BigFloat operator+(const BigFloat& a, const BigFloat& b) { return sum(a, b, b.sign_); }
    friend BigFloat operator-(const BigFloat& a, const BigFloat& b) { return sum(a, b, -b.sign_); }
    // Values of one or two limbs (a double, a product of two: nearly all the exact forms make)
    // here, in 128-bit arithmetic; longer ones out of line.
    friend BigFloat operator*(const BigFloat& a, const BigFloat& b) {
        BigFloat r; // the one result, built in place
        if (a.sign_ == 0 || b.sign_ == 0) return r;
        r.sign_ = a.sign_ * b.sign_;
        r.exp_ = a.exp_ + b.exp_;
        if (a.mag.size() <= 2 && b.mag.size() <= 2)
            r.product_of_small(a, b); // odd times odd is odd: already normal
        else
            product_of_limbs(a, b, r);
        return r;
    }
    friend BigFloat operator-(BigFloat a) {
        a.sign_ = -a.sign_;
        return a;
    }
    friend int sign(const BigFloat& x) { return x.sign_; }

    // x 2^k, exactly.
    BigFloat scaled(long k) const {
        BigFloat r = *this;
        if (r.sign_ != 0) r.exp_ += k;
        return r;
    }

    // An approximation: |x| = m 2^e with m in [1, 2) (to about 2^-52), for first guesses only.
    struct Approx {
        double m = 0; // signed; 0 for x = 0
        long e = 0;
    };
    Approx approx() const;

    // x = hi + lo within err (|x - hi - lo| <= err <= 2^-104 |x|), from its leading 128 bits:
    // for a bounded double-double. err is infinite for an x whose parts would leave double's
    // normal range.
    struct Leading {
        double hi = 0, lo = 0, err = 0;
    };
    Leading leading() const;

  private:
    int sign_ = 0;
    long exp_ = 0; // value = sign * mag * 2^exp
    Limbs mag;     // little-endian, odd (lowest bit set) unless zero

    void normalize();
    // a + b with b's sign taken as b_sign: a difference without a negated copy of b. Operands
    // of at most two limbs less than 64 bits apart here; the rest out of line.
    static BigFloat sum(const BigFloat& a, const BigFloat& b, int b_sign) {
        BigFloat r; // the one result, built in place
        if (b_sign == 0 || a.sign_ == 0) {
            r = b_sign == 0 ? a : b;
            if (b_sign != 0) r.sign_ = b_sign;
            return r;
        }
        bool a_lower = a.exp_ <= b.exp_;
        const BigFloat& x = a_lower ? a : b; // the operand of the smaller exponent
        const BigFloat& y = a_lower ? b : a;
        int x_sign = a_lower ? a.sign_ : b_sign, y_sign = a_lower ? b_sign : a.sign_;
        auto d = static_cast<unsigned long>(y.exp_ - x.exp_);
        if (x.mag.size() <= 2 && y.mag.size() <= 2 && d < 64)
            r.sum_of_small(x, x_sign, y, y_sign, unsigned(d));
        else
            sum_of_limbs(x, x_sign, y, y_sign, d, r);
        return r;
    }
    static void sum_of_limbs(const BigFloat& x, int x_sign, const BigFloat& y, int y_sign,
                             unsigned long d, BigFloat& r);
    static void product_of_limbs(const BigFloat& a, const BigFloat& b, BigFloat& r);

    static unsigned __int128 two_limbs(const BigFloat& x) {
        unsigned __int128 m = x.mag[0];
        if (x.mag.size() == 2) m |= static_cast<unsigned __int128>(x.mag[1]) << 64;
        return m;
    }
    // x + y 2^d into *this (new), x and y of at most two limbs, d < 64: below 2^192. x is odd
    // (normal) and y 2^d even for d > 0, so only d = 0 leaves trailing zero bits.
    void sum_of_small(const BigFloat& x, int x_sign, const BigFloat& y, int y_sign, unsigned d) {
        using U = unsigned __int128;
        U xm = two_limbs(x), ym = two_limbs(y);
        U lo = ym << d; // y 2^d = top 2^128 + lo
        std::uint64_t top = d != 0 ? std::uint64_t(ym >> (128 - d)) : 0;
        if (x_sign == y_sign) {
            U s = lo + xm;
            top += s < lo;
            lo = s, sign_ = x_sign;
        } else if (top != 0 || lo >= xm) {
            top -= lo < xm;
            lo -= xm, sign_ = y_sign;
        } else {
            lo = xm - lo, sign_ = x_sign;
        }
        exp_ = x.exp_;
        if (lo == 0 && top == 0) {
            sign_ = 0, exp_ = 0;
            return;
        }
        if (d == 0) { // shifted down to an odd value
            auto low = std::uint64_t(lo), high = std::uint64_t(lo >> 64);
            int zeros = low != 0    ? __builtin_ctzll(low)
                        : high != 0 ? 64 + __builtin_ctzll(high)
                                    : 128 + __builtin_ctzll(top);
            if (zeros >= 128) {
                lo = U(top) >> (zeros - 128), top = 0;
            } else if (zeros != 0) {
                lo = (lo >> zeros) | (U(top) << (128 - zeros));
                top = zeros < 64 ? top >> zeros : 0;
            }
            exp_ += zeros;
        }
        mag.set_four(std::uint64_t(lo), std::uint64_t(lo >> 64), top, 0);
    }
    // a b into *this (new), a and b of at most two limbs each: four limbs at most, schoolbook in
    // 128 bits.
    void product_of_small(const BigFloat& a, const BigFloat& b) {
        using U = unsigned __int128;
        std::uint64_t a0 = a.mag[0], b0 = b.mag[0];
        U p00 = U(a0) * b0;
        if (a.mag.size() == 1 && b.mag.size() == 1) {
            mag.set_two(std::uint64_t(p00), std::uint64_t(p00 >> 64));
            return;
        }
        std::uint64_t a1 = a.mag.size() == 2 ? a.mag[1] : 0, b1 = b.mag.size() == 2 ? b.mag[1] : 0;
        U p01 = U(a0) * b1, p10 = U(a1) * b0, p11 = U(a1) * b1;
        U mid = (p00 >> 64) + std::uint64_t(p01) + std::uint64_t(p10); // below 3 2^64
        U high = (mid >> 64) + (p01 >> 64) + (p10 >> 64) + std::uint64_t(p11);
        mag.set_four(std::uint64_t(p00), std::uint64_t(mid), std::uint64_t(high),
                     std::uint64_t((high >> 64) + (p11 >> 64)));
    }
};

// x enclosed in bounded double-double from its leading bits: the filters' view of an exact value
// (an infinite bound beyond double's normal range, whose signs are then undecided).
inline BoundedDD enclosure(const BigFloat& x) {
    BigFloat::Leading l = x.leading();
    TwoTerm z = fast_two_sum(l.hi, l.lo);
    return {z.hi, z.lo, l.err == 0 ? 0 : dd_detail::up(l.err)};
}

} // namespace linequad
