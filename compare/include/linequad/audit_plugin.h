/* The audit's plugin ABI: a shared library that exports
 *
 *     int linequad_audit_plugin(int abi, const lq_solver** solvers);
 *
 * is audited with `linequad audit --plugin libmine.so --solvers mine,...` without rebuilding
 * linequad. It is called with LQ_ABI (4) and, while it returns -1, with 3, 2 and then 1 (the
 * earlier ABIs, whose solvers are lq_solver_v3, lq_solver_v2 and lq_solver_v1: what a plugin built
 * against their headers returns, loaded and graded as it was); it sets *solvers to an array of
 * solvers that lives as long as the library is loaded and returns their number, or returns -1 when
 * it does not speak that ABI. Plain C, so that any language with a C FFI can be audited; the
 * doubles are exactly those of the posed case (a binary32 solver gets floats held in doubles).
 *
 * The library runs in a worker process of its own (`linequad plugin-worker`), never in the
 * process that holds the exact reference and the report: a crash, an exit, an uncaught C++
 * exception, a call that does not return within --solver-timeout, output on stdout or stderr,
 * or a changed floating-point environment is counted against the case (or reported beside it)
 * and the run goes on. Before every call the environment is put back to the one the library
 * had once loaded. */
#ifndef LINEQUAD_AUDIT_PLUGIN_H
#define LINEQUAD_AUDIT_PLUGIN_H

#include <stddef.h> /* NULL, for the fields a plugin leaves empty */

