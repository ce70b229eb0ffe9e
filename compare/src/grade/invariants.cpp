// Invariants checked on every input, for every solver:
//  - the verdict on bad input equals the oracle's (validation is shared and exact); a fast
//    solver may refuse more (out_of_range) but never accept what the oracle refuses;
//  - a result has at most two hits (four: a closed two-nappe cone), sorted by t, each naming a
//    part the shape has (lateral without caps), each t and point finite (the oracle may give
//    +-inf, the correct rounding of a root beyond double's range; never NaN), each t inside the
//    range; an on-surface interval is ordered and inside the range;
//  - the oracle's Mpzf and Gmpq kernels agree bit for bit;
//  - when the oracle says no hit and no interval, no solver reports an on-surface interval;
//  - a certified result that says it is certain has the oracle's classification;
//  - the correct solver returns the oracle's answer bit for bit (all hits with points, and the
//    nearest without);
//  - the batch solvers (stable and correct in four or eight double lanes, stable32 in eight float
//    lanes, and a scalar tail) return the scalar solver's result, bit for bit (correct's rung
//    too, for all, nearest and any), for this line among variants of it;
//  - on the case rounded to float: correct32 is the float oracle's answer bit for bit, and the
//    float solvers answer in floats;
//  - every solver returns for the prepared shape what it returns for the shape, bit for bit
//    (bounds, certainty and rung included);
//  - the correct solver's hit test has a hit exactly when the oracle has one, within its bound of
//    one of the oracle's roots;
//  - a scene holding the shape answers as the shape's solver does (stable and correct; all,
//    nearest and any): its boxes, hierarchy and capsules lose no hit on any input, and its verdict
//    on bad input is the solver's (a refusal of what double cannot hold may instead be the
//    oracle's "no hit" when the line never comes near the shape).
#include "linequad/invariants.hpp"

#include "linequad/batch.hpp"
#include "linequad/exact.hpp"
#include "linequad/registry.hpp"
#include "linequad/scene.hpp"

#include "numeric/format.hpp"
#include "shapes/all.hpp"

#include <cmath>
#include <cstring>
#include <initializer_list>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

