// The Python module linequad (python/linequad/__init__.py imports it as _linequad): shapes from
// keyword fields, read by the case format's own reader so that a bad field is named as it is in a
// case file; intersect() on (N, 3) numpy arrays, every line solved in C++ with the GIL released,
// the answers in a structured array; and the exact oracle as one more solver.
#include "linequad/audit.hpp"
#include "linequad/audit_solver.hpp"
#include "linequad/batch.hpp"
#include "linequad/case_io.hpp"
#include "linequad/exact.hpp"
#include "linequad/solvers.hpp"
#include "report/report_html.hpp"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <type_traits>
#include <vector>

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

// A row with no answer yet: no hit in any slot (t inf, point NaN), no interval.
Row blank_row() {
    Row row{};
    for (int k = 0; k < max_hits; ++k) {
        row.t[k] = std::numeric_limits<double>::infinity();
        row.p[k][0] = row.p[k][1] = row.p[k][2] = NAN;
    }
    row.s0 = row.s1 = NAN;
    return row;
}

// One line's answer into its row: the blank row, then what the result holds (a copy and a few
// stores a line: the binding's cost beside the batch's, bench/python_throughput.py).
void fill(Row& row, const Result& r, Query q, const Row& blank) {
    row = blank;
    row.count = r.count;
    row.on_surface = r.on_surface;
    row.certain = r.certainty == Certainty::certain;
    row.error = std::uint8_t(r.error_code);
    for (int k = 0; k < r.count; ++k) {
        const Hit& h = r.hits[k];
        row.t[k] = h.t;
        row.kind[k] = std::uint8_t(h.kind);
        row.part[k] = std::uint8_t(h.part);
        if (q.points) row.p[k][0] = h.p.x, row.p[k][1] = h.p.y, row.p[k][2] = h.p.z;
    }
    if (r.on_surface) row.s0 = r.s0, row.s1 = r.s1;
}

// The C++ batch call that answers a solver's rays, where there is one: stable and correct on
// double rays, stable32 on float rays (each bit for bit its scalar solver). Other solvers, and
// the oracle, answer line by line.
enum class BatchCall { none, stable, correct, stable32 };
BatchCall batch_call(const std::string& solver, Precision precision) {
    if (precision == Precision::binary32)
        return solver == "stable" ? BatchCall::stable32 : BatchCall::none;
    if (solver == "stable") return BatchCall::stable;
    if (solver == "correct") return BatchCall::correct;
    return BatchCall::none;
}

// The batch call itself: stable32 for float lines, else stable or correct.
template <class T>
void batch_solve(BatchCall call, const Shape& shape, const LineArraysT<T>& lines, Query q,
                 Result* out) {
    std::visit(
        [&](const auto& s) {
            if constexpr (std::is_same_v<T, float>)
                stable32::intersect(s, lines, q, out);
            else if (call == BatchCall::stable)
                stable::intersect(s, lines, q, out);
            else
                correct::intersect(s, lines, q, out);
        },
        shape);
}

// (N, 3) rows laid out as the batch's structure of arrays, a chunk at a time: small enough to
// stay in cache, large enough that a batch's set-up (a shape's preparation) is paid rarely.
template <class T>
struct Chunk {
    static constexpr std::size_t size = 4096;
    std::vector<T> xyz = std::vector<T>(6 * size);
    std::vector<Result> out = std::vector<Result>(size);

    LineArraysT<T> lines(const T* o, const T* d, std::size_t m, Interval range) {
        T* a = xyz.data();
        for (std::size_t j = 0; j < m; ++j)
            for (int k = 0; k < 3; ++k)
                a[k * size + j] = o[3 * j + k], a[(3 + k) * size + j] = d[3 * j + k];
        return {a, a + size, a + 2 * size, a + 3 * size, a + 4 * size, a + 5 * size, m, range};
    }
    void solve(BatchCall call, const Shape& shape, const LineArraysT<T>& lines, Query q) {
        batch_solve(call, shape, lines, q, out.data());
    }
};

