// linequad sense: which side of a plane or a general quadric each point is on, exactly.
#include "cli/cli.hpp"
#include "linequad/case_io.hpp"
#include "linequad/exact.hpp"

#include "io/jsonl.hpp"

#include <memory>
#include <new>
#include <stdexcept>

namespace linequad::cli {

namespace {

struct SenseArgs {
    std::string file = "-", max_line_bytes = "1048576";
    bool oracle = false;
};

SenseResult answer(const SenseQuery& q, bool oracle) {
    return std::visit(
        [&](const auto& s) {
            if (q.u) return oracle ? exact::sense(s, q.p, *q.u) : sense(s, q.p, *q.u);
            return oracle ? exact::sense(s, q.p) : sense(s, q.p);
        },
        q.surface);
}

int run_sense(const SenseArgs& a) {
    std::size_t max_bytes = std::size_t(to_whole(a.max_line_bytes));
    jsonl::LineReader in(a.file, max_bytes);
    jsonl::Output out;
    std::string why;
    bool malformed = false;
    SenseQuery q;
    jsonl::each_line(
        in, max_bytes, &why,
        [&](const std::string& line, auto&& parse) {
            if (parse([&] { return parse_sense_query(line, &q, &why); })) {
                out.line(format_sense(q.id, answer(q, a.oracle)));
                return;
            }
            malformed = true;
            out.line(format_failure(q.id, "sense", "malformed",
                                    "line " + std::to_string(in.number()) + ": " + why));
        },
        [&](const std::string& too_long) {
            malformed = true;
            out.line(format_failure("null", "sense", "malformed", too_long));
        });
    out.finish();
    return malformed ? 1 : 0;
}

} // namespace

Command sense_command(CLI::App& app) {
    auto a = std::make_shared<SenseArgs>();
    CLI::App* s = app.add_subcommand(
        "sense",
        "Which side of a plane or a general quadric each point is on: the exact sign of "
        "f(p) (with a direction u, the side u points into from a point on the surface). "
        "One JSON object per line: {\"shape\":\"plane\",\"n\":[a,b,c],\"d\":d,\"p\":[x,y,z]} "
        "or {\"shape\":\"quadric\",\"q\":[A,B,C,D,E,F,G,H,J,K],\"p\":[...],\"u\":[...]}.");
    s->add_flag("--oracle", a->oracle,
                "answer with the exact oracle (CGAL) instead of the library's filtered sign "
                "(the same answers, slower)");
    add_max_line_bytes(s, a->max_line_bytes);
    s->add_option("file", a->file, "the queries (- or nothing: standard input)")->type_name("FILE");
    return {s, [a](const std::string&) { return run_sense(*a); }, {}};
}

} // namespace linequad::cli
