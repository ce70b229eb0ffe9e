/* The audit's plugin ABI: a shared library that exports
 *
 *     int linequad_audit_plugin(int abi, const lq_solver** solvers);
 *
 * is audited with `linequad audit --plugin libmine.so --solvers mine,...` without rebuilding
 * linequad. It is called once with LQ_ABI; it sets *solvers to an array of solvers that lives
 * as long as the library is loaded and returns their number, or returns -1 when it does not
 * speak this ABI. Plain C, so that any language with a C FFI can be audited; the doubles are
 * exactly those of the case (a binary32 solver gets floats held in doubles). */
#ifndef LINEQUAD_AUDIT_PLUGIN_H
#define LINEQUAD_AUDIT_PLUGIN_H

#ifdef __cplusplus
extern "C" {
#endif

#define LQ_ABI 1

/* Shapes, as in linequad/shapes.hpp. */
enum lq_shape_kind {
    LQ_CYLINDER = 0,          /* p: C[3], H[3], r */
    LQ_ELLIPTIC_CYLINDER = 1, /* p: C[3], a[3], b[3], c[3] */
    LQ_ELLIPTIC_CONE = 2,     /* p: C[3], H[3], a[3], b[3] (apex H, base centre C) */
    LQ_FRUSTUM = 3            /* p: C0[3], r0, C1[3], r1 */
};
typedef struct {
    int kind; /* lq_shape_kind */
    double p[12];
    int finite, caps, nappes;
} lq_shape;

/* L(t) = L0 + t v for t0 <= t <= t1 (posed as the solver declared: see lq_parametrisation). */
typedef struct {
    double L0[3], v[3], t0, t1;
} lq_line;

enum lq_hit_kind { LQ_CROSS = 0, LQ_TANGENT = 1 };
enum lq_part { LQ_LATERAL = 0, LQ_BASE = 1, LQ_TOP = 2 };
typedef struct {
    double t, p[3];
    int kind, part; /* read only when the solver declares them */
} lq_hit;

enum lq_status {
    LQ_HITS = 0,          /* count hits (0 to 4), in order of t */
    LQ_ON_SURFACE = 1,    /* the line lies on the surface for s0 <= t <= s1 */
    LQ_REFUSED = 2,       /* the input is refused; error names why */
    LQ_UNREPRESENTED = 3, /* the library cannot represent this case: not graded, counted */
};
typedef struct {
    int status, count;
    lq_hit hits[4];
    double s0, s1;
    int surface_part;
    /* For LQ_REFUSED: a linequad error code name ("zero_direction", "bad_radius", ...; see
     * linequad::code_name) if one fits, else the library's own words (graded as a refusal the
     * oracle does not make). */
    char error[64];
} lq_answer;

enum lq_answers { LQ_ALL = 0, LQ_NEAREST = 1, LQ_FIRST_ENTRY = 2 };
enum lq_parametrisation { LQ_LINE = 0, LQ_UNIT_DIRECTION = 1, LQ_SEGMENT = 2 };
enum lq_surface { LQ_AS_POSED = 0, LQ_CLOSED = 1, LQ_INFINITE = 2 };
enum lq_carries { LQ_POINTS = 1, LQ_KINDS = 2, LQ_PARTS = 4 };

typedef struct {
    const char* name;
    int precision; /* 64: binary64, 32: binary32 */
    int answers, parametrisation, surface;
    int carries;         /* lq_carries, or-ed */
    unsigned shapes;     /* bit k set: takes shape kind k */
    const char* mapping; /* how a case is handed over, what cannot be represented */
    /* Fills *out; returns 0, or nonzero when it could not answer at all (graded as a refusal). */
    int (*solve)(void* self, const lq_shape* shape, const lq_line* line, lq_answer* out);
    void* self;
} lq_solver;

typedef int (*lq_plugin_entry)(int abi, const lq_solver** solvers);

#ifdef __cplusplus
}
#endif

#endif
