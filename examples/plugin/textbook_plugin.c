/* An example plugin for `linequad audit --plugin`: a renderer's textbook ray-cylinder test,
 * written in plain C against linequad/audit_plugin.h, audited without rebuilding linequad:
 *
 *     cc -O2 -shared -fPIC -I<linequad>/include textbook_plugin.c -o libtextbook.so -lm
 *     linequad audit --plugin ./libtextbook.so --solvers correct,textbook --shapes cylinder
 *
 * It answers the nearest hit of a finite open cylinder: normalise the axis, project, solve
 * a t^2 + b t + c = 0 with the school formula, keep roots inside the height and the range. */
#include "linequad/audit_plugin.h"

#include <math.h>
#include <string.h>

static double dot3(const double* a, const double* b) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static int solve(void* self, const lq_shape* s, const lq_line* l, lq_answer* out) {
    (void)self;
    memset(out, 0, sizeof *out);
    if (s->kind != LQ_CYLINDER || s->caps || !s->finite) {
        out->status = LQ_UNREPRESENTED; /* this test knows open, finite cylinders only */
        return 0;
    }
    const double *C = s->p, *H = s->p + 3, r = s->p[6];
    double axis[3] = {H[0] - C[0], H[1] - C[1], H[2] - C[2]};
    double h = sqrt(dot3(axis, axis));
    if (!(r > 0) || !(h > 0) || dot3(l->v, l->v) == 0) {
        out->status = LQ_REFUSED;
        strcpy(out->error, h > 0 && r > 0 ? "zero_direction" : "degenerate shape");
        return 0;
    }
    for (int k = 0; k < 3; ++k)
        axis[k] /= h;
    double w[3] = {l->L0[0] - C[0], l->L0[1] - C[1], l->L0[2] - C[2]};
    double vd = dot3(l->v, axis), wd = dot3(w, axis);
    double a = dot3(l->v, l->v) - vd * vd;
    double b = 2 * (dot3(l->v, w) - vd * wd);
    double c = dot3(w, w) - wd * wd - r * r;
    double disc = b * b - 4 * a * c;
    out->status = LQ_HITS;
    if (a == 0 || disc < 0) return 0;
    double roots[2] = {(-b - sqrt(disc)) / (2 * a), (-b + sqrt(disc)) / (2 * a)};
    for (int i = 0; i < 2; ++i) {
        double t = roots[i], z = wd + t * vd;
        if (t < l->t0 || t > l->t1 || z < 0 || z > h) continue;
        lq_hit* hit = &out->hits[out->count++];
        hit->t = t;
        for (int k = 0; k < 3; ++k)
            hit->p[k] = l->L0[k] + t * l->v[k];
        break; /* the nearest only */
    }
    return 0;
}

static const lq_solver solvers[] = {{
    .name = "textbook",
    .precision = 64,
    .answers = LQ_NEAREST,
    .parametrisation = LQ_LINE,
    .surface = LQ_AS_POSED,
    .carries = LQ_POINTS,
    .shapes = 1u << LQ_CYLINDER,
    .mapping = "the school formula on a normalised axis; open finite cylinders only",
    .solve = solve,
    .inside = LQ_INSIDE_AS_ANSWERS, /* a ray that starts inside finds the wall it leaves through */
    .contact = LQ_CONTACT_INTERVAL,
    .start_on_surface = LQ_ON_SURFACE_AS_INSIDE,
    .tangent = LQ_TANGENT_HIT, /* linequad's own semantics: a touch is a hit */
    /* Left 0 or NULL: no self, no batch entry, no surface tolerance, negative distances read
     * as they are, no sense entry (a tracker's side of a point, ABI 4). */
}};

int linequad_audit_plugin(int abi, const lq_solver** out) {
    if (abi != LQ_ABI) return -1;
    *out = solvers;
    return 1;
}