namespace linequad {

namespace {

bool same_bits(double a, double b) {
    return std::memcmp(&a, &b, sizeof a) == 0;
}

// The same answer, bit for bit (signed zeros included); bounds and certainty aside.
bool same_answer(const Result& a, const Result& b) {
    if (a.error_code != b.error_code || a.count != b.count || a.on_surface != b.on_surface)
        return false;
    if (a.on_surface &&
        !(same_bits(a.s0, b.s0) && same_bits(a.s1, b.s1) && a.surface_part == b.surface_part))
        return false;
    for (int i = 0; i < a.count; ++i) {
        const Hit &x = a.hits[i], &y = b.hits[i];
        if (x.kind != y.kind || x.part != y.part || !same_bits(x.t, y.t) ||
            !same_bits(x.p.x, y.p.x) || !same_bits(x.p.y, y.p.y) || !same_bits(x.p.z, y.p.z))
            return false;
    }
    return true;
}

struct Checker {
    const Case& c;
    std::string broken;
    bool require(bool ok, const char* what, const std::string& solver, const Result& r) {
        if (ok || !broken.empty()) return ok;
        broken = std::string(what) + "\nsolver " + solver + "\ncase " + format_case(c) +
                 "\nresult " + format_result(c.id, solver, r);
        return false;
    }
    void shape(const std::string& name, const Result& r) {
        if (!r.ok()) return;
        // Parts beyond the lateral surface: a closed shape's discs, a capsule's round ends.
        auto [parts, most] = std::visit(
            [](const auto& s) {
                using S = std::decay_t<decltype(s)>;
                bool two_solids = has_caps(s) && nappes_of(s) == 2;
                return std::pair{has_caps(s) || detail::is_composite<S>, two_solids ? max_hits : 2};
            },
            c.shape);
        require(r.count <= most, "at most two hits (four for a closed two-nappe cone)", name, r);
        for (int i = 0; i < r.count; ++i)
            require(parts || r.hits[i].part == Part::lateral, "caps only on a closed shape", name,
                    r);
        require(parts || r.surface_part == Part::lateral, "caps only on a closed shape", name, r);
        require(!(r.on_surface && r.count), "hits or an interval, not both", name, r);
        // Infinities are correct roundings beyond the format's range.
        bool oracle = name == "exact" || name == "correct" || name == "correct32";
        for (int i = 0; i < r.count; ++i) {
            const Hit& h = r.hits[i];
            require(oracle ? !std::isnan(h.t) : std::isfinite(h.t), "finite t", name, r);
            require(c.line.range.contains(h.t), "t inside the range", name, r);
            bool nan_p = std::isnan(h.p.x) || std::isnan(h.p.y) || std::isnan(h.p.z);
            require(oracle ? !nan_p : is_finite(h.p), "finite point", name, r);
        }
        for (int i = 1; i < r.count; ++i)
            require(r.hits[i - 1].t <= r.hits[i].t, "hits sorted by t", name, r);
        if (r.on_surface) {
            require(!std::isnan(r.s0) && !std::isnan(r.s1) && r.s0 <= r.s1, "ordered interval",
                    name, r);
            require(r.s0 >= c.line.range.t0 && r.s1 <= c.line.range.t1, "interval inside the range",
                    name, r);
        }
    }
};

} // namespace

namespace {

// A solver by name on a prepared shape (the fast solvers and the oracle).
template <class P>
Result solve_prepared(std::string_view name, const P& p, const Line& l, Query q) {
    if (name == "seed") return seed::intersect(p, l, q);
    if (name == "stable") return stable::intersect(p, l, q);
    if (name == "certified") return certified::intersect(p, l, q);
    if (name == "correct") return correct::intersect(p, l, q);
    if (name == "seed32") return seed32::intersect(p, l, q);
    if (name == "stable32") return stable32::intersect(p, l, q);
    if (name == "correct32") return correct32::intersect(p, l, q);
    return exact::intersect(p, l, q, name == "exact32" ? Precision::binary32 : Precision::binary64);
}

// Every named solver returns for the prepared shape what it returns for the shape, bit for bit.
void check_prepared(Checker& k, std::initializer_list<std::string_view> names) {
    const Case& c = k.c;
    std::visit(
        [&](const auto& s) {
            auto p = prepare(s);
            for (std::string_view name : names)
                for (Query q : {Query{}, Query{Need::any, false}}) {
                    Precision precision =
                        name == "exact32" ? Precision::binary32 : Precision::binary64;
                    Result given = name.substr(0, 5) == "exact"
                                       ? exact::intersect(s, c.line, q, precision)
                                       : find_solver(name)->solve(c.shape, c.line, q);
                    Result prepared = solve_prepared(name, p, c.line, q);
                    k.require(format_result(c.id, std::string(name), given) ==
                                      format_result(c.id, std::string(name), prepared) &&
                                  given.rung == prepared.rung,
                              "a prepared shape gives the same answer", std::string(name),
                              prepared);
                }
        },
        c.shape);
}

// Nine lines through the batch (two full batches of four double lanes, one of eight float
// lanes, and a scalar tail): this one, reversed, doubled, moved, halved, moved back, reversed
// and doubled, moved twice, and this one again; each the scalar solver's answer bit for bit. A
// float case's variants are rounded to float.
template <class R>
void check_batch(Checker& k) {
    const Case& c = k.c;
    const Line& l = c.line;
    Line variants[9] = {l,
                        {l.L0, -1.0 * l.v, l.range},
                        {l.L0, 2.0 * l.v, l.range},
                        {l.L0 + l.v, l.v, l.range},
                        {l.L0, 0.5 * l.v, l.range},
                        {l.L0 - l.v, l.v, l.range},
                        {l.L0, -2.0 * l.v, l.range},
                        {l.L0 + 2.0 * l.v, l.v, l.range},
                        l};
    std::vector<R> soa[6];
    for (Line& v : variants) {
        if constexpr (std::is_same_v<R, float>) v = rounded_to_binary32(v);
        for (int a = 0; a < 3; ++a)
            soa[a].push_back(R(v.L0[a])), soa[3 + a].push_back(R(v.v[a]));
    }
    LineArraysT<R> lines{
        soa[0].data(), soa[1].data(), soa[2].data(), soa[3].data(), soa[4].data(), soa[5].data(), 9,
        l.range};
    Result batch[9];
    std::visit(
        [&](const auto& s) {
            if constexpr (std::is_same_v<R, float>)
                stable32::intersect(s, lines, Query{}, batch);
            else
                stable::intersect(s, lines, Query{}, batch);
        },
        c.shape);
    const char* name = std::is_same_v<R, float> ? "stable32" : "stable";
    for (int i = 0; i < 9; ++i) {
        Result scalar = find_solver(name)->solve(c.shape, variants[i], Query{});
        k.require(format_result(c.id, "", batch[i]) == format_result(c.id, "", scalar),
                  "batch equals scalar bit for bit", std::string(name) + " (batch)", batch[i]);
    }
    if constexpr (std::is_same_v<R, double>) {
        // correct's batch, for each query: its lanes prove what the scalar rung proves.
        for (Query q : {Query{}, Query{Need::nearest, false}, Query{Need::any, false}}) {
            std::visit([&](const auto& s) { correct::intersect(s, lines, q, batch); }, c.shape);
            for (int i = 0; i < 9; ++i) {
                Result scalar = correct::intersect(c.shape, variants[i], q);
                k.require(format_result(c.id, "", batch[i], q.points) ==
                                  format_result(c.id, "", scalar, q.points) &&
                              batch[i].rung == scalar.rung,
                          "batch equals scalar bit for bit, rung for rung", "correct (batch)",
                          batch[i]);
            }
        }
    }
}

// The float solvers on the case rounded to float: correct32 is the oracle's float answer, bit for
// bit (and the oracles in Mpzf and Gmpq agree on it).
std::string broken_in_binary32(const Case& given) {
    Case c = given;
    c.shape = rounded_to_binary32(c.shape);
    c.line = rounded_to_binary32(c.line);
    c.precision = Precision::binary32;
    Checker k{c, {}};
    Result oracle = exact::intersect(c.shape, c.line, {}, Precision::binary32);
    Result gmpq = exact::intersect_gmpq(c.shape, c.line, {}, Precision::binary32);
    k.require(format_result(c.id, "", gmpq) == format_result(c.id, "", oracle),
              "Mpzf and Gmpq agree in float", "exact_gmpq", gmpq);
    for (Query q : {Query{}, Query{Need::nearest, false}}) {
        Result want = q.need == Need::all
                          ? oracle
                          : exact::intersect(c.shape, c.line, q, Precision::binary32);
        Result got = correct32::intersect(c.shape, c.line, q);
        k.shape("correct32", got);
        k.require(same_answer(got, want), "correct32 equals the oracle's float answer bit for bit",
                  "correct32", got);
    }
    for (const char* name : {"seed32", "stable32"}) {
        Result r = find_solver(name)->solve(c.shape, c.line, Query{});
        k.shape(name, r);
        if (!oracle.ok())
            k.require(r.error_code == oracle.error_code, "same verdict on bad input", name, r);
        else
            k.require(r.ok() || r.error_code == ErrorCode::out_of_range,
                      "refuses only what float cannot hold", name, r);
        k.require(answered_in_floats(r), "a float solver answers in floats", name, r);
    }
    check_prepared(k, {"seed32", "stable32", "correct32", "exact32"});
    check_batch<float>(k);
    return k.broken;
}

} // namespace

bool answered_in_floats(const Result& r) {
    using detail::Binary32;
    bool ok = !r.on_surface || (Binary32::holds(r.s0) && Binary32::holds(r.s1));
    for (int i = 0; i < r.count; ++i) {
        const Hit& h = r.hits[i];
        for (double x : {h.t, h.p.x, h.p.y, h.p.z})
            ok = ok && Binary32::holds(x);
    }
    return ok;
}

namespace {

// The scene's answer as a Result, to show it beside the case.
Result as_result(const SceneAnswer& a) {
    Result r;
    r.error_code = a.error.code, r.error_field = a.error.field;
    for (const SceneHit& h : a.hits)
        if (r.count < max_hits) r.hits[r.count++] = h.hit;
    return r;
}

// A solver's refusal of what double cannot hold (out_of_range) comes only from the shapes a line
// comes near: a culled shape's answer is "no hit", which must then be the oracle's.
void check_scene(Checker& k, const Result& oracle) {
    const Case& c = k.c;
    for (SceneSolver solver : {SceneSolver::stable, SceneSolver::correct}) {
        std::string name = solver == SceneSolver::correct ? "scene (correct)" : "scene (stable)";
        Scene scene({c.shape}, solver);
        for (Query q :
             {Query{Need::all, true}, Query{Need::nearest, true}, Query{Need::any, false}}) {
            Result want = solver == SceneSolver::correct ? correct::intersect(c.shape, c.line, q)
                                                         : stable::intersect(c.shape, c.line, q);
            SceneAnswer a;
            scene.intersect(c.line, q, a);
            // Culling never loses a hit, but it may skip what the solver would have invented or
            // refused: a scene that solved nothing and answers no hit, where the oracle has none,
            // answers rightly whatever the solver says (its own errors are graded elsewhere).
            bool culled = (want.error_code == ErrorCode::out_of_range ||
                           (want.ok() && a.shapes_solved == 0)) &&
                          a.ok() && a.hits.empty() && oracle.ok() && !oracle.any_hit();
            bool same = culled || a.error.code == want.error_code;
            if (!culled && same && want.ok()) {
                std::size_t n = std::size_t(want.count) + (want.on_surface ? 1 : 0);
                same = a.hits.size() == n;
                for (int i = 0; same && !want.on_surface && i < want.count; ++i) {
                    const Hit &g = a.hits[std::size_t(i)].hit, &w = want.hits[i];
                    same = same_bits(g.t, w.t) && same_bits(g.p.x, w.p.x) &&
                           same_bits(g.p.y, w.p.y) && same_bits(g.p.z, w.p.z) && g.kind == w.kind &&
                           g.part == w.part;
                }
            }
            k.require(same, "a scene of the shape answers as its solver", name, as_result(a));
            if (solver == SceneSolver::correct && q.need != Need::any) {
                // The oracle's scene, its own exact order: the correct scene's, bit for bit.
                SceneAnswer o;
                exact::intersect({c.shape}, c.line, q, o);
                bool equal = o.error.code == a.error.code && o.hits.size() == a.hits.size();
                for (std::size_t i = 0; equal && i < o.hits.size(); ++i) {
                    const SceneHit &g = a.hits[i], &w = o.hits[i];
                    equal = g.shape == w.shape && g.tied == w.tied && same_bits(g.hit.t, w.hit.t) &&
                            same_bits(g.hit.p.x, w.hit.p.x) && same_bits(g.hit.p.y, w.hit.p.y) &&
                            same_bits(g.hit.p.z, w.hit.p.z) && g.hit.kind == w.hit.kind &&
                            g.hit.part == w.hit.part;
                }
                bool refused = a.error.code == ErrorCode::out_of_range && o.ok();
                k.require(equal || refused, "a correct scene equals the oracle's scene", name,
                          as_result(a));
            }
        }
    }
}

} // namespace

std::string broken_invariant(const Case& c) {
    Checker k{c, {}};
    Result oracle = exact::intersect(c.shape, c.line);
    k.shape("exact", oracle);
    Result gmpq = exact::intersect_gmpq(c.shape, c.line);
    k.require(format_result(c.id, "", gmpq) == format_result(c.id, "", oracle),
              "Mpzf and Gmpq agree", "exact_gmpq", gmpq);
    // A float solver answers the case only when its inputs are floats (it names the first that
    // is not); its oracle is the float one.
    Result oracle32 = exact::intersect(c.shape, c.line, {}, Precision::binary32);
    for (const Solver& s : all_solvers()) {
        std::string name(s.name);
        Result r = s(c.shape, c.line);
        const Result& want = s.precision == Precision::binary32 ? oracle32 : oracle;
        k.shape(name, r);
        if (!want.ok()) {
            k.require(!r.ok() && r.error_code == want.error_code, "same verdict on bad input", name,
                      r);
        } else if (!r.ok()) {
            k.require(r.error_code == ErrorCode::out_of_range,
                      "refuses only what double cannot hold", name, r);
        } else {
            if (!want.any_hit())
                k.require(!r.on_surface, "no invented on-surface interval", name, r);
            if (r.certainty == Certainty::certain) {
                bool same = r.count == want.count && r.on_surface == want.on_surface &&
                            (!r.on_surface || r.surface_part == want.surface_part);
                for (int i = 0; same && i < r.count; ++i)
                    same =
                        r.hits[i].kind == want.hits[i].kind && r.hits[i].part == want.hits[i].part;
                k.require(same, "a certain classification is the oracle's", name, r);
            }
        }
    }
    for (Query q : {Query{}, Query{Need::nearest, false}}) {
        Result want = q.need == Need::all ? oracle : exact::intersect(c.shape, c.line, q);
        Result got = correct::intersect(c.shape, c.line, q);
        k.require(same_answer(got, want), "correct equals the oracle bit for bit", "correct", got);
    }
    // A prepared shape: the same answers, bit for bit, from every solver and the oracle.
    check_prepared(k, {"seed", "stable", "certified", "correct", "exact"});
    // The hit test: a hit exactly when the oracle has one (or the interval), and then within
    // its bound of one of the oracle's roots (each within half an ulp of exact).
    Result any = correct::intersect(c.shape, c.line, {Need::any, false});
    bool any_ok = any.error_code == oracle.error_code && any.on_surface == oracle.on_surface &&
                  any.count == (oracle.ok() && !oracle.on_surface && oracle.count > 0 ? 1 : 0);
    for (int i = 0; any_ok && i < any.count; ++i) {
        bool near = false;
        for (int j = 0; j < oracle.count; ++j) {
            double t = oracle.hits[j].t;
            double half_ulp = detail::Binary64::half_ulp(t);
            near = near || any.hits[i].t == t || // equal infinities too
                   std::fabs(any.hits[i].t - t) <= any.hits[i].bound + half_ulp;
        }
        any_ok = near;
    }
    k.require(any_ok, "correct's hit test is within its bound of the oracle", "correct (any)", any);
    if (k.broken.empty()) k.broken = broken_in_binary32(c);
    check_batch<double>(k);
    check_scene(k, oracle);
    return k.broken;
}

} // namespace linequad
