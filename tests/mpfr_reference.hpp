// Rounding references from 4096-bit MPFR, which is exact for the sums the tests form.
#pragma once

#include "linequad/shapes.hpp"

#include <mpfr.h>

namespace linequad::test {

// (hi + lo + e) 2^k rounded to the nearest double, or float (held in a double), ties to even.
inline double mpfr_rounded(double hi, double lo, double e, int k, Precision p) {
    mpfr_t x;
    mpfr_init2(x, 4096);
    mpfr_set_d(x, hi, MPFR_RNDN);
    mpfr_add_d(x, x, lo, MPFR_RNDN);
    mpfr_add_d(x, x, e, MPFR_RNDN);
    mpfr_mul_2si(x, x, k, MPFR_RNDN);
    double r =
        p == Precision::binary32 ? double(mpfr_get_flt(x, MPFR_RNDN)) : mpfr_get_d(x, MPFR_RNDN);
    mpfr_clear(x);
    return r;
}

} // namespace linequad::test
