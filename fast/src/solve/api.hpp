// The public entry points of a solver type (Seed, Stable, Certified, Correct): a shape as given,
// a prepared shape (both instantiated for every shape) and the variant.
#pragma once

#include "numeric/fp_environment.hpp"
#include "shapes/all.hpp"

#include "linequad/solvers.hpp"

#define LINEQUAD_INSTANTIATE_INTERSECT(S)                                                          \
    template Result intersect(const S&, const Line&, Query);                                       \
    template Result intersect(const Prepared<S>&, const Line&, Query);

#define LINEQUAD_DEFINE_SOLVER(ns, Solver)                                                         \
    namespace linequad::ns {                                                                       \
    template <class S, if_solvable<S>>                                                             \
    Result intersect(const S& shape, const Line& line, Query query) {                              \
        numeric::StandardEnvironment standard;                                                     \
        return detail::solve_shape<detail::Solver>(detail::source(shape), line, query);            \
    }                                                                                              \
    Result intersect(const Shape& shape, const Line& line, Query query) {                          \
        return std::visit([&](const auto& s) { return intersect(s, line, query); }, shape);        \
    }                                                                                              \
    LINEQUAD_FOR_EACH_SHAPE(LINEQUAD_INSTANTIATE_INTERSECT)                                        \
    }
