// Cells and models (linequad/cells.hpp): regions in OpenMC's syntax, the model's checks, and the
// exact queries a tracker asks, on models whose answers are known exactly.
#include "support.hpp"

#include "linequad/audit_solver.hpp"
#include "linequad/case_io.hpp"
#include "linequad/cells.hpp"
#include "linequad/exact.hpp"
#include "linequad/solvers.hpp"
#include "linequad/tracking_audit.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <type_traits>

using namespace linequad;

namespace {

// x^2 + y^2 + z^2 - r^2 in GQ form.
Quadric sphere(double r2) {
    return {{1, 1, 1, 0, 0, 0, 0, 0, 0, -r2}};
}
Plane plane_x(double d) {
    return {{1, 0, 0}, d};
}

Model build(std::vector<Model::Surface> surfaces, std::vector<Model::CellSource> cells) {
    std::string error;
    std::optional<Model> m = Model::build(std::move(surfaces), cells, error);
    INFO(error);
    REQUIRE(m);
    return *m;
}
std::string build_error(std::vector<Model::Surface> surfaces,
                        std::vector<Model::CellSource> cells) {
    std::string error;
    std::optional<Model> m = Model::build(std::move(surfaces), cells, error);
    CHECK(!m);
    return error;
}

// The concentric spheres of radius 1 and 2: inside, the shell, outside.
Model spheres() {
    return build({{1, sphere(1)}, {2, sphere(4)}},
                 {{10, "core", "-1"}, {20, "shell", "1 -2"}, {30, "outside", "2"}});
}

// An in-process solver of planes and quadrics answering with linequad's correct solver.
audit::ExternalSolver correct_distances() {
    audit::ExternalSolver mine;
    mine.name = "mine";
    mine.on<Plane>() = [](const Plane& s, const Line& l) -> std::optional<Result> {
        return correct::intersect(s, l, {Need::all, false});
    };
    mine.on<Quadric>() = [](const Quadric& s, const Line& l) -> std::optional<Result> {
        return correct::intersect(s, l, {Need::all, false});
    };
    return mine;
}

std::vector<Sense> senses(std::initializer_list<int> s) {
    std::vector<Sense> out;
    for (int x : s)
        out.push_back(Sense(x));
    return out;
}

} // namespace

TEST_CASE("cells: a region's text parses with OpenMC's precedence", "[cells]") {
    std::string error;
    // ~ binds tightest, then intersection, then union: "-1 2 | ~3" is (-1 and 2) or (not 3).
    std::optional<Region> r = Region::parse("-1 2 | ~3", error);
    REQUIRE(r);
    for (Region::Token& t : r->tokens())
        if (t.op == Region::Op::half_space) t.surface = int(t.id) - 1;
    CHECK(r->contains(senses({-1, 1, 1})) == true);   // -1 and 2
    CHECK(r->contains(senses({1, 1, -1})) == true);   // not 3
    CHECK(r->contains(senses({1, 1, 1})) == false);   // neither
    CHECK(r->contains(senses({-1, -1, 1})) == false); // 2 fails, 3 holds
    // An undecided sense decides nothing unless the other operand does.
    CHECK(!r->contains(senses({-1, 0, 1})).has_value());
    CHECK(r->contains(senses({-1, 0, -1})) == true); // ~3 holds whatever 2 is
    CHECK(r->contains(senses({1, 0, 1})) == false);  // -1 fails: the intersection is false

    std::optional<Region> nested = Region::parse("~(1 | -2) +3", error);
    REQUIRE(nested);
    for (Region::Token& t : nested->tokens())
        if (t.op == Region::Op::half_space) t.surface = int(t.id) - 1;
    CHECK(nested->contains(senses({-1, 1, 1})) == true);
    CHECK(nested->contains(senses({1, 1, 1})) == false);
    CHECK(nested->contains(senses({-1, 1, -1})) == false);
}

TEST_CASE("cells: a malformed region is refused, naming what and the column", "[cells]") {
    struct Bad {
        const char* text;
        const char* error;
    };
    const Bad bad[] = {
        {"", "the region is empty at column 1"},
        {"   ", "the region is empty at column 4"},
        {"(1 2", "a '(' without its ')' at column 1"},
        {"1 2)", "a ')' without its '(' at column 4"},
        {"1 |", "'|' with nothing after it at column 4"},
        {"~", "the region ends where a surface or '(' was expected at column 2"},
        {"1 & 2", "unexpected '&' at column 3"},
        {"()", "'()' holds no region at column 2"},
        {"-0", "surface id 0 has no sign to give a side at column 1"},
        {"- 4", "unexpected '-' at column 1"},
        {"99999999999999999999", "a surface id too large at column 1"},
    };
    for (const Bad& b : bad) {
        std::string error;
        INFO(b.text);
        CHECK(!Region::parse(b.text, error));
        CHECK(error == b.error);
    }
    // Nesting is bounded, not left to exhaust the stack.
    std::string error;
    CHECK(!Region::parse(std::string(1000000, '~') + "1", error));
    CHECK(error == "complements nested too deep at column 1001");
    CHECK(!Region::parse(std::string(100000, '(') + "1" + std::string(100000, ')'), error));
    CHECK(error == "parentheses nested too deep at column 1001");
    CHECK(Region::parse(std::string(999, '~') + "1", error));
}

TEST_CASE("cells: a model with a problem is refused, naming the surface or cell", "[cells]") {
    CHECK(build_error({{1, sphere(1)}}, {}) == "the model has no cells");
    CHECK(build_error({{1, sphere(1)}, {1, sphere(4)}}, {{1, "", "-1"}}) ==
          "surface 1 is defined twice");
    CHECK(build_error({{1, sphere(1)}}, {{5, "", "-1"}, {5, "", "1"}}) ==
          "cell 5 is defined twice");
    CHECK(build_error({{1, sphere(1)}}, {{5, "", "-1 -2"}}) ==
          "cell 5: region \"-1 -2\" names surface 2, which the model does not define");
    CHECK(build_error({{1, sphere(1)}}, {{5, "", "(-1"}}) ==
          "cell 5: region \"(-1\": a '(' without its ')' at column 1");
    CHECK(build_error({{3, Plane{{0, 0, 0}, 1}}}, {{5, "", "-3"}}).rfind("surface 3: ", 0) == 0);
    Quadric nan = sphere(1);
    nan.q[4] = std::nan("");
    CHECK(build_error({{7, nan}}, {{5, "", "-7"}}).rfind("surface 7: ", 0) == 0);
}

