// Fair verdicts on other people's code: declared tolerances graded rigorously (both ways),
// conventions that are not charged, mismatches split by which way they are wrong, cases outside
// a contract never asked, elliptic frames along the axes, and VecGeom as a peer.
#include "grade/tolerance.hpp"
#include "io/shape_types.hpp"
#include "linequad/audit.hpp"
#include "linequad/audit_solver.hpp"
#include "linequad/exact.hpp"
#include "linequad/solvers.hpp"

#include "support.hpp"

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <random>

using namespace linequad;
using namespace linequad::test;
namespace fs = std::filesystem;

namespace {

using Real = long double;

Real dot_l(Vec3 a, Vec3 w) {
    return Real(a.x) * Real(w.x) + Real(a.y) * Real(w.y) + Real(a.z) * Real(w.z);
}
Real norm_l(Vec3 a) {
    return std::sqrt(dot_l(a, a));
}

// The support function h(w) = max over the solid of x . w, in long double (64-bit significand:
// its rounding, a few 2^-64 of the scene, is far below the 10^-3 tolerance tested).
Real support(const Shape& s, Vec3 w) {
    // A disc of radius r at P, perpendicular to the unit axis u: P.w + r |w - (w.u) u|.
    auto disc = [&](Vec3 P, Real r, Vec3 axis) {
        Real n = norm_l(axis), wu = dot_l(axis, w) / n;
        Real across = std::sqrt(std::max(Real(0), dot_l(w, w) - wu * wu));
        return dot_l(P, w) + r * across;
    };
    auto section = [&](Vec3 a, Vec3 b) { return std::hypot(dot_l(a, w), dot_l(b, w)); };
    return std::visit(
        [&](const auto& x) -> Real {
            using S = std::decay_t<decltype(x)>;
            if constexpr (std::is_same_v<S, Sphere>) return dot_l(x.C, w) + x.r * norm_l(w);
            if constexpr (std::is_same_v<S, Capsule>)
                return std::max(dot_l(x.C, w), dot_l(x.H, w)) + x.r * norm_l(w);
            if constexpr (std::is_same_v<S, Cylinder>)
                return std::max(disc(x.C, x.r, x.H - x.C), disc(x.H, x.r, x.H - x.C));
            if constexpr (std::is_same_v<S, Frustum>)
                return std::max(disc(x.C0, x.r0, x.C1 - x.C0), disc(x.C1, x.r1, x.C1 - x.C0));
            if constexpr (std::is_same_v<S, EllipticCylinder>)
                return dot_l(x.C, w) + section(x.a, x.b) + std::max(Real(0), dot_l(x.c, w));
            if constexpr (std::is_same_v<S, EllipticCone>)
                return std::max(dot_l(x.H, w), dot_l(x.C, w) + section(x.a, x.b));
            if constexpr (std::is_same_v<S, Ellipsoid>)
                return dot_l(x.C, w) +
                       std::sqrt(dot_l(x.a, w) * dot_l(x.a, w) + dot_l(x.b, w) * dot_l(x.b, w) +
                                 dot_l(x.c, w) * dot_l(x.c, w));
            return 0;
        },
        s);
}

// A closed solid from a family's case (caps put on), or nothing for one that bounds no convex
// solid.
std::optional<Shape> closed_solid(Shape s) {
    if (!close_with_discs(s)) return std::nullopt;
    bool one = std::visit([](const auto& x) { return nappes_of(x) == 1; }, s);
    if (!one) return std::nullopt;
    return s;
}

} // namespace

