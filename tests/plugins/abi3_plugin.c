/* A plugin built against the third plugin ABI: it speaks ABI 3 only, and its solvers end at
 * `negative_zero` (lq_solver_v3). linequad still loads it and grades it under the conventions it
 * declares (tests/test_fair_verdicts.cpp): a tangent touch no hit, a surface 2^-20 thick. Its
 * solver answers no hit on every case, as a nearest-hit solver: enough to show how it is read. */
#include "linequad/audit_plugin.h"

#include <string.h>

static int solve(void* self, const lq_shape* s, const lq_line* l, lq_answer* out) {
    (void)self, (void)s, (void)l;
    memset(out, 0, sizeof *out);
    out->status = LQ_HITS;
    return 0;
}

/* Two solvers, so that the second is read only where lq_solver_v3's size puts it (ABI 4's
 * larger lq_solver would read it from the wrong place). */
static const lq_solver_v3 solvers[] = {
    {"third_abi", 64, LQ_NEAREST, LQ_LINE, LQ_AS_POSED, 0, 1u << LQ_SPHERE, "no hit, ever", solve,
     NULL, LQ_INSIDE_AS_ANSWERS, LQ_CONTACT_INTERVAL, NULL, LQ_ON_SURFACE_AS_INSIDE,
     LQ_TANGENT_NO_HIT, 0x1p-20, 0, 0},
    {"third_abi_relative", 64, LQ_NEAREST, LQ_LINE, LQ_AS_POSED, 0, 1u << LQ_SPHERE, "no hit, ever",
     solve, NULL, LQ_INSIDE_AS_ANSWERS, LQ_CONTACT_INTERVAL, NULL, LQ_ON_SURFACE_AS_INSIDE,
     LQ_TANGENT_HIT, 0, 0x1p-30, 0}};

int linequad_audit_plugin(int abi, const lq_solver** out) {
    if (abi != 3) return -1;
    *out = (const lq_solver*)solvers;
    return 2;
}
