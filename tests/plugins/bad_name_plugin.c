/* A plugin whose solver's name would break a file name, a markdown table and a replay command:
 * linequad refuses it when it loads, naming what is wrong (tests/test_worker.cpp). */
#include "linequad/audit_plugin.h"

static int solve(void* self, const lq_shape* s, const lq_line* l, lq_answer* out) {
    (void)self, (void)s, (void)l;
    out->status = LQ_HITS;
    return 0;
}

static const lq_solver solvers[] = {
    {"a/b|c'd", 64, LQ_ALL, LQ_LINE, LQ_AS_POSED, 0, 1u << LQ_CYLINDER, "", solve, 0, 0, 0, 0}};

int linequad_audit_plugin(int abi, const lq_solver** out) {
    if (abi != LQ_ABI) return -1;
    *out = solvers;
    return 1;
}