TEST_CASE("tolerance: each bracket lies in S grown by delta and holds S shrunk by delta",
          "[tolerance]") {
    // Convex solids compare by their support functions: A inside B exactly when h_A <= h_B in
    // every direction, and S grown by d has h_S + d |w|. So outer within delta: h_outer <= h_S +
    // delta; inner holding S shrunk: h_S <= h_inner + delta; and inner within delta of S as
    // well, for every unit w sampled. (Neither need contain or lie in S: a cone's ends moved
    // apart along its axis make a longer cone that leaves S's base rim out.)
    const double delta = 1e-3;
    std::mt19937_64 rng(7);
    std::normal_distribution<double> g;
    int brackets_checked = 0, shapes_seen[shape_kinds] = {};
    for (Frames frames : {Frames::any, Frames::aligned})
        for (int shape = 0; shape < shape_kinds; ++shape)
            for (std::uint64_t i = 0; i < 40; ++i) {
                Case c = make_case(Family::generic, shape, Range::line, 1, i, frames);
                std::optional<Shape> s = closed_solid(c.shape);
                if (!s) continue;
                INFO(format_case(c));
                for (const audit::Bracket& b : audit::brackets(*s, delta)) {
                    ++brackets_checked, ++shapes_seen[shape];
                    for (int k = 0; k < 200; ++k) {
                        Vec3 w{g(rng), g(rng), g(rng)};
                        Real n = norm_l(w), h = support(*s, w) / n;
                        CHECK(support(b.outer, w) / n <= h + delta);
                        if (!b.inner) continue;
                        CHECK(h <= support(*b.inner, w) / n + delta);
                        // The inner solid lies within delta of S too (a solid between the two
                        // holds it: the proof needs it inside S grown by delta).
                        CHECK(support(*b.inner, w) / n <= h + delta);
                    }
                }
            }
    CHECK(brackets_checked > 500);
    for (int shape = 0; shape < shape_kinds; ++shape) {
        // The unbounded surfaces are not convex solids: no brackets (convex_solid).
        std::string name = shape_name_at(std::size_t(shape));
        if (name != "plane" && name != "quadric") CHECK(shapes_seen[shape] > 0);
    }
}

TEST_CASE("tolerance: an answer right for a surface within delta is within tolerance, one "
          "beyond it a mismatch",
          "[tolerance][audit]") {
    // A solver answering exactly for the sphere, cylinder or capsule grown by delta/2 (and one by
    // 3 delta): declared delta, the first is never charged; the second is, on the near-tangent
    // lines that miss the true solid by more than delta.
    const double delta = 1e-6;
    auto grown_by = [](const char* name, double d) {
        audit::ExternalSolver e;
        e.name = name;
        e.answers = audit::Answers::first_entry;
        e.surface = audit::Surface::closed;
        e.kinds = e.parts = e.points = false;
        e.tolerance = {1e-6, 0};
        e.on<Sphere>() = [d](const Sphere& s, const Line& l) -> std::optional<Result> {
            Case c;
            c.shape = Sphere{s.C, s.r + d}, c.line = l;
            return audit::reference_for(audit::Answers::first_entry, c);
        };
        e.on<Cylinder>() = [d](const Cylinder& s, const Line& l) -> std::optional<Result> {
            Case c;
            c.shape = Cylinder{s.C, s.H, s.r + d, true, true}, c.line = l;
            return audit::reference_for(audit::Answers::first_entry, c);
        };
        e.on<Capsule>() = [d](const Capsule& s, const Line& l) -> std::optional<Result> {
            Case c;
            c.shape = Capsule{s.C, s.H, s.r + d}, c.line = l;
            return audit::reference_for(audit::Answers::first_entry, c);
        };
        return e;
    };
    audit::Options o;
    o.cases_per_group = 300;
    o.families = {Family::generic, Family::near_tangent};
    o.shapes = {0, 4, 6};
    o.solvers = {"half", "three"};
    audit::Report r = audit::run(o, {grown_by("half", delta / 2), grown_by("three", 3 * delta)});
    audit::Row half = r.total("half"), three = r.total("three");
    CHECK(half.cases > 1000);
    CHECK(half.cases_mismatched == 0);
    CHECK(half.within_tolerance > 50);
    CHECK(three.cases_mismatched > 50);
    CHECK(three.mismatches[audit::invented] > 0);
}

