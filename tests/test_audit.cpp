// The audit: deterministic families, exact shard merging, report round trips, grading of
// result files, malformed input and interruption.
#include "support.hpp"

#include "run/ordered_pool.hpp"

#include "linequad/audit.hpp"
#include "linequad/exact.hpp"

#include <atomic>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <thread>

using namespace linequad;
using namespace linequad::test;
namespace fs = std::filesystem;

namespace {

// The parts of a row that must merge exactly (timings and the choice among equally bad worst
// cases may differ).
void require_same(const audit::Row& a, const audit::Row& b) {
    CHECK(a.cases == b.cases);
    CHECK(a.graded_roots == b.graded_roots);
    CHECK(a.graded_coords == b.graded_coords);
    CHECK(a.cases_mismatched == b.cases_mismatched);
    CHECK(a.mismatches == b.mismatches);
    CHECK(a.t_error.count == b.t_error.count);
    CHECK(a.p_error.count == b.p_error.count);
    CHECK(a.t_max == b.t_max);
    CHECK(a.p_max == b.p_max);
    CHECK(a.t_sum == b.t_sum);
}

audit::Options small(std::uint64_t cases) {
    audit::Options o;
    o.cases_per_group = cases;
    o.seed = 5;
    o.plots = false;
    return o;
}

} // namespace

TEST_CASE("families: every case is valid, reproducible alone, and exercises its family",
          "[audit]") {
    for (int f = 0; f < family_count; ++f)
        for (int shape = 0; shape < shape_kinds; ++shape) {
            if (!family_applies(Family(f), shape)) continue;
            int hits = 0;
            for (std::uint64_t i = 0; i < 200; ++i) {
                Case c = make_case(Family(f), shape, Range::line, 9, i);
                INFO(format_case(c));
                // Only the degenerate family may produce frames that are exactly singular.
                ErrorCode v = validate(c.shape, c.line).code;
                if (Family(f) == Family::degenerate_frame)
                    REQUIRE((v == ErrorCode::none || v == ErrorCode::singular_frame));
                else
                    REQUIRE(v == ErrorCode::none);
                REQUIRE(format_case(make_case(Family(f), shape, Range::line, 9, i)) ==
                        format_case(c));
                hits += exact::intersect(c.shape, c.line).any_hit();
            }
            INFO(family_name(Family(f)) << " shape " << shape);
            // The families aim at the shapes (lines exactly along the axis meet only the
            // lateral surface they lie on, so that family hits less often).
            CHECK(hits > (Family(f) == Family::axis_parallel ? 20 : 40));
        }
    // Exactly tangent lines (near_tangent, k = 0) are tangent for the oracle.
    int tangent = 0;
    for (std::uint64_t i = 0; i < 61 * 20; i += 61)
        for (int shape = 0; shape < shape_kinds; ++shape) {
            Result r =
                exact::intersect(make_case(Family::near_tangent, shape, Range::line, 3, i).shape,
                                 make_case(Family::near_tangent, shape, Range::line, 3, i).line);
            tangent += r.count == 1 && r.hits[0].kind == HitKind::tangent;
        }
    CHECK(tangent >= 55); // 60 lines; a few may touch outside the finite extent
}

TEST_CASE("audit: the worker pool does every item once and in order and stops when told",
          "[audit]") {
    // Many tiny items on more workers than cores: the workers race for every item.
    for (int threads : {1, 2, 8}) {
        INFO(threads << " threads");
        constexpr std::size_t n = 20000;
        std::vector<std::size_t> seen;
        audit::in_order<std::size_t>(
            n, threads, [](std::size_t i) { return 3 * i; },
            [&](std::size_t i, std::size_t&& r) {
                REQUIRE(r == 3 * i);
                seen.push_back(i);
            },
            [] { return false; });
        REQUIRE(seen.size() == n);
        for (std::size_t i = 0; i < n; ++i)
            REQUIRE(seen[i] == i);
        // A stop: what is consumed is a prefix of the items, each once.
        std::atomic<std::size_t> made{0};
        seen.clear();
        audit::in_order<std::size_t>(
            n, threads, [&](std::size_t i) { return ++made, i; },
            [&](std::size_t i, std::size_t&&) { seen.push_back(i); },
            [&] { return made.load() >= 100; });
        REQUIRE(seen.size() < n);
        for (std::size_t i = 0; i < seen.size(); ++i)
            REQUIRE(seen[i] == i);
        // An exception in an item stops the pool and reaches the caller.
        CHECK_THROWS_AS(audit::in_order<std::size_t>(
                            n, threads,
                            [](std::size_t i) -> std::size_t {
                                if (i == 777) throw std::runtime_error("item 777");
                                return i;
                            },
                            [](std::size_t, std::size_t&&) {}, [] { return false; }),
                        std::runtime_error);
    }
}