TEST_CASE("cells: the cells at a point, with the direction deciding a point on a surface",
          "[cells]") {
    Model m = spheres();
    auto cells_at = [&](Vec3 p, Vec3 u) {
        Model::Location l = m.locate(p, u);
        REQUIRE(l.error.ok());
        CHECK(l.undecided.empty());
        std::vector<std::int64_t> ids;
        for (int c : l.cells)
            ids.push_back(m.cells()[std::size_t(c)].id);
        return ids;
    };
    CHECK(cells_at({0, 0, 0}, {1, 0, 0}) == std::vector<std::int64_t>{10});
    CHECK(cells_at({1.5, 0, 0}, {1, 0, 0}) == std::vector<std::int64_t>{20});
    CHECK(cells_at({0, 3, 0}, {1, 0, 0}) == std::vector<std::int64_t>{30});
    // On the unit sphere exactly: the side u points into.
    CHECK(cells_at({1, 0, 0}, {1, 0, 0}) == std::vector<std::int64_t>{20});
    CHECK(cells_at({1, 0, 0}, {-1, 0, 0}) == std::vector<std::int64_t>{10});
    // Tangent there (grad f . u = 0): the quadratic part of f at u, positive: outside.
    CHECK(cells_at({1, 0, 0}, {0, 1, 0}) == std::vector<std::int64_t>{20});

    // An overlap and a gap are reported as such, not resolved.
    Model overlap =
        build({{1, plane_x(0)}, {2, plane_x(1)}}, {{1, "left", "-2"}, {2, "right", "1"}});
    Model::Location both = overlap.locate({0.5, 0, 0}, {0, 1, 0});
    CHECK(both.cells == std::vector<int>{0, 1});
    Model gap = build({{1, plane_x(0)}, {2, plane_x(1)}}, {{1, "left", "-1"}, {2, "right", "2"}});
    CHECK(gap.locate({0.5, 0, 0}, {0, 1, 0}).cells.empty());

    // Moving along a surface: the cells it bounds are undecided.
    Model halves = build({{1, plane_x(1)}}, {{1, "", "-1"}, {2, "", "1"}});
    Model::Location along = halves.locate({1, 0, 0}, {0, 0, 1});
    CHECK(along.cells.empty());
    CHECK(along.undecided == std::vector<int>{0, 1});

    CHECK(m.locate({std::nan(""), 0, 0}, {1, 0, 0}).error.code == ErrorCode::not_a_number);
    CHECK(m.locate({0, 0, 0}, {0, 0, 0}).error.code == ErrorCode::zero_direction);
}

TEST_CASE("cells: the next crossing is exact: distance correctly rounded, surfaces, cells entered",
          "[cells]") {
    Model m = spheres();
    SECTION("from the centre outwards: the unit sphere at t = 1, into the shell") {
        Model::Crossing c = m.next_crossing(m.cell_index(10), {0, 0, 0}, {1, 0, 0});
        REQUIRE(c.exit == Model::Exit::leaves);
        CHECK(c.t == 1);
        CHECK(c.surfaces == std::vector<int>{0});
        CHECK(c.entered == std::vector<int>{1});
    }
    SECTION("an oblique ray: t is the oracle's correctly rounded root") {
        Vec3 p{0.25, -0.375, 0.125}, u{0.3, 0.7, -0.1};
        Model::Crossing c = m.next_crossing(m.cell_index(10), p, u);
        REQUIRE(c.exit == Model::Exit::leaves);
        Result want = exact::intersect(sphere(1), Line{p, u, Range::ray}, {});
        REQUIRE(want.count == 1);
        CHECK(test::same_bits(c.t, want.hits[0].t));
        // From the shell the same ray leaves through the outer sphere, into the outside.
        Vec3 q{1.5, 0, 0};
        Model::Crossing out = m.next_crossing(m.cell_index(20), q, {1, 0, 0});
        REQUIRE(out.exit == Model::Exit::leaves);
        CHECK(out.t == 0.5);
        CHECK(out.entered == std::vector<int>{2});
        // Inwards from the shell: the unit sphere, into the core.
        Model::Crossing in = m.next_crossing(m.cell_index(20), q, {-1, 0, 0});
        REQUIRE(in.exit == Model::Exit::leaves);
        CHECK(in.t == 0.5);
        CHECK(in.entered == std::vector<int>{0});
    }
    SECTION("a particle on a surface, moving into its cell, leaves at the far side") {
        Model::Crossing c = m.next_crossing(m.cell_index(10), {-1, 0, 0}, {1, 0, 0});
        REQUIRE(c.exit == Model::Exit::leaves);
        CHECK(c.t == 2);
    }
    SECTION("the outside never ends along a ray away from the spheres") {
        CHECK(m.next_crossing(m.cell_index(30), {3, 0, 0}, {1, 0, 0}).exit == Model::Exit::escapes);
    }
    SECTION("a particle not in the cell asked about") {
        CHECK(m.next_crossing(m.cell_index(10), {3, 0, 0}, {1, 0, 0}).exit ==
              Model::Exit::not_inside);
        CHECK(m.next_crossing(7, {0, 0, 0}, {1, 0, 0}).exit == Model::Exit::error);
    }
}

TEST_CASE("cells: coincident surfaces tie and surfaces an ulp apart are told apart exactly",
          "[cells]") {
    SECTION("x = 1 written twice (x - 1 and 2x - 2): one crossing through both, a tie") {
        Model m = build({{1, plane_x(1)}, {2, Plane{{2, 0, 0}, 2}}},
                        {{1, "in", "-1 -2"}, {2, "out", "1 2"}});
        Model::Crossing c = m.next_crossing(0, {0, 0, 0}, {1, 0, 0});
        REQUIRE(c.exit == Model::Exit::leaves);
        CHECK(c.t == 1);
        CHECK(c.surfaces == std::vector<int>{0, 1});
        CHECK(c.entered == std::vector<int>{1});
    }
    SECTION("crossings that round to the same t are taken in their exact order") {
        // Along +x from the origin: the plane x = 1 at t = 1, and the sphere
        // x^2 + y^2 + z^2 = 1 + 2^-52 at t = sqrt(1 + 2^-52), just below 1 + 2^-53: both round
        // to 1. The sphere is written twice (the second times 2), so its crossing is a tie.
        Quadric twice{{2, 2, 2, 0, 0, 0, 0, 0, 0, -(2 + 0x1p-51)}};
        Model m = build({{1, plane_x(1)}, {2, sphere(1 + 0x1p-52)}, {3, twice}},
                        {{1, "left", "-1 -2"}, {2, "sliver", "1 -2"}, {3, "outside", "2"}});
        Model::Crossing c = m.next_crossing(m.cell_index(1), {0, 0, 0}, {1, 0, 0});
        REQUIRE(c.exit == Model::Exit::leaves);
        CHECK(c.t == 1);
        CHECK(c.surfaces == std::vector<int>{0}); // the plane alone: it comes first, exactly
        CHECK(c.entered == std::vector<int>{m.cell_index(2)});
        // From the plane into the sliver no double lies inside it; the particle leaves it through
        // both writings of the sphere at once, at sqrt(1 + 2^-52) - 1 correctly rounded.
        Model::Crossing out = m.next_crossing(m.cell_index(2), {1, 0, 0}, {1, 0, 0});
        REQUIRE(out.exit == Model::Exit::leaves);
        CHECK(out.surfaces == std::vector<int>{1, 2});
        CHECK(out.entered == std::vector<int>{m.cell_index(3)});
        Result want =
            exact::intersect(sphere(1 + 0x1p-52), Line{{1, 0, 0}, {1, 0, 0}, Range::ray}, {});
        REQUIRE(want.count == 1);
        CHECK(test::same_bits(out.t, want.hits[0].t));
    }
}

