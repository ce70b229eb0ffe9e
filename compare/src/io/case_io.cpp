#include "linequad/case_io.hpp"

#include "io/jsonl.hpp"
#include "io/shape_types.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <map>
#include <mutex>
#include <set>

namespace linequad {

const char* interned(std::string_view name) {
    static std::mutex m;
    static std::set<std::string, std::less<>> names;
    std::lock_guard<std::mutex> lock(m);
    auto it = names.find(name);
    if (it == names.end()) it = names.emplace(name).first;
    return it->c_str();
}

std::string hex(double x) {
    if (std::isnan(x)) return "nan";
    if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
    char buf[40];
    std::snprintf(buf, sizeof buf, "%a", x);
    return buf;
}

namespace {

using jsonl::Json;

// A number: a JSON number, or a string holding a C99 hex float, a decimal, "inf", "-inf" or
// "nan". Every NaN reads as the one quiet NaN that "nan" writes back, so a case round-trips bit
// for bit.
bool to_double(const Json& v, double* out) {
    if (v.is_number_float()) return *out = v.get<double>(), true;
    if (v.is_number_integer() && !v.is_number_unsigned())
        return *out = double(v.get<std::int64_t>()), true; // rounded once, to nearest
    if (v.is_number_unsigned()) return *out = double(v.get<std::uint64_t>()), true;
    if (!v.is_string()) return false;
    const std::string& s = v.get_ref<const std::string&>();
    if (s.empty() || std::isspace(static_cast<unsigned char>(s[0]))) return false;
    char* end = nullptr;
    double x = std::strtod(s.c_str(), &end); // correctly rounded for decimal and hex (glibc)
    if (end != s.c_str() + s.size()) return false;
    // Overflow gives inf (reported later as infinite input), underflow the subnormal.
    *out = std::isnan(x) ? std::numeric_limits<double>::quiet_NaN() : x;
    return true;
}

struct Reader {
    const Json& obj;
    std::string* why;

