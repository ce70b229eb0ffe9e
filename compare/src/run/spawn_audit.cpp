// The spawned-ray audit (linequad/spawn_audit.hpp).
#include "linequad/spawn_audit.hpp"

#include "linequad/exact.hpp"
#include "linequad/families.hpp"
#include "linequad/solvers.hpp"
#include "linequad/spawn.hpp"

#include "io/escape.hpp"
#include "io/shape_types.hpp"
#include "numeric/big_float.hpp"
#include "shapes/all.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>

namespace linequad::audit {

namespace {

const Family spawn_families[] = {Family::generic,  Family::near_tangent, Family::axis_parallel,
                                 Family::scale,    Family::extent_edge,  Family::rim,
                                 Family::cap_axis, Family::inside_start, Family::two_nappes};

bool uses_stable(SpawnMethod m) {
    return m == SpawnMethod::stable_epsilon || m == SpawnMethod::stable_spawned;
}

Result solve_with(SpawnMethod m, const Shape& s, const Line& l, Query q) {
    return uses_stable(m) ? stable::intersect(s, l, q) : correct::intersect(s, l, q);
}

// The exact form along l of the shape, or of the patch of a shape made of patches that holds
// `part` (the oracle's arithmetic is not needed: big floats suffice).
template <class S>
exact_form::LineQuadratic<BigFloat> form_of(const S& s, const Line& l) {
    using detail::ShapeTraits;
    int orientation = ShapeTraits<S>::template exact_orientation<BigFloat>(s);
    return ShapeTraits<S>::template exact_quadratic<BigFloat>(s, l, orientation);
}
exact_form::LineQuadratic<BigFloat> form_along(const Shape& shape, const Line& l,
                                               Part part = Part::lateral) {
    return std::visit(
        [&](const auto& s) {
            using S = std::decay_t<decltype(s)>;
            if constexpr (detail::is_composite<S>) {
                return detail::with_patch(s, part, [&](const auto& p) { return form_of(p, l); });
            } else {
                return form_of(s, l);
            }
        },
        shape);
}

BigFloat value_at(const exact_form::LineQuadratic<BigFloat>& q, const BigFloat& T) {
    return q.A * T * T + BigFloat(2.0) * q.B * T + q.C0;
}

// A capsule's side of the point at t, exactly: the sign of its distance to the axis segment minus
// r, read from the patch whose part of the axis its projection falls on.
int capsule_side_at(const Shape& shape, const Line& l, double t) {
    BigFloat T(t);
    auto side = form_along(shape, l, Part::lateral);
    BigFloat u = side.Z0 + T * side.dZ; // (P - C).h, 0 at C and h.h at H
    Part part = sign(u) < 0                       ? Part::base
                : sign(BigFloat(u - side.hi)) > 0 ? Part::top
                                                  : Part::lateral;
    return sign(value_at(part == Part::lateral ? side : form_along(shape, l, part), T));
}

// Which side of the surface the point at t on line l is, exactly: +1 outside, -1 inside, 0 on
// it. solid: of the closed shape (inside: within the lateral surface, strictly between its
// bounded ends, off a two-solid cone's apex plane); else of the quadric alone (the sign of Q).
int side_at(const Shape& shape, const Line& l, double t, bool solid) {
    if (std::holds_alternative<Capsule>(shape)) return capsule_side_at(shape, l, t);
    auto q = form_along(shape, l);
    BigFloat T(t);
    int sq = sign(value_at(q, T));
    if (!solid || sq >= 0) return sq;
    BigFloat Z = q.Z0 + T * q.dZ;
    int worst = -1; // the largest of the signs of lo - Z, Z - hi, -|Z| (two solids)
    if (q.lo_bounded) worst = std::max(worst, sign(BigFloat(q.lo - Z)));
    if (q.hi_bounded) worst = std::max(worst, sign(BigFloat(Z - q.hi)));
    if (q.two_solids) worst = std::max(worst, -std::abs(sign(Z)));
    return worst;
}

// The side a crossing of the quadric at t on l goes into: the sign of Q'(t) = 2 (A t + B), for
// t a root's correctly rounded value (right unless the two roots are within its rounding).
int side_after(const Shape& shape, const Line& l, double t, Part part) {
    auto q = form_along(shape, l, part);
    return sign(BigFloat(q.A * BigFloat(t) + q.B));
}

bool closed(const Shape& s) {
    return is_closed(s);
}

// Grades one method's spawned ray from `left` (its solver's hit) in direction d, which should
// start on side `into` (the side the crossing it leaves went into). A hit from a start on the
// other side (or on the surface) is the crossing left, found again: a self-hit.
void grade(SpawnMethod m, const Shape& shape, const Hit& left, Vec3 d, int into, bool next,
           double epsilon, SpawnTally& t) {
    Line ray;
    if (m == SpawnMethod::stable_epsilon) {
        ray = {left.p, d, Interval(epsilon / norm(d), std::numeric_limits<double>::infinity())};
    } else if (m == SpawnMethod::correct_at_hit) {
        ray = {left.p, d, Range::ray};
    } else {
        SpawnedRay s = spawn_ray(shape, left, d);
        if (!s.ok()) {
            ++t.refused;
            return;
        }
        ray = s.line;
    }
    Result r = solve_with(m, shape, ray, {Need::nearest, false});
    ++t.spawns;
    if (r.ok() && (r.count > 0 || r.on_surface)) {
        if (side_at(shape, ray, ray.range.t0, closed(shape)) != into) ++t.self_hits;
    } else if (next) {
        ++t.lost;
    }
}

bool simple_crossings(const Result& r) {
    if (!r.ok() || r.on_surface || r.count == 0) return false;
    for (int i = 0; i < r.count; ++i)
        if (r.hits[i].kind != HitKind::cross) return false;
    return true;
}

Shape whole(Shape s) {
    make_whole(s, 1);
    return s;
}

// Every method's parent answer on `line`, or nothing for a method whose solver disagrees with
// the oracle on how many hits there are.
struct Parents {
    Result exact;
    Result by[spawn_method_count];
    bool usable[spawn_method_count] = {};
};
Parents parents(const Shape& s, const Line& l) {
    Parents p;
    p.exact = exact::intersect(s, l, {Need::all, true});
    Result st = stable::intersect(s, l, {Need::all, true});
    Result co = correct::intersect(s, l, {Need::all, true});
    for (int m = 0; m < spawn_method_count; ++m) {
        const Result& r = uses_stable(SpawnMethod(m)) ? st : co;
        p.by[m] = r;
        p.usable[m] = r.ok() && !r.on_surface && r.count == p.exact.count;
    }
    return p;
}

} // namespace

const char* spawn_method_name(SpawnMethod m) {
    switch (m) {
    case SpawnMethod::stable_epsilon:
        return "stable, t >= epsilon";
    case SpawnMethod::correct_at_hit:
        return "correct, from the hit";
    case SpawnMethod::stable_spawned:
        return "stable, spawn_ray";
    case SpawnMethod::correct_spawned:
        return "correct, spawn_ray";
    }
    return "?";
}

std::vector<SpawnRow> run_spawn_audit(const SpawnAuditOptions& o) {
    std::vector<SpawnRow> rows;
    for (Family f : spawn_families) {
        SpawnRow through{family_name(f), "through", {}}, reflect{family_name(f), "reflect", {}};
        for (int shape = 0; shape < int(std::variant_size_v<Shape>); ++shape) {
            if (!family_applies(f, shape)) continue;
            // The unbounded surfaces (plane, quadric) have no spawn offset yet (docs/limits.md).
            bool unbounded = with_shape_type(std::size_t(shape), [](auto tag) {
                return is_unbounded_surface<typename decltype(tag)::type>;
            });
            if (unbounded) continue;
            for (std::uint64_t i = 0; i < o.cases; ++i) {
                Case c = make_case(f, shape, Range::line, o.seed, i);
                Line line{c.line.L0, c.line.v, Range::line};
                // through: from each crossing on along the line.
                Parents p = parents(c.shape, line);
                if (simple_crossings(p.exact)) {
                    for (int k = 0; k < p.exact.count; ++k) {
                        // A closed shape's crossings enter and leave its solids in turn.
                        int into = closed(c.shape) ? (k % 2 == 0 ? -1 : 1)
                                                   : side_after(c.shape, line, p.exact.hits[k].t,
                                                                p.exact.hits[k].part);
                        bool next = k + 1 < p.exact.count;
                        for (int m = 0; m < spawn_method_count; ++m) {
                            if (!p.usable[m])
                                ++through.methods[m].misparent;
                            else
                                grade(SpawnMethod(m), c.shape, p.by[m].hits[k], line.v, into, next,
                                      o.epsilon, through.methods[m]);
                        }
                    }
                }
                // reflect: off the whole shape's first crossing, out of the convex solid.
                Shape solid = whole(c.shape);
                Parents q = parents(solid, line);
                if (!simple_crossings(q.exact)) continue;
                Vec3 n = normal(solid, q.exact.hits[0]);
                if (!(dot(n, line.v) < 0)) continue; // the first crossing enters the solid
                Vec3 d = line.v - (2 * dot(line.v, n)) * n;
                for (int m = 0; m < spawn_method_count; ++m) {
                    if (!q.usable[m])
                        ++reflect.methods[m].misparent;
                    else
                        grade(SpawnMethod(m), solid, q.by[m].hits[0], d, 1, false, o.epsilon,
                              reflect.methods[m]);
                }
            }
        }
        rows.push_back(through);
        rows.push_back(reflect);
    }
    return rows;
}

namespace {

std::string percent(std::uint64_t n, std::uint64_t of) {
    char buf[64];
    if (of == 0) return "-";
    double p = 100.0 * double(n) / double(of);
    std::snprintf(buf, sizeof buf, n == 0 ? "0" : p < 0.01 ? "%.1e%%" : "%.2f%%", p);
    return buf;
}

} // namespace

std::string spawn_report_markdown(const std::vector<SpawnRow>& rows, const SpawnAuditOptions& o,
                                  const std::string& command) {
    char campaign[160];
    std::snprintf(campaign, sizeof campaign,
                  "%llu cases per family and shape, seed %llu; epsilon = %g (a distance along "
                  "the ray).\n\n",
                  (unsigned long long)o.cases, (unsigned long long)o.seed, o.epsilon);
    std::string out = "# Spawned rays: self-intersection\n\n" + escape::markdown_code(command) +
                      "\n\n" + campaign;
    out += "A ray leaves each crossing of a family's line: **through** on along the line (the "
           "exact next crossing is the line's next hit), **reflect** mirrored off the first "
           "crossing of the shape made whole, out of the convex solid (the exact answer: no "
           "hit). A self-hit is a first hit where there is none, or nearer the point left than "
           "the exact next crossing; lost: no hit where there is one. Rates are of the spawns "
           "graded; refused: spawn_ray declined the direction (not graded); parent: the "
           "solver's answer on the line itself had another number of hits (not graded).\n\n";
    out += "| family | kind | method | spawns | self-hits | lost | refused | parent |\n";
    out += "|---|---|---|---:|---:|---:|---:|---:|\n";
    SpawnTally total[spawn_method_count];
    for (const SpawnRow& r : rows) {
        for (int m = 0; m < spawn_method_count; ++m) {
            const SpawnTally& t = r.methods[m];
            out += "| " + r.family + " | " + r.kind + " | " + spawn_method_name(SpawnMethod(m)) +
                   " | " + std::to_string(t.spawns) + " | " + percent(t.self_hits, t.spawns) +
                   " (" + std::to_string(t.self_hits) + ") | " + percent(t.lost, t.spawns) + " (" +
                   std::to_string(t.lost) + ") | " + std::to_string(t.refused) + " | " +
                   std::to_string(t.misparent) + " |\n";
            SpawnTally& s = total[m];
            s.spawns += t.spawns, s.self_hits += t.self_hits, s.lost += t.lost;
            s.refused += t.refused, s.misparent += t.misparent;
        }
    }
    out += "\n## Every family\n\n| method | spawns | self-hits | lost | refused | parent |\n";
    out += "|---|---:|---:|---:|---:|---:|\n";
    for (int m = 0; m < spawn_method_count; ++m) {
        const SpawnTally& t = total[m];
        out += std::string("| ") + spawn_method_name(SpawnMethod(m)) + " | " +
               std::to_string(t.spawns) + " | " + percent(t.self_hits, t.spawns) + " (" +
               std::to_string(t.self_hits) + ") | " + percent(t.lost, t.spawns) + " (" +
               std::to_string(t.lost) + ") | " + std::to_string(t.refused) + " | " +
               std::to_string(t.misparent) + " |\n";
    }
    return out;
}

} // namespace linequad::audit