// The rows to answer into: `out` when given (an array intersect() returned, reused: no fresh
// memory to fault in for a caller that asks again and again), else a new array.
py::array_t<Row> rows_for(std::size_t n, const py::object& out) {
    if (out.is_none()) return py::array_t<Row>{py::ssize_t(n)};
    py::array a = py::reinterpret_borrow<py::array>(out);
    if (!py::isinstance<py::array>(out) || !a.dtype().is(py::dtype::of<Row>()) || a.ndim() != 1 ||
        std::size_t(a.shape(0)) != n || !(a.flags() & py::array::c_style) || !a.writeable())
        throw py::value_error("out: expected a writeable array that intersect() returned, of " +
                              std::to_string(n) + " rows");
    return py::reinterpret_borrow<py::array_t<Row>>(out);
}

template <class T>
py::array solve(const PyShape& s, const py::array& origins, const py::array& directions,
                const std::string& solver, Query q, Interval range, Precision precision,
                const py::object& out_arg) {
    auto L0 = rows<T>(origins, "origins"), v = rows<T>(directions, "directions");
    if (L0.shape(0) != v.shape(0))
        throw py::value_error("origins and directions: " + std::to_string(L0.shape(0)) +
                              " rows against " + std::to_string(v.shape(0)));
    const Solver* fast = solver_of(solver, precision); // a float field refused per row
    BatchCall call = batch_call(solver, precision);
    std::size_t n = std::size_t(L0.shape(0));
    py::array_t<Row> out = rows_for(n, out_arg);
    Row* rows_out = out.mutable_data();
    const T *o = L0.data(), *d = v.data();
    const Row blank = blank_row();
    {
        // Released for the solving alone: the arrays' references are taken and dropped with it
        // held (another thread may hold `out` too).
        py::gil_scoped_release released;
        if (call != BatchCall::none) {
            // Kept from call to call (a thread's own: the GIL is released): a caller answering
            // 4,096 rays a call would otherwise pay for the buffer's first touch every time.
            thread_local Chunk<T> kept;
            Chunk<T>& chunk = kept;
            for (std::size_t start = 0; start < n; start += Chunk<T>::size) {
                std::size_t m = std::min(Chunk<T>::size, n - start);
                chunk.solve(call, s.shape, chunk.lines(o + 3 * start, d + 3 * start, m, range), q);
                const Result* answers = chunk.out.data();
                for (std::size_t j = 0; j < m; ++j)
                    fill(rows_out[start + j], answers[j], q, blank);
            }
        } else {
            for (std::size_t i = 0; i < n; ++i) {
                Line l{{double(o[3 * i]), double(o[3 * i + 1]), double(o[3 * i + 2])},
                       {double(d[3 * i]), double(d[3 * i + 1]), double(d[3 * i + 2])},
                       range};
                Result r =
                    fast ? fast->solve(s.shape, l, q) : exact::intersect(s.shape, l, q, precision);
                if (!fast && r.ok()) r.certainty = Certainty::certain; // the oracle's is exact
                fill(rows_out[i], r, q, blank);
            }
        }
    }
    return out;
}