TEST_CASE("audit: the report is the same for any number of threads (timings aside)", "[audit]") {
    // Three chunks per family, shape, range and precision (the last one partial): more chunks
    // than workers, finishing out of order, whatever the chunk size.
    audit::Options o = small(2 * audit::chunk_size + audit::chunk_size / 2);
    o.families = {Family::generic, Family::near_tangent, Family::scale};
    o.threads = 1;
    audit::Report one = audit::run(o);
    auto without_timings = [](audit::Report r) {
        r.seconds = 0, r.date.clear(), r.run.clear();
        for (auto& [key, row] : r.rows)
            row.ns = {};
        return audit::to_json(r);
    };
    for (int threads : {2, 3, 8}) {
        INFO(threads << " threads");
        o.threads = threads;
        audit::Report many = audit::run(o);
        CHECK(many.complete());
        CHECK(without_timings(many) == without_timings(one));
    }
}

TEST_CASE("audit: shards merge into exactly the unsharded report", "[audit]") {
    audit::Options whole = small(60);
    whole.families = {Family::generic, Family::near_tangent, Family::apex};
    audit::Report full = audit::run(whole);
    audit::Report merged;
    for (int k = 0; k < 3; ++k) {
        audit::Options part = whole;
        part.shard = k, part.shards = 3;
        audit::Report r = audit::run(part);
        // Through the JSON format, as shards from other machines arrive.
        fs::path dir = scratch("shard" + std::to_string(k));
        audit::write_json(r, (dir / "report.json").string());
        audit::Report back;
        std::string why;
        REQUIRE(audit::read_json((dir / "report.json").string(), &back, &why));
        if (k == 0) {
            merged = back;
        } else {
            REQUIRE(audit::unmergeable(merged, back).empty());
            merged.merge(back);
        }
        fs::remove_all(dir);
    }
    REQUIRE(merged.rows.size() == full.rows.size());
    for (const auto& [key, row] : full.rows) {
        INFO(key.name());
        require_same(merged.rows.at(key), row);
    }
    CHECK(merged.complete());
    for (const auto& [key, points] : full.curves)
        for (const auto& [k, p] : points) {
            CHECK(merged.curves.at(key).at(k).cases == p.cases);
            CHECK(merged.curves.at(key).at(k).t_error.count == p.t_error.count);
        }
}

