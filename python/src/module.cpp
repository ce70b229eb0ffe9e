// The Python module linequad (python/linequad/__init__.py imports it as _linequad): shapes from
// keyword fields, read by the case format's own reader so that a bad field is named as it is in a
// case file; intersect() on (N, 3) numpy arrays, every line solved in C++ with the GIL released,
// the answers in a structured array; and the exact oracle as one more solver.
#include "linequad/audit.hpp"
#include "linequad/case_io.hpp"
#include "linequad/exact.hpp"
#include "linequad/solvers.hpp"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

namespace py = pybind11;
using namespace linequad;

namespace {

// One line's answer, as the structured array holds it: unused hit slots have t = inf and a NaN
// point; `error` is an ErrorCode (linequad.error_codes names them), 0 when the line was answered.
struct Row {
    std::uint8_t count, on_surface, certain, error;
    double t[max_hits];
    std::uint8_t kind[max_hits], part[max_hits];
    double p[max_hits][3];
    double s0, s1;
};

struct PyShape {
    Shape shape;
    std::string kind, call; // repr: the call that made it (empty: a campaign's case)
};

// A name that is a case-format word (a shape kind, a field): letters, digits and underscores.
std::string word(const std::string& name, const char* what) {
    bool ok = !name.empty();
    for (char c : name)
        ok = ok && ((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                    c == '_');
    if (!ok)
        throw py::value_error(std::string(what) + " \"" + name + "\": not a name linequad knows");
    return "\"" + name + "\"";
}

// A Python value as the case format's JSON: numbers as exact hex-floats, sequences of them,
// booleans and integers as they are. No field nests deeper than a list of numbers: `depth`
// bounds the recursion whatever a caller passes.
std::string json_value(const py::handle& v, const std::string& field, int depth = 0) {
    if (depth > 2)
        throw py::value_error("field \"" + field +
                              "\": expected a number or a sequence of numbers");
    if (py::isinstance<py::bool_>(v)) return v.cast<bool>() ? "true" : "false";
    if (py::isinstance<py::int_>(v)) return py::str(v).cast<std::string>();
    if (py::isinstance<py::str>(v) || py::isinstance<py::bytes>(v))
        throw py::value_error("field \"" + field + "\": expected a number, not text");
    if (py::hasattr(v, "__len__") && py::hasattr(v, "__iter__")) {
        std::string out = "[";
        bool first = true;
        for (py::handle x : v) {
            out += (first ? "" : ",") + json_value(x, field, depth + 1);
            first = false;
        }
        return out + "]";
    }
    try {
        return "\"" + hex(py::float_(py::reinterpret_borrow<py::object>(v)).cast<double>()) + "\"";
    } catch (const py::error_already_set&) {
        throw py::value_error("field \"" + field +
                              "\": expected a number or a sequence of numbers");
    }
}

PyShape make_shape(const std::string& kind, const py::kwargs& fields) {
    std::string text, shown; // the case format's fields; the call, for repr
    for (auto item : fields) {
        std::string name = item.first.cast<std::string>();
        if (name == "L0" || name == "v" || name == "shape" || name == "range" || name == "id")
            throw py::value_error("field \"" + name + "\": not a field of a shape");
        text += "," + word(name, "field") + ":" + json_value(item.second, name);
        shown += ", " + name + "=" + py::repr(item.second).cast<std::string>();
    }
    // The case reader wants a line: a valid one, never the one named in an error.
    std::string line =
        "{\"shape\":" + word(kind, "shape") + text + ",\"L0\":[0,0,0],\"v\":[1,0,0]}";
    Case c;
    std::string why;
    if (!parse_case(line, &c, &why)) throw py::value_error(why);
    if (Error e = validate(c.shape, c.line); !e.ok()) throw py::value_error(message(e));
    return {c.shape, kind, shown};
}

Need need_of(const std::string& need) {
    if (need == "all") return Need::all;
    if (need == "nearest") return Need::nearest;
    if (need == "any") return Need::any;
    throw py::value_error("need \"" + need + "\": expected all, nearest or any");
}

// The solver of that name answering in `precision` (binary32: its float solver, e.g. correct32);
// "exact" is the oracle.
const Solver* solver_of(const std::string& name, Precision precision) {
    if (name == "exact") return nullptr;
    std::string want = precision == Precision::binary32 ? name + "32" : name;
    for (const Solver& s : fast_solvers())
        if (s.name == want) return &s;
    std::string known = "exact";
    for (const Solver& s : fast_solvers())
        if (s.precision == precision)
            known += ", " + std::string(s.name).substr(
                                0, s.name.size() - (precision == Precision::binary32 ? 2 : 0));
    throw py::value_error("solver \"" + name + "\": not one of " + known);
}

// (N, 3) rows of one floating type, C-contiguous.
template <class T>
py::array_t<T, py::array::c_style> rows(const py::array& a, const char* name) {
    if (a.ndim() != 2 || a.shape(1) != 3)
        throw py::value_error(std::string(name) + ": expected an (N, 3) array");
    return py::array_t<T, py::array::c_style>::ensure(a);
}

template <class T>
py::array solve(const PyShape& s, const py::array& origins, const py::array& directions,
                const std::string& solver, Query q, Interval range, Precision precision) {
    auto L0 = rows<T>(origins, "origins"), v = rows<T>(directions, "directions");
    if (L0.shape(0) != v.shape(0))
        throw py::value_error("origins and directions: " + std::to_string(L0.shape(0)) +
                              " rows against " + std::to_string(v.shape(0)));
    const Solver* fast = solver_of(solver, precision); // a float field refused per row
    py::ssize_t n = L0.shape(0);
    py::array_t<Row> out(n);
    Row* rows_out = out.mutable_data();
    const T *o = L0.data(), *d = v.data();
    {
        py::gil_scoped_release released;
        for (py::ssize_t i = 0; i < n; ++i) {
            Line l{{double(o[3 * i]), double(o[3 * i + 1]), double(o[3 * i + 2])},
                   {double(d[3 * i]), double(d[3 * i + 1]), double(d[3 * i + 2])},
                   range};
            Result r =
                fast ? fast->solve(s.shape, l, q) : exact::intersect(s.shape, l, q, precision);
            Row& row = rows_out[i];
            row.count = r.count;
            row.on_surface = r.on_surface;
            row.certain = r.certainty == Certainty::certain;
            row.error = std::uint8_t(r.error_code);
            for (int k = 0; k < max_hits; ++k) {
                bool hit = k < r.count;
                row.t[k] = hit ? r.hits[k].t : std::numeric_limits<double>::infinity();
                row.kind[k] = hit ? std::uint8_t(r.hits[k].kind) : 0;
                row.part[k] = hit ? std::uint8_t(r.hits[k].part) : 0;
                Vec3 p = hit && q.points ? r.hits[k].p : Vec3{NAN, NAN, NAN};
                row.p[k][0] = p.x, row.p[k][1] = p.y, row.p[k][2] = p.z;
            }
            row.s0 = r.on_surface ? r.s0 : NAN;
            row.s1 = r.on_surface ? r.s1 : NAN;
        }
    }
    return out;
}

py::array intersect(const PyShape& s, const py::array& origins, const py::array& directions,
                    const std::string& solver, const std::string& need, bool points, double t0,
                    double t1) {
    Query q{need_of(need), points && need != "any"};
    Interval range(t0, t1);
    auto is = [](const py::array& a, auto tag) {
        return py::isinstance<py::array_t<decltype(tag)>>(a) &&
               a.dtype().is(py::dtype::of<decltype(tag)>());
    };
    if (is(origins, double{}) && is(directions, double{}))
        return solve<double>(s, origins, directions, solver, q, range, Precision::binary64);
    if (is(origins, float{}) && is(directions, float{}))
        return solve<float>(s, origins, directions, solver, q, range, Precision::binary32);
    throw py::type_error("origins and directions: expected two float64 arrays or two float32 "
                         "arrays (float32 rays are answered by the float solvers)");
}

// The index in Shape of the shape named `name`, or the variant's size.
template <std::size_t I = 0>
std::size_t shape_kind(const std::string& name) {
    if constexpr (I < std::variant_size_v<Shape>) {
        if (name == shape_name(Shape(std::variant_alternative_t<I, Shape>{}))) return I;
        return shape_kind<I + 1>(name);
    } else {
        return I;
    }
}

// A campaign's cases, as `linequad cases` writes them: the same cases in the same order.
py::dict cases(const std::vector<std::string>& families, const std::vector<std::string>& shapes,
               std::uint64_t n, std::uint64_t seed, const std::string& precision) {
    audit::Options o;
    o.seed = seed, o.cases_per_group = n;
    if (n < 1 || n > 1000000) throw py::value_error("n: expected 1 to 1000000 cases a group");
    for (const std::string& name : families) {
        Family f;
        if (!parse_family(name, &f)) throw py::value_error("family \"" + name + "\": unknown");
        o.families.push_back(f);
    }
    for (const std::string& name : shapes) {
        std::size_t k = shape_kind(name);
        if (k == std::variant_size_v<Shape>)
            throw py::value_error("shape \"" + name + "\": unknown");
        o.shapes.push_back(int(k));
    }
    if (precision != "binary64" && precision != "binary32")
        throw py::value_error("precision \"" + precision + "\": expected binary64 or binary32");
    o.precision = precision == "binary32" ? Precision::binary32 : Precision::binary64;
    std::vector<Case> all;
    {
        py::gil_scoped_release released;
        audit::for_each_case(o, [&](const Case& c) { all.push_back(c); });
    }
    py::ssize_t count = py::ssize_t(all.size());
    py::array_t<double> L0({count, py::ssize_t(3)}), v({count, py::ssize_t(3)}), t0(count),
        t1(count);
    py::array_t<int> k(count);
    py::list made, ids, family, lines;
    for (py::ssize_t i = 0; i < count; ++i) {
        const Case& c = all[std::size_t(i)];
        for (int j = 0; j < 3; ++j) {
            L0.mutable_at(i, j) = c.line.L0[j];
            v.mutable_at(i, j) = c.line.v[j];
        }
        t0.mutable_at(i) = c.line.range.t0, t1.mutable_at(i) = c.line.range.t1;
        k.mutable_at(i) = c.k;
        made.append(PyShape{c.shape, shape_name(c.shape), ""});
        ids.append(c.id), family.append(c.family), lines.append(format_case(c));
    }
    py::dict out;
    out["shapes"] = made, out["origins"] = L0, out["directions"] = v, out["t0"] = t0;
    out["t1"] = t1, out["family"] = family, out["k"] = k, out["id"] = ids;
    out["lines"] = lines; // the case format's lines, as `linequad cases` writes them
    return out;
}

// A results file graded against its cases file by the audit (its --cases-file --results path):
// the verdict lines and report.json's text; report.md and figures written into out_dir.
py::tuple grade(const std::string& cases_file, const std::string& results_file,
                const std::string& out_dir) {
    audit::Options o;
    o.cases_file = cases_file, o.results_file = results_file, o.out_dir = out_dir;
    o.command = "linequad.audit (Python)";
    audit::Report r;
    {
        py::gil_scoped_release released;
        r = audit::run(o);
    }
    py::list lines;
    for (const audit::Verdict& v : audit::verdicts(r))
        lines.append(audit::verdict_line(v));
    return py::make_tuple(lines, audit::to_json(r));
}

} // namespace

PYBIND11_MODULE(_linequad, m) {
    m.doc() = "linequad: exact and correctly rounded line-surface intersections on numpy arrays";
    PYBIND11_NUMPY_DTYPE(Row, count, on_surface, certain, error, t, kind, part, p, s0, s1);
    py::class_<PyShape>(m, "Shape")
        .def_property_readonly("kind", [](const PyShape& s) { return s.kind; })
        .def_property_readonly("_case_text",
                               [](const PyShape& s) {
                                   Case c;
                                   c.shape = s.shape, c.line = Line{{}, {1, 0, 0}, Range::line};
                                   return format_case(c);
                               })
        .def("__repr__", [](const PyShape& s) {
            if (s.call.empty()) return "<linequad.Shape " + s.kind + ">"; // a campaign's case
            return "linequad.shape(\"" + s.kind + "\"" + s.call + ")";
        });
    m.def("shape", &make_shape, py::arg("kind"),
          "A shape from its case-format fields: shape(\"cylinder\", C=(0, 0, 0), H=(0, 0, 1), "
          "r=1, caps=True). A bad field raises ValueError naming it.");
    m.def("intersect", &intersect, py::arg("shape"), py::arg("origins"), py::arg("directions"),
          py::arg("solver") = "correct", py::arg("need") = "all", py::arg("points") = true,
          py::arg("t0") = -std::numeric_limits<double>::infinity(),
          py::arg("t1") = std::numeric_limits<double>::infinity(),
          "Every line L0 + t v, t0 <= t <= t1, against the shape: a structured array of one row "
          "per line (count, on_surface, certain, error, t[4], kind[4], part[4], p[4][3], s0, "
          "s1). float64 rays are answered by the named solver, float32 rays by its float one "
          "(correct32 for correct); solver=\"exact\" is the oracle.");
    m.def("cases", &cases, py::arg("families") = std::vector<std::string>{},
          py::arg("shapes") = std::vector<std::string>{}, py::arg("n") = 100, py::arg("seed") = 1,
          py::arg("precision") = "binary64",
          "A campaign's cases, the same as `linequad cases` writes (families and shapes: names, "
          "empty for all; n cases per family, shape and range): a dict of shapes (a list), "
          "origins and directions ((N, 3) arrays), t0, t1, family, k, id and lines (the case "
          "format's).");
    m.def("_grade", &grade, py::arg("cases_file"), py::arg("results_file"), py::arg("out_dir"));
    py::list names;
    for (const Solver& s : fast_solvers())
        if (s.precision == Precision::binary64) names.append(std::string(s.name));
    names.append("exact");
    m.attr("solvers") = names;
    py::list codes;
    for (int c = 0; c <= int(ErrorCode::foreign); ++c)
        codes.append(std::string(code_name(ErrorCode(c))));
    m.attr("error_codes") = py::tuple(codes);
    m.attr("hit_kinds") = py::make_tuple("cross", "tangent");
    m.attr("parts") = py::make_tuple("lateral", "base", "top");
}