TEST_CASE("cells: a sphere and an axis-aligned cylinder have the exact sense OpenMC's definition "
          "gives, whatever their doubles",
          "[cells]") {
    // R = 1 - 0.63 exactly (Sterbenz): (1, -0.63, z) lies on the z-cylinder around
    // (0.63, -0.63) of radius R, and (0.63, -0.63 + ..., ...) does not; the expanded quadric's
    // constant 2 (0.63)^2 - R^2 is no double, which is why the cylinder is posed by its centre.
    const double R = 1.0 - 0.63;
    Cylinder pin{{0.63, -0.63, 0}, {0.63, -0.63, 5}, R};
    pin.finite = false;
    Vec3 on{1.0, -0.63, 2.5};
    CHECK(sense(pin, on).sense == Sense::on);
    CHECK(sense(pin, on, {1, 0, 0}).sense == Sense::positive);
    CHECK(sense(pin, on, {-1, 0.5, 3}).sense == Sense::negative);
    CHECK(sense(pin, on, {0, 1, 0}).sense == Sense::positive); // tangent: curving away
    CHECK(sense(pin, on, {0, 0, -1}).sense == Sense::on);      // along the surface
    CHECK(sense(pin, {std::nextafter(1.0, 2.0), -0.63, 0}).sense == Sense::positive);
    CHECK(sense(pin, {std::nextafter(1.0, 0.0), -0.63, 0}).sense == Sense::negative);
    Sphere ball{{0.1, 0.2, 0.3}, 0.7};
    // Against the oracle on points at and beside both surfaces: their rounded hits, and points
    // a few ulps off.
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> box(-2, 2);
    int decided = 0;
    for (int i = 0; i < 3000; ++i) {
        Line l{{box(rng), box(rng), box(rng)}, {box(rng), box(rng), box(rng)}, Range::line};
        Vec3 u{box(rng), box(rng), box(rng)};
        auto compare = [&](const auto& s) {
            Result r = correct::intersect(s, l);
            for (int k = 0; k < r.count; ++k) {
                Vec3 p = r.hits[k].p;
                for (Vec3 q : {p, Vec3{std::nextafter(p.x, 9.0), p.y, p.z}}) {
                    INFO(i << " " << q.x << " " << q.y << " " << q.z);
                    CHECK(sense(s, q, u).sense == exact::sense(s, q, u).sense);
                    CHECK(sense(s, q).sense == exact::sense(s, q).sense);
                    decided += sense(s, q).sense != Sense::on;
                }
            }
        };
        compare(pin);
        compare(ball);
    }
    CHECK(decided > 1000);
    // What a cell's cylinder cannot be: finite, capped, oblique; and radii that are no radius.
    Cylinder finite = pin;
    finite.finite = true;
    CHECK(check_sense(finite, {}).code == ErrorCode::bad_option);
    Cylinder oblique = pin;
    oblique.H = {1, 1, 5};
    CHECK(check_sense(oblique, {}).code == ErrorCode::bad_option);
    CHECK(std::string(check_sense(oblique, {}).field).rfind("H - C", 0) == 0);
    Cylinder no_axis = pin;
    no_axis.H = no_axis.C;
    CHECK(check_sense(no_axis, {}).code == ErrorCode::degenerate_axis);
    CHECK(check_sense(Sphere{{0, 0, 0}, 0}, {}).code == ErrorCode::bad_radius);
    CHECK(check_sense(Sphere{{0, 0, 0}, NAN}, {}).code == ErrorCode::not_a_number);
    CHECK(sense(Sphere{{0, 0, 0}, -1}, {}).error.code == ErrorCode::bad_radius);
    // From the command line, as a model file writes them.
    std::filesystem::path dir = test::scratch("cells_centred_sense");
    std::ofstream(dir / "q.jsonl")
        << R"({"id":1,"shape":"cylinder","C":[0.63,-0.63,0],"H":[0.63,-0.63,1],"r":"0x1.7ae147ae147aep-2","p":[1,-0.63,2],"u":[0,0,1]})"
        << "\n"
        << R"({"id":2,"shape":"sphere","C":[0,0,0],"r":0.1,"p":[0.1,0,0],"u":[-1,0,0]})"
        << "\n";
    test::Ran cli = test::program("sense q.jsonl", dir);
    CHECK(cli.status == 0);
    CHECK(cli.out == "{\"id\":1,\"sense\":\"on\",\"sign\":0}\n"
                     "{\"id\":2,\"sense\":\"negative\",\"sign\":-1}\n");
}

