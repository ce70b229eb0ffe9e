// Solvers from outside linequad in the audit: posing a case the way a library takes it, the exact
// reference for nearest and first-entry answers, crashes caught, plugins loaded through the C ABI,
// and reports that say what was measured and what was not.
#include "support.hpp"

#include "linequad/audit.hpp"
#include "linequad/audit_solver.hpp"
#include "linequad/solvers.hpp"
#include "peers/peers.hpp"

#include <nlohmann/json.hpp>

#include <cfenv>
#include <cstdlib>

using namespace linequad;
using namespace linequad::test;
namespace fs = std::filesystem;

namespace {

Case case_of(const Shape& s, const Line& l, Precision p = Precision::binary64) {
    Case c;
    c.id = "\"t\"";
    c.shape = s;
    c.line = l;
    c.precision = p;
    return c;
}

const Cylinder closed_cylinder{{0, 0, 0}, {0, 0, 2}, 1, true, true};

// correct, answering what a library declares: its answers are then the exact reference's.
audit::ExternalSolver correct_as(audit::Answers answers, audit::Parametrisation p,
                                 audit::Surface surface) {
    audit::ExternalSolver e;
    e.name = "correct_as";
    e.answers = answers, e.parametrisation = p, e.surface = surface;
    Need need = answers == audit::Answers::nearest ? Need::nearest : Need::all;
    e.on<Cylinder>() = [need](const Cylinder& c, const Line& l) -> std::optional<Result> {
        return correct::intersect(c, l, {need, true});
    };
    return e;
}

} // namespace

TEST_CASE("a segment is posed so that from + v is exactly to", "[external]") {
    audit::ExternalSolver e;
    e.parametrisation = audit::Parametrisation::segment;
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(-1, 1);
    for (Precision p : {Precision::binary64, Precision::binary32})
        for (int i = 0; i < 2000; ++i) {
            double scale = std::ldexp(1.0, int(rng() % 40) - 20);
            Line l{{u(rng) * scale, u(rng), u(rng)},
                   {u(rng), u(rng) * scale, u(rng)},
                   Interval(u(rng), 1 + u(rng) * u(rng) + 1)};
            Case c = case_of(closed_cylinder, l, p);
            if (p == Precision::binary32) c.line = rounded_to_binary32(c.line);
            std::optional<Case> posed = audit::posed_for(e, c);
            REQUIRE(posed);
            const Line& q = posed->line;
            CHECK(q.range == Interval(Range::segment));
            for (int k = 0; k < 3; ++k) {
                double from = q.L0[k], to = q.L0[k] + q.v[k];
                // to - from and from + v are both exact: the library sees (from, to), the
                // reference solves (from, v).
                CHECK(to - q.v[k] == from);
                if (p == Precision::binary32) {
                    CHECK(double(float(from)) == from);
                    CHECK(double(float(q.v[k])) == q.v[k]);
                    CHECK(double(float(to)) == to);
                }
                // from and to are the range's ends, to within the rounding of the format.
                double want_from = c.line.L0[k] + c.line.range.t0 * c.line.v[k];
                double want_to = c.line.L0[k] + c.line.range.t1 * c.line.v[k];
                // Forming L(t) rounds once (half an ulp), the format's rounding and the Fast2Sum
                // move once more each (half an ulp of to): 1.5 ulps of the larger end, and an ulp
                // is at most 2^-52 (2^-23) of it; 2^-50 (2^-22) leaves a little room.
                double tol = (p == Precision::binary32 ? 0x1p-22 : 0x1p-50) *
                             std::max({std::fabs(want_from), std::fabs(want_to), 1e-300});
                CHECK(std::fabs(from - want_from) <= tol);
                CHECK(std::fabs(to - want_to) <= tol);
            }
        }
    // An unbounded range has no segment.
    CHECK_FALSE(audit::posed_for(e, case_of(closed_cylinder, {{0, 0, 0}, {1, 0, 0}, Range::ray})));
}