#ifdef __cplusplus
extern "C" {
#endif

#define LQ_ABI 4

/* Shapes, as in linequad/shapes.hpp. */
enum lq_shape_kind {
    LQ_CYLINDER = 0,          /* p: C[3], H[3], r */
    LQ_ELLIPTIC_CYLINDER = 1, /* p: C[3], a[3], b[3], c[3] */
    LQ_ELLIPTIC_CONE = 2,     /* p: C[3], H[3], a[3], b[3] (apex H, base centre C) */
    LQ_FRUSTUM = 3,           /* p: C0[3], r0, C1[3], r1 */
    LQ_SPHERE = 4,            /* p: C[3], r; a closed solid: finite 1, caps 0, nappes 1 */
    LQ_ELLIPSOID = 5,         /* p: C[3], a[3], b[3], c[3]; a closed solid, as the sphere */
    LQ_CAPSULE = 6,           /* p: C[3], H[3], r; a closed solid; parts: LQ_LATERAL, and the
                                 hemispheres LQ_BASE (around C) and LQ_TOP (around H) */
    LQ_PLANE = 7,             /* p: n[3], d, coincident (1: L0 is on the plane, f(L0) taken as 0);
                                 n . x = d, unbounded: finite 0; its inside n . x < d */
    LQ_QUADRIC = 8 /* p: A B C D E F G H J K (MCNP's GQ order), coincident; as the plane */
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
    LQ_UNREPRESENTED = 3, /* the library cannot represent this case: not graded, counted (by the
                             reason in error, if it gives one) */
};
typedef struct {
    int status, count;
    lq_hit hits[4];
    double s0, s1;
    int surface_part;
    /* For LQ_REFUSED: a linequad error code name ("zero_direction", "bad_radius", ...; see
     * linequad::code_name) if one fits, else the library's own words (graded as a refusal the
     * oracle does not make). For LQ_UNREPRESENTED: why, if the library says (counted by it). */
    char error[64];
} lq_answer;

/* What a solver answers of a line and a shape. */
enum lq_answers {
    LQ_ALL = 0,         /* every hit in the range, in order of t */
    LQ_NEAREST = 1,     /* the hit with the smallest t in the range */
    LQ_FIRST_ENTRY = 2, /* the first hit where the line enters the closed solid (a physics ray
                           test: a solid the line starts in is ignored until it is left) */
    LQ_FIRST_EXIT = 3   /* ABI 2: the first point where the line leaves the closed solid
                           (Geant4's DistanceToOut); asked only of lines that start inside it */
};
enum lq_parametrisation { LQ_LINE = 0, LQ_UNIT_DIRECTION = 1, LQ_SEGMENT = 2 };
enum lq_surface { LQ_AS_POSED = 0, LQ_CLOSED = 1, LQ_INFINITE = 2 };
enum lq_carries { LQ_POINTS = 1, LQ_KINDS = 2, LQ_PARTS = 4 };
/* ABI 2: what a nearest or first-entry solver answers when the range starts inside the closed
 * solid. */
enum lq_inside {
    LQ_INSIDE_AS_ANSWERS = 0, /* nothing special: the nearest hit, or the first entry */
    LQ_INSIDE_NO_HIT = 1,     /* no hit when the start is strictly inside */
    LQ_INSIDE_T0 = 2,         /* a hit at the range's start t0 (Geometric Tools' Ray3 queries) */
    LQ_INSIDE_ZERO = 3,       /* a hit at t = 0 (Jolt's fraction 0, PhysX's initial overlap) */
    LQ_INSIDE_UNDEFINED = 4   /* ABI 3: not defined (VecGeom's DistanceToIn): not asked */
};
/* ABI 3: what a start on the surface is answered as. */
enum lq_start_on_surface {
    LQ_ON_SURFACE_AS_INSIDE = 0,   /* as a start inside (the inside convention, unless no hit) */
    LQ_ON_SURFACE_BY_DIRECTION = 1 /* by where the line goes: moving in, an entry at t0; moving
                                      out, no entry (VecGeom, Geant4) */
};
/* ABI 3: whether a line that only touches the surface hits it. */
enum lq_tangent { LQ_TANGENT_HIT = 0, LQ_TANGENT_NO_HIT = 1 };
/* ABI 2: how a line lying on the surface over an interval is answered. */
enum lq_contact {
    LQ_CONTACT_INTERVAL = 0,   /* LQ_ON_SURFACE with the interval */
    LQ_CONTACT_FIRST_POINT = 1 /* one hit at the interval's first point in the range */
};

typedef struct {
    const char* name; /* letters, digits and _ . + - (at most 64): it names files and rows */
    int precision;    /* 64: binary64, 32: binary32 */
    int answers, parametrisation, surface;
    int carries;         /* lq_carries, or-ed */
    unsigned shapes;     /* bit k set: takes shape kind k */
    const char* mapping; /* how a case is handed over, what cannot be represented */
    /* Fills *out; returns 0, or nonzero when it could not answer at all (graded as a refusal). */
    int (*solve)(void* self, const lq_shape* shape, const lq_line* line, lq_answer* out);
    void* self;
    /* ABI 2 from here. */
    int inside;  /* lq_inside */
    int contact; /* lq_contact */
    /* Optional (NULL: none): n cases in one call, as a packet or SIMD solver takes them; fills
     * out[0..n). Returns 0, or nonzero when it could not answer (the cases are then asked one at
     * a time through solve, as they are when this call crashes or times out). */
    int (*solve_batch)(void* self, int n, const lq_shape* shapes, const lq_line* lines,
                       lq_answer* out);
    /* ABI 3 from here: the library's own contract, graded as it means it (see
     * docs/semantics.md). 0 in every field: linequad's exact semantics. */
    int start_on_surface; /* lq_start_on_surface */
    int tangent;          /* lq_tangent */
    /* How far its surface may lie from the exact one (VecGeom's kTolerance), in scene units plus
     * relative to the scene's magnitude: an answer right for some solid between the shape shrunk
     * and grown by that much is counted within tolerance, not as a mismatch. Finite, >= 0. */
    double tolerance_absolute, tolerance_relative;
    /* A distance in [-negative_zero, 0) (scene units) reads as 0. Finite, >= 0. */
    double negative_zero;
    /* ABI 4 from here. Optional (NULL: none): the side of a surface the library puts the point
     * p on, as its tracker's find-cell decides it (OpenMC's Surface::sense: the sign of f, and
     * for a point it counts as on the surface, the side the direction of travel u points into).
     * Writes -1 (the negative half-space, f < 0) or +1 to *side; returns 0, or nonzero when it
     * could not. Asked of the surfaces cells are built from (LQ_PLANE, LQ_QUADRIC, LQ_SPHERE,
     * and LQ_CYLINDER infinite along a coordinate axis) by `linequad cells MODEL --audit
     * --plugin LIB --solvers NAME`: that tracker then finds its cells by these sides
     * (docs/cells.md). */
    int (*sense)(void* self, const lq_shape* shape, const double p[3], const double u[3],
                 int* side);
} lq_solver;

/* The solvers of ABI 3: lq_solver without the fields of ABI 4. */
typedef struct {
    const char* name;
    int precision;
    int answers, parametrisation, surface;
    int carries;
    unsigned shapes;
    const char* mapping;
    int (*solve)(void* self, const lq_shape* shape, const lq_line* line, lq_answer* out);
    void* self;
    int inside;
    int contact;
    int (*solve_batch)(void* self, int n, const lq_shape* shapes, const lq_line* lines,
                       lq_answer* out);
    int start_on_surface;
    int tangent;
    double tolerance_absolute, tolerance_relative;
    double negative_zero;
} lq_solver_v3;

/* The solvers of ABI 2: lq_solver without the fields of ABI 3. */
typedef struct {
    const char* name;
    int precision;
    int answers, parametrisation, surface;
    int carries;
    unsigned shapes;
    const char* mapping;
    int (*solve)(void* self, const lq_shape* shape, const lq_line* line, lq_answer* out);
    void* self;
    int inside;
    int contact;
    int (*solve_batch)(void* self, int n, const lq_shape* shapes, const lq_line* lines,
                       lq_answer* out);
} lq_solver_v2;

/* The solvers of ABI 1: lq_solver without the fields of ABI 2 (what a plugin built against the
 * first header returns when asked for ABI 1). */
typedef struct {
    const char* name;
    int precision;
    int answers, parametrisation, surface;
    int carries;
    unsigned shapes;
    const char* mapping;
    int (*solve)(void* self, const lq_shape* shape, const lq_line* line, lq_answer* out);
    void* self;
} lq_solver_v1;

typedef int (*lq_plugin_entry)(int abi, const lq_solver** solvers);

#ifdef __cplusplus
}
#endif

#endif
