/* A plugin whose one solver declares a convention out of range, chosen by the environment variable
 * LQ_TEST_BAD_FIELD (tolerance_absolute, tolerance_relative, negative_zero: -1, NaN or infinity
 * by LQ_TEST_BAD_VALUE; tangent, start_on_surface, inside: a value the ABI does not know). Unset:
 * a valid declaration of each convention. linequad must refuse it at load, naming the solver and
 * the field (tests/test_fair_verdicts.cpp). */
#include "linequad/audit_plugin.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static int solve(void* self, const lq_shape* s, const lq_line* l, lq_answer* out) {
    (void)self, (void)s, (void)l;
    memset(out, 0, sizeof *out);
    out->status = LQ_HITS;
    return 0;
}

static lq_solver solver;

int linequad_audit_plugin(int abi, const lq_solver** out) {
    if (abi != LQ_ABI) return -1;
    const char* field = getenv("LQ_TEST_BAD_FIELD");
    const char* how = getenv("LQ_TEST_BAD_VALUE");
    double bad = !how                      ? -1
                 : strcmp(how, "nan") == 0 ? NAN
                 : strcmp(how, "inf") == 0 ? INFINITY
                                           : -1;
    memset(&solver, 0, sizeof solver);
    solver.name = "declares";
    solver.precision = 64;
    solver.answers = LQ_FIRST_ENTRY;
    solver.parametrisation = LQ_UNIT_DIRECTION;
    solver.surface = LQ_CLOSED;
    solver.shapes = 1u << LQ_SPHERE;
    solver.mapping = "no hit, ever";
    solver.solve = solve;
    solver.inside = LQ_INSIDE_UNDEFINED;
    solver.start_on_surface = LQ_ON_SURFACE_BY_DIRECTION;
    solver.tangent = LQ_TANGENT_NO_HIT;
    solver.tolerance_absolute = 1e-9;
    solver.tolerance_relative = 0x1p-50;
    solver.negative_zero = 5e-10;
    if (field) {
        if (strcmp(field, "tolerance_absolute") == 0) solver.tolerance_absolute = bad;
        if (strcmp(field, "tolerance_relative") == 0) solver.tolerance_relative = bad;
        if (strcmp(field, "negative_zero") == 0) solver.negative_zero = bad;
        if (strcmp(field, "tangent") == 0) solver.tangent = 7;
        if (strcmp(field, "start_on_surface") == 0) solver.start_on_surface = -3;
        if (strcmp(field, "inside") == 0) solver.inside = 9;
    }
    *out = &solver;
    return 1;
}
