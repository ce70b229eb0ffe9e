// Scenes in the case format and the scene audit: records round-trip and malformed ones are named;
// every family's contacts are exact; correct scenes equal the oracle on every family; scenes
// written and read back grade alike; linequad solve answers scene lines.
#include "support.hpp"

#include "linequad/exact.hpp"
#include "linequad/scene_audit.hpp"

#include <nlohmann/json.hpp>

#include <fstream>

using namespace linequad;
using namespace linequad::test;
namespace fs = std::filesystem;

TEST_CASE("scene format: records round-trip and malformed ones name the field", "[case_io]") {
    audit::SceneCase sc = audit::make_scene(audit::SceneFamily::coaxial, 5, 3, 8);
    Record r;
    std::string why;
    REQUIRE(parse_record(format_scene(sc.header), &r, &why));
    CHECK(r.kind == RecordKind::scene);
    CHECK((r.scene.id == sc.header.id && r.scene.family == "coaxial" && r.scene.k == sc.header.k));
    for (const SceneShape& s : sc.shapes) {
        REQUIRE(parse_record(format_scene_shape(s), &r, &why));
        CHECK(r.kind == RecordKind::scene_shape);
        CHECK(r.shape.id == s.id);
        CHECK(format_scene_shape(r.shape) == format_scene_shape(s)); // every bit
    }
    for (const SceneLine& l : sc.lines) {
        REQUIRE(parse_record(format_scene_line(l), &r, &why));
        CHECK(r.kind == RecordKind::scene_line);
        CHECK(format_scene_line(r.line) == format_scene_line(l));
    }
    REQUIRE(parse_record(
        R"({"id":9,"shape":"cylinder","C":[0,0,0],"H":[0,0,1],"r":1,"L0":[2,0,0],"v":[-1,0,0]})",
        &r, &why));
    CHECK(r.kind == RecordKind::single_case);

    struct Bad {
        const char* line;
        RecordKind meant;
        const char* says;
    } bad[] = {
        {R"({"scene":1,"shapes":[]})", RecordKind::scene,
         "field \"shapes\": not a field of a scene"},
        {R"({"scene":1,"k":0.5})", RecordKind::scene, "field \"k\""},
        {R"({"shape_id":"a","shape":"cylinder","C":[0,0,0],"H":[0,0,1]})", RecordKind::scene_shape,
         "field \"r\": missing"},
        {R"({"shape_id":"a","shape":"cylinder","C":[0,0,0],"H":[0,0,1],"r":1,"L0":[0,0,0]})",
         RecordKind::scene_shape, "field \"L0\": not a field of a scene's cylinder"},
        {R"({"id":1,"L0":[0,0,0]})", RecordKind::scene_line, "field \"v\": missing"},
        {R"({"id":1,"L0":[0,0,0],"v":[1,0,0],"r":1})", RecordKind::scene_line,
         "field \"r\": not a field of a scene's line"},
        {R"({"id":1,"L0":[0,0,0],)", RecordKind::unreadable, "not valid JSON"},
    };
    for (const Bad& b : bad) {
        INFO(b.line);
        CHECK_FALSE(parse_record(b.line, &r, &why));
        CHECK(r.kind == b.meant);
        CHECK_THAT(why, Catch::Contains(b.says));
    }
    // Where single cases are read, a scene's record is named as one.
    Case c;
    CHECK_FALSE(parse_case(R"({"scene":"s"})", &c, &why));
    CHECK_THAT(why, Catch::Contains("a scene's record"));
}

TEST_CASE("scene families: the contacts they are built on are exact", "[scene_audit]") {
    // touching: every line but the generic fifth goes through a contact of two shapes (across it
    // or tangent to both there), so the oracle must find two shapes at exactly one t. Integer
    // rotations and dyadic radii make that so even 2^39 from the origin.
    for (std::uint64_t i = 0; i < 28; ++i) {
        audit::SceneCase sc = audit::make_scene(audit::SceneFamily::touching, 1, i, 10);
        std::vector<Shape> shapes = sc.shape_list();
        for (std::size_t j = 0; j < sc.lines.size(); ++j) {
            if (j % 5 == 4) continue;
            INFO("scene " << sc.header.id << " line " << j);
            SceneAnswer a;
            exact::intersect(shapes, sc.lines[j].line, {Need::all, false}, a);
            REQUIRE(a.ok());
            CHECK(std::any_of(a.hits.begin(), a.hits.end(),
                              [](const SceneHit& h) { return h.tied; }));
        }
    }
    // shared_rim: along the axis, the line crosses the two discs A and B share at one t.
    for (std::uint64_t i = 0; i < 8; ++i) {
        audit::SceneCase sc = audit::make_scene(audit::SceneFamily::shared_rim, 1, i, 8);
        std::vector<Shape> shapes = sc.shape_list();
        for (std::size_t j = 2; j < sc.lines.size(); j += 4) {
            INFO("scene " << sc.header.id << " line " << j);
            SceneAnswer a;
            exact::intersect(shapes, sc.lines[j].line, {Need::all, false}, a);
            REQUIRE(a.ok());
            CHECK(std::count_if(a.hits.begin(), a.hits.end(),
                                [](const SceneHit& h) { return h.tied; }) >= 2);
        }
    }
}