    bool fail(std::string_view field, std::string_view what) {
        *why = "field \"" + std::string(field) + "\": " + std::string(what);
        return false;
    }
    const Json* find(const char* field) const {
        auto it = obj.find(field);
        return it == obj.end() ? nullptr : &*it;
    }
    const Json* need(const char* field) {
        const Json* v = find(field);
        if (!v) fail(field, "missing");
        return v;
    }
    bool number(const char* field, double* out) {
        const Json* v = need(field);
        if (!v) return false;
        if (!to_double(*v, out)) return fail(field, "expected a number (hex-float or decimal)");
        return true;
    }
    bool vec(const char* field, Vec3* out) {
        const Json* v = need(field);
        if (!v) return false;
        double c[3];
        if (!v->is_array() || v->size() != 3 || !to_double((*v)[0], &c[0]) ||
            !to_double((*v)[1], &c[1]) || !to_double((*v)[2], &c[2]))
            return fail(field, "expected an array of 3 numbers");
        *out = {c[0], c[1], c[2]};
        return true;
    }
    bool coefficients(const char* field, std::array<double, 10>* out) {
        const Json* v = need(field);
        if (!v) return false;
        bool ok = v->is_array() && v->size() == 10;
        for (std::size_t i = 0; ok && i < 10; ++i)
            ok = to_double((*v)[i], &(*out)[i]);
        if (!ok) return fail(field, "expected an array of 10 numbers (A B C D E F G H J K)");
        return true;
    }
};

// Fields every case may have, whatever its shape.
const char* const common_fields[] = {"id", "shape",  "L0", "v",    "range",    "t0",
                                     "t1", "family", "k",  "note", "precision"};

template <class S>
bool known_field(const std::string& key) {
    for (const char* f : common_fields)
        if (key == f) return true;
    // Options some shapes take (a closed solid by definition takes none).
    if (key == "finite" || key == "caps") return has_extent_options<S>;
    if (key == "nappes") return has_nappes<S>;
    if (key == "coincident") return has_coincident<S>;
    bool known = false;
    detail::for_each_field<S>([&](const auto& f) { known = known || key == f.name; });
    return known;
}

// "cylinder, elliptic_cylinder or elliptic_cone"
std::string shape_names() {
    std::string out;
    for (std::size_t i = 0; i < shape_count; ++i)
        out += std::string(i == 0 ? "" : i + 1 == shape_count ? " or " : ", ") + shape_name_at(i);
    return out;
}

bool read_field(Reader& r, const char* name, Vec3* out) {
    return r.vec(name, out);
}
bool read_field(Reader& r, const char* name, double* out) {
    return r.number(name, out);
}
bool read_field(Reader& r, const char* name, std::array<double, 10>* out) {
    return r.coefficients(name, out);
}

bool read_bool(Reader& r, const char* name, bool* out) {
    const Json* f = r.find(name);
    if (!f) return true;
    if (!f->is_boolean()) return r.fail(name, "expected true or false");
    *out = f->get<bool>();
    return true;
}

// The shape's own fields, from its table, and its options.
template <class S>
bool read_shape(Reader& r, Shape* out) {
    S s;
    bool ok = true;
    detail::for_each_field<S>(
        [&](const auto& f) { ok = ok && read_field(r, f.name, &(s.*f.member)); });
    if (!ok) return false;
    if constexpr (has_extent_options<S>)
        if (!read_bool(r, "finite", &s.finite) || !read_bool(r, "caps", &s.caps)) return false;
    if constexpr (has_coincident<S>)
        if (!read_bool(r, "coincident", &s.coincident)) return false;
    if constexpr (has_nappes<S>) {
        if (const Json* n = r.find("nappes")) {
            if (!n->is_number_integer() || (*n != 1 && *n != 2))
                return r.fail("nappes", "expected 1 or 2");
            s.nappes = n->get<int>();
        }
    }
    *out = s;
    return true;
}

constexpr Range shorthands[] = {Range::line, Range::ray, Range::segment};

// The range: a shorthand ("range"), or its ends ("t0", "t1"; either may be left out, or be
// "inf" or "-inf"), not both.
bool read_range(Reader& r, Interval* out) {
    const Json *range = r.find("range"), *t0 = r.find("t0"), *t1 = r.find("t1");
    if (range && (t0 || t1)) return r.fail(t0 ? "t0" : "t1", "give either range or t0, t1");
    if (range) {
        if (!range->is_string()) return r.fail("range", "expected a string");
        for (Range x : shorthands)
            if (range->get_ref<const std::string&>() == range_name(x)) return *out = x, true;
        return r.fail("range", "expected line, ray or segment");
    }
    Interval i;
    if (t0 && !r.number("t0", &i.t0)) return false;
    if (t1 && !r.number("t1", &i.t1)) return false;
    *out = i;
    return true;
}

std::string json_string(std::string_view s) {
    return jsonl::dump(Json(std::string(s)));
}

void put_field(std::string& out, const char* name, Vec3 p) {
    out += ",\"";
    out += name;
    out += "\":[\"" + hex(p.x) + "\",\"" + hex(p.y) + "\",\"" + hex(p.z) + "\"]";
}
void put_field(std::string& out, const char* name, double x) {
    out += ",\"";
    out += name;
    out += "\":\"" + hex(x) + "\"";
}
void put_field(std::string& out, const char* name, const std::array<double, 10>& q) {
    out += ",\"";
    out += name;
    out += "\":[";
    for (std::size_t i = 0; i < q.size(); ++i)
        out += (i == 0 ? "\"" : ",\"") + hex(q[i]) + "\"";
    out += "]";
}

// The shorthand an interval is, if any.
bool shorthand(Interval i, Range* r) {
    for (Range x : shorthands)
        if (i == Interval(x)) return *r = x, true;
    return false;
}

bool read_part(const Json& v, Part* out) {
    for (Part p : {Part::lateral, Part::base, Part::top})
        if (v.is_string() && v.get_ref<const std::string&>() == part_name(p)) return *out = p, true;
    return false;
}

// A binary32 case's numbers must each be a float (NaN and the infinities are: the solvers then
// name them); the first that is not is named, with its value.
bool float_or_refuse(Reader& r, const char* field, double x) {
    if (std::isnan(x) || detail::Binary32::holds(x)) return true;
    return r.fail(field, "not a binary32 value (the case's precision is binary32): " + hex(x));
}
bool float_or_refuse(Reader& r, const char* field, Vec3 p) {
    return float_or_refuse(r, field, p.x) && float_or_refuse(r, field, p.y) &&
           float_or_refuse(r, field, p.z);
}
bool float_or_refuse(Reader& r, const char* field, const std::array<double, 10>& q) {
    for (double x : q)
        if (!float_or_refuse(r, field, x)) return false;
    return true;
}
bool all_binary32(Reader& r, const Case& c) {
    if (!float_or_refuse(r, "L0", c.line.L0) || !float_or_refuse(r, "v", c.line.v) ||
        !float_or_refuse(r, "t0", c.line.range.t0) || !float_or_refuse(r, "t1", c.line.range.t1))
        return false;
    return std::visit(
        [&](const auto& s) {
            bool ok = true;
            detail::for_each_field<std::decay_t<decltype(s)>>(
                [&](const auto& f) { ok = ok && float_or_refuse(r, f.name, s.*f.member); });
            return ok;
        },
        c.shape);
}

// Parses a line that must be a JSON object; says why not.
bool parse_object(std::string_view line, Json* obj, std::string* why) {
    std::string err;
    if (!jsonl::parse(line, obj, &err)) return *why = "not valid JSON: " + err, false;
    if (!obj->is_object()) return *why = "not a JSON object", false;
    return true;
}

// The "shape" field: the index of the shape it names.
bool read_kind(Reader& r, std::size_t* kind) {
    const Json* shape = r.need("shape");
    if (!shape) return false;
    *kind = shape->is_string() ? shape_index(shape->get_ref<const std::string&>()) : shape_count;
    if (*kind == shape_count) return r.fail("shape", "expected " + shape_names());
    return true;
}

bool read_k(Reader& r, int* out) {
    const Json* k = r.find("k");
    if (!k) return true;
    double x;
    if (!to_double(*k, &x) || x != std::floor(x) || std::fabs(x) > 1e6)
        return r.fail("k", "expected an integer from -1000000 to 1000000");
    *out = int(x);
    return true;
}

bool read_family(Reader& r, std::string* out) {
    const Json* f = r.find("family");
    if (!f) return true;
    if (!f->is_string()) return r.fail("family", "expected a string");
    *out = f->get<std::string>();
    return true;
}

// An id as its text in the line (every digit of a number kept), else as nlohmann reads it.
std::string id_text(std::string_view line, const char* key, const Json& id) {
    std::string raw = jsonl::member_text(line, key);
    return raw.empty() ? jsonl::dump(id) : raw;
}

bool parse_case_object(const Json& obj, std::string_view line, Case* c, std::string* why) {
    Reader r{obj, why};
    if (const Json* id = r.find("id")) c->id = id_text(line, "id", *id);
    if (r.find("scene") || r.find("shape_id"))
        return r.fail(r.find("scene") ? "scene" : "shape_id",
                      "a scene's record, where a single case is read (linequad solve and "
                      "linequad scenes read scenes)");
    std::size_t kind;
    if (!read_kind(r, &kind)) return false;
    for (const auto& m : obj.items()) {
        bool known = with_shape_type(
            kind, [&](auto tag) { return known_field<typename decltype(tag)::type>(m.key()); });
        if (!known)
            return r.fail(m.key(),
                          std::string("not a field of a ") + shape_name_at(kind) + " case");
    }

    if (!r.vec("L0", &c->line.L0) || !r.vec("v", &c->line.v)) return false;
    if (!read_range(r, &c->line.range)) return false;
    if (!read_family(r, &c->family) || !read_k(r, &c->k)) return false;
    if (const Json* p = r.find("precision")) {
        if (p->is_string() && p->get_ref<const std::string&>() == "binary32")
            c->precision = Precision::binary32;
        else if (!p->is_string() || p->get_ref<const std::string&>() != "binary64")
            return r.fail("precision", "expected binary64 or binary32");
    }
    bool shape_ok = with_shape_type(
        kind, [&](auto tag) { return read_shape<typename decltype(tag)::type>(r, &c->shape); });
    if (!shape_ok) return false;
    return c->precision == Precision::binary64 || all_binary32(r, *c);
}

// Every field of obj is one of `fields`, or (shape records) of the shape's kind.
bool only_fields(Reader& r, const Json& obj, std::initializer_list<const char*> fields,
                 const char* what) {
    for (const auto& m : obj.items())
        if (std::none_of(fields.begin(), fields.end(), [&](const char* f) { return m.key() == f; }))
            return r.fail(m.key(), std::string("not a field of ") + what);
    return true;
}

bool parse_scene_shape(Reader& r, const Json& obj, SceneShape* s) {
    std::size_t kind;
    if (!read_kind(r, &kind)) return false;
    for (const auto& m : obj.items()) {
        const std::string& key = m.key();
        bool known =
            key == "shape_id" || key == "shape" || key == "finite" || key == "caps" ||
            key == "note" || with_shape_type(kind, [&](auto tag) {
                using S = typename decltype(tag)::type;
                bool field = (key == "nappes" && has_nappes<S>) ||
                             (key == "coincident" && has_coincident<S>);
                detail::for_each_field<S>([&](const auto& f) { field = field || key == f.name; });
                return field;
            });
        if (!known)
            return r.fail(key, std::string("not a field of a scene's ") + shape_name_at(kind));
    }
    return with_shape_type(
        kind, [&](auto tag) { return read_shape<typename decltype(tag)::type>(r, &s->shape); });
}

} // namespace

bool parse_case(std::string_view line, Case* c, std::string* why) {
    *c = Case{};
    Json obj;
    if (!parse_object(line, &obj, why)) return false;
    return parse_case_object(obj, line, c, why);
}

bool parse_record(std::string_view line, Record* rec, std::string* why) {
    *rec = Record{};
    Json obj;
    if (!parse_object(line, &obj, why)) return false;
    Reader r{obj, why};
    if (const Json* id = r.find("scene")) {
        rec->kind = RecordKind::scene;
        rec->scene.id = id_text(line, "scene", *id);
        return only_fields(r, obj, {"scene", "family", "k", "note"}, "a scene") &&
               read_family(r, &rec->scene.family) && read_k(r, &rec->scene.k);
    }
    if (const Json* id = r.find("shape_id")) {
        rec->kind = RecordKind::scene_shape;
        rec->shape.id = id_text(line, "shape_id", *id);
        return parse_scene_shape(r, obj, &rec->shape);
    }
    if (r.find("shape")) {
        rec->kind = RecordKind::single_case;
        return parse_case_object(obj, line, &rec->single, why);
    }
    rec->kind = RecordKind::scene_line;
    if (const Json* id = r.find("id")) rec->line.id = id_text(line, "id", *id);
    return only_fields(r, obj, {"id", "L0", "v", "range", "t0", "t1", "note"},
                       "a scene's line (a single case names its \"shape\")") &&
           r.vec("L0", &rec->line.line.L0) && r.vec("v", &rec->line.line.v) &&
           read_range(r, &rec->line.line.range);
}

namespace {

// ,"shape":..., the shape's fields; returns its options (finite, caps, nappes) to put after.
std::string put_shape(std::string& out, const Shape& shape) {
    out += ",\"shape\":\"" + std::string(shape_name(shape)) + "\"";
    return std::visit(
        [&](const auto& s) {
            using S = std::decay_t<decltype(s)>;
            detail::for_each_field<S>([&](const auto& f) { put_field(out, f.name, s.*f.member); });
            std::string o;
            if constexpr (has_extent_options<S>) {
                o = s.finite ? ",\"finite\":true" : ",\"finite\":false";
                if (s.caps) o += ",\"caps\":true";
            }
            if constexpr (has_nappes<S>)
                if (s.nappes != 1) o += ",\"nappes\":" + std::to_string(s.nappes);
            if constexpr (has_coincident<S>)
                if (s.coincident) o += ",\"coincident\":true";
            return o;
        },
        shape);
}

// ,"L0", "v" and the range.
void put_line(std::string& out, const Line& l) {
    put_field(out, "L0", l.L0);
    put_field(out, "v", l.v);
    Range range;
    if (shorthand(l.range, &range)) {
        out += ",\"range\":\"" + std::string(range_name(range)) + "\"";
    } else {
        if (l.range.has_t0()) put_field(out, "t0", l.range.t0);
        if (l.range.has_t1()) put_field(out, "t1", l.range.t1);
    }
}

} // namespace

std::string format_case(const Case& c) {
    std::string out = "{\"id\":" + c.id;
    std::string options = put_shape(out, c.shape);
    put_line(out, c.line);
    out += options;
    if (!c.family.empty()) out += ",\"family\":" + json_string(c.family);
    if (!c.family.empty() || c.k != 0) out += ",\"k\":" + std::to_string(c.k);
    if (c.precision == Precision::binary32) out += ",\"precision\":\"binary32\"";
    out += "}";
    return out;
}

std::string format_result(const std::string& id, std::string_view solver, const Result& r,
                          Carries carries) {
    // A refusal of another library's own is written under its own name, as it was read.
    if (!r.ok())
        return format_failure(id, solver,
                              r.error_code == ErrorCode::foreign ? r.error_field
                                                                 : code_name(r.error_code),
                              message(r.error()));
    std::string out = "{\"id\":" + id + ",\"solver\":" + json_string(solver) + ",\"hits\":[";
    for (int i = 0; i < r.count; ++i) {
        const Hit& h = r.hits[i];
        if (i) out += ",";
        out += "{\"t\":\"" + hex(h.t) + "\"";
        if (carries.kinds)
            out += h.kind == HitKind::tangent ? ",\"kind\":\"tangent\"" : ",\"kind\":\"cross\"";
        if (carries.parts) out += ",\"part\":\"" + std::string(part_name(h.part)) + "\"";
        if (carries.points) put_field(out, "p", h.p);
        if (!std::isnan(h.bound)) {
            put_field(out, "bound", h.bound);
            out += h.certain ? ",\"certain\":true" : ",\"certain\":false";
        }
        out += "}";
    }
    out += "],\"on_surface\":";
    if (!r.on_surface) {
        out += "null";
    } else {
        auto end = [](double t) {
            return std::isinf(t) ? std::string("null") : "\"" + hex(t) + "\"";
        };
        out += "[" + end(r.s0) + "," + end(r.s1) + "]";
        if (carries.parts)
            out += ",\"surface_part\":\"" + std::string(part_name(r.surface_part)) + "\"";
    }
    if (r.certainty != Certainty::unknown)
        out += r.certainty == Certainty::certain ? ",\"certain\":true" : ",\"certain\":false";
    out += "}";
    return out;
}

std::string format_scene(const SceneHeader& s) {
    std::string out = "{\"scene\":" + s.id;
    if (!s.family.empty()) out += ",\"family\":" + json_string(s.family);
    if (!s.family.empty() || s.k != 0) out += ",\"k\":" + std::to_string(s.k);
    return out + "}";
}

std::string format_scene_shape(const SceneShape& s) {
    std::string out = "{\"shape_id\":" + s.id;
    std::string options = put_shape(out, s.shape);
    return out + options + "}";
}

std::string format_scene_line(const SceneLine& l) {
    std::string out = "{\"id\":" + l.id;
    put_line(out, l.line);
    return out + "}";
}

std::string format_scene_answer(const std::string& id, std::string_view solver,
                                const SceneHeader& scene, const std::vector<std::string>& shape_ids,
                                const SceneAnswer& a, bool points) {
    auto shape_id = [&](std::uint32_t i) {
        return i < shape_ids.size() ? shape_ids[i] : std::string("null");
    };
    std::string out =
        "{\"id\":" + id + ",\"solver\":" + json_string(solver) + ",\"scene\":" + scene.id;
    if (!a.ok())
        return out + ",\"error\":" + json_string(message(a.error)) +
               ",\"code\":" + json_string(code_name(a.error.code)) +
               ",\"shape\":" + shape_id(a.error_shape) + "}";
    out += ",\"hits\":[";
    for (std::size_t i = 0; i < a.hits.size(); ++i) {
        const SceneHit& h = a.hits[i];
        if (i) out += ",";
        out += "{\"t\":\"" + hex(h.hit.t) + "\",\"kind\":\"";
        out += h.hit.kind == HitKind::tangent ? "tangent\"" : "cross\"";
        out += ",\"part\":\"" + std::string(part_name(h.hit.part)) + "\"";
        if (points) put_field(out, "p", h.hit.p);
        out += ",\"shape\":" + shape_id(h.shape);
        out += h.tied ? ",\"tied\":true}" : ",\"tied\":false}";
    }
    out += "],\"shapes_solved\":" + std::to_string(a.shapes_solved);
    out += ",\"exact_comparisons\":" + std::to_string(a.exact_comparisons) + "}";
    return out;
}

std::string format_failure(const std::string& id, std::string_view solver, std::string_view code,
                           std::string_view message) {
    return "{\"id\":" + id + ",\"solver\":" + json_string(solver) +
           ",\"error\":" + json_string(message) + ",\"code\":" + json_string(code) + "}";
}

namespace {

// The surfaces a model and a sense query take, by their "shape", and each one's own fields.
const std::map<std::string, std::vector<std::string>>& surface_kinds() {
    static const std::map<std::string, std::vector<std::string>> kinds = {
        {"plane", {"n", "d"}},
        {"quadric", {"q"}},
        {"sphere", {"C", "r"}},
        {"cylinder", {"C", "H", "r"}}};
    return kinds;
}
// Reads `shape` into *kind: one of surface_kinds(), or fails naming them.
bool read_surface_kind(Reader& r, std::string* kind) {
    const Json* shape = r.need("shape");
    if (!shape) return false;
    *kind = shape->is_string() ? shape->get<std::string>() : "";
    if (!surface_kinds().count(*kind))
        return r.fail("shape", "expected plane, quadric, sphere or cylinder");
    return true;
}
// Whether field f is one of kind's own or one of `common`.
bool surface_field(const std::string& kind, const std::string& f,
                   std::initializer_list<const char*> common) {
    for (const char* c : common)
        if (f == c) return true;
    const std::vector<std::string>& own = surface_kinds().at(kind);
    return std::find(own.begin(), own.end(), f) != own.end();
}

// A plane's fields ("n", "d"), a quadric's ("q"), a sphere's ("C", "r") or a cylinder's ("C",
// "H", "r": infinite, along a coordinate axis), `kind` being one of them.
bool read_surface(Reader& r, const std::string& kind, SurfaceShape* out) {
    if (kind == "plane") {
        Plane plane{};
        if (!r.vec("n", &plane.n) || !r.number("d", &plane.d)) return false;
        *out = plane;
    } else if (kind == "sphere") {
        Sphere sphere{};
        if (!r.vec("C", &sphere.C) || !r.number("r", &sphere.r)) return false;
        *out = sphere;
    } else if (kind == "cylinder") {
        Cylinder cylinder{};
        cylinder.finite = false;
        if (!r.vec("C", &cylinder.C) || !r.vec("H", &cylinder.H) || !r.number("r", &cylinder.r))
            return false;
        *out = cylinder;
    } else {
        Quadric quadric{};
        if (!r.coefficients("q", &quadric.q)) return false;
        *out = quadric;
    }
    return true;
}

// A model's id: a JSON integer from 1 to 2^63 - 1 (OpenMC's ids are positive).
bool read_id(Reader& r, std::int64_t* out) {
    const Json* id = r.need("id");
    if (!id) return false;
    if (!id->is_number_integer() ||
        (id->is_number_unsigned() && id->get<std::uint64_t>() > std::uint64_t(INT64_MAX)) ||
        (!id->is_number_unsigned() && id->get<std::int64_t>() < 1))
        return r.fail("id", "expected a positive integer");
    *out =
        id->is_number_unsigned() ? std::int64_t(id->get<std::uint64_t>()) : id->get<std::int64_t>();
    return true;
}

} // namespace

bool parse_model(std::string_view text, ModelFile* out, std::string* why) {
    *out = ModelFile{};
    std::vector<Model::Surface>* surfaces = &out->surfaces;
    std::vector<Model::CellSource>* cells = &out->cells;
    Json doc;
    std::string err;
    if (!jsonl::parse(text, &doc, &err)) return *why = "not valid JSON: " + err, false;
    jsonl::ReleaseOnUnwind release(doc);
    if (!doc.is_object()) return *why = "not a JSON object", false;
    Reader top{doc, why};
    if (!only_fields(top, doc, {"surfaces", "cells", "box", "note"}, "a model")) return false;
    if (const Json* box = top.find("box")) {
        Json corners = Json::object();
        if (box->is_array() && box->size() == 2) corners = {{"lo", (*box)[0]}, {"hi", (*box)[1]}};
        Reader b{corners, why};
        std::array<Vec3, 2> at{};
        if (!box->is_array() || box->size() != 2 || !b.vec("lo", &at[0]) || !b.vec("hi", &at[1]))
            return top.fail("box", "expected [[x0, y0, z0], [x1, y1, z1]]");
        if (!(at[0].x < at[1].x && at[0].y < at[1].y && at[0].z < at[1].z) ||
            !std::isfinite(at[1].x - at[0].x + at[1].y - at[0].y + at[1].z - at[0].z))
            return top.fail("box", "expected finite corners, the first below the second");
        out->box = at;
    }
    const Json* s = top.need("surfaces");
    const Json* c = s ? top.need("cells") : nullptr;
    if (!s || !c) return false;
    if (!s->is_array()) return top.fail("surfaces", "expected an array");
    if (!c->is_array()) return top.fail("cells", "expected an array");
    // Each element of a model's array, read by `read` (an object's Reader), its errors prefixed
    // with the element: "surfaces[3]: field "q": ...".
    auto each = [&](const Json& array, const char* name, auto read) {
        for (std::size_t i = 0; i < array.size(); ++i) {
            const Json& obj = array[i];
            std::string inner;
            Reader r{obj, &inner};
            if (!obj.is_object()) inner = "not a JSON object";
            if (!obj.is_object() || !read(r, obj)) {
                *why = std::string(name) + "[" + std::to_string(i) + "]: " + inner;
                return false;
            }
        }
        return true;
    };
    bool surfaces_read = each(*s, "surfaces", [&](Reader& r, const Json& obj) {
        Model::Surface surface{};
        std::string kind;
        if (!read_surface_kind(r, &kind)) return false;
        for (const auto& m : obj.items())
            if (!surface_field(kind, m.key(), {"id", "shape", "note"}))
                return r.fail(m.key(), "not a field of a model's " + kind);
        if (!read_id(r, &surface.id) || !read_surface(r, kind, &surface.shape)) return false;
        surfaces->push_back(surface);
        return true;
    });
    return surfaces_read && each(*c, "cells", [&](Reader& r, const Json& obj) {
               Model::CellSource cell{};
               if (!only_fields(r, obj, {"id", "name", "region", "note"}, "a model's cell") ||
                   !read_id(r, &cell.id))
                   return false;
               const Json* region = r.need("region");
               if (!region) return false;
               if (!region->is_string()) return r.fail("region", "expected a string");
               cell.region = region->get<std::string>();
               if (const Json* name = r.find("name")) {
                   if (!name->is_string()) return r.fail("name", "expected a string");
                   cell.name = name->get<std::string>();
               }
               cells->push_back(std::move(cell));
               return true;
           });
}

bool parse_sense_query(std::string_view line, SenseQuery* q, std::string* why) {
    *q = SenseQuery{};
    Json obj;
    if (!parse_object(line, &obj, why)) return false;
    Reader r{obj, why};
    if (const Json* id = r.find("id")) q->id = id_text(line, "id", *id);
    std::string kind;
    if (!read_surface_kind(r, &kind)) return false;
    for (const auto& m : obj.items())
        if (!surface_field(kind, m.key(), {"id", "shape", "p", "u"}))
            return r.fail(m.key(), "not a field of a " + kind + " sense query");
    if (!read_surface(r, kind, &q->surface)) return false;
    if (!r.vec("p", &q->p)) return false;
    if (r.find("u")) {
        Vec3 u;
        if (!r.vec("u", &u)) return false;
        q->u = u;
    }
    return true;
}

std::string format_sense(const std::string& id, const SenseResult& r) {
    if (!r.ok()) return format_failure(id, "sense", code_name(r.error.code), message(r.error));
    return "{\"id\":" + id + ",\"sense\":" + json_string(sense_name(r.sense)) +
           ",\"sign\":" + std::to_string(int(r.sense)) + "}";
}

// A result line's hits, into pr (at most max_hits, checked by the caller).
bool read_hits(Reader& r, const Json& hits, ParsedResult* pr, std::string* why) {
    for (const Json& h : hits) {
        Reader hr{h, why};
        Hit& out = pr->result.hits[pr->result.count++];
        out = Hit{0,    {}, std::numeric_limits<double>::quiet_NaN(), HitKind::cross, Part::lateral,
                  false};
        if (!h.is_object() || !hr.number("t", &out.t))
            return r.fail("hits", "each hit needs t, a number");
        if (const Json* kind = hr.find("kind")) {
            if (!kind->is_string() || (*kind != "cross" && *kind != "tangent"))
                return r.fail("hits", "kind must be cross or tangent");
            out.kind = *kind == "tangent" ? HitKind::tangent : HitKind::cross;
            pr->has_kinds = true;
        }
        if (const Json* part = hr.find("part")) {
            if (!read_part(*part, &out.part))
                return r.fail("hits", "part must be lateral, base or top");
            pr->has_parts = true;
        }
        if (hr.find("p")) {
            if (!hr.vec("p", &out.p)) return r.fail("hits", "p must be 3 numbers");
            pr->has_points = true;
        }
        if (hr.find("bound") && !hr.number("bound", &out.bound))
            return r.fail("hits", "bound must be a number");
        if (const Json* c = hr.find("certain")) {
            if (!c->is_boolean()) return r.fail("hits", "certain must be true or false");
            out.certain = c->get<bool>();
        }
    }
    return true;
}

bool parse_result(std::string_view line, ParsedResult* pr, std::string* why) {
    *pr = ParsedResult{};
    Json obj;
    if (!parse_object(line, &obj, why)) return false;
    Reader r{obj, why};
    const Json* id = r.need("id");
    if (!id) return false;
    pr->id = id_text(line, "id", *id);
    pr->has_id = true;
    if (const Json* s = r.find("solver")) {
        if (!s->is_string()) return r.fail("solver", "expected a solver's name");
        pr->solver = s->get<std::string>();
    }
    if (const Json* e = r.find("error")) {
        if (!e->is_string()) return r.fail("error", "expected a message");
        pr->error_message = e->get<std::string>();
        const Json* code = r.find("code");
        if (code && !code->is_string()) return r.fail("code", "expected a string");
        pr->error_code = code ? code->get<std::string>() : "error";
        // The code names the kind of refusal. One that is not linequad's is the solver's own
        // (ErrorCode::foreign), kept by its name: a refusal the oracle never makes.
        pr->result.error_code = ErrorCode::foreign;
        pr->result.error_field = interned(pr->error_code);
        for (int c = int(ErrorCode::not_a_number); c < int(ErrorCode::foreign); ++c)
            if (pr->error_code == code_name(ErrorCode(c)))
                pr->result.error_code = ErrorCode(c), pr->result.error_field = "";
        return true;
    }
    const Json* hits = r.need("hits");
    if (!hits) return false;
    if (!hits->is_array() || hits->size() > std::size_t(max_hits))
        return r.fail("hits", "expected an array of at most " + std::to_string(max_hits) + " hits");
    if (!read_hits(r, *hits, pr, why)) return false;
    const Json* on = r.find("on_surface");
    if (on && on->is_array()) {
        if (on->size() != 2) return r.fail("on_surface", "expected [t0, t1]");
        double e[2];
        for (int i = 0; i < 2; ++i) {
            if ((*on)[i].is_null())
                e[i] = i == 0 ? -INFINITY : INFINITY;
            else if (!to_double((*on)[i], &e[i]))
                return r.fail("on_surface", "expected numbers or null");
        }
        pr->result.on_surface = true;
        pr->result.s0 = e[0], pr->result.s1 = e[1];
        if (const Json* part = r.find("surface_part")) {
            if (!read_part(*part, &pr->result.surface_part))
                return r.fail("surface_part", "expected lateral, base or top");
            pr->has_parts = true;
        }
    } else if (on && !on->is_null()) {
        return r.fail("on_surface", "expected null or [t0, t1]");
    }
    if (const Json* c = r.find("certain")) {
        if (!c->is_boolean()) return r.fail("certain", "expected true or false");
        pr->result.certainty = c->get<bool>() ? Certainty::certain : Certainty::uncertain;
    }
    return true;
}

} // namespace linequad
