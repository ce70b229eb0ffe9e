// Other libraries' line-quadric intersections, audited beside linequad's: each built only when its
// Debian package is present (scripts/install-deps.sh installs them). Each adapter states how a
// case is handed over and what the library cannot represent (ExternalSolver::mapping).
#pragma once

#include "linequad/audit_solver.hpp"

#include <string>
#include <vector>

namespace linequad::peers {

// The peers this build has, in a fixed order: occt, embree, bullet, ode (those present).
const std::vector<audit::ExternalSolver>& solvers();

// The peers that run out of process, as plugins (VecGeom: some of its solids crash): the plugin's
// path and the solvers it offers, for each one built (found beside this program, or installed).
struct PluginPeer {
    std::string path;
    std::vector<std::string> solvers;
};
std::vector<PluginPeer> plugin_peers();

// One per library, defined in its adapter's file when the library is built in.
audit::ExternalSolver occt();
audit::ExternalSolver embree();
audit::ExternalSolver bullet();
audit::ExternalSolver ode();

// The unit vector along d, and two more completing a right-handed orthonormal frame (for
// libraries whose shapes stand on a coordinate axis and are moved into place by a rotation).
struct Basis {
    Vec3 x, y, z;
};
Basis basis_along(Vec3 d);

// The hits of a library's answer at parameters ts (any order), inside [t0, t1], sorted.
Result hits_in_range(const double* ts, const Vec3* points, int n, Interval range);

} // namespace linequad::peers
