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
    // Into an empty *this.
    void copy_from(const Limbs& o) {
        reserve(o.size_);
        std::memcpy(data_, o.data_, o.size_ * sizeof *data_);
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
    friend BigFloat operator*(const BigFloat& a, const BigFloat& b);
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
    // a + b with b's sign taken as b_sign: a difference without a negated copy of b.
    static BigFloat sum(const BigFloat& a, const BigFloat& b, int b_sign);
    static void sum_of_limbs(const BigFloat& x, int x_sign, const BigFloat& y, int y_sign, long d,
                             BigFloat& r);
};

// x enclosed in bounded double-double from its leading bits: the filters' view of an exact value
// (an infinite bound beyond double's normal range, whose signs are then undecided).
inline BoundedDD enclosure(const BigFloat& x) {
    BigFloat::Leading l = x.leading();
    TwoTerm z = fast_two_sum(l.hi, l.lo);
    return {z.hi, z.lo, l.err == 0 ? 0 : dd_detail::up(l.err)};
}

} // namespace linequad