TEST_CASE("cells: a model's spheres and cylinders track exactly, from JSON and from geometry.xml",
          "[cells]") {
    namespace fs = std::filesystem;
    // The same two pins from a JSON model, the sphere around them too.
    const char* json = R"({"box":[[-2,-2,-2],[2,2,2]],
      "surfaces":[{"id":1,"shape":"cylinder","C":[-0.63,0,0],"H":[-0.63,0,1],"r":0.39218},
                  {"id":2,"shape":"cylinder","C":[0.63,0,0],"H":[0.63,0,1],"r":0.39218},
                  {"id":3,"shape":"sphere","C":[0,0,0.1],"r":1.7}],
      "cells":[{"id":1,"region":"-1 -3"},{"id":2,"region":"-2 -3"},{"id":3,"region":"1 2 -3"},
               {"id":4,"region":"3"}]})";
    ModelFile file;
    std::string why;
    REQUIRE(parse_model(json, &file, &why));
    std::optional<Model> m = Model::build(file.surfaces, file.cells, why);
    INFO(why);
    REQUIRE(m);
    for (int f = 0; f < track_family_count; ++f)
        for (std::uint64_t i = 0; i < 100; ++i) {
            std::optional<TrackRay> ray =
                track_ray(*m, (*file.box)[0], (*file.box)[1], TrackFamily(f), 3, i);
            if (!ray) break;
            GradedTrack g = grade_linequad_track(exact::track(*m, ray->p, ray->u, 1000),
                                                 m->track(ray->p, ray->u, 1000));
            INFO(track_family_name(TrackFamily(f)) << " ray " << i);
            CHECK(g.outcome == TrackOutcome::right);
        }
    // An oblique cylinder, or a field a cylinder does not have, is refused by name.
    std::string oblique = json;
    const std::string axis = "\"H\":[-0.63,0,1]";
    oblique.replace(oblique.find(axis), axis.size(), "\"H\":[-0.62,0,1]");
    REQUIRE(parse_model(oblique, &file, &why));
    CHECK(!Model::build(file.surfaces, file.cells, why));
    CHECK(why.find("surface 1: ") == 0);
    CHECK(why.find("H - C") != std::string::npos);
    std::string extra = json;
    extra.replace(extra.find("\"r\":1.7"), 7, "\"r\":1.7,\"q\":[1]");
    CHECK(!parse_model(extra, &file, &why));
    CHECK(why.find("surfaces[2]") == 0);
    // OpenMC's assembly patch: four off-centre pins of decimal radii.
    fs::path dir = test::scratch("cells_assembly");
    fs::path xml = fs::path(LINEQUAD_SOURCE_DIR) / "examples/models/assembly_openmc.xml";
    test::Ran audit = test::program("cells '" + xml.string() +
                                        "' --audit --rays 150 --points 500 --box "
                                        "-1.26,-1.26,-10,1.26,1.26,10",
                                    dir);
    REQUIRE(audit.status == 0);
    CHECK(audit.out.find("**linequad's cells went wrong on 0**") != std::string::npos);
    CHECK(audit.out.find(", 0 lie in two cells or more, 0 in no cell") != std::string::npos);
}

TEST_CASE("cells: a union's inner surface is not a boundary", "[cells]") {
    // Two overlapping unit balls, centred at x = 0 and x = 1, as one cell.
    Quadric right{{1, 1, 1, 0, 0, 0, -2, 0, 0, 0}}; // (x - 1)^2 + y^2 + z^2 - 1
    Model m = build({{1, sphere(1)}, {2, right}}, {{1, "lens", "-1 | -2"}, {2, "rest", "1 2"}});
    Model::Crossing c = m.next_crossing(0, {-0.5, 0, 0}, {1, 0, 0});
    REQUIRE(c.exit == Model::Exit::leaves);
    CHECK(c.t == 2.5); // crosses sphere 1 at x = 1 inside ball 2, leaves at x = 2
    CHECK(c.surfaces == std::vector<int>{1});
    CHECK(c.entered == std::vector<int>{1});
}

TEST_CASE("cells: a particle moving along a surface its cell rests on is named, not tracked",
          "[cells]") {
    Model m = build({{1, plane_x(1)}, {2, sphere(4)}}, {{1, "", "-1 -2"}, {2, "", "1 -2"}});
    CHECK(m.next_crossing(0, {1, 0, 0}, {0, 1, 0}).exit == Model::Exit::along);
    Model::Crossing bad = m.next_crossing(0, {0, 0, 0}, {0, 0, 0});
    CHECK(bad.exit == Model::Exit::error);
    CHECK(bad.error.code == ErrorCode::zero_direction);
}

TEST_CASE("cells: the textbook tracker, graded against the exact track", "[cells]") {
    // examples/models/spheres.json: radii 1, 2 and 4.
    Model m = build({{1, sphere(1)}, {2, sphere(4)}, {3, sphere(16)}}, {{10, "core", "-1"},
                                                                        {20, "shell", "1 -2"},
                                                                        {30, "moderator", "2 -3"},
                                                                        {40, "outside", "3"}});
    SECTION("a generic ray: every cell right, distances within a few ulps") {
        Vec3 p{0.25, -0.375, 0.125}, u{0.3, 0.7, -0.1};
        Model::Track exact = m.track(p, u, 100);
        REQUIRE(exact.error.ok());
        REQUIRE(exact.steps.size() == 3); // core -> shell -> moderator -> outside
        TrackerRun run = textbook_track(m, p, u, 100);
        GradedTrack g = grade_track(exact, run);
        CHECK(g.outcome == TrackOutcome::right);
        CHECK(g.steps == 3);
        // The textbook's distance is a sum of rounded steps, each from a rounded position: a
        // few ulps of t, far below the 2^-20 a wrong root would cost.
        CHECK(g.max_t_ulps < 0x1p20);
    }
    SECTION("a source 2^26 away: the textbook's quadratic cancels and misses the model") {
        // The audit's first failing far-source ray on examples/models/spheres.json.
        Vec3 p{-0x1.0d0f7f70f97acp+26, -0x1.4f1a232b3dd4bp+24, 0x1.ab78c3c766d0cp+26};
        Vec3 u{0x1.5a350fd1c6a96p+0, 0x1.af2f45fecaaa6p-2, -0x1.1305035327346p+1};
        Model::Track exact = m.track(p, u, 100);
        REQUIRE(exact.error.ok());
        REQUIRE(exact.start == std::vector<int>{3});
        CHECK(exact.steps.empty()); // it passes the spheres by, exactly
        TrackerRun run = textbook_track(m, p, u, 100);
        CHECK(!run.steps.empty()); // the textbook crosses the outer sphere all the same
        GradedTrack g = grade_track(exact, run);
        CHECK(g.outcome == TrackOutcome::extra);
        CHECK(g.failed_step == 1);
    }
    SECTION("the grading names each way a tracker fails") {
        Model::Track exact = m.track({0, 0, 0}, {1, 0, 0}, 100);
        REQUIRE(exact.steps.size() == 3);
        TrackerRun lost{0, {{1, 1, -1}}, false};
        CHECK(grade_track(exact, lost).outcome == TrackOutcome::lost);
        TrackerRun wrong{0, {{1, 1, 2}}, false};
        CHECK(grade_track(exact, wrong).outcome == TrackOutcome::wrong_cell);
        TrackerRun missed{0, {{1, 1, 1}}, true};
        GradedTrack g = grade_track(exact, missed);
        CHECK(g.outcome == TrackOutcome::missed);
        CHECK(g.failed_step == 2);
        TrackerRun extra{0, {{1, 1, 1}, {2, 1, 2}, {4, 2, 3}, {5, 1, 2}}, false};
        CHECK(grade_track(exact, extra).outcome == TrackOutcome::extra);
        TrackerRun right{0, {{1, 1, 1}, {2, 1, 2}, {4, 2, 3}}, true};
        GradedTrack ok = grade_track(exact, right);
        CHECK(ok.outcome == TrackOutcome::right);
        CHECK(ok.steps == 3);
        CHECK(ok.max_t_ulps == 0);
        TrackerRun wrong_start{1, {}, false};
        CHECK(grade_track(exact, wrong_start).outcome == TrackOutcome::wrong_cell);
    }
}

