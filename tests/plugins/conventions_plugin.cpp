// A plugin whose solvers answer exactly, each under one of the conventions the plugin ABI
// declares (a start inside answered as no hit, as t0 or as 0; the first exit; a contact as its
// first point), computed from linequad's correct solver. Declared as they answer, they must grade
// with no mismatch (tests/test_worker.cpp): what a library means is not charged as an error.
#include "linequad/audit_plugin.h"
#include "linequad/solvers.hpp"

#include <cmath>
#include <cstring>

using namespace linequad;

namespace {

Vec3 vec(const double* p) {
    return {p[0], p[1], p[2]};
}

Shape shape_of(const lq_shape& s) {
    bool finite = s.finite, caps = s.caps;
    switch (s.kind) {
    case LQ_CYLINDER:
        return Cylinder{vec(s.p), vec(s.p + 3), s.p[6], finite, caps};
    case LQ_ELLIPTIC_CYLINDER:
        return EllipticCylinder{vec(s.p), vec(s.p + 3), vec(s.p + 6), vec(s.p + 9), finite, caps};
    case LQ_ELLIPTIC_CONE: {
        EllipticCone c{vec(s.p), vec(s.p + 3), vec(s.p + 6), vec(s.p + 9), finite, caps};
        c.nappes = s.nappes;
        return c;
    }
    case LQ_FRUSTUM:
        return Frustum{vec(s.p), s.p[3], vec(s.p + 4), s.p[7], finite, caps};
    case LQ_SPHERE:
        return Sphere{vec(s.p), s.p[3]};
    case LQ_ELLIPSOID:
        return Ellipsoid{vec(s.p), vec(s.p + 3), vec(s.p + 6), vec(s.p + 9)};
    default:
        return Capsule{vec(s.p), vec(s.p + 3), s.p[6]};
    }
}

Line line_of(const lq_line& l) {
    return {vec(l.L0), vec(l.v), Interval(l.t0, l.t1)};
}

int crossings(const Result& r) {
    int n = 0;
    for (int i = 0; i < r.count; ++i)
        n += r.hits[i].kind == HitKind::cross;
    return n;
}

// Where the range starts: 0 outside, 1 strictly inside the solid, 2 on its surface.
int start(const Shape& s, const Line& l) {
    Line at = l, before = l;
    at.range = Interval(l.range.t0, l.range.t0);
    before.range = Interval(-INFINITY, l.range.t0);
    Result a = correct::intersect(s, at, {Need::all, false});
    if (a.count > 0 || a.on_surface) return 2;
    Result b = correct::intersect(s, before, {Need::all, false});
    return (crossings(b) - crossings(a)) % 2 != 0 ? 1 : 0;
}

void put(const Result& r, lq_answer* out) {
    if (r.on_surface) {
        out->status = LQ_ON_SURFACE;
        out->s0 = r.s0, out->s1 = r.s1, out->surface_part = int(r.surface_part);
        return;
    }
    out->status = LQ_HITS;
    for (int i = 0; i < r.count; ++i) {
        lq_hit& h = out->hits[out->count++];
        h.t = r.hits[i].t;
        for (int k = 0; k < 3; ++k)
            h.p[k] = r.hits[i].p[k];
        h.kind = int(r.hits[i].kind), h.part = int(r.hits[i].part);
    }
}

void hit_at(const Line& l, double t, lq_answer* out) {
    out->status = LQ_HITS;
    out->count = 1;
    out->hits[0].t = t;
    for (int k = 0; k < 3; ++k)
        out->hits[0].p[k] = std::fma(t, l.v[k], l.L0[k]);
}

// The first entry (first = true) or the first exit, from the start's side.
Result first_crossing(const Shape& s, const Line& l, bool entry) {
    Result all = correct::intersect(s, l, {Need::all, true});
    if (all.on_surface) return all;
    Line before = l;
    before.range = Interval(-INFINITY, l.range.t0);
    Line at = l;
    at.range = Interval(l.range.t0, l.range.t0);
    bool inside = (crossings(correct::intersect(s, before, {Need::all, false})) -
                   crossings(correct::intersect(s, at, {Need::all, false}))) %
                      2 !=
                  0;
    Result out;
    for (int i = 0; i < all.count; ++i) {
        const Hit& h = all.hits[i];
        if (entry) {
            if (!inside) {
                out.hits[out.count++] = h;
                break;
            }
            if (h.kind == HitKind::cross) inside = false;
        } else if (h.kind == HitKind::cross) {
            if (inside) {
                out.hits[out.count++] = h;
                break;
            }
            inside = true;
        }
    }
    return out;
}

enum Kind {
    nearest_at_zero,
    first_entry_no_hit,
    nearest_at_t0,
    first_exit,
    contact_point,
    every_hit
};

template <Kind K>
int solve(void*, const lq_shape* cs, const lq_line* cl, lq_answer* out) {
    Shape s = shape_of(*cs);
    Line l = line_of(*cl);
    Result check = correct::intersect(s, l, {Need::all, false});
    if (!check.ok()) {
        out->status = LQ_REFUSED;
        std::strncpy(out->error, code_name(check.error_code), sizeof out->error - 1);
        return 0;
    }
    switch (K) {
    case nearest_at_zero:
        if (start(s, l) != 0) return hit_at(l, 0, out), 0;
        put(correct::intersect(s, l, {Need::nearest, true}), out);
        return 0;
    case nearest_at_t0:
        if (start(s, l) != 0) return hit_at(l, l.range.t0, out), 0;
        put(correct::intersect(s, l, {Need::nearest, true}), out);
        return 0;
    case first_entry_no_hit:
        if (start(s, l) == 1) return out->status = LQ_HITS, 0;
        put(first_crossing(s, l, true), out);
        return 0;
    case first_exit:
        put(first_crossing(s, l, false), out);
        return 0;
    case every_hit:
        put(correct::intersect(s, l, {Need::all, true}), out);
        return 0;
    case contact_point: {
        Result all = correct::intersect(s, l, {Need::all, true});
        if (!all.on_surface) return put(all, out), 0;
        out->status = LQ_HITS;
        out->count = 1;
        out->hits[0].t = all.s0;
        out->hits[0].part = int(all.surface_part);
        return 0;
    }
    }
    return 1;
}

// A packet solver's entry: n cases in one call (here, each in turn), as Embree's rtcIntersect4/8/16
// or a renderer's ray packets take them. `crashes`: a packet of more than one case faults, while
// one case at a time answers (the audit asks again so, and charges no case).
template <bool crashes>
int solve_packet(void* self, int n, const lq_shape* shapes, const lq_line* lines, lq_answer* out) {
    if (crashes && n > 1) *static_cast<volatile int*>(nullptr) = 1;
    for (int i = 0; i < n; ++i)
        solve<every_hit>(self, &shapes[i], &lines[i], &out[i]);
    return 0;
}

constexpr unsigned every_shape = (1u << (LQ_CAPSULE + 1)) - 1;
constexpr int everything = LQ_POINTS | LQ_KINDS | LQ_PARTS;

const lq_solver solvers[] = {
    {"nearest_at_zero", 64, LQ_NEAREST, LQ_SEGMENT, LQ_CLOSED, everything, every_shape,
     "Jolt's ray test: a fraction of from-to, 0 from inside", solve<nearest_at_zero>, nullptr,
     LQ_INSIDE_ZERO, LQ_CONTACT_INTERVAL, nullptr},
    {"first_entry_no_hit", 64, LQ_FIRST_ENTRY, LQ_LINE, LQ_CLOSED, everything, every_shape,
     "no hit from inside", solve<first_entry_no_hit>, nullptr, LQ_INSIDE_NO_HIT,
     LQ_CONTACT_INTERVAL, nullptr},
    {"nearest_at_t0", 64, LQ_NEAREST, LQ_UNIT_DIRECTION, LQ_CLOSED, everything, every_shape,
     "Geometric Tools' Ray3: t0 from inside", solve<nearest_at_t0>, nullptr, LQ_INSIDE_T0,
     LQ_CONTACT_INTERVAL, nullptr},
    {"first_exit", 64, LQ_FIRST_EXIT, LQ_LINE, LQ_CLOSED, everything, every_shape,
     "Geant4's DistanceToOut", solve<first_exit>, nullptr, LQ_INSIDE_AS_ANSWERS,
     LQ_CONTACT_INTERVAL, nullptr},
    {"contact_point", 64, LQ_ALL, LQ_LINE, LQ_AS_POSED, everything, every_shape,
     "a contact as its first point", solve<contact_point>, nullptr, LQ_INSIDE_AS_ANSWERS,
     LQ_CONTACT_FIRST_POINT, nullptr},
    {"packet", 64, LQ_ALL, LQ_LINE, LQ_AS_POSED, everything, every_shape, "a packet entry",
     solve<every_hit>, nullptr, LQ_INSIDE_AS_ANSWERS, LQ_CONTACT_INTERVAL, solve_packet<false>},
    {"packet_crashes", 64, LQ_ALL, LQ_LINE, LQ_AS_POSED, everything, every_shape,
     "a packet entry that faults", solve<every_hit>, nullptr, LQ_INSIDE_AS_ANSWERS,
     LQ_CONTACT_INTERVAL, solve_packet<true>},
};

} // namespace

extern "C" int linequad_audit_plugin(int abi, const lq_solver** out) {
    if (abi != LQ_ABI) return -1;
    *out = solvers;
    return int(sizeof solvers / sizeof solvers[0]);
}
