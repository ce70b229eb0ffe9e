// libFuzzer target: compare/'s readers and writers. Whatever the bytes, nothing crashes, and what
// is read is written back faithfully:
// - JSON: parse -> write -> parse gives the same value, and writing it again the same text;
// - a case: parse -> format -> parse gives the same case, bit for bit (the formatted text of
//   every double is exact, so equal text is equal bits); a scene's record (header, shape, line)
//   likewise, and of the same kind;
// - a result line and a report: format(parse(x)) is a fixed point of format(parse(.));
// - a scene file (many lines): read, written and read again, it is written the same;
// - a region and a model file: refused with a reason, or read into a model that answers.
// A failure aborts with the input and what broke.
#include "linequad/audit.hpp"
#include "linequad/case_io.hpp"
#include "linequad/cells.hpp"
#include "linequad/scene_audit.hpp"

#include "io/jsonl.hpp"
#ifdef LINEQUAD_FUZZ_OPENMC
#include "cli/openmc_geometry.hpp"
#endif

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

using namespace linequad;

namespace {

[[noreturn]] void broken(const char* what, std::string_view input, const std::string& detail) {
    std::fprintf(stderr, "invariant broken: %s\ninput: %.*s\n%s\n", what, int(input.size()),
                 input.data(), detail.c_str());
    std::abort();
}

void json_round_trip(std::string_view text) {
    jsonl::Json a, b;
    std::string why;
    if (!jsonl::parse(text, &a, &why)) return;
    std::string written = jsonl::dump(a);
    if (!jsonl::parse(written, &b, &why)) broken("written JSON does not parse", text, why);
    if (!(a == b)) broken("JSON changed through write and parse", text, written);
    if (jsonl::dump(b) != written) broken("JSON written twice differs", text, written);
}

void case_round_trip(std::string_view text) {
    Case c, d;
    std::string why;
    if (!parse_case(text, &c, &why)) return;
    std::string formatted = format_case(c);
    if (!parse_case(formatted, &d, &why)) broken("a formatted case does not parse", text, why);
    if (format_case(d) != formatted || d.id != c.id || d.family != c.family || d.k != c.k)
        broken("a case changed through format and parse", text, formatted);
}

// A scene's records: the kind survives, and the text is a fixed point after one round.
void record_round_trip(std::string_view text) {
    Record a, b;
    std::string why;
    if (!parse_record(text, &a, &why) || a.kind == RecordKind::single_case) return;
    std::string formatted = a.kind == RecordKind::scene         ? format_scene(a.scene)
                            : a.kind == RecordKind::scene_shape ? format_scene_shape(a.shape)
                                                                : format_scene_line(a.line);
    if (!parse_record(formatted, &b, &why)) broken("a formatted record does not parse", text, why);
    std::string again = b.kind == RecordKind::scene         ? format_scene(b.scene)
                        : b.kind == RecordKind::scene_shape ? format_scene_shape(b.shape)
                                                            : format_scene_line(b.line);
    if (b.kind != a.kind || again != formatted || b.id() != a.id())
        broken("a scene's record changed through format and parse", text, formatted);
}

void result_round_trip(std::string_view text) {
    ParsedResult a, b;
    std::string why;
    if (!parse_result(text, &a, &why)) return;
    std::string once = format_result(a.id, a.solver, a.result, a.has_points);
    if (!parse_result(once, &b, &why)) broken("a formatted result does not parse", text, why);
    std::string twice = format_result(b.id, b.solver, b.result, b.has_points);
    if (twice != once) broken("a result line is not a fixed point", text, once + "\n" + twice);
}

void report_round_trip(std::string_view text) {
    audit::Report a, b;
    std::string why;
    if (!audit::from_json(text, &a, &why)) return;
    std::string once = audit::to_json(a);
    if (!audit::from_json(once, &b, &why)) broken("a written report does not read", text, why);
    if (audit::to_json(b) != once) broken("a report is not a fixed point", text, once);
    audit::markdown(b); // renders whatever it holds
}

// A whole scene file (records a line each): what reads is written back as read, a fixed point.
void scenes_round_trip(std::string_view text) {
    std::vector<audit::SceneCase> a, b;
    try {
        a = audit::scenes_from_text(text);
    } catch (const std::runtime_error&) {
        return; // refused, naming the line: the file is all or nothing
    }
    std::string once = audit::format_scenes(a);
    try {
        b = audit::scenes_from_text(once);
    } catch (const std::runtime_error& e) {
        broken("written scenes do not read", text, e.what());
    }
    if (audit::format_scenes(b) != once) broken("scenes are not a fixed point", text, once);
}

// A region's text and a model file: whatever the bytes, a refusal that says why, or a region in
// proper postfix and a model whose track answers, its steps in order along the ray.
void model_reads(std::string_view text) {
    std::string why;
    if (std::optional<Region> r = Region::parse(text, why)) {
        int operands = 0;
        for (const Region::Token& t : r->tokens()) {
            operands += t.op == Region::Op::half_space   ? 1
                        : t.op == Region::Op::complement ? 0
                                                         : -1;
            if (operands < 1) broken("a region's postfix lacks an operand", text, "");
        }
        if (operands != 1) broken("a region's postfix leaves other than one value", text, "");
    } else if (why.empty()) {
        broken("a region refused without a reason", text, "");
    }
    ModelFile file;
    why.clear();
    bool read = parse_model(text, &file, &why);
#ifdef LINEQUAD_FUZZ_OPENMC
    // A geometry.xml (its universes flattened): the same promise.
    if (!read) {
        std::string xml_why;
        if (cli::parse_openmc_geometry(text, &file, &xml_why))
            read = true;
        else if (xml_why.empty())
            broken("a geometry.xml refused without a reason", text, "");
    }
#endif
    if (!read) {
        if (why.empty()) broken("a model refused without a reason", text, "");
        return;
    }
    std::optional<Model> m = Model::build(std::move(file.surfaces), file.cells, why);
    if (!m) return;
    Model::Track t = m->track({0.25, 0.5, 0.125}, {1, 0.375, -0.25}, 100);
    for (std::size_t k = 1; k < t.steps.size(); ++k)
        if (!(t.steps[k - 1].t <= t.steps[k].t)) broken("a track's steps out of order", text, "");
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    std::string_view text(reinterpret_cast<const char*>(data), size);
    json_round_trip(text);
    case_round_trip(text);
    record_round_trip(text);
    result_round_trip(text);
    report_round_trip(text);
    scenes_round_trip(text);
    model_reads(text);
    return 0;
}
