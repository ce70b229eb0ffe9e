#include "linequad/solvers.hpp"

#include "linequad_build_info.hpp"

namespace linequad {

Result Solver::operator()(const Shape& s, const Line& l, Query q) const {
    switch (s.index()) {
    case 0:
        return cylinder(std::get<Cylinder>(s), l, q);
    case 1:
        return elliptic_cylinder(std::get<EllipticCylinder>(s), l, q);
    default:
        return elliptic_cone(std::get<EllipticCone>(s), l, q);
    }
}

const std::vector<Solver>& fast_solvers() {
    static const std::vector<Solver> solvers = {
        {"seed", "the seed derivations as written (errata fixed): textbook quadratic",
         seed::intersect, seed::intersect, seed::intersect},
        {"stable", "geometric discriminant, closest-approach origin, stable root pair",
         stable::intersect, stable::intersect, stable::intersect},
        {"certified", "stable's geometry with rigorous error bounds; certain or marked uncertain",
         certified::intersect, certified::intersect, certified::intersect},
        {"correct",
         "exact classification, correctly rounded t and points: double-double, then exact",
         correct::intersect, correct::intersect, correct::intersect},
    };
    return solvers;
}

BuildInfo build_info() {
    return {LINEQUAD_VERSION, LINEQUAD_COMPILER, LINEQUAD_FAST_FLAGS};
}

} // namespace linequad
