/* A transport code's surface distances, written as OpenMC writes them (src/surface.cpp): the
 * plane's -f / (n . u) and the quadric's a, k, c with (-k -+ sqrt(k^2 - a c)) / a, in double,
 * every root in the range returned. Declared for LQ_PLANE and LQ_QUADRIC: the audit reads their
 * fields as audit_plugin.h lays them out (a wrong order would show on the generic family at
 * once) and grades what the textbook formula gets wrong (tests/test_worker.cpp). */
#include "linequad/audit_plugin.h"

#include <math.h>
#include <string.h>

static void keep(lq_answer* out, const lq_line* l, double t) {
    if (t >= l->t0 && t <= l->t1) out->hits[out->count++].t = t;
}

static int solve(void* self, const lq_shape* s, const lq_line* l, lq_answer* out) {
    (void)self;
    memset(out, 0, sizeof *out);
    out->status = LQ_HITS;
    const double* p = s->p;
    double A = 0, B = 0, C = 0, D = 0, E = 0, F = 0, G, H, J, K;
    int coincident;
    if (s->kind == LQ_PLANE) {
        G = p[0], H = p[1], J = p[2], K = -p[3], coincident = p[4] != 0;
    } else {
        A = p[0], B = p[1], C = p[2], D = p[3], E = p[4], F = p[5];
        G = p[6], H = p[7], J = p[8], K = p[9], coincident = p[10] != 0;
    }
    double x = l->L0[0], y = l->L0[1], z = l->L0[2], u = l->v[0], v = l->v[1], w = l->v[2];
    double a = A * u * u + B * v * v + C * w * w + D * u * v + E * v * w + F * u * w;
    double k = A * u * x + B * v * y + C * w * z +
               0.5 * (D * (u * y + v * x) + E * (v * z + w * y) + F * (w * x + u * z) + G * u +
                      H * v + J * w);
    double c = coincident ? 0.0
                          : A * x * x + B * y * y + C * z * z + D * x * y + E * y * z + F * x * z +
                                G * x + H * y + J * z + K;
    if (a == 0) {
        if (k != 0) {
            keep(out, l, -0.5 * c / k);
        } else if (c == 0) {
            out->status = LQ_ON_SURFACE, out->s0 = l->t0, out->s1 = l->t1;
        }
        return 0;
    }
    double quad = k * k - a * c;
    if (quad < 0) return 0;
    if (quad == 0) {
        keep(out, l, -k / a);
        return 0;
    }
    double root = sqrt(quad), t1 = (-k - root) / a, t2 = (-k + root) / a;
    keep(out, l, t1 < t2 ? t1 : t2);
    keep(out, l, t1 < t2 ? t2 : t1);
    return 0;
}

static const lq_solver solvers[] = {
    {"transport_textbook", 64, LQ_ALL, LQ_LINE, LQ_AS_POSED, 0,
     (1u << LQ_PLANE) | (1u << LQ_QUADRIC),
     "OpenMC's plane and quadric distances: every root in the range", solve, NULL,
     LQ_INSIDE_AS_ANSWERS, LQ_CONTACT_INTERVAL, NULL, 0, 0, 0, 0, 0}};

int linequad_audit_plugin(int abi, const lq_solver** out) {
    if (abi != LQ_ABI) return -1;
    *out = solvers;
    return 1;
}