TEST_CASE("cells: linequad's tracks are the oracle's bit for bit on every shipped model and family",
          "[cells]") {
    namespace fs = std::filesystem;
    int models = 0;
    for (const fs::directory_entry& e :
         fs::directory_iterator(fs::path(LINEQUAD_SOURCE_DIR) / "examples/models")) {
        if (e.path().extension() != ".json") continue;
        ++models;
        std::ifstream in(e.path());
        std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        ModelFile file;
        std::string why;
        INFO(e.path().string() << ": " << why);
        REQUIRE(parse_model(text, &file, &why));
        REQUIRE(file.box);
        std::optional<Model> m = Model::build(file.surfaces, file.cells, why);
        REQUIRE(m);
        for (int f = 0; f < track_family_count; ++f) {
            int rays = 0, steps = 0;
            for (std::uint64_t i = 0; i < 150; ++i) {
                std::optional<TrackRay> ray =
                    track_ray(*m, (*file.box)[0], (*file.box)[1], TrackFamily(f), 7, i);
                if (!ray) break;
                Model::Track oracle = exact::track(*m, ray->p, ray->u, 1000);
                GradedTrack g = grade_linequad_track(oracle, m->track(ray->p, ray->u, 1000));
                INFO(track_family_name(TrackFamily(f))
                     << " ray " << i << ": " << track_outcome_name(g.outcome) << " at step "
                     << g.failed_step);
                CHECK(g.outcome == TrackOutcome::right);
                ++rays, steps += int(oracle.steps.size());
            }
            // Each family applies to some model: the two with planes and curved surfaces.
            if (e.path().filename() == "pin_cell.json") {
                INFO(track_family_name(TrackFamily(f)));
                CHECK(rays == 150);
                CHECK(steps > 0);
            }
        }
    }
    CHECK(models >= 5);
}

TEST_CASE("cells: the grading of linequad's tracks names each difference from the oracle's",
          "[cells]") {
    Model m = spheres();
    Model::Track oracle = m.track({0, 0, 0}, {1, 0, 0}, 100);
    REQUIRE(oracle.steps.size() == 2);
    CHECK(grade_linequad_track(oracle, oracle).outcome == TrackOutcome::right);
    Model::Track t = oracle;
    t.steps[1].t = std::nextafter(t.steps[1].t, 3.0); // an ulp off
    GradedTrack g = grade_linequad_track(oracle, t);
    CHECK(g.outcome == TrackOutcome::inexact);
    CHECK(g.failed_step == 2);
    CHECK(g.max_t_ulps == 1);
    t = oracle, t.steps[0].surfaces = {0, 1};
    CHECK(grade_linequad_track(oracle, t).outcome == TrackOutcome::inexact);
    t = oracle, t.steps[0].cells = {2};
    CHECK(grade_linequad_track(oracle, t).outcome == TrackOutcome::wrong_cell);
    t = oracle, t.steps[0].cells = {};
    CHECK(grade_linequad_track(oracle, t).outcome == TrackOutcome::lost);
    t = oracle, t.steps.pop_back();
    CHECK(grade_linequad_track(oracle, t).outcome == TrackOutcome::missed);
    t = oracle, t.steps.push_back(t.steps.back());
    CHECK(grade_linequad_track(oracle, t).outcome == TrackOutcome::extra);
    t = oracle, t.start = {1};
    CHECK(grade_linequad_track(oracle, t).outcome == TrackOutcome::wrong_cell);
}

TEST_CASE("cells: points in two cells or in none are found, named and replayable", "[cells]") {
    // Cells 10 and 20 overlap in the unit ball's half x < 0; cell 30, the outside for x > 0
    // only, leaves a gap outside the ball where x < 0.
    Model m =
        build({{1, sphere(1)}, {2, plane_x(0)}},
              {{10, "ball", "-1"}, {20, "left half ball", "-1 -2"}, {30, "outside, right", "1 2"}});
    PointSample s = sample_points(m, {-1, -1, -1}, {1, 1, 1}, 3, 4000);
    CHECK(s.points == 4000);
    REQUIRE(s.overlaps.size() == 1);
    CHECK(s.overlaps[0].first == std::vector<int>{0, 1});
    // Each share is a volume's over the box's 8: the ball's left half pi/12 of it, the box's
    // left half outside the ball 1/2 - pi/12.
    // 4000 draws: a share within 5 standard deviations (at most sqrt(0.25/4000) each).
    double half_ball = std::acos(-1.0) / 12;
    CHECK(std::fabs(double(s.overlaps[0].second) / 4000 - half_ball) < 5 * 0.0080);
    CHECK(std::fabs(double(s.in_none) / 4000 - (0.5 - half_ball)) < 5 * 0.0080);
    // The first overlapping point's query line locates to both cells.
    REQUIRE(!s.first_overlap.empty());
    auto number = [&](const std::string& key, int k) {
        std::size_t at = s.first_overlap.find("\"" + key + "\":[");
        for (int i = 0; i <= k; ++i)
            at = s.first_overlap.find('"', s.first_overlap.find('"', at + key.size() + 4) + 1);
        std::size_t open = s.first_overlap.rfind('"', at - 1);
        return std::strtod(s.first_overlap.substr(open + 1, at - open - 1).c_str(), nullptr);
    };
    Vec3 p{number("p", 0), number("p", 1), number("p", 2)};
    Vec3 u{number("u", 0), number("u", 1), number("u", 2)};
    CHECK(m.locate(p, u).cells == std::vector<int>{0, 1});
    // A model without overlaps or gaps: none found.
    PointSample clean = sample_points(spheres(), {-3, -3, -3}, {3, 3, 3}, 3, 2000);
    CHECK(clean.overlaps.empty());
    CHECK(clean.in_none == 0);
}

