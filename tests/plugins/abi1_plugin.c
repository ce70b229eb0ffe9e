/* A plugin built against the first plugin ABI: it speaks ABI 1 only, and its solvers end at
 * `self` (lq_solver_v1). linequad still loads it (tests/test_worker.cpp). Its solver answers no
 * hit on every case: enough to show it is called and graded. */
#include "linequad/audit_plugin.h"

#include <string.h>

static int solve(void* self, const lq_shape* s, const lq_line* l, lq_answer* out) {
    (void)self, (void)s, (void)l;
    memset(out, 0, sizeof *out);
    out->status = LQ_HITS;
    return 0;
}

static const lq_solver_v1 solvers[] = {{"first_abi", 64, LQ_ALL, LQ_LINE, LQ_AS_POSED, 0,
                                        1u << LQ_CYLINDER, "no hit, ever", solve, NULL}};

int linequad_audit_plugin(int abi, const lq_solver** out) {
    if (abi != 1) return -1;
    *out = (const lq_solver*)solvers;
    return 1;
}
