// Exact signs of small polynomials in doubles, by floating-point expansions (Shewchuk 1997).
//
// An Expansion holds a sum of doubles that is exact, nonoverlapping and ordered by increasing
// magnitude, so its sign is the sign of its last nonzero component. Products are exact as long
// as they neither overflow nor underflow; callers scale their inputs by powers of two first.
#pragma once

#include "numeric/bounded_dd.hpp"
#include "numeric/eft.hpp"

#include <cmath>
#include <cstddef>

namespace linequad {

// Each add keeps at most one more term than it had, so Capacity must be at least the number of
// doubles added: 4 per product of three (the determinants below add at most 48).
template <std::size_t Capacity>
class Expansion {
  public:
    // Grow-Expansion: adds one double exactly.
    void add(double b) {
        if (b == 0) return; // exact, and common: a product with a zero factor
        std::size_t out = 0;
        double q = b;
        for (std::size_t i = 0; i < size_; ++i) {
            TwoTerm s = two_sum(q, terms_[i]);
            q = s.hi;
            if (s.lo != 0) terms_[out++] = s.lo;
        }
        if (q != 0) terms_[out++] = q;
        size_ = out;
    }
    void add_product(double a, double b) {
        TwoTerm p = two_prod(a, b);
        add(p.lo);
        add(p.hi);
    }
    void add_product(double a, double b, double c) {
        TwoTerm p = two_prod(a, b);
        add_product(p.lo, c);
        add_product(p.hi, c);
    }
    int sign() const {
        if (size_ == 0) return 0;
        return terms_[size_ - 1] > 0 ? 1 : -1;
    }
    std::size_t size() const { return size_; }
    double operator[](std::size_t i) const { return terms_[i]; }

  private:
    double terms_[Capacity]; // the first size_ of them hold the sum
    std::size_t size_ = 0;
};

// The sum enclosed in double-double: its two largest components, and a bound on the others. Their
// bits lie below the lowest bit of the component above them and overlap no other's, so all of
// them below the second-largest sum to less than twice the third-largest. Exact (e = 0) where at
// most two components are left, a zero among them.
template <std::size_t Capacity>
BoundedDD enclosure(const Expansion<Capacity>& x) {
    std::size_t n = x.size();
    if (n == 0) return BoundedDD(0);
    if (n == 1) return BoundedDD(x[0]);
    TwoTerm top = fast_two_sum(x[n - 1], x[n - 2]); // exact: the largest is above the other's bits
    return {top.hi, top.lo, n == 2 ? 0 : 2 * std::fabs(x[n - 3])};
}

} // namespace linequad