TEST_CASE("families: --frames builds circular or axis-aligned frames, --shapes the shapes asked",
          "[audit]") {
    // Every family's cases for the elliptic shapes and the frustum, on circular and on axis
    // frames: the elliptic shapes' a and b orthogonal to c and of one length, and with axis
    // frames along a coordinate axis. Random frames are built by rounded normalisation, so
    // orthogonality and equal lengths hold to a few ulps of the products: 2^-40 of |a||c| is
    // far above that and far below any oblique frame the families build (degenerate_frame's
    // tilts on circular frames are at most 2^-k of c, which keeps them round). The cone's axis
    // H - C is a difference of rounded positions (the scale family moves them up to 2^50 away):
    // each coordinate within 2 ulps of the largest position, so 2^-40 of |a| times that too.
    auto near_zero = [](double x, double scale) { return std::fabs(x) <= 0x1p-40 * scale; };
    int checked = 0;
    for (Frames frames : {Frames::circular, Frames::axis})
        for (int f = 0; f < family_count; ++f)
            for (int shape = 1; shape < shape_kinds; ++shape) {
                if (!family_applies(Family(f), shape)) continue;
                for (std::uint64_t i = 0; i < 30; ++i) {
                    Case c = make_case(Family(f), shape, Range::line, 3, i, frames);
                    INFO(format_case(c));
                    REQUIRE(c.id.find(std::string("/") + frames_name(frames)) != std::string::npos);
                    if (std::holds_alternative<Sphere>(c.shape)) continue; // round by definition
                    // The unbounded surfaces have no semi-axes: their frames are integer rotations.
                    if (std::holds_alternative<Plane>(c.shape) ||
                        std::holds_alternative<Quadric>(c.shape))
                        continue;
                    if (const auto* k = std::get_if<Capsule>(&c.shape)) { // round by definition
                        Vec3 h = k->H - k->C;
                        int along = (h.x != 0) + (h.y != 0) + (h.z != 0);
                        if (frames == Frames::axis) CHECK(along == 1);
                        ++checked;
                        continue;
                    }
                    if (const auto* e = std::get_if<Ellipsoid>(&c.shape)) { // a spheroid
                        CHECK(near_zero(dot(e->a, e->c), norm(e->a) * norm(e->c)));
                        CHECK(near_zero(dot(e->b, e->c), norm(e->b) * norm(e->c)));
                        CHECK(near_zero(dot(e->a, e->b), norm(e->a) * norm(e->b)));
                        ++checked;
                        continue;
                    }
                    Vec3 a{}, b{}, axis{};
                    double position = 0; // the largest coordinate the axis was rounded from
                    if (const auto* e = std::get_if<EllipticCylinder>(&c.shape))
                        a = e->a, b = e->b, axis = e->c;
                    else if (const auto* k = std::get_if<EllipticCone>(&c.shape))
                        a = k->a, b = k->b, axis = k->H - k->C,
                        position = std::fmax(max_abs(k->H), max_abs(k->C));
                    else
                        axis = std::get<Frustum>(c.shape).C1 - std::get<Frustum>(c.shape).C0;
                    if (a != Vec3{}) {
                        double scale = norm(a) * (norm(axis) + position);
                        CHECK(near_zero(dot(a, axis), scale));
                        CHECK(near_zero(dot(b, axis), scale));
                        CHECK(near_zero(dot(a, b), norm(a) * norm(b)));
                        CHECK(near_zero(norm(a) - norm(b), norm(a)));
                    }
                    if (frames == Frames::axis) {
                        int zeros = (axis.x == 0) + (axis.y == 0) + (axis.z == 0);
                        CHECK(zeros == 2);
                    }
                    ++checked;
                }
            }
    CHECK(checked > 1000);

    // The audit builds only the shapes asked, on the frames asked, and says so.
    audit::Options o = small(4);
    o.families = {Family::generic, Family::apex};
    o.shapes = {3};
    o.frames = Frames::axis;
    audit::Report r = audit::run(o);
    CHECK(r.shapes == std::vector<std::string>{"frustum"});
    CHECK(r.frames == "axis");
    for (const auto& [key, row] : r.rows) {
        CHECK(key.shape == "frustum");
        CHECK(row.cases == 12); // 4 cases x 3 ranges
    }
    fs::path dir = scratch("frames");
    audit::write_json(r, (dir / "report.json").string());
    audit::Report back;
    std::string why;
    REQUIRE(audit::read_json((dir / "report.json").string(), &back, &why));
    CHECK(back.frames == "axis");
    back.frames = "circular";
    back.shards_included = {1};
    CHECK(audit::unmergeable(r, back).rfind("frames differ", 0) == 0);
    fs::remove_all(dir);
}

TEST_CASE("audit: grading a results file gives the in-process verdict", "[audit]") {
    fs::path dir = scratch("results");
    audit::Options o = small(40);
    o.families = {Family::near_tangent, Family::axis_parallel};
    o.solvers = {"stable"};
    audit::Report direct = audit::run(o);
    {
        std::ofstream cases(dir / "cases.jsonl"), results(dir / "results.jsonl");
        audit::for_each_case(o, [&](const Case& c) {
            cases << format_case(c) << "\n";
            results << format_result(c.id, "stable", run("stable", c.shape, c.line)) << "\n";
        });
    }
    audit::Options g = o;
    g.cases_file = (dir / "cases.jsonl").string();
    g.results_file = (dir / "results.jsonl").string();
    audit::Report graded = audit::run(g);
    for (const auto& [key, row] : direct.rows) {
        INFO(key.name());
        REQUIRE(graded.rows.count(key));
        require_same(graded.rows.at(key), row);
    }
    fs::remove_all(dir);
}

