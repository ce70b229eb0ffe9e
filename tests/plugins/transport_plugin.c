/* A transport code's surface distances, written as OpenMC writes them (src/surface.cpp): the
 * plane's -f / (n . u) and the quadric's a, k, c with (-k -+ sqrt(k^2 - a c)) / a, in double,
 * every root in the range returned. Declared for LQ_PLANE and LQ_QUADRIC: the audit reads their
 * fields as audit_plugin.h lays them out (a wrong order would show on the generic family at
 * once) and grades what the textbook formula gets wrong (tests/test_worker.cpp). Its sense entry
 * is OpenMC's too (ABI 4), and a second solver's the same without the 1e-12 band: a tracker's
 * cell search through the plugin (tests/test_cells.cpp). */
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

/* f at p and its gradient, as OpenMC's Surface::evaluate and normal write them. */
static double evaluate(const lq_shape* s, const double* r, double* n) {
    const double* p = s->p;
    double x = r[0], y = r[1], z = r[2];
    if (s->kind == LQ_PLANE) {
        n[0] = p[0], n[1] = p[1], n[2] = p[2];
        return p[0] * x + p[1] * y + p[2] * z - p[3];
    }
    n[0] = 2 * p[0] * x + p[3] * y + p[5] * z + p[6];
    n[1] = 2 * p[1] * y + p[3] * x + p[4] * z + p[7];
    n[2] = 2 * p[2] * z + p[4] * y + p[5] * x + p[8];
    return x * (p[0] * x + p[3] * y + p[6]) + y * (p[1] * y + p[4] * z + p[7]) +
           z * (p[2] * z + p[5] * x + p[8]) + p[9];
}

/* OpenMC's Surface::sense: the sign of f, and where |f| < 1e-12 (FP_COINCIDENT) the side the
 * direction points into. `band` is that 1e-12, or 0 for the variant without it. */
static int sense_with(const lq_shape* s, const double* p, const double* u, double band) {
    double n[3], f = evaluate(s, p, n);
    if (fabs(f) < band || f == 0) return n[0] * u[0] + n[1] * u[1] + n[2] * u[2] > 0 ? 1 : -1;
    return f > 0 ? 1 : -1;
}
static int openmc_sense(void* self, const lq_shape* s, const double p[3], const double u[3],
                        int* side) {
    (void)self;
    *side = sense_with(s, p, u, 1e-12);
    return 0;
}
static int unbanded_sense(void* self, const lq_shape* s, const double p[3], const double u[3],
                          int* side) {
    (void)self;
    *side = sense_with(s, p, u, 0);
    return 0;
}

static const lq_solver solvers[] = {
    {"transport_textbook", 64, LQ_ALL, LQ_LINE, LQ_AS_POSED, 0,
     (1u << LQ_PLANE) | (1u << LQ_QUADRIC),
     "OpenMC's plane and quadric distances: every root in the range; its sense (|f| < 1e-12: by "
     "the direction)",
     solve, NULL, LQ_INSIDE_AS_ANSWERS, LQ_CONTACT_INTERVAL, NULL, 0, 0, 0, 0, 0, openmc_sense},
    {"transport_unbanded", 64, LQ_ALL, LQ_LINE, LQ_AS_POSED, 0,
     (1u << LQ_PLANE) | (1u << LQ_QUADRIC),
     "OpenMC's distances; its sense without the 1e-12 band (the direction only where f = 0)", solve,
     NULL, LQ_INSIDE_AS_ANSWERS, LQ_CONTACT_INTERVAL, NULL, 0, 0, 0, 0, 0, unbanded_sense}};

int linequad_audit_plugin(int abi, const lq_solver** out) {
    if (abi != LQ_ABI) return -1;
    *out = solvers;
    return 2;
}
