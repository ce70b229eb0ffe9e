// Correct rounding of numbers (X + Y sqrt(D)) / Den with X, Y, D, Den exact rationals.
#pragma once

#include <gmp.h>
#include <mpfr.h>

#include <cstddef>

namespace linequad::exact {

// All values share one D (the discriminant of one case), so sqrt(D) is enclosed once per
// precision. Usage: add() each value, run(), then result(i).
class SurdRounder {
  public:
    SurdRounder();
    ~SurdRounder();
    SurdRounder(const SurdRounder&) = delete;
    SurdRounder& operator=(const SurdRounder&) = delete;

    void reset(mpq_srcptr D);
    // Y may be null (a rational value). Returns the value's index.
    int add(mpq_srcptr X, mpq_srcptr Y, mpq_srcptr Den);
    void run();
    double result(int i) const { return values_[i].out; }

  private:
    // A sign-definite interval: the value lies in sign * [lo, hi], 0 <= lo <= hi. Every
    // operation below combines quantities of known sign without cancellation, so magnitudes
    // suffice and each bound is rounded in one known direction.
    struct Mag {
        int sign = 0;
        mpfr_t lo, hi;
    };
    struct Value {
        mpq_t num;     // rational part: X / Den, or X^2 - Y^2 D (rationalised form)
        mpq_t X, Y, Den;
        int form = 0;  // 0: rational, 1: (X + Y sqrt D) / Den, 2: (X^2 - Y^2 D) / (Den (X - Y sqrt D))
        bool done = false;
        double out = 0;
    };

    void set_q(Mag& m, mpq_srcptr q);
    void mul(Mag& r, const Mag& a, const Mag& b);
    void div(Mag& r, const Mag& a, const Mag& b);
    void add_same_sign(Mag& r, const Mag& a, const Mag& b);
    bool try_round(Value& v);
    void set_precision(mpfr_prec_t p);

    mpq_t D_;
    int sign_D_ = 0;
    static constexpr std::size_t capacity = 8; // two roots, each with t and three coordinates
    Value values_[capacity];
    std::size_t used_ = 0;
    Mag sqrtD_, t1_, t2_, t3_, t4_;
    mpfr_prec_t prec_ = 0;
};

} // namespace linequad::exact
