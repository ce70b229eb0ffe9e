#include "peers/peers.hpp"

#include <unistd.h>

#include <climits>
#include <cmath>

namespace linequad::peers {

const std::vector<audit::ExternalSolver>& solvers() {
    static const std::vector<audit::ExternalSolver> all = [] {
        std::vector<audit::ExternalSolver> v;
#ifdef LINEQUAD_PEER_OCCT
        v.push_back(occt());
#endif
#ifdef LINEQUAD_PEER_EMBREE
        v.push_back(embree());
#endif
#ifdef LINEQUAD_PEER_BULLET
        v.push_back(bullet());
#endif
#ifdef LINEQUAD_PEER_ODE
        v.push_back(ode());
#endif
        return v;
    }();
    return all;
}

std::vector<PluginPeer> plugin_peers() {
    std::vector<PluginPeer> out;
#ifdef LINEQUAD_PEER_VECGEOM
    // Beside the program in the build tree; else where `cmake --install` puts it.
    char self[PATH_MAX];
    ssize_t n = ::readlink("/proc/self/exe", self, sizeof self - 1);
    std::string dir = n > 0 ? std::string(self, std::size_t(n)) : std::string();
    dir = dir.substr(0, dir.rfind('/') + 1);
    for (std::string path : {dir + LINEQUAD_PEER_VECGEOM,
                             std::string(LINEQUAD_PEER_PLUGIN_DIR "/" LINEQUAD_PEER_VECGEOM)})
        if (::access(path.c_str(), R_OK) == 0) {
            out.push_back({path, {"vecgeom", "vecgeom_out"}});
            break;
        }
#endif
    return out;
}

Basis basis_along(Vec3 d) {
    Vec3 z = (1 / norm(d)) * d;
    // The coordinate axis least aligned with z, made orthogonal to it.
    Vec3 e = std::fabs(z.x) <= std::fabs(z.y) && std::fabs(z.x) <= std::fabs(z.z) ? Vec3{1, 0, 0}
             : std::fabs(z.y) <= std::fabs(z.z)                                   ? Vec3{0, 1, 0}
                                                                                  : Vec3{0, 0, 1};
    Vec3 x = cross(e, z);
    x = (1 / norm(x)) * x;
    return {x, cross(z, x), z};
}

Result hits_in_range(const double* ts, const Vec3* points, int n, Interval range) {
    Result r;
    for (int i = 0; i < n && r.count < max_hits; ++i) {
        if (!range.contains(ts[i])) continue;
        // Insertion in order of t (at most four hits).
        int k = r.count++;
        for (; k > 0 && r.hits[k - 1].t > ts[i]; --k)
            r.hits[k] = r.hits[k - 1];
        r.hits[k] = Hit{ts[i], points[i], NAN, HitKind::cross, Part::lateral, false};
    }
    return r;
}

} // namespace linequad::peers