TEST_CASE("a unit direction is posed with the range as distances", "[external]") {
    audit::ExternalSolver e;
    e.parametrisation = audit::Parametrisation::unit_direction;
    Line l{{-3, 0, 1}, {0, 0, 4}, Range::segment};
    std::optional<Case> posed = audit::posed_for(e, case_of(closed_cylinder, l));
    REQUIRE(posed);
    CHECK(posed->line.v == Vec3{0, 0, 1});
    CHECK(posed->line.range == Interval(0, 4));
    CHECK(posed->line.L0 == l.L0);
}

TEST_CASE("surfaces are posed closed or infinite as the library has them", "[external]") {
    audit::ExternalSolver closed, infinite;
    closed.surface = audit::Surface::closed;
    infinite.surface = audit::Surface::infinite;
    Line l{{-3, 0, 1}, {1, 0, 0}};
    Cylinder open{{0, 0, 0}, {0, 0, 2}, 1};
    auto c = audit::posed_for(closed, case_of(open, l));
    REQUIRE(c);
    CHECK(std::get<Cylinder>(c->shape).caps);
    auto i = audit::posed_for(
        infinite, case_of(EllipticCone{{0, 0, -1}, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, l));
    REQUIRE(i);
    CHECK_FALSE(std::get<EllipticCone>(i->shape).finite);
    CHECK(std::get<EllipticCone>(i->shape).nappes == 2);
    // A closed solid cannot be made of an infinite surface.
    Cylinder endless = open;
    endless.finite = false;
    CHECK_FALSE(audit::posed_for(closed, case_of(endless, l)));
}

TEST_CASE("the first entry into a closed solid, decided exactly", "[external]") {
    using audit::Answers;
    // From outside: the entry at x = -1, t = 2.
    Result r = audit::reference_for(Answers::first_entry,
                                    case_of(closed_cylinder, {{-3, 0, 1}, {1, 0, 0}, Range::ray}));
    REQUIRE(r.count == 1);
    CHECK(r.hits[0].t == 2);
    // From inside: the line leaves at t = 1 and never enters again.
    Line inside{{0, 0, 1}, {1, 0, 0}, Range::ray};
    CHECK(audit::reference_for(Answers::first_entry, case_of(closed_cylinder, inside)).count == 0);
    // The nearest hit from inside is the exit.
    Result n = audit::reference_for(Answers::nearest, case_of(closed_cylinder, inside));
    REQUIRE(n.count == 1);
    CHECK(n.hits[0].t == 1);
    // Starting on the surface and going in: the entry is at t = 0 itself.
    Result on = audit::reference_for(Answers::first_entry,
                                     case_of(closed_cylinder, {{-1, 0, 1}, {1, 0, 0}, Range::ray}));
    REQUIRE(on.count == 1);
    CHECK(on.hits[0].t == 0);
    // Starting on the surface and going out: no entry.
    CHECK(audit::reference_for(Answers::first_entry,
                               case_of(closed_cylinder, {{-1, 0, 1}, {-1, 0, 0}, Range::ray}))
              .count == 0);
}

TEST_CASE("an external solver that answers exactly what it declares grades perfect", "[external]") {
    using namespace audit;
    std::vector<ExternalSolver> ext = {
        correct_as(Answers::all, Parametrisation::line, Surface::as_posed),
        correct_as(Answers::nearest, Parametrisation::unit_direction, Surface::closed),
        correct_as(Answers::nearest, Parametrisation::segment, Surface::infinite)};
    ext[1].name = "nearest_unit_closed", ext[2].name = "nearest_segment_infinite";
    Options o;
    o.cases_per_group = 300;
    o.families = {Family::generic, Family::near_tangent, Family::rim};
    o.shapes = {0};
    o.solvers = {"correct_as", "nearest_unit_closed", "nearest_segment_infinite"};
    Report r = run(o, ext);
    for (const std::string& name : o.solvers) {
        INFO(name);
        Row t = r.total(name);
        CHECK(t.cases > 0);
        CHECK(t.cases_mismatched == 0);
        CHECK(t.t_max == 0);
        CHECK(t.s_max == 0);
        CHECK(t.timed());
    }
    // The segment solver cannot take lines and rays: a third of the cases.
    CHECK(r.total("nearest_segment_infinite").unrepresented > 0);
    CHECK(r.external.at("nearest_unit_closed").answers == std::string("nearest hit"));
}

TEST_CASE("a solver that answers a chunk at a time is graded as one that answers a case",
          "[external]") {
    using namespace audit;
    ExternalSolver e;
    e.name = "chunks";
    e.answers = Answers::nearest;
    e.worker_shapes = 1u << 0; // the cylinder alone
    std::vector<std::size_t> sizes;
    e.chunk = [&](const std::vector<Case>& posed, std::vector<ExternalAnswer>& out) {
        sizes.push_back(posed.size());
        for (std::size_t j = 0; j < posed.size(); ++j)
            out[j].result =
                correct::intersect(posed[j].shape, posed[j].line, {Need::nearest, true});
        if (sizes.size() == 1) std::fesetround(FE_UPWARD); // left so: put back, and noted
    };
    Options o;
    o.cases_per_group = 300;
    o.families = {Family::generic, Family::near_tangent};
    o.shapes = {0, 4}; // the sphere is not its shape: not asked
    o.solvers = {"chunks"};
    o.threads = 1;
    Report r = run(o, {e});
    Row t = r.total("chunks");
    CHECK(t.cases == 1800);
    CHECK(t.cases_mismatched == 0);
    CHECK(t.t_max == 0);
    CHECK(sizes == std::vector<std::size_t>(6, 300)); // one call a group: 2 families, 3 ranges
    CHECK(std::fegetround() == FE_TONEAREST);
    REQUIRE(t.environment.size() == 1);
    CHECK(t.environment.begin()->second == 300); // the first chunk's cases
}

TEST_CASE("a solver that aborts is counted as crashed, and the run goes on", "[external]") {
    audit::ExternalSolver e;
    e.name = "aborts";
    e.on<Cylinder>() = [](const Cylinder& c, const Line& l) -> std::optional<Result> {
        if (c.r < 1) std::abort();
        return correct::intersect(c, l);
    };
    Result crashed = *e(Cylinder{{0, 0, 0}, {0, 0, 1}, 0.5}, Line{{-2, 0, 0.5}, {1, 0, 0}});
    CHECK(crashed.error_code == ErrorCode::foreign);
    CHECK(std::string(crashed.error_field) == "crashed (abort)");
    // The next call is answered as usual.
    Result fine = *e(Cylinder{{0, 0, 0}, {0, 0, 1}, 2}, Line{{-3, 0, 0.5}, {1, 0, 0}});
    CHECK(fine.count == 2);
    audit::Options o;
    o.cases_per_group = 50;
    o.families = {Family::generic};
    o.shapes = {0};
    o.solvers = {"aborts"};
    audit::Report r = audit::run(o, {e});
    audit::Row t = r.total("aborts");
    REQUIRE(t.foreign.count("crashed (abort)"));
    CHECK(t.foreign.at("crashed (abort)") == t.mismatches[audit::crashed]);
}

TEST_CASE("a results file's unknown error code is named, and p99 never exceeds max",
          "[external][cli]") {
    fs::path dir = scratch("unknown_code");
    std::ofstream(dir / "cases.jsonl")
        << R"({"id":1,"shape":"cylinder","C":[0,0,0],"H":[0,0,1],"r":1,"L0":[-2,0,0.5],"v":[1,0,0]})"
        << "\n"
        << R"({"id":2,"shape":"cylinder","C":[0,0,0],"H":[0,0,1],"r":1,"L0":[-2,0,0.5],"v":[1,0,0]})"
        << "\n"
        << R"({"id":3,"shape":"cylinder","C":[0,0,0],"H":[0,0,1],"r":1,"L0":[-2,0,0.5],"v":[1,0,0]})"
        << "\n";
    std::ofstream(dir / "results.jsonl")
        << R"({"id":3,"solver":"mine","error":"cannot","code":"unrepresented"})"
        << "\n"
        << R"({"id":1,"solver":"mine","error":"gave up","code":"E_TOO_CLOSE"})"
        << "\n"
        << R"({"id":2,"solver":"mine","hits":[{"t":"0x1.0000000000001p+0","kind":"cross"},{"t":3,"kind":"cross"}]})"
        << "\n";
    Ran ran = program("audit --cases-file cases.jsonl --results results.jsonl --out out", dir);
    REQUIRE(ran.status == 0);
    audit::Report r;
    std::string why;
    REQUIRE(audit::read_json((dir / "out" / "report.json").string(), &r, &why));
    audit::Row t = r.total("mine");
    CHECK(t.foreign.at("E_TOO_CLOSE") == 1);
    CHECK(t.t_max == 1);
    CHECK(t.t_quantile(0.99) <= double(t.t_max));
    CHECK(r.cases_count == 3);
    CHECK(t.unrepresented == 1); // as linequad solve writes it for an external solver
    CHECK(t.cases == 2);
    CHECK_FALSE(t.timed());
    std::string md = slurp(dir / "out" / "report.md");
    CHECK(md.find("'E\\_TOO\\_CLOSE' 1") != std::string::npos); // its name, escaped for markdown
    CHECK(md.find("(3 cases)") != std::string::npos);
    CHECK(md.find("| seed |") == std::string::npos);
    CHECK(md.find("pareto.svg") == std::string::npos); // nothing was timed
}

TEST_CASE("a cases file is solved by the solvers and keeps its families", "[external][cli]") {
    fs::path dir = scratch("cases_file_run");
    REQUIRE(program("cases --families near_tangent,rim --shapes cylinder --cases 20 > c.jsonl", dir)
                .status == 0);
    Ran ran =
        program("audit --cases-file c.jsonl --solvers correct,stable --out out --no-plots", dir);
    REQUIRE(ran.status == 0);
    audit::Report r;
    std::string why;
    REQUIRE(audit::read_json((dir / "out" / "report.json").string(), &r, &why));
    CHECK(r.families == std::vector<std::string>{"near_tangent", "rim"});
    CHECK(r.cases_count == 120);
    CHECK(r.total("correct").cases == 120);
    CHECK(r.total("correct").cases_mismatched == 0);
}

TEST_CASE("the example plugin is audited and replayed without rebuilding linequad",
          "[external][cli]") {
    fs::path dir = scratch("plugin");
    std::string plugin = LINEQUAD_EXAMPLE_PLUGIN;
    Ran ran = program("audit --plugin '" + plugin +
                          "' --solvers correct,textbook --families generic,near_tangent --shapes "
                          "cylinder --cases 100 --out out --no-plots",
                      dir);
    REQUIRE(ran.status == 0);
    audit::Report r;
    std::string why;
    REQUIRE(audit::read_json((dir / "out" / "report.json").string(), &r, &why));
    audit::Row t = r.total("textbook");
    // Two families, three ranges, 100 cases each; infinite cylinders it cannot represent.
    CHECK(t.cases + t.unrepresented == 600);
    CHECK(t.unrepresented < 100);
    CHECK(r.external.at("textbook").plugin == plugin);
    CHECK(r.external.at("textbook").answers == "nearest hit");
    // The school formula misses near tangency; on generic cylinders it is close.
    audit::Row generic;
    for (const auto& [key, row] : r.rows)
        if (key.solver == "textbook" && key.family == "generic") generic.merge(row);
    CHECK(generic.cases_mismatched < generic.cases / 20);
    CHECK(t.cases_mismatched > generic.cases_mismatched);
    // Its worst cases replay through the same plugin, named by its absolute path, quoted
    // (tests/test_worker.cpp replays every one of them).
    std::string md = slurp(dir / "out" / "report.md");
    CHECK(md.find("| linequad replay --plugin '" + fs::canonical(plugin).string() +
                  "' --solver 'textbook'") != std::string::npos);
    std::ofstream(dir / "one.jsonl")
        << R"({"id":"one","shape":"cylinder","C":[0,0,0],"H":[0,0,1],"r":1,"L0":[-2,0,0.5],"v":[1,0,0]})"
        << "\n";
    Ran solve = program("solve --plugin '" + plugin + "' --solver textbook one.jsonl", dir);
    REQUIRE(solve.status == 0);
    CHECK(solve.out.find(R"("t":"0x1p+0")") != std::string::npos);
    // Caps it cannot represent.
    std::ofstream(dir / "capped.jsonl")
        << R"({"id":"c","shape":"cylinder","C":[0,0,0],"H":[0,0,1],"r":1,"caps":true,"L0":[-2,0,0.5],"v":[1,0,0]})"
        << "\n";
    Ran capped = program("solve --plugin '" + plugin + "' --solver textbook capped.jsonl", dir);
    CHECK(capped.out.find("unrepresented") != std::string::npos);
}

TEST_CASE("a plugin that is not one is refused by name", "[external][cli]") {
    fs::path dir = scratch("bad_plugin");
    std::ofstream(dir / "not.so") << "not a shared library\n";
    Ran ran = program("audit --plugin not.so --cases 1 --out out", dir);
    CHECK(ran.status == 2);
    CHECK(ran.err.find("not.so: cannot load it") != std::string::npos);
    Ran unknown = program("audit --solvers nosuch --cases 1 --out out", dir);
    CHECK(unknown.status == 2);
    CHECK(unknown.err.find("no solver named 'nosuch'") != std::string::npos);
}

TEST_CASE("the peer libraries built in are audited through their adapters", "[external][peers]") {
    const std::vector<audit::ExternalSolver>& peers = linequad::peers::solvers();
    if (peers.empty()) return; // none of their packages is installed
    audit::Options o;
    o.cases_per_group = 100;
    o.families = {Family::generic, Family::near_tangent, Family::rim};
    o.frames = Frames::axis;
    for (const audit::ExternalSolver& p : peers)
        o.solvers.push_back(p.name);
    audit::Report r = audit::run(o, peers);
    for (const audit::ExternalSolver& p : peers) {
        INFO(p.name);
        audit::Row t = r.total(p.name), generic, generic_plane;
        for (const auto& [key, row] : r.rows)
            if (key.solver == p.name && key.family == "generic")
                (key.shape == "plane" ? generic_plane : generic).merge(row);
        // OCCT's gp_Pln normalises n, which rounds: a line lying exactly in the plane may be
        // found off it, and nothing else goes wrong on generic planes.
        std::uint64_t on_surface = generic_plane.mismatches[audit::on_surface_missed];
        CHECK(generic_plane.cases_mismatched == on_surface);
        CHECK(t.cases > 0);
        CHECK(t.foreign.empty()); // no crash, no error of their own on these families
        // The adapters' mappings are exact enough that the double libraries classify generic
        // cases as the oracle does (Bullet's collision margin aside); a wrong frame, parameter
        // or range would show here at once.
        if (p.name == "occt" || p.name == "ode") CHECK(generic.cases_mismatched == 0);
    }
}

TEST_CASE("a report from before scene errors reads, and writes back a fixed point", "[external]") {
    audit::Options o;
    o.cases_per_group = 4;
    o.families = {Family::generic};
    o.shapes = {0};
    o.solvers = {"correct"};
    auto j = nlohmann::json::parse(audit::to_json(audit::run(o)));
    for (auto& row : j["rows"])
        row.erase("scene_ulps");
    audit::Report old_report, again;
    std::string why;
    REQUIRE(audit::from_json(j.dump(), &old_report, &why));
    CHECK(old_report.total("correct").s_error.total() == 0);
    std::string once = audit::to_json(old_report);
    REQUIRE(audit::from_json(once, &again, &why));
    CHECK(audit::to_json(again) == once);
    // A scene histogram holding more values than the row graded is still refused.
    auto bad = nlohmann::json::parse(audit::to_json(audit::run(o)));
    bad["rows"][0]["scene_ulps"]["histogram"] = {{0, 1000}};
    CHECK_FALSE(audit::from_json(bad.dump(), &again, &why));
    CHECK(why.find("scene_ulps.histogram") != std::string::npos);
}
