/* A plugin built against the second plugin ABI: it speaks ABI 2 only, and its solvers end at
 * `solve_batch` (lq_solver_v2). linequad still loads it and grades it as it did before ABI 3
 * (tests/test_fair_verdicts.cpp): no tolerance, a tangent touch a hit. Its solver answers no hit
 * on every case, as a nearest-hit solver: enough to show how it is graded. */
#include "linequad/audit_plugin.h"

#include <string.h>

static int solve(void* self, const lq_shape* s, const lq_line* l, lq_answer* out) {
    (void)self, (void)s, (void)l;
    memset(out, 0, sizeof *out);
    out->status = LQ_HITS;
    return 0;
}

static const lq_solver_v2 solvers[] = {{"second_abi", 64, LQ_NEAREST, LQ_LINE, LQ_AS_POSED, 0,
                                        1u << LQ_SPHERE, "no hit, ever", solve, NULL,
                                        LQ_INSIDE_AS_ANSWERS, LQ_CONTACT_INTERVAL, NULL}};

int linequad_audit_plugin(int abi, const lq_solver** out) {
    if (abi != 2) return -1;
    *out = (const lq_solver*)solvers;
    return 1;
}