TEST_CASE("cells: the transport loop takes a user's distances as it takes linequad's", "[cells]") {
    // An in-process solver answering with linequad's correct solver: the loop with its distances
    // must run as the loop with correct distances does, step for step, whatever the family.
    audit::ExternalSolver mine = correct_distances();
    Model m =
        build({{1, sphere(1)}, {2, sphere(4)}, {3, plane_x(0.5)}}, {{10, "core", "-1"},
                                                                    {20, "shell, left", "1 -2 -3"},
                                                                    {30, "shell, right", "1 -2 3"},
                                                                    {40, "outside", "2"}});
    CHECK(external_distances_problem(m, mine).empty());
    int steps = 0;
    for (int f = 0; f < track_family_count; ++f)
        for (std::uint64_t i = 0; i < 200; ++i) {
            std::optional<TrackRay> ray =
                track_ray(m, {-3, -3, -3}, {3, 3, 3}, TrackFamily(f), 5, i);
            if (!ray) break;
            TrackerRun theirs = textbook_track(m, ray->p, ray->u, 100, mine),
                       ours = textbook_track(m, ray->p, ray->u, 100, TrackerDistances::correct);
            INFO(track_family_name(TrackFamily(f)) << " ray " << i);
            CHECK(theirs.start == ours.start);
            CHECK(theirs.escaped == ours.escaped);
            REQUIRE(theirs.steps.size() == ours.steps.size());
            for (std::size_t k = 0; k < ours.steps.size(); ++k) {
                CHECK(theirs.steps[k].t == ours.steps[k].t);
                CHECK(theirs.steps[k].cell == ours.steps[k].cell);
            }
            steps += int(ours.steps.size());
        }
    CHECK(steps > 1000);
    // A solver without the model's planes, or taking its lines otherwise, cannot give them.
    audit::ExternalSolver spheres_only = mine;
    spheres_only.on<Plane>() = nullptr;
    CHECK(external_distances_problem(m, spheres_only) ==
          "solver 'mine' does not take the model's planes");
    audit::ExternalSolver unit = mine;
    unit.parametrisation = audit::Parametrisation::unit_direction;
    CHECK(!external_distances_problem(m, unit).empty());
}

TEST_CASE("cells: the transport loop finds its cells by a user's sides where it has them",
          "[cells]") {
    // linequad's correct distances, and the sides exact (linequad's sense, the direction
    // deciding a point on the surface): a backscattered particle, some 2^-20 to 2^-50 box sizes
    // past a surface, starts in the oracle's cell, where the textbook's sides (|f| < 1e-12: the
    // side u points into) put it in the next one.
    audit::ExternalSolver mine = correct_distances();
    int calls = 0;
    mine.sense = [&](const Shape& s, Vec3 p, Vec3 u) {
        ++calls;
        return std::visit(
            [&](const auto& x) {
                if constexpr (std::is_same_v<std::decay_t<decltype(x)>, Plane> ||
                              std::is_same_v<std::decay_t<decltype(x)>, Quadric>)
                    return int(sense(x, p, u).sense);
                else
                    return 0;
            },
            s);
    };
    CHECK(mine.has_sense());
    Model m =
        build({{1, sphere(1)}, {2, sphere(4)}, {3, plane_x(0.5)}}, {{10, "core", "-1"},
                                                                    {20, "shell, left", "1 -2 -3"},
                                                                    {30, "shell, right", "1 -2 3"},
                                                                    {40, "outside", "2"}});
    int rays = 0, textbook_wrong = 0;
    for (std::uint64_t i = 0; i < 200; ++i) {
        std::optional<TrackRay> ray =
            track_ray(m, {-3, -3, -3}, {3, 3, 3}, TrackFamily::backscatter, 5, i);
        if (!ray) continue;
        Model::Track exact = exact::track(m, ray->p, ray->u, 100);
        REQUIRE(exact.start.size() == 1);
        INFO("ray " << i);
        TrackerRun theirs = textbook_track(m, ray->p, ray->u, 100, mine);
        CHECK(theirs.start == exact.start[0]);
        CHECK(grade_track(exact, theirs).outcome == TrackOutcome::right);
        textbook_wrong += textbook_track(m, ray->p, ray->u, 100, TrackerDistances::correct).start !=
                          exact.start[0];
        ++rays;
    }
    CHECK(rays > 150);
    CHECK(textbook_wrong > 10);
    CHECK(calls > rays * 4);
    // A side it cannot give (a call that answers 0 here) is undecided: no cell found, lost.
    mine.sense = [](const Shape&, Vec3, Vec3) { return 0; };
    std::optional<TrackRay> ray = track_ray(m, {-3, -3, -3}, {3, 3, 3}, TrackFamily::generic, 5, 0);
    REQUIRE(ray);
    CHECK(textbook_track(m, ray->p, ray->u, 100, mine).start == -1);
}