TEST_CASE("tolerance: a tangent rule and an undefined start inside are not charged",
          "[tolerance][audit]") {
    // The exact first entry with touches dropped, asked nothing that starts inside: declared so,
    // no mismatch; declared as linequad's semantics, the touches are charged as missed.
    auto solver = [](const char* name, bool declared) {
        audit::ExternalSolver e;
        e.name = name;
        e.answers = audit::Answers::first_entry;
        e.surface = audit::Surface::closed;
        e.kinds = e.parts = e.points = false;
        if (declared) {
            e.tangent = audit::TangentRule::no_hit;
            e.inside = audit::StartInside::undefined;
            e.on_surface = audit::StartOnSurface::by_direction;
        }
        e.on<Sphere>() = [](const Sphere& s, const Line& l) -> std::optional<Result> {
            Case c;
            c.shape = s, c.line = l;
            Result r = audit::reference_for(audit::Answers::first_entry, c);
            if (r.count == 1 && r.hits[0].kind == HitKind::tangent) r.count = 0;
            return r;
        };
        return e;
    };
    audit::Options o;
    o.cases_per_group = 300;
    o.families = {Family::near_tangent, Family::inside_start};
    o.shapes = {4};
    o.solvers = {"declared", "undeclared"};
    audit::Report r = audit::run(o, {solver("declared", true), solver("undeclared", false)});
    audit::Row declared = r.total("declared"), undeclared = r.total("undeclared");
    CHECK(declared.cases > 500);
    CHECK(declared.cases_mismatched == 0);
    CHECK(audit::not_asked_count(declared) > 50);
    CHECK(undeclared.mismatches[audit::missed] > 0);
    CHECK(r.external.at("declared").conventions.find("a tangent touch is no hit") !=
          std::string::npos);
}

TEST_CASE("a first-exit solver is asked no case that starts outside", "[audit][external]") {
    std::atomic<std::uint64_t> calls{0};
    audit::ExternalSolver e;
    e.name = "exits";
    e.answers = audit::Answers::first_exit;
    e.surface = audit::Surface::closed;
    e.on<Cylinder>() = [&](const Cylinder& s, const Line& l) -> std::optional<Result> {
        ++calls;
        Case c;
        c.shape = s, c.line = l;
        return audit::reference_for(audit::Answers::first_exit, c);
    };
    audit::Options o;
    o.cases_per_group = 300;
    o.families = {Family::generic, Family::inside_start};
    o.shapes = {0};
    o.solvers = {"exits"};
    audit::Report r = audit::run(o, {e});
    audit::Row t = r.total("exits");
    CHECK(t.cases > 100);
    CHECK(t.cases_mismatched == 0);
    CHECK(calls.load() == t.cases);
    CHECK(t.not_asked.at("first exit: the range does not start inside the solid") > 1000);
}

TEST_CASE("mismatches say which way: hits invented, hits missed, calls that crashed",
          "[audit][external]") {
    audit::ExternalSolver none, extra;
    none.name = "none", extra.name = "extra";
    none.on<Sphere>() = [](const Sphere&, const Line&) -> std::optional<Result> {
        return Result{};
    };
    extra.on<Sphere>() = [](const Sphere& s, const Line& l) -> std::optional<Result> {
        Result r = correct::intersect(s, l);
        if (r.ok() && !r.on_surface && r.count < max_hits) {
            r.hits[r.count] = r.count ? r.hits[r.count - 1] : Hit{};
            r.hits[r.count].t = r.count ? std::nextafter(r.hits[r.count].t, INFINITY) : 0;
            ++r.count;
        }
        return r;
    };
    audit::Options o;
    o.cases_per_group = 100;
    o.families = {Family::generic};
    o.shapes = {4};
    o.solvers = {"none", "extra"};
    audit::Report r = audit::run(o, {none, extra});
    audit::Row n = r.total("none"), x = r.total("extra");
    CHECK(n.mismatches[audit::missed] == n.cases_mismatched);
    CHECK(n.mismatches[audit::invented] == 0);
    CHECK(x.mismatches[audit::invented] == x.cases_mismatched);
    CHECK(x.cases_mismatched == x.cases);
    // And the JSON carries them by name, with the new counts, read back equal.
    audit::Report back;
    std::string why;
    REQUIRE(audit::from_json(audit::to_json(r), &back, &why));
    CHECK(back.total("none").mismatches[audit::missed] == n.mismatches[audit::missed]);
    CHECK(audit::to_json(r).find("\"invented\"") != std::string::npos);
    CHECK(audit::to_json(r).find("\"hit_count\"") == std::string::npos);
}

