// A physics engine's ray test against a capped cylinder, in float, written as such engines write
// it: the ray from `from` to `to` (a fraction of the way), the infinite cylinder's quadratic by
// the school formula on a normalised axis, then the end discs by their planes, and a ray that
// starts inside the solid answered as fraction 0. Declared as it answers, so that what the audit
// charges it with is inaccuracy alone (tests/test_worker.cpp: rays from far away).
#include "linequad/audit_plugin.h"

#include <cmath>
#include <initializer_list>

namespace {

struct V {
    float x, y, z;
};
V operator-(V a, V b) {
    return {a.x - b.x, a.y - b.y, a.z - b.z};
}
V operator+(V a, V b) {
    return {a.x + b.x, a.y + b.y, a.z + b.z};
}
V operator*(float s, V a) {
    return {s * a.x, s * a.y, s * a.z};
}
float dot(V a, V b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
V vec(const double* p) {
    return {float(p[0]), float(p[1]), float(p[2])};
}

int solve(void*, const lq_shape* s, const lq_line* l, lq_answer* out) {
    out->status = LQ_HITS;
    V C = vec(s->p), H = vec(s->p + 3), from = vec(l->L0), d = vec(l->v);
    float r = float(s->p[6]);
    V axis = H - C;
    float h = std::sqrt(dot(axis, axis));
    axis = (1 / h) * axis;
    V w = from - C;
    float wz = dot(w, axis), dz = dot(d, axis);
    V w_perp = w - wz * axis, d_perp = d - dz * axis;
    // Inside (or on) the solid at the start: fraction 0.
    if (wz >= 0 && wz <= h && dot(w_perp, w_perp) <= r * r) {
        out->count = 1;
        out->hits[0].t = 0;
        return 0;
    }
    float best = INFINITY;
    float a = dot(d_perp, d_perp), b = 2 * dot(w_perp, d_perp), c = dot(w_perp, w_perp) - r * r;
    float disc = b * b - 4 * a * c;
    if (a > 0 && disc >= 0) {
        float t = (-b - std::sqrt(disc)) / (2 * a), z = wz + t * dz;
        if (t >= 0 && t <= 1 && z >= 0 && z <= h) best = t;
    }
    for (float plane : {0.0f, h})
        if (dz != 0) {
            float t = (plane - wz) / dz;
            V p = w + t * d;
            V q = p - dot(p, axis) * axis;
            if (t >= 0 && t <= 1 && dot(q, q) <= r * r && t < best) best = t;
        }
    if (best <= 1) {
        out->count = 1;
        out->hits[0].t = best;
    }
    return 0;
}

const lq_solver solvers[] = {{"physics_float", 32, LQ_FIRST_ENTRY, LQ_SEGMENT, LQ_CLOSED, 0,
                              1u << LQ_CYLINDER,
                              "a physics engine's ray test: float, from-to, inside is fraction 0",
                              solve, nullptr, LQ_INSIDE_ZERO, LQ_CONTACT_INTERVAL, nullptr}};

} // namespace

extern "C" int linequad_audit_plugin(int abi, const lq_solver** out) {
    if (abi != LQ_ABI) return -1;
    *out = solvers;
    return 1;
}
