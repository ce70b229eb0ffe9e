// Correct rounding of numbers (X + Y sqrt(D)) / Den whose parts are exact dyadic numbers.
//
// Every exact quantity of the oracle is dyadic: the inputs are doubles and the derivation only
// adds and multiplies. So each part is carried as an integer times a power of two and enters
// MPFR through mpfr_set_z_2exp (rounded in a chosen direction, no division).
#pragma once

#include "linequad/result.hpp"
#include "linequad/shapes.hpp"

#include <gmp.h>
#include <mpfr.h>

#include <cstddef>

namespace linequad::exact {

struct Dyadic {
    mpz_t m; // the value is m * 2^e
    long e = 0;
    Dyadic() { mpz_init(m); }
    ~Dyadic() { mpz_clear(m); }
    Dyadic(const Dyadic&) = delete;
    Dyadic& operator=(const Dyadic&) = delete;
    int sign() const { return mpz_sgn(m); }
};

// One case's values share D (its discriminant), so sqrt(D) is enclosed once per precision.
// Usage: set D(), fill slots from next(), run(), then result(i).
class SurdRounder {
  public:
    enum class Form {
        rational,  // X / Den
        sum,       // (X + Y sqrt(D)) / Den, X and Y of one sign: no cancellation
        conjugate, // N2 / (Den (X - Y sqrt(D))) with N2 = X^2 - Y^2 D, for X, Y of opposite sign
    };
    struct Value {
        Dyadic X, Y, Den, N2;
        Form form = Form::rational;
        bool done = false;
        double out = 0;
    };

    SurdRounder();
    ~SurdRounder();
    SurdRounder(const SurdRounder&) = delete;
    SurdRounder& operator=(const SurdRounder&) = delete;

    Dyadic& D() { return D_; }
    void clear() { used_ = 0; }
    Value& next(); // a slot to fill, in order; its index is size() - 1
    std::size_t size() const { return used_; }
    void run(Precision target = Precision::binary64); // rounds every value to target
    double result(std::size_t i) const { return values_[i].out; }

  private:
    // A sign-definite interval: the value lies in sign * [lo, hi], 0 <= lo <= hi. The forms
    // above combine quantities of known sign without cancellation, so magnitudes suffice and
    // each bound is rounded in one known direction.
    struct Mag {
        int sign = 0;
        mpfr_t lo, hi;
    };

    void set(Mag& m, const Dyadic& d);
    static void mul(Mag& r, const Mag& a, const Mag& b);
    static void div(Mag& r, const Mag& a, const Mag& b);
    static void add_same_sign(Mag& r, const Mag& a, const Mag& b);
    bool try_round(Value& v);
    void set_precision(mpfr_prec_t p);

    static constexpr std::size_t capacity = 4 * max_hits; // each hit: t and three coordinates
    Dyadic D_;
    Value values_[capacity];
    std::size_t used_ = 0;
    Mag sqrtD_, t1_, t2_, t3_, t4_;
    mpfr_prec_t prec_ = 0;
    Precision target_ = Precision::binary64;
};

} // namespace linequad::exact