TEST_CASE("a report of the previous format is refused, naming why", "[audit]") {
    audit::Options o;
    o.cases_per_group = 10;
    o.families = {Family::generic};
    o.shapes = {4};
    o.solvers = {"correct"};
    std::string text = audit::to_json(audit::run(o));
    std::string old = "linequad-audit-2";
    text.replace(text.find("linequad-audit-3"), old.size(), old);
    audit::Report r;
    std::string why;
    CHECK_FALSE(audit::from_json(text, &r, &why));
    CHECK(why.find("older report format") != std::string::npos);
    CHECK(why.find("invented and missed") != std::string::npos);
}

TEST_CASE("declarations out of range are refused, naming the solver and the field",
          "[external][worker][cli]") {
    // In process: the run refuses before it starts.
    audit::ExternalSolver e;
    e.name = "thick";
    e.on<Sphere>() = [](const Sphere& s, const Line& l) -> std::optional<Result> {
        return correct::intersect(s, l);
    };
    audit::Options o;
    o.cases_per_group = 10;
    o.families = {Family::generic};
    o.shapes = {4};
    o.solvers = {"thick"};
    for (double bad : {-1.0, double(NAN), double(INFINITY)}) {
        e.tolerance.absolute = bad;
        CHECK_THROWS_WITH(audit::run(o, {e}), Catch::Contains("solver 'thick'") &&
                                                  Catch::Contains("tolerance_absolute"));
    }
    // From a plugin: refused at load, each field by name.
    fs::path dir = scratch("declarations");
    Ran fine = program(std::string("solvers --plugin '") + LINEQUAD_DECLARATIONS_PLUGIN + "'", dir);
    REQUIRE(fine.status == 0);
    CHECK(fine.out.find("declares") != std::string::npos);
    // The plugin reads which field to spoil from its environment, which its worker inherits.
    auto refused = [&](const char* field, const char* value) {
        ::setenv("LQ_TEST_BAD_FIELD", field, 1);
        ::setenv("LQ_TEST_BAD_VALUE", value, 1);
        Ran ran =
            program(std::string("solvers --plugin '") + LINEQUAD_DECLARATIONS_PLUGIN + "'", dir);
        ::unsetenv("LQ_TEST_BAD_FIELD");
        ::unsetenv("LQ_TEST_BAD_VALUE");
        INFO(field << " " << value << ": " << ran.err);
        CHECK(ran.status != 0);
        CHECK(ran.err.find("solver 'declares'") != std::string::npos);
        CHECK(ran.err.find(field) != std::string::npos);
    };
    for (const char* field : {"tolerance_absolute", "tolerance_relative", "negative_zero"})
        for (const char* value : {"neg", "nan", "inf"})
            refused(field, value);
    for (const char* field : {"tangent", "start_on_surface", "inside"})
        refused(field, "");
}

namespace {
// The report of `solvers`, a plugin of an earlier ABI's, on two families of spheres.
audit::Report earlier_abi_audit(const char* plugin, const std::string& solvers, const char* dir) {
    fs::path at = scratch(dir);
    Ran ran = program(std::string("audit --plugin '") + plugin + "' --solvers " + solvers +
                          " --families generic,near_tangent --shapes sphere --cases 50 "
                          "--no-plots --out out",
                      at);
    REQUIRE(ran.status == 0);
    return read_report(at / "out");
}
} // namespace

TEST_CASE("a plugin of ABI 2 loads and grades as it did", "[external][worker][cli]") {
    audit::Report r = earlier_abi_audit(LINEQUAD_ABI2_PLUGIN, "second_abi", "abi2");
    audit::Row t = r.total("second_abi");
    CHECK(t.cases == 300);
    // No hit, ever: every case the nearest-hit reference hits is missed; touches are hits (no
    // tangent rule), nothing is within a tolerance it never declared.
    CHECK(t.cases_mismatched == t.mismatches[audit::missed]);
    CHECK(t.cases_mismatched > 100);
    CHECK(t.within_tolerance == 0);
    CHECK(r.external.at("second_abi").conventions.empty());
}