TEST_CASE("audit: the batch point is graded on every case as stable is", "[audit]") {
    audit::Options o = small(60);
    o.solvers = {"stable", audit::batch_name};
    audit::Report r = audit::run(o);
    REQUIRE(r.solvers == std::vector<std::string>{"stable", "batch"});
    int rows = 0;
    for (const auto& [key, row] : r.rows) {
        if (key.solver != audit::batch_name) continue;
        audit::RowKey stable{key.family, key.shape, "stable"};
        INFO(key.name());
        REQUIRE(r.rows.count(stable));
        // Bit for bit the same results, so the same grades; and a time for every chunk.
        require_same(row, r.rows.at(stable));
        auto chunks = [](const audit::TimeHistogram& h) {
            return std::accumulate(h.count.begin(), h.count.end(), std::uint64_t(0));
        };
        CHECK(chunks(row.ns) == chunks(r.rows.at(stable).ns));
        CHECK(row.ns.median() > 0);
        ++rows;
    }
    CHECK(rows == int(r.rows.size() / 2));
}

TEST_CASE("audit: unanswered and malformed answers count as refused, malformed cases are named",
          "[audit]") {
    fs::path dir = scratch("malformed");
    audit::Options o = small(5);
    o.families = {Family::generic};
    {
        std::ofstream cases(dir / "cases.jsonl"), results(dir / "results.jsonl");
        int n = 0;
        audit::for_each_case(o, [&](const Case& c) {
            cases << format_case(c) << "\n";
            if (n == 0)
                results << format_result(c.id, "mine", run("stable", c.shape, c.line)) << "\n";
            if (n == 1) // names its case, but its hit has no t: graded as refused
                results << "{\"id\":" << c.id << ",\"solver\":\"mine\",\"hits\":[{}]}\n";
            ++n;
        });
    }
    o.cases_file = (dir / "cases.jsonl").string();
    o.results_file = (dir / "results.jsonl").string();
    audit::Report r = audit::run(o);
    audit::Row t = r.total("mine");
    std::uint64_t cases = 5 * shape_kinds * 3; // 5 cases x every shape x 3 ranges
    CHECK(t.cases == cases);
    CHECK(t.mismatches[audit::refused] == cases - 1);

    std::ofstream(dir / "bad_cases.jsonl")
        << format_case(make_case(Family::generic, 0, Range::line, 1, 0))
        << "\n{\"id\":2,\"shape\":\"cylinder\"}\n";
    o.cases_file = (dir / "bad_cases.jsonl").string();
    try {
        audit::run(o);
        FAIL("a malformed cases file must be refused");
    } catch (const std::exception& e) {
        CHECK_THAT(e.what(), Catch::Contains("line 2") && Catch::Contains("field \"L0\": missing"));
    }
    fs::remove_all(dir);
}

TEST_CASE("audit: a stopped run keeps what it measured", "[audit]") {
    fs::path dir = scratch("interrupted");
    audit::Options o = small(200000); // far more than can run before the stop
    o.out_dir = dir.string();
    std::thread stopper([] {
        std::this_thread::sleep_for(std::chrono::milliseconds(300));
        std::raise(SIGINT);
    });
    audit::Report r = audit::run(o);
    stopper.join();
    CHECK(r.status == audit::Status::stopped);
    CHECK_FALSE(r.complete());
    audit::Report saved;
    std::string why;
    REQUIRE(audit::read_json((dir / "report.json").string(), &saved, &why));
    CHECK(saved.status == audit::Status::stopped);
    CHECK(saved.total("stable").cases > 0);
    CHECK(fs::exists(dir / "report.md"));
    fs::remove_all(dir);
}

TEST_CASE("audit: ulps and histograms", "[audit]") {
    CHECK(audit::ulps_between(1.0, 1.0) == 0);
    CHECK(audit::ulps_between(1.0, std::nextafter(1.0, 2.0)) == 1);
    CHECK(audit::ulps_between(-0.0, 0.0) == 0);
    CHECK(audit::ulps_between(-0x1p-1074, 0x1p-1074) == 2);
    audit::Histogram h;
    for (int i = 0; i < 99; ++i)
        h.add(1);
    h.add(1000);
    CHECK(h.quantile(0.5) == 1);
    CHECK(h.quantile(0.99) == 1);
    CHECK(h.quantile(1.0) >= 1000);
    CHECK(h.quantile(1.0) <= 1000 * 1.19); // quarter-octave buckets above 16
}