TEST_CASE("cells: the CLI answers queries on a model file and refuses a bad one by name",
          "[cells]") {
    namespace fs = std::filesystem;
    fs::path dir = test::scratch("cells_cli");
    fs::path model = fs::path(LINEQUAD_SOURCE_DIR) / "examples/models/spheres.json";
    {
        std::ofstream q(dir / "q.jsonl");
        q << R"({"id":1,"p":[0,0,0],"u":[1,0,0],"cell":10})"
          << "\n"
          << R"({"id":2,"p":[0,0,0],"u":[0,0,-1]})"
          << "\n"
          << R"({"id":3,"p":[0,0,0],"u":[0,0,0]})"
          << "\n"
          << R"({"id":4,"p":[0,0],"u":[1,0,0]})"
          << "\n";
    }
    test::Ran r = test::program("cells '" + model.string() + "' q.jsonl", dir);
    CHECK(r.status == 1); // line 4 is malformed
    CHECK(r.out.find(R"({"id":1,"exit":"leaves","t":"0x1p+0","surfaces":[1],"entered":[20])") !=
          std::string::npos);
    CHECK(r.out.find(R"("steps":[{"t":"0x1p+0","surfaces":[1],"cells":[20])") != std::string::npos);
    CHECK(r.out.find(R"({"id":3,"solver":"cells","error")") != std::string::npos);
    CHECK(r.out.find("line 4: field \\\"p\\\": expected an array of 3 numbers") !=
          std::string::npos);

    std::ofstream(dir / "bad.json") << R"({"surfaces":[{"id":1,"shape":"plane","n":[1,0,0],"d":0}],
        "cells":[{"id":1,"region":"-1 -2"}]})";
    test::Ran bad = test::program("cells bad.json < /dev/null", dir);
    CHECK(bad.status == 2);
    CHECK(bad.err == "linequad cells: bad.json: cell 1: region \"-1 -2\" names surface 2, which "
                     "the model does not define\n");
    std::ofstream(dir / "typo.json") << R"({"surfaces":[{"id":1,"shape":"plane","n":[1,0,0]}],
        "cells":[]})";
    test::Ran typo = test::program("cells typo.json < /dev/null", dir);
    CHECK(typo.status == 2);
    CHECK(typo.err == "linequad cells: typo.json: surfaces[0]: field \"d\": missing\n");

    test::Ran audit = test::program("cells '" + model.string() + "' --audit --rays 200", dir);
    CHECK(audit.status == 0);
    CHECK(audit.out.rfind("# Tracking audit: ", 0) == 0);
    CHECK(audit.out.find("**The textbook tracker went wrong on ") != std::string::npos);
    test::Ran no_box = test::program("cells bad.json --audit", dir);
    CHECK(no_box.status == 2);
    // --out: report.md and the page made from it, each replay a command with a copy button.
    test::Ran out = test::program(
        "cells '" + model.string() + "' --audit --rays 100 --points 100 --out rep", dir);
    CHECK(out.status == 0);
    std::ifstream md(dir / "rep/report.md"), html(dir / "rep/report.html");
    std::string md_text((std::istreambuf_iterator<char>(md)), std::istreambuf_iterator<char>()),
        html_text((std::istreambuf_iterator<char>(html)), std::istreambuf_iterator<char>());
    CHECK(md_text.find("**linequad's cells went wrong on 0**") != std::string::npos);
    CHECK(md_text.find("| linequad cells | grazing | 100 | 100 |") != std::string::npos);
    CHECK(md_text.find("`echo '{\"id\":\"far_source/") != std::string::npos);
    CHECK(html_text.find("linequad (replay|cells) ") != std::string::npos);
    CHECK(html_text.find("<h1") != std::string::npos);
    // A plugin's distances and sides in the same loop, out of process: OpenMC's distances without
    // its 1e-12 rule (tests/plugins/transport_plugin.c) fail where the textbook's do on far
    // sources; its sense is OpenMC's, and without the 1e-12 band (`transport_unbanded`) it finds
    // the cell a backscattered particle is in, which the band mistakes (it takes the side u points
    // into) on a quarter of those rays.
    std::string plugin = std::string(" --plugin '") + LINEQUAD_TRANSPORT_PLUGIN + "'";
    test::Ran user = test::program("cells '" + model.string() +
                                       "' --audit --rays 300 --points 10 --solvers "
                                       "transport_textbook,transport_unbanded" +
                                       plugin,
                                   dir);
    CHECK(user.status == 0);
    // The by-family table's row: "rays | right | ..." after the tracker and the family.
    auto row_of = [&](const std::string& tracker, const std::string& family) {
        std::string head = "| " + tracker + " | " + family + " | ";
        std::size_t at = user.out.find(head);
        if (at == std::string::npos) return std::string();
        std::size_t from = at + head.size();
        return user.out.substr(from, user.out.find('\n', from) - from);
    };
    auto right_of = [&](const std::string& tracker, const std::string& family) {
        std::string row = row_of(tracker, family); // "300 | 224 | ..."
        std::size_t bar = row.find(" | ");
        return bar == std::string::npos ? -1 : std::atoi(row.c_str() + bar + 3);
    };
    const std::string banded = "textbook, transport\\_textbook distances and sides",
                      unbanded = "textbook, transport\\_unbanded distances and sides";
    CHECK(!row_of("textbook", "far\\_source").empty());
    CHECK(row_of(banded, "far\\_source") == row_of("textbook", "far\\_source"));
    CHECK(row_of(banded, "backscatter") == row_of("textbook", "backscatter"));
    CHECK(right_of("textbook", "backscatter") < 280);
    CHECK(right_of(unbanded, "backscatter") == 300);
    test::Ran own = test::program("cells '" + model.string() + "' --audit --solvers correct", dir);
    CHECK(own.status == 2);
    CHECK(own.err.find("'correct' is linequad's own") != std::string::npos);
    test::Ran cylinders =
        test::program("cells '" + model.string() + "' --audit --solvers textbook --plugin '" +
                          LINEQUAD_EXAMPLE_PLUGIN + "'",
                      dir);
    CHECK(cylinders.status == 2);
    CHECK(cylinders.err.find("does not take the model's quadrics") != std::string::npos);
}