// The C++ batch call alone, timed, on the same rays laid out beforehand as a C++ caller holds
// them (structure of arrays): one call answering every ray into results held for all of them
// (chunk 0), or a call per `chunk` rays into one reused buffer of results; each buffer touched
// before the clock starts. What intersect()'s binding adds is measured against it
// (bench/python_throughput.py).
double batch_seconds(const PyShape& s, const py::array& origins, const py::array& directions,
                     const std::string& solver, std::size_t chunk) {
    auto L0 = rows<double>(origins, "origins"), v = rows<double>(directions, "directions");
    BatchCall call = batch_call(solver, Precision::binary64);
    if (call == BatchCall::none || L0.shape(0) != v.shape(0))
        throw py::value_error("_batch_seconds: stable or correct, as many directions as origins");
    std::size_t n = std::size_t(L0.shape(0)), step = chunk == 0 ? n : chunk;
    std::vector<double> soa(6 * n);
    for (std::size_t i = 0; i < n; ++i)
        for (int k = 0; k < 3; ++k)
            soa[k * n + i] = L0.data()[3 * i + k], soa[(3 + k) * n + i] = v.data()[3 * i + k];
    std::vector<Result> out(std::max<std::size_t>(step, 1));
    Query q;
    py::gil_scoped_release released;
    auto start = std::chrono::steady_clock::now();
    for (std::size_t at = 0; at < n; at += step) {
        const double* a = soa.data() + at;
        batch_solve(call, s.shape,
                    LineArrays{a, a + n, a + 2 * n, a + 3 * n, a + 4 * n, a + 5 * n,
                               std::min(step, n - at), Interval()},
                    q, out.data());
    }
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

py::array intersect(const PyShape& s, const py::array& origins, const py::array& directions,
                    const std::string& solver, const std::string& need, bool points, double t0,
                    double t1, const py::object& out) {
    Query q{need_of(need), points && need != "any"};
    Interval range(t0, t1);
    auto is = [](const py::array& a, auto tag) {
        return py::isinstance<py::array_t<decltype(tag)>>(a) &&
               a.dtype().is(py::dtype::of<decltype(tag)>());
    };
    if (is(origins, double{}) && is(directions, double{}))
        return solve<double>(s, origins, directions, solver, q, range, Precision::binary64, out);
    if (is(origins, float{}) && is(directions, float{}))
        return solve<float>(s, origins, directions, solver, q, range, Precision::binary32, out);
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

// Campaign options from the Python call (names checked as cases() checks them).
audit::Options campaign(const std::vector<std::string>& families,
                        const std::vector<std::string>& shapes, std::uint64_t n, std::uint64_t seed,
                        const std::string& precision) {
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
    return o;
}

// A campaign's cases, as `linequad cases` writes them: the same cases in the same order.
py::dict cases(const std::vector<std::string>& families, const std::vector<std::string>& shapes,
               std::uint64_t n, std::uint64_t seed, const std::string& precision) {
    audit::Options o = campaign(families, shapes, n, seed, precision);
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

// A keyword's value among the names of an enumeration (its C++ enumerators' names).
template <class E>
E choice(const std::string& value, const char* keyword,
         std::initializer_list<std::pair<const char*, E>> names) {
    std::string known;
    for (const auto& [name, e] : names) {
        if (value == name) return e;
        known += (known.empty() ? "" : ", ") + std::string(name);
    }
    throw py::value_error(std::string(keyword) + " \"" + value + "\": expected " + known);
}

// What a Python solver declares: the plugin ABI's declarations, as keywords.
struct Declared {
    std::string answers, parametrisation, surface, inside, on_surface, tangent;
    double tolerance_absolute, tolerance_relative, negative_zero;
    bool contact_as_point;
};

// One row of a Python solver's t's as its answer: the finite ones, in order, each a crossing
// with t alone (inf or NaN: an empty slot). More hits than any shape has is no answer.
Result answer_of(const double* t, py::ssize_t slots) {
    double hits[max_hits];
    int count = 0;
    for (py::ssize_t k = 0; k < slots; ++k) {
        if (!std::isfinite(t[k])) continue;
        if (count == max_hits)
            return Result::failure(ErrorCode::foreign, "answered more than 4 hits");
        hits[count++] = t[k];
    }
    std::sort(hits, hits + count);
    Result r;
    for (int k = 0; k < count; ++k)
        r.hits[k] = Hit{hits[k], {}, NAN, HitKind::cross, Part::lateral, false};
    r.count = std::uint8_t(count);
    return r;
}

// A chunk of posed cases handed to fn as arrays (in the cases' precision), its t's read back.
// Whatever fn raises or returns that is not one row of t's a case is charged to every case of
// the chunk, with what it was; the audit goes on.
void answer_in_python(py::handle fn, Precision precision, const std::vector<Case>& posed,
                      std::vector<audit::ExternalAnswer>& out) {
    py::gil_scoped_acquire gil;
    py::ssize_t m = py::ssize_t(posed.size());
    std::string why;
    try {
        py::list shapes;
        py::array_t<double> L0({m, py::ssize_t(3)}), v({m, py::ssize_t(3)}), t0(m), t1(m);
        for (py::ssize_t i = 0; i < m; ++i) {
            const Case& c = posed[std::size_t(i)];
            shapes.append(PyShape{c.shape, shape_name(c.shape), ""});
            for (int k = 0; k < 3; ++k)
                L0.mutable_at(i, k) = c.line.L0[k], v.mutable_at(i, k) = c.line.v[k];
            t0.mutable_at(i) = c.line.range.t0, t1.mutable_at(i) = c.line.range.t1;
        }
        py::object as = precision == Precision::binary32
                            ? py::object(py::module_::import("numpy").attr("float32"))
                            : py::object(py::module_::import("numpy").attr("float64"));
        py::object got = fn(shapes, L0.attr("astype")(as), v.attr("astype")(as),
                            t0.attr("astype")(as), t1.attr("astype")(as));
        auto t = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(got);
        if (!t)
            throw py::value_error("returned " + py::repr(got).cast<std::string>().substr(0, 80) +
                                  ", not an array of numbers");
        if (t.ndim() == 0 || t.ndim() > 2 || t.shape(0) != m)
            throw py::value_error("returned an array of shape " +
                                  py::repr(t.attr("shape")).cast<std::string>() + " for " +
                                  std::to_string(m) + " lines");
        py::ssize_t slots = t.ndim() == 1 ? 1 : t.shape(1);
        for (py::ssize_t i = 0; i < m; ++i)
            out[std::size_t(i)].result = answer_of(t.data() + i * slots, slots);
        return;
    } catch (py::error_already_set& e) {
        why = e.what();
    } catch (const std::exception& e) {
        why = e.what();
    }
    if (why.size() > 200) why = why.substr(0, 200) + "...";
    const char* text = interned("the chunk's call failed: " + why);
    for (audit::ExternalAnswer& a : out)
        a.result = Result::failure(ErrorCode::foreign, text);
}

// linequad.audit: fn graded as a solver of the campaign's cases beside nothing else, under
// what it declares; the verdict lines and report.json's text, the report written into out_dir
// when it is given.
py::tuple run_audit(const py::object& fn, const std::vector<std::string>& families,
                    const std::vector<std::string>& shapes, std::uint64_t n, std::uint64_t seed,
                    const std::string& precision, const std::string& out_dir,
                    const std::string& name, const Declared& d) {
    using namespace audit;
    if (!PyCallable_Check(fn.ptr())) throw py::type_error("fn: expected a callable");
    Options o = campaign(families, shapes, n, seed, precision);
    o.out_dir = out_dir, o.plots = !out_dir.empty(), o.threads = 1;
    if (!out_dir.empty()) o.finish_with = write_report_html;
    o.command = "linequad.audit (Python)";
    o.solvers = {name};
    ExternalSolver e;
    e.name = name, e.precision = o.precision;
    e.answers = choice<Answers>(d.answers, "answers",
                                {{"all", Answers::all},
                                 {"nearest", Answers::nearest},
                                 {"first_entry", Answers::first_entry},
                                 {"first_exit", Answers::first_exit}});
    e.parametrisation =
        choice<Parametrisation>(d.parametrisation, "parametrisation",
                                {{"line", Parametrisation::line},
                                 {"unit_direction", Parametrisation::unit_direction},
                                 {"segment", Parametrisation::segment}});
    e.surface = choice<Surface>(d.surface, "surface",
                                {{"as_posed", Surface::as_posed},
                                 {"closed", Surface::closed},
                                 {"infinite", Surface::infinite}});
    e.inside = choice<StartInside>(d.inside, "inside",
                                   {{"as_answers", StartInside::as_answers},
                                    {"no_hit", StartInside::no_hit},
                                    {"at_t0", StartInside::at_t0},
                                    {"at_zero", StartInside::at_zero},
                                    {"undefined", StartInside::undefined}});
    e.on_surface = choice<StartOnSurface>(
        d.on_surface, "on_surface",
        {{"as_inside", StartOnSurface::as_inside}, {"by_direction", StartOnSurface::by_direction}});
    e.tangent = choice<TangentRule>(d.tangent, "tangent",
                                    {{"hit", TangentRule::hit}, {"no_hit", TangentRule::no_hit}});
    e.tolerance = {d.tolerance_absolute, d.tolerance_relative};
    e.negative_zero = d.negative_zero;
    e.contact_as_point = d.contact_as_point;
    e.points = e.kinds = e.parts = false; // its answers are t's
    e.mapping = "a Python callable, fn(shapes, origins, directions, t0, t1) -> t's, a chunk of "
                "cases a call";
    e.not_replayable = "a Python callable: call it on the case to replay it";
    for (int k : o.shapes.empty() ? std::vector<int>{} : o.shapes)
        e.worker_shapes |= 1u << k;
    if (o.shapes.empty()) e.worker_shapes = (1u << std::variant_size_v<Shape>)-1;
    if (std::string p = declaration_problem(e); !p.empty()) throw py::value_error(p);
    // fn borrowed, not owned: the audit copies its solvers with the GIL released, and a
    // handle's copy touches no reference count (the caller holds fn until run() returns).
    e.chunk = [fn = py::handle(fn), precision = e.precision](const std::vector<Case>& posed,
                                                             std::vector<ExternalAnswer>& out) {
        answer_in_python(fn, precision, posed, out);
    };
    Report r;
    {
        py::gil_scoped_release released;
        r = run(o, {e});
    }
    py::list lines;
    for (const Verdict& v : verdicts(r))
        lines.append(verdict_line(v));
    return py::make_tuple(lines, to_json(r));
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
          py::arg("t1") = std::numeric_limits<double>::infinity(), py::arg("out") = py::none(),
          "Every line L0 + t v, t0 <= t <= t1, against the shape: a structured array of one row "
          "per line (count, on_surface, certain, error, t[4], kind[4], part[4], p[4][3], s0, "
          "s1). float64 rays are answered by the named solver, float32 rays by its float one "
          "(correct32 for correct); solver=\"exact\" is the oracle. out: an array an earlier "
          "call returned for as many rays, answered into and returned.");
    m.def("cases", &cases, py::arg("families") = std::vector<std::string>{},
          py::arg("shapes") = std::vector<std::string>{}, py::arg("n") = 100, py::arg("seed") = 1,
          py::arg("precision") = "binary64",
          "A campaign's cases, the same as `linequad cases` writes (families and shapes: names, "
          "empty for all; n cases per family, shape and range): a dict of shapes (a list), "
          "origins and directions ((N, 3) arrays), t0, t1, family, k, id and lines (the case "
          "format's).");
    m.def("_batch_seconds", &batch_seconds, py::arg("shape"), py::arg("origins"),
          py::arg("directions"), py::arg("solver"), py::arg("chunk"));
    m.def(
        "_audit",
        [](const py::object& fn, const std::vector<std::string>& families,
           const std::vector<std::string>& shapes, std::uint64_t n, std::uint64_t seed,
           const std::string& precision, const std::string& out_dir, const std::string& name,
           const std::string& answers, const std::string& parametrisation,
           const std::string& surface, const std::string& inside, const std::string& on_surface,
           const std::string& tangent, double tolerance_absolute, double tolerance_relative,
           double negative_zero, bool contact_as_point) {
            return run_audit(fn, families, shapes, n, seed, precision, out_dir, name,
                             {answers, parametrisation, surface, inside, on_surface, tangent,
                              tolerance_absolute, tolerance_relative, negative_zero,
                              contact_as_point});
        },
        py::arg("fn"), py::arg("families"), py::arg("shapes"), py::arg("n"), py::arg("seed"),
        py::arg("precision"), py::arg("out_dir"), py::arg("name"), py::arg("answers"),
        py::arg("parametrisation"), py::arg("surface"), py::arg("inside"), py::arg("on_surface"),
        py::arg("tangent"), py::arg("tolerance_absolute"), py::arg("tolerance_relative"),
        py::arg("negative_zero"), py::arg("contact_as_point"));
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