TEST_CASE("scene audit: correct scenes equal the oracle on every family", "[scene_audit]") {
    audit::SceneAuditOptions o;
    o.scenes = 16, o.lines = 12, o.seed = 7;
    std::vector<audit::SceneRow> rows = audit::run_scene_audit(o);
    REQUIRE(rows.size() == std::size_t(audit::scene_family_count));
    for (const audit::SceneRow& row : rows) {
        INFO(row.family);
        const audit::SceneTally& t = row.tally;
        CHECK(t.scenes == 16);
        CHECK(t.lines > 16 * 6); // the spawned families lose a line where the parent has no hit
        CHECK(t.correct_differs_all == 0);
        CHECK(t.correct_differs_nearest == 0);
        CHECK(t.correct_refused == 0);
        CHECK(t.embree_differs == 0); // Embree's traversal, where it is built in
        CHECK(t.hits > t.lines);      // the lines are aimed at the shapes
        if (row.family != "far_grid") {
            // Built on contacts: ties, and the exact comparisons that decide them.
            CHECK(t.tie_lines > 0);
            CHECK(t.refined_all > 0);
        }
    }
}

TEST_CASE("scene audit: scenes written and read back grade alike", "[scene_audit]") {
    fs::path dir = scratch("scene_audit_round_trip");
    audit::SceneAuditOptions o;
    o.scenes = 4, o.lines = 6, o.seed = 3;
    o.families = {audit::SceneFamily::nested, audit::SceneFamily::spawned};
    o.write_cases = (dir / "scenes.jsonl").string();
    std::vector<audit::SceneRow> generated = audit::run_scene_audit(o);
    audit::SceneAuditOptions again;
    again.cases_file = o.write_cases;
    std::vector<audit::SceneRow> read = audit::run_scene_audit(again);
    REQUIRE(read.size() == generated.size());
    for (std::size_t i = 0; i < read.size(); ++i) {
        const audit::SceneTally &a = generated[i].tally, &b = read[i].tally;
        CHECK(read[i].family == generated[i].family);
        CHECK((a.scenes == b.scenes && a.shapes == b.shapes && a.lines == b.lines));
        CHECK((a.hits == b.hits && a.tie_lines == b.tie_lines && a.solved == b.solved));
        CHECK((a.refined_all == b.refined_all && a.comparisons_all == b.comparisons_all));
        CHECK((a.stable_wrong == b.stable_wrong && a.stable_missed == b.stable_missed &&
               a.stable_misordered == b.stable_misordered &&
               a.stable_max_ulps == b.stable_max_ulps));
    }
    // A file that breaks the format is refused by its line.
    std::ofstream(dir / "bad.jsonl") << format_scene({"\"s\"", "", 0}) << "\n"
                                     << R"({"id":1,"L0":[0,0,0],"v":[1,0,0]})"
                                     << "\n"
                                     << R"({"shape_id":"a","shape":"cylinder","C":[0,0,0],)"
                                     << R"("H":[0,0,1],"r":1})"
                                     << "\n";
    again.cases_file = (dir / "bad.jsonl").string();
    CHECK_THROWS_WITH(audit::run_scene_audit(again),
                      Catch::Contains("line 3") && Catch::Contains("after the scene's lines"));
    fs::remove_all(dir);
}

TEST_CASE("cli: solve answers a scene's lines and a broken shape breaks its scene", "[cli]") {
    fs::path dir = scratch("cli_scenes");
    std::ofstream(dir / "scenes.jsonl")
        << R"({"scene":"pair"})"
        << "\n"
        << R"({"shape_id":"A","shape":"cylinder","C":[0,0,0],"H":[0,0,2],"r":1})"
        << "\n"
        << R"({"shape_id":"B","shape":"cylinder","C":[2,0,0],"H":[2,0,2],"r":1})"
        << "\n"
        << R"({"id":1,"L0":[-3,0,1],"v":[1,0,0]})"
        << "\n"
        << R"({"scene":"broken"})"
        << "\n"
        << R"({"shape_id":"A","shape":"cylinder","C":[0,0,0],"H":[0,0,2],"r":"one"})"
        << "\n"
        << R"({"id":2,"L0":[-3,0,1],"v":[1,0,0]})"
        << "\n";
    Ran ran = program("solve --solver correct,exact,seed scenes.jsonl", dir);
    CHECK(ran.status == 1); // the malformed shape
    std::vector<nlohmann::json> out;
    std::istringstream in(ran.out);
    for (std::string l; std::getline(in, l);)
        out.push_back(nlohmann::json::parse(l));
    REQUIRE(out.size() == 9); // line 1 by three solvers; the bad shape; line 2
    for (int s = 0; s < 2; ++s) {
        const nlohmann::json& a = out[std::size_t(s)];
        CHECK(a["scene"] == "pair");
        REQUIRE(a["hits"].size() == 4);
        // A's exit and B's entry at x = 1: exactly one t, tied.
        CHECK((a["hits"][1]["shape"] == "A" && a["hits"][2]["shape"] == "B"));
        CHECK((a["hits"][1]["tied"] == true && a["hits"][2]["tied"] == true));
        CHECK(a["hits"][1]["t"] == "0x1p+2");
    }
    CHECK(out[2]["code"] == "scene_unsupported");
    CHECK(out[3]["code"] == "malformed_case");
    for (int s = 6; s < 9; ++s) {
        CHECK(out[std::size_t(s)]["code"] == "malformed_scene");
        CHECK_THAT(out[std::size_t(s)]["error"].get<std::string>(),
                   Catch::Contains("line 6") && Catch::Contains("field \"r\""));
    }
    fs::remove_all(dir);
}