TEST_CASE("cells: OpenMC's geometry.xml is read exactly, and what is not taken is named with its "
          "line",
          "[cells]") {
    namespace fs = std::filesystem;
    fs::path dir = test::scratch("cells_xml");
    fs::path model = fs::path(LINEQUAD_SOURCE_DIR) / "examples/models/pin_cell_openmc.xml";
    // Along +x from the pin's centre: the fuel's radius 0.375, the clad's 0.4375, the cell's
    // reflective side at 0.625, each exact (R^2 is a double for these radii).
    std::ofstream(dir / "q.jsonl") << R"({"id":1,"p":[0,0,0],"u":[1,0,0]})"
                                   << "\n";
    auto track_into = [](int outside) {
        return R"({"id":1,"start":[1],"start_undecided":[],"steps":[)"
               R"({"t":"0x1.8p-2","surfaces":[1],"cells":[2],"undecided":[]},)"
               R"({"t":"0x1.cp-2","surfaces":[2],"cells":[3],"undecided":[]},)"
               R"({"t":"0x1.4p-1","surfaces":[4],"cells":[)" +
               std::to_string(outside) + R"(],"undecided":[]}],"truncated":false})" + "\n";
    };
    test::Ran r = test::program("cells '" + model.string() + "' q.jsonl", dir);
    REQUIRE(r.status == 0);
    CHECK(r.out == track_into(4));
    test::Ran audit = test::program("cells '" + model.string() +
                                        "' --audit --rays 100 --box -0.625,-0.625,-1,0.625,0.625,1",
                                    dir);
    CHECK(audit.status == 0);
    // The same pin written as OpenMC users write it: a universe of fuel, clad and water filling
    // the lattice cell. Flattened, its cells are the universe's within the filling cell's
    // region: the same track, the universe's cells by their own ids.
    std::ofstream(dir / "universe.xml") << R"xml(<geometry>
  <cell id="1" universe="1" material="1" name="fuel" region="-1"/>
  <cell id="2" universe="1" material="2" name="clad" region="1 -2"/>
  <cell id="3" universe="1" material="3" name="water" region="2"/>
  <cell id="10" fill="1" name="pin" region="3 -4 5 -6 7 -8"/>
  <cell id="20" material="void" name="outside" region="~(3 -4 5 -6 7 -8)"/>
  <surface coeffs="0.0 0.0 0.375" id="1" type="z-cylinder"/>
  <surface coeffs="0.0 0.0 0.4375" id="2" type="z-cylinder"/>
  <surface coeffs="-0.625" id="3" type="x-plane"/>
  <surface coeffs="0.625" id="4" type="x-plane"/>
  <surface coeffs="-0.625" id="5" type="y-plane"/>
  <surface coeffs="0.625" id="6" type="y-plane"/>
  <surface coeffs="-1.0" id="7" type="z-plane"/>
  <surface coeffs="1.0" id="8" type="z-plane"/>
</geometry>)xml";
    test::Ran universe = test::program("cells universe.xml q.jsonl", dir);
    REQUIRE(universe.status == 0);
    CHECK(universe.out == track_into(20));
    // Every ray of every family tracks exactly through it as through the file written flat
    // (linequad's cells: the same rows; the textbook loop asks other surfaces of a cell, the
    // filling cell's too, and may differ).
    test::Ran flat_audit = test::program("cells '" + model.string() +
                                             "' --audit --rays 200 --points 500 --box "
                                             "-0.625,-0.625,-1,0.625,0.625,1",
                                         dir),
              universe_audit = test::program("cells universe.xml --audit --rays 200 --points 500 "
                                             "--box -0.625,-0.625,-1,0.625,0.625,1",
                                             dir);
    REQUIRE(universe_audit.status == 0);
    auto own_rows = [](const std::string& md) {
        std::string rows;
        for (std::size_t at = md.find("| linequad cells |"); at != std::string::npos;
             at = md.find("| linequad cells |", at + 1))
            rows += md.substr(at, md.find('\n', at) - at) + "\n";
        return rows;
    };
    CHECK(!own_rows(flat_audit.out).empty());
    CHECK(own_rows(universe_audit.out) == own_rows(flat_audit.out));

    struct Bad {
        const char* xml;
        const char* error;
    };
    const Bad bad[] = {
        {"<geometry>\n<surface id=\"1\" type=\"z-cone\" coeffs=\"0.1 0 0 0.5\"/>\n</geometry>",
         "line 2: surface 1 (z-cone): coeffs \"0.1 0 0 0.5\": its general-quadric coefficient K "
         "is not a double, and linequad poses a surface exactly, never rounded (such cones are "
         "not taken yet)"},
        {"<geometry>\n<surface id=\"2\" type=\"y-cylinder\" coeffs=\"0.5 0.25 "
         "-0.4572\"/>\n</geometry>",
         "line 2: surface 2 (y-cylinder): coeffs \"0.5 0.25 -0.4572\": the radius is not positive"},
        {"<geometry>\n\n<surface id=\"4\" type=\"x-torus\" coeffs=\"0 0 0 1 1 1\"/>\n</geometry>",
         "line 3: surface 4 (x-torus): a surface type linequad does not pose (it poses plane, "
         "x-/y-/z-plane, sphere, x-/y-/z-cylinder, x-/y-/z-cone and quadric)"},
        {"<geometry>\n<cell id=\"1\" fill=\"2\" region=\"-1\"/>\n</geometry>",
         "line 2: cell 1: fill 2: no cell is in that universe"},
        {"<geometry>\n<cell id=\"1\" universe=\"3\" region=\"-1\"/>\n</geometry>",
         "line 2: no cell is in the root universe (0)"},
        {"<geometry>\n<cell id=\"1\" material=\"1\"/>\n</geometry>",
         "line 2: cell 1: has no region (an infinite cell is not taken in the root universe)"},
        {"<geometry>\n<lattice id=\"3\"/>\n</geometry>",
         "line 2: <lattice> is not taken yet (linequad reads surfaces, cells and the universes "
         "that fill them)"},
        {"<geometry>\n<cell id=\"1\" fill=\"2\" region=\"-1\"/>\n"
         "<cell id=\"2\" universe=\"2\" fill=\"2\" region=\"-1\"/>\n</geometry>",
         "line 3: cell 2: fill 2: the universe contains itself"},
        {"<geometry>\n<cell id=\"1\" fill=\"2\" region=\"-1\"/>\n"
         "<cell id=\"2\" fill=\"2\" region=\"1\"/>\n<cell id=\"3\" universe=\"2\"/>\n"
         "</geometry>",
         "line 3: cell 2: fill 2: the universe fills another cell too (a universe placed more "
         "than once is not taken yet: its cells would need ids of their own)"},
        {"<geometry>\n<cell id=\"1\" fill=\"2\" region=\"-1\" translation=\"1 0 0\"/>\n"
         "</geometry>",
         "line 2: cell 1: translation is not taken yet (a universe fills a cell as it is)"},
        {"<geometry>\n<surface id=\"1\" type=\"z-plane\" coeffs=\"1 2\"/>\n</geometry>",
         "line 2: surface 1 (z-plane): coeffs \"1 2\": expected 1 coefficient"},
        {"<geometry>\n<surface id=\"x\" type=\"z-plane\" coeffs=\"1\"/>\n</geometry>",
         "line 2: surface with id \"x\": expected a positive integer id"},
        {"<geometry>\n<surface id=\"1\" type=\"plane\" coeffs=\"1 0 0 1\"/>\n"
         "<cell id=\"1\" region=\"-1 -2\"/>\n</geometry>",
         "cell 1: region \"-1 -2\" names surface 2, which the model does not define"},
    };
    for (const Bad& b : bad) {
        std::ofstream(dir / "bad.xml") << b.xml;
        test::Ran ran = test::program("cells bad.xml < /dev/null", dir);
        INFO(b.xml);
        CHECK(ran.status == 2);
        CHECK(ran.err == std::string("linequad cells: bad.xml: ") + b.error + "\n");
    }
    // Universes nested a thousand deep (each level's regions wrapped once more): refused at 64.
    {
        std::ofstream deep(dir / "deep.xml");
        deep << "<geometry>\n<surface id=\"1\" type=\"sphere\" coeffs=\"0 0 0 1\"/>\n";
        for (int u = 0; u < 1000; ++u)
            deep << "<cell id=\"" << u + 1 << "\" universe=\"" << u << "\" fill=\"" << u + 1
                 << "\" region=\"-1\"/>\n";
        deep << "</geometry>\n";
    }
    test::Ran deep = test::program("cells deep.xml < /dev/null", dir);
    CHECK(deep.status == 2);
    CHECK(deep.err.find("universes nested more than 64 deep") != std::string::npos);
}
