// Solvers by name, error messages, and what the library was built with.
#include "linequad/solvers.hpp"

#include "linequad_build_info.hpp"

namespace linequad {

const char* range_name(Range r) {
    switch (r) {
    case Range::line:
        return "line";
    case Range::ray:
        return "ray";
    case Range::segment:
        return "segment";
    }
    return "?";
}

const char* precision_name(Precision p) {
    return p == Precision::binary32 ? "binary32" : "binary64";
}

const char* part_name(Part p) {
    switch (p) {
    case Part::lateral:
        return "lateral";
    case Part::base:
        return "base";
    case Part::top:
        return "top";
    }
    return "?";
}

const char* code_name(ErrorCode c) {
    switch (c) {
    case ErrorCode::none:
        return "none";
    case ErrorCode::not_a_number:
        return "not_a_number";
    case ErrorCode::infinite:
        return "infinite";
    case ErrorCode::zero_direction:
        return "zero_direction";
    case ErrorCode::bad_radius:
        return "bad_radius";
    case ErrorCode::degenerate_axis:
        return "degenerate_axis";
    case ErrorCode::singular_frame:
        return "singular_frame";
    case ErrorCode::empty_range:
        return "empty_range";
    case ErrorCode::out_of_range:
        return "out_of_range";
    case ErrorCode::bad_option:
        return "bad_option";
    case ErrorCode::not_binary32:
        return "not_binary32";
    case ErrorCode::along_surface:
        return "along_surface";
    case ErrorCode::zero_coefficients:
        return "zero_coefficients";
    case ErrorCode::foreign:
        return "foreign";
    }
    return "?";
}

std::string message(const Error& e) {
    std::string f = e.field;
    switch (e.code) {
    case ErrorCode::none:
        return "";
    case ErrorCode::not_a_number:
        return f + " has a NaN coordinate";
    case ErrorCode::infinite:
        return f + " has an infinite coordinate";
    case ErrorCode::zero_direction:
        return "the direction " + f + " is the zero vector";
    case ErrorCode::bad_radius:
        return "the radius " + f + " is not positive";
    case ErrorCode::degenerate_axis:
        return f + ": the axis has zero length (H = C)";
    case ErrorCode::singular_frame:
        return "the frame " + f + " is singular (linearly dependent)";
    case ErrorCode::empty_range:
        return f + ": the range holds no t (t0 > t1, or an end at the wrong infinity)";
    case ErrorCode::out_of_range:
        return f + ": magnitudes too far apart for the solver's format (overflow or underflow)";
    case ErrorCode::bad_option:
        if (f == "caps") return "caps: only a finite shape has end discs to close it";
        if (f == "nappes") return "nappes: a cone has 1 or 2";
        return f + ": not an option this shape takes"; // a field that says why, where it can
    case ErrorCode::not_binary32:
        return f + " is not a binary32 value (a float solver takes float inputs)";
    case ErrorCode::along_surface:
        return f + " does not leave the surface at the hit (tangent to it within rounding)";
    case ErrorCode::zero_coefficients:
        return f + " has every coefficient 0 (it is no surface)";
    case ErrorCode::foreign:
        return f + " (the solver's own refusal, not one of linequad's)";
    }
    return "?";
}

const std::vector<Solver>& fast_solvers() {
    static const std::vector<Solver> solvers = {
        {"seed", "the seed derivations as written (errata fixed): textbook quadratic",
         [](const Shape& s, const Line& l, Query q) { return seed::intersect(s, l, q); }},
        {"stable", "geometric discriminant, closest-approach origin, stable root pair",
         [](const Shape& s, const Line& l, Query q) { return stable::intersect(s, l, q); }},
        {"certified", "stable's geometry with rigorous error bounds; certain or marked uncertain",
         [](const Shape& s, const Line& l, Query q) { return certified::intersect(s, l, q); }},
        {"correct",
         "exact classification, correctly rounded t and points: Newton, double-double, exact",
         [](const Shape& s, const Line& l, Query q) { return correct::intersect(s, l, q); }},
        {"seed32", "seed evaluated in float",
         [](const Shape& s, const Line& l, Query q) { return seed32::intersect(s, l, q); },
         Precision::binary32},
        {"stable32", "stable evaluated in float",
         [](const Shape& s, const Line& l, Query q) { return stable32::intersect(s, l, q); },
         Precision::binary32},
        {"correct32",
         "correct's exact classification, with t and points correctly rounded to float",
         [](const Shape& s, const Line& l, Query q) { return correct32::intersect(s, l, q); },
         Precision::binary32},
    };
    return solvers;
}

BuildInfo build_info() {
    return {LINEQUAD_VERSION, LINEQUAD_COMPILER, LINEQUAD_FAST_FLAGS};
}

} // namespace linequad
