// Solvers by name, for programs that pick one at run time (the CLI, the audit). A renderer that
// knows its shape calls seed::intersect or stable::intersect directly.
#pragma once

#include "linequad/cylinder.hpp"
#include "linequad/elliptic_cone.hpp"
#include "linequad/elliptic_cylinder.hpp"

#include <string_view>
#include <vector>

namespace linequad {

struct Solver {
    std::string_view name;
    std::string_view summary;
    Result (*cylinder)(const Cylinder&, const Line&, Query);
    Result (*elliptic_cylinder)(const EllipticCylinder&, const Line&, Query);
    Result (*elliptic_cone)(const EllipticCone&, const Line&, Query);

    Result operator()(const Shape& s, const Line& l, Query q = {}) const;
};

// seed, stable, certified and correct, in that order.
const std::vector<Solver>& fast_solvers();

struct BuildInfo {
    const char* version;
    const char* compiler;
    const char* fast_flags; // the flags fast/ was compiled with
};
BuildInfo build_info();

} // namespace linequad
