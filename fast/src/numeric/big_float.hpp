// Exact dyadic numbers m 2^e (m an integer of any length) for the correct solver's last rung:
// what CGAL::Mpzf is to the oracle, without GMP. Sums, differences and products of doubles are
// exact here at any magnitude, subnormals included, which Shewchuk expansions of doubles cannot
// promise once a product underflows. Only ring operations: the rung never divides.
#pragma once

#include <cstdint>
#include <vector>

namespace linequad {

class BigFloat {
  public:
    BigFloat() = default;
    explicit BigFloat(double x); // exact
    static BigFloat pow2(long e);

    friend BigFloat operator+(const BigFloat& a, const BigFloat& b);
    friend BigFloat operator-(const BigFloat& a, const BigFloat& b) { return a + (-b); }
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

  private:
    int sign_ = 0;
    long exp_ = 0;                  // value = sign * mag * 2^exp
    std::vector<std::uint64_t> mag; // little-endian limbs, odd (lowest bit set) unless zero

    void normalize();
};

} // namespace linequad
