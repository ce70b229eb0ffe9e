#include "linequad/case_io.hpp"

#include "shape_types.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>

namespace linequad {

std::string hex(double x) {
    if (std::isnan(x)) return "nan";
    if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
    char buf[40];
    std::snprintf(buf, sizeof buf, "%a", x);
    return buf;
}

namespace {

using json::Value;

bool to_double(const Value& v, double* out) {
    if (v.type != Value::Type::number && v.type != Value::Type::string) return false;
    const std::string& s = v.text;
    if (s.empty() || std::isspace(static_cast<unsigned char>(s[0]))) return false;
    if (s == "nan" || s == "-nan") return *out = std::numeric_limits<double>::quiet_NaN(), true;
    char* end = nullptr;
    errno = 0;
    double x = std::strtod(s.c_str(), &end); // correctly rounded for decimal and hex (glibc)
    if (end != s.c_str() + s.size()) return false;
    *out = x; // overflow gives inf (reported later as infinite input), underflow the subnormal
    return true;
}

struct Reader {
    const Value& obj;
    std::string* why;

    bool fail(std::string_view field, std::string_view what) {
        *why = "field \"" + std::string(field) + "\": " + std::string(what);
        return false;
    }
    const Value* need(const char* field) {
        const Value* v = obj.find(field);
        if (!v) fail(field, "missing");
        return v;
    }
    bool number(const char* field, double* out) {
        const Value* v = need(field);
        if (!v) return false;
        if (!to_double(*v, out)) return fail(field, "expected a number (hex-float or decimal)");
        return true;
    }
    bool vec(const char* field, Vec3* out) {
        const Value* v = need(field);
        if (!v) return false;
        double c[3];
        if (v->type != Value::Type::array || v->items.size() != 3 ||
            !to_double(v->items[0], &c[0]) || !to_double(v->items[1], &c[1]) ||
            !to_double(v->items[2], &c[2]))
            return fail(field, "expected an array of 3 numbers");
        *out = {c[0], c[1], c[2]};
        return true;
    }
};

// Fields every case may have, whatever its shape.
const char* const common_fields[] = {"id", "shape",  "L0",     "v", "range", "t0",
                                     "t1", "finite", "family", "k", "note"};

template <class S>
bool known_field(const std::string& key) {
    for (const char* f : common_fields)
        if (key == f) return true;
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

// The shape's own fields, from its table.
template <class S>
bool read_shape(Reader& r, bool finite, Shape* out) {
    S s;
    bool ok = true;
    detail::for_each_field<S>(
        [&](const auto& f) { ok = ok && read_field(r, f.name, &(s.*f.member)); });
    s.finite = finite;
    *out = s;
    return ok;
}

constexpr Range shorthands[] = {Range::line, Range::ray, Range::segment};

// The range: a shorthand ("range"), or its ends ("t0", "t1"; either may be left out, or be
// "inf" or "-inf"), not both.
bool read_range(Reader& r, const Value& obj, Interval* out) {
    const Value *range = obj.find("range"), *t0 = obj.find("t0"), *t1 = obj.find("t1");
    if (range && (t0 || t1)) return r.fail(t0 ? "t0" : "t1", "give either range or t0, t1");
    if (range) {
        if (range->type != Value::Type::string) return r.fail("range", "expected a string");
        for (Range x : shorthands)
            if (range->text == range_name(x)) return *out = x, true;
        return r.fail("range", "expected line, ray or segment");
    }
    Interval i;
    if (t0 && !r.number("t0", &i.t0)) return false;
    if (t1 && !r.number("t1", &i.t1)) return false;
    *out = i;
    return true;
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

// The shorthand an interval is, if any.
bool shorthand(Interval i, Range* r) {
    for (Range x : shorthands)
        if (i == Interval(x)) return *r = x, true;
    return false;
}

} // namespace

bool parse_case(std::string_view line, Case* c, std::string* why) {
    *c = Case{};
    Value obj;
    std::string err;
    if (!json::parse(line, &obj, &err)) {
        *why = "not valid JSON: " + err;
        return false;
    }
    if (obj.type != Value::Type::object) {
        *why = "not a JSON object";
        return false;
    }
    if (const Value* id = obj.find("id")) {
        c->id.clear();
        json::write(c->id, *id);
    }
    Reader r{obj, why};
    const Value* shape = r.need("shape");
    if (!shape) return false;
    std::size_t kind = shape->type == Value::Type::string ? shape_index(shape->text) : shape_count;
    if (kind == shape_count) return r.fail("shape", "expected " + shape_names());
    for (const auto& m : obj.members) {
        bool known = with_shape_type(
            kind, [&](auto tag) { return known_field<typename decltype(tag)::type>(m.first); });
        if (!known)
            return r.fail(m.first,
                          std::string("not a field of a ") + shape_name_at(kind) + " case");
    }

    if (!r.vec("L0", &c->line.L0) || !r.vec("v", &c->line.v)) return false;
    if (!read_range(r, obj, &c->line.range)) return false;
    bool finite = true;
    if (const Value* f = obj.find("finite")) {
        if (f->type != Value::Type::boolean) return r.fail("finite", "expected true or false");
        finite = f->boolean;
    }
    if (const Value* f = obj.find("family")) {
        if (f->type != Value::Type::string) return r.fail("family", "expected a string");
        c->family = f->text;
    }
    if (const Value* k = obj.find("k")) {
        double x;
        if (!to_double(*k, &x) || x != std::floor(x) || std::fabs(x) > 1e6)
            return r.fail("k", "expected an integer");
        c->k = int(x);
    }
    return with_shape_type(kind, [&](auto tag) {
        return read_shape<typename decltype(tag)::type>(r, finite, &c->shape);
    });
}

std::string format_case(const Case& c) {
    std::string out = "{\"id\":" + c.id + ",\"shape\":\"" + shape_name(c.shape) + "\"";
    bool finite = std::visit(
        [&](const auto& s) {
            using S = std::decay_t<decltype(s)>;
            detail::for_each_field<S>([&](const auto& f) { put_field(out, f.name, s.*f.member); });
            return s.finite;
        },
        c.shape);
    put_field(out, "L0", c.line.L0);
    put_field(out, "v", c.line.v);
    Range range;
    if (shorthand(c.line.range, &range)) {
        out += ",\"range\":\"" + std::string(range_name(range)) + "\"";
    } else {
        if (c.line.range.has_t0()) put_field(out, "t0", c.line.range.t0);
        if (c.line.range.has_t1()) put_field(out, "t1", c.line.range.t1);
    }
    out += finite ? ",\"finite\":true" : ",\"finite\":false";
    if (!c.family.empty()) {
        out += ",\"family\":";
        json::write_string(out, c.family);
        out += ",\"k\":" + std::to_string(c.k);
    }
    out += "}";
    return out;
}

std::string format_result(const std::string& id, std::string_view solver, const Result& r,
                          bool points) {
    if (!r.ok()) return format_failure(id, solver, code_name(r.error_code), message(r.error()));
    std::string out = "{\"id\":" + id + ",\"solver\":";
    json::write_string(out, solver);
    out += ",\"hits\":[";
    for (int i = 0; i < r.count; ++i) {
        const Hit& h = r.hits[i];
        if (i) out += ",";
        out += "{\"t\":\"" + hex(h.t) + "\",\"kind\":\"";
        out += h.kind == HitKind::tangent ? "tangent\"" : "cross\"";
        if (points) put_field(out, "p", h.p);
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
    }
    if (r.certainty != Certainty::unknown)
        out += r.certainty == Certainty::certain ? ",\"certain\":true" : ",\"certain\":false";
    out += "}";
    return out;
}

std::string format_failure(const std::string& id, std::string_view solver, std::string_view code,
                           std::string_view message) {
    std::string out = "{\"id\":" + id + ",\"solver\":";
    json::write_string(out, solver);
    out += ",\"error\":";
    json::write_string(out, message);
    out += ",\"code\":";
    json::write_string(out, code);
    out += "}";
    return out;
}

bool parse_result(std::string_view line, ParsedResult* pr, std::string* why) {
    *pr = ParsedResult{};
    Value obj;
    std::string err;
    if (!json::parse(line, &obj, &err)) return *why = "not valid JSON: " + err, false;
    if (obj.type != Value::Type::object) return *why = "not a JSON object", false;
    Reader r{obj, why};
    if (const Value* id = obj.find("id"))
        json::write(pr->id, *id);
    else
        return r.fail("id", "missing");
    if (const Value* s = obj.find("solver"); s && s->type == Value::Type::string)
        pr->solver = s->text;
    if (const Value* e = obj.find("error")) {
        pr->error_message = e->type == Value::Type::string ? e->text : "error";
        const Value* code = obj.find("code");
        pr->error_code = code && code->type == Value::Type::string ? code->text : "error";
        // The code names the kind of refusal. One that no solver of linequad's gives stands as
        // out_of_range, a refusal the oracle never makes: it is graded as refused.
        pr->result.error_code = ErrorCode::out_of_range;
        for (int c = int(ErrorCode::not_a_number); c <= int(ErrorCode::out_of_range); ++c)
            if (pr->error_code == code_name(ErrorCode(c))) pr->result.error_code = ErrorCode(c);
        pr->result.error_field = "";
        return true;
    }
    const Value* hits = r.need("hits");
    if (!hits) return false;
    if (hits->type != Value::Type::array || hits->items.size() > 2)
        return r.fail("hits", "expected an array of at most 2 hits");
    for (const Value& h : hits->items) {
        Reader hr{h, why};
        Hit& out = pr->result.hits[pr->result.count++];
        out = Hit{0, {}, std::numeric_limits<double>::quiet_NaN(), HitKind::cross, false};
        if (h.type != Value::Type::object || !hr.number("t", &out.t))
            return r.fail("hits", "each hit needs t");
        const Value* kind = h.find("kind");
        if (!kind || kind->type != Value::Type::string ||
            (kind->text != "cross" && kind->text != "tangent"))
            return r.fail("hits", "kind must be cross or tangent");
        out.kind = kind->text == "tangent" ? HitKind::tangent : HitKind::cross;
        if (h.find("p")) {
            if (!hr.vec("p", &out.p)) return r.fail("hits", "p must be 3 numbers");
            pr->has_points = true;
        }
        if (h.find("bound") && !hr.number("bound", &out.bound))
            return r.fail("hits", "bound must be a number");
        if (const Value* c = h.find("certain"))
            out.certain = c->type == Value::Type::boolean && c->boolean;
    }
    const Value* on = obj.find("on_surface");
    if (on && on->type == Value::Type::array) {
        if (on->items.size() != 2) return r.fail("on_surface", "expected [t0, t1]");
        double e[2];
        for (int i = 0; i < 2; ++i) {
            if (on->items[i].type == Value::Type::null)
                e[i] = i == 0 ? -INFINITY : INFINITY;
            else if (!to_double(on->items[i], &e[i]))
                return r.fail("on_surface", "expected numbers or null");
        }
        pr->result.on_surface = true;
        pr->result.s0 = e[0], pr->result.s1 = e[1];
    } else if (on && on->type != Value::Type::null) {
        return r.fail("on_surface", "expected null or [t0, t1]");
    }
    if (const Value* c = obj.find("certain")) {
        if (c->type != Value::Type::boolean) return r.fail("certain", "expected true or false");
        pr->result.certainty = c->boolean ? Certainty::certain : Certainty::uncertain;
    }
    return true;
}

} // namespace linequad