TEST_CASE("a plugin of ABI 3 loads and is graded under the conventions it declares",
          "[external][worker][cli]") {
    audit::Report r =
        earlier_abi_audit(LINEQUAD_ABI3_PLUGIN, "third_abi,third_abi_relative", "abi3");
    CHECK(r.total("third_abi").cases == 300);
    CHECK(r.total("third_abi").cases_mismatched > 100);
    // Each solver's ABI 3 fields read where lq_solver_v3 lays them out, the second one's too.
    const audit::Report::External &first = r.external.at("third_abi"),
                                  &second = r.external.at("third_abi_relative");
    CHECK(first.tolerance_absolute == 0x1p-20);
    CHECK(first.tolerance_relative == 0);
    CHECK(first.conventions.find("a tangent touch is no hit") != std::string::npos);
    CHECK(second.tolerance_absolute == 0);
    CHECK(second.tolerance_relative == 0x1p-30);
    CHECK(second.conventions.find("tangent") == std::string::npos);
}

TEST_CASE("families: --frames aligned puts every vector along a coordinate axis, the elliptic "
          "sections elliptic",
          "[audit]") {
    auto along_one_axis = [](Vec3 w) { return (w.x != 0) + (w.y != 0) + (w.z != 0) == 1; };
    int elliptic = 0, checked = 0;
    for (int f = 0; f < family_count; ++f)
        for (int shape = 0; shape < shape_kinds; ++shape) {
            if (!family_applies(Family(f), shape)) continue;
            for (std::uint64_t i = 0; i < 20; ++i) {
                Case c = make_case(Family(f), shape, Range::line, 3, i, Frames::aligned);
                INFO(format_case(c));
                CHECK(c.id.find("/aligned") != std::string::npos);
                auto distinct = [&](Vec3 a, Vec3 b) {
                    ++checked;
                    CHECK(along_one_axis(a));
                    CHECK(along_one_axis(b));
                    CHECK(dot(a, b) == 0);
                    elliptic += norm(a) != norm(b);
                };
                if (const auto* e = std::get_if<EllipticCylinder>(&c.shape)) {
                    distinct(e->a, e->b);
                    CHECK(along_one_axis(e->c));
                } else if (const auto* k = std::get_if<EllipticCone>(&c.shape)) {
                    distinct(k->a, k->b);
                    CHECK(along_one_axis(k->H - k->C));
                } else if (const auto* e = std::get_if<Ellipsoid>(&c.shape)) {
                    distinct(e->a, e->b);
                    CHECK(along_one_axis(e->c));
                } else if (const auto* y = std::get_if<Cylinder>(&c.shape)) {
                    CHECK(along_one_axis(y->H - y->C));
                }
            }
        }
    CHECK(checked > 500);
    CHECK(elliptic > checked / 2);
}

#ifdef LINEQUAD_VECGEOM_PLUGIN
TEST_CASE("VecGeom: graded by its own contract, out of process", "[external][worker][cli]") {
    // Generic cases on elliptic frames along the axes: nothing beyond VecGeom's declared
    // tolerance, a first exit never asked from outside, every solid it holds graded.
    fs::path dir = scratch("vecgeom");
    Ran ran = program(std::string("audit --solvers vecgeom,vecgeom_out --frames aligned "
                                  "--families generic,near_tangent,inside_start --cases 200 "
                                  "--no-plots --out out"),
                      dir);
    REQUIRE(ran.status == 0);
    audit::Report r = read_report(dir / "out");
    for (const char* shape :
         {"cylinder", "elliptic_cylinder", "elliptic_cone", "frustum", "sphere", "ellipsoid"}) {
        INFO(shape);
        const audit::Row& row = r.rows.at({"generic", shape, "vecgeom"});
        CHECK(row.cases > 100);
        CHECK(row.cases_mismatched == 0);
    }
    // Few generic lines start inside a solid: its first exit is asked only of those.
    for (const auto& [key, row] : r.rows)
        if (key.solver == "vecgeom_out" && key.family == "generic")
            CHECK(row.cases_mismatched == 0);
    CHECK(r.total("vecgeom_out").cases > 100);
    CHECK(audit::not_asked_count(r.total("vecgeom_out")) > 1000);
    CHECK(r.total("vecgeom").within_tolerance > 0);
    CHECK(r.external.at("vecgeom").conventions.find("a tangent touch is no hit") !=
          std::string::npos);
    // The capsule is no VecGeom solid: counted, not graded.
    CHECK(r.rows.count({"generic", "capsule", "vecgeom"}) == 0);
}
#endif
