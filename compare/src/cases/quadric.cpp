// The general quadric's cases, and the constructions the plane's share (cases/surfaces.hpp).
#include "cases/surfaces.hpp"

namespace linequad {
namespace surfaces {

namespace {

// f(y) = a y_x^2 + b y_y^2 + c y_z^2 + g . y + k, and a point y0 = N x0 on it (x0 integer; N is
// R^T R's factor).
struct Local {
    Vec3 diag{}, g{};
    double k = 0;
    Vec3 x0{};
};

int nonzero(Rng& r, int lo, int hi) {
    int x = r.integer(lo, hi);
    return x == 0 ? 1 : x;
}

// The kind's local form, its point x0, and k from it (f(N x0) = 0) unless the kind fixes k.
Local local_form(Kind kind, Rng& r, double N, int thin) {
    double a = r.integer(1, 4), b = r.integer(1, 4), c = r.integer(1, 4);
    Local l;
    Vec3 x0{double(r.integer(-2, 2)), double(r.integer(-2, 2)), double(r.integer(-2, 2))};
    auto value = [&](Vec3 x) {
        Vec3 y = N * x;
        return l.diag.x * y.x * y.x + l.diag.y * y.y * y.y + l.diag.z * y.z * y.z + dot(l.g, y);
    };
    switch (kind) {
    case Kind::ellipsoid:
        // thin: one axis 2^-thin of the others (its coefficient 2^(2 thin)), the point on a
        // long axis.
        l.diag = {a, b, thin > 0 ? std::ldexp(c, 2 * thin) : c};
        if (thin > 0) x0 = {double(nonzero(r, -2, 2)), 0, 0};
        if (x0 == Vec3{}) x0.x = 1;
        break;
    case Kind::one_sheet:
    case Kind::two_sheets:
        l.diag = {a, b, -c};
        // One sheet: f(y0) > 0 before k (k < 0); two sheets: < 0.
        x0 = kind == Kind::one_sheet ? Vec3{double(nonzero(r, -2, 2)), x0.y, 0}
                                     : Vec3{0, 0, double(nonzero(r, -2, 2))};
        break;
    case Kind::cone: {
        // x^2 + y^2 = z^2 scaled by a: a Pythagorean triple on it.
        static const Vec3 triples[] = {{3, 4, 5}, {4, 3, 5}, {1, 0, 1}, {0, 1, 1}, {0, 0, 0}};
        l.diag = {a, a, -a};
        x0 = triples[r.integer(0, 4)];
        x0 = {r.coin() ? x0.x : -x0.x, r.coin() ? x0.y : -x0.y, r.coin() ? x0.z : -x0.z};
        break;
    }
    case Kind::elliptic_paraboloid:
        l.diag = {a, b, 0}, l.g = {0, 0, -c};
        break;
    case Kind::hyperbolic_paraboloid:
        l.diag = {a, -b, 0}, l.g = {0, 0, -c};
        break;
    case Kind::cylinder:
        l.diag = {a, thin > 0 ? std::ldexp(b, 2 * thin) : b, 0};
        x0 = {double(nonzero(r, -2, 2)), thin > 0 ? 0.0 : x0.y, x0.z};
        break;
    case Kind::plane_pair: // a (x - y)(x + y) = 0
        l.diag = {a, -a, 0};
        x0.y = r.coin() ? x0.x : -x0.x;
        break;
    case Kind::parallel_planes: // a x^2 = a x0^2
        l.diag = {a, 0, 0};
        x0.x = nonzero(r, -2, 2);
        break;
    case Kind::line: // rank 2, semidefinite: the z axis
        l.diag = {a, b, 0}, x0.x = x0.y = 0;
        break;
    case Kind::point:
        l.diag = {a, b, c}, x0 = {};
        break;
    case Kind::empty:
        l.diag = {a, b, c}, l.x0 = {};
        l.k = r.integer(1, 9);
        return l;
    case Kind::plane:
        l.g = direction(r);
        break;
    }
    l.x0 = x0;
    l.k = -value(x0);
    return l;
}

} // namespace

Vec3 direction(Rng& r) {
    Vec3 d = r.ivec(3);
    while (d == Vec3{})
        d = r.ivec(3);
    return d;
}

Built build(Kind kind, Rng& r, bool rotate, int thin) {
    IntegerRotation R{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, 1};
    if (rotate) R = integer_rotation(r);
    Local l = local_form(kind, r, R.N * R.N, thin); // R^T R = N^2 I: y0 = N^2 x0
    Vec3 O = r.ivec(6);
    // World form about O: S = R diag R^T (symmetric), linear R g.
    double S[3][3];
    Vec3 dg = l.diag;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            S[i][j] = R.col[0][i] * dg.x * R.col[0][j] + R.col[1][i] * dg.y * R.col[1][j] +
                      R.col[2][i] * dg.z * R.col[2][j];
    Vec3 gl = l.g.x * R.col[0] + l.g.y * R.col[1] + l.g.z * R.col[2];
    // f(x) = (x - O)^T S (x - O) + gl . (x - O) + k, expanded.
    double A = S[0][0], B = S[1][1], C = S[2][2], D = 2 * S[0][1], E = 2 * S[1][2], F = 2 * S[2][0];
    double G = gl.x - (2 * A * O.x + D * O.y + F * O.z);
    double H = gl.y - (2 * B * O.y + D * O.x + E * O.z);
    double J = gl.z - (2 * C * O.z + E * O.y + F * O.x);
    double K = A * O.x * O.x + B * O.y * O.y + C * O.z * O.z + D * O.x * O.y + E * O.y * O.z +
               F * O.z * O.x - dot(gl, O) + l.k;
    Built b;
    b.q = Quadric{{A, B, C, D, E, F, G, H, J, K}};
    Vec3 x = l.x0.x * R.col[0] + l.x0.y * R.col[1] + l.x0.z * R.col[2]; // R x0 = P - O
    b.P = O + x;
    b.n = Vec3{2 * (S[0][0] * x.x + S[0][1] * x.y + S[0][2] * x.z),
               2 * (S[1][0] * x.x + S[1][1] * x.y + S[1][2] * x.z),
               2 * (S[2][0] * x.x + S[2][1] * x.y + S[2][2] * x.z)} +
          gl;
    b.O = O, b.axis = R.col[2];
    return b;
}

namespace {

Kind any_kind(Rng& r) {
    return Kind(r.integer(0, nondegenerate_kinds - 1));
}

// A direction across n (tangent at the point), nonzero: n x e_i for the e_i least along n.
Vec3 across(Vec3 n, Rng& r) {
    Vec3 e[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    Vec3 best = cross(n, e[r.integer(0, 2)]);
    for (const Vec3& u : e)
        if (max_abs(best) == 0) best = cross(n, u);
    return best == Vec3{} ? direction(r) : best;
}

Case make(const Quadric& q, Vec3 L0, Vec3 v) {
    Case c;
    c.shape = q;
    c.line = Line{L0, v};
    return c;
}

// A line through P at parameter s (an integer or eighths: exact).
Line through(Vec3 P, Vec3 d, Rng& r) {
    double s = r.integer(-32, 32) * 0.125;
    return {P - s * d, d};
}

} // namespace

bool quadric_applies(Family f) {
    switch (f) {
    case Family::generic:
    case Family::near_tangent:
    case Family::axis_parallel:
    case Family::apex:
    case Family::degenerate_frame:
    case Family::scale:
    case Family::far_origin:
    case Family::inside_start:
    case Family::thin:
        return true;
    default:
        return false;
    }
}

Case quadric_case(Family f, Rng& r, int k, Frames frames, Precision p) {
    bool rotate = frames == Frames::any && r.coin();
    double off = std::ldexp(1.0, -k) * (r.coin() ? 1 : -1); // 2^-k beside, either side
    switch (f) {
    case Family::generic: {
        Built b = build(any_kind(r), r, rotate);
        Line l = through(b.P, direction(r), r);
        return make(b.q, l.L0, l.v);
    }
    case Family::near_tangent: {
        // Tangent at P (k = 0: exactly; a ruled surface's tangent may lie on it), else moved
        // 2^-k along the gradient.
        Built b = build(any_kind(r), r, rotate);
        Vec3 d = across(b.n, r);
        Line l = through(b.P, d, r);
        if (k > 0) l.L0 = l.L0 + off * b.n;
        return make(b.q, l.L0, l.v);
    }
    case Family::axis_parallel: {
        // Along a cylinder's (or parallel planes') axis: on the surface through P, or 2^-k
        // inside or outside; tilted by 2^-k across it.
        Kind kind = r.coin() ? Kind::cylinder : Kind::parallel_planes;
        Built b = build(kind, r, rotate);
        Vec3 d = b.axis;
        Vec3 L0 = b.P - double(r.integer(-4, 4)) * d;
        if (k > 0) {
            if (r.coin())
                L0 = L0 + off * b.n;
            else
                d = d + off * b.n;
        }
        return make(b.q, L0, d);
    }
    case Family::apex: {
        // Through a cone's apex or a hyperboloid's centre (the throat), or 2^-k beside it.
        Built b = build(r.coin() ? Kind::cone : Kind::one_sheet, r, rotate);
        Vec3 d = r.coin() ? b.axis : direction(r);
        Vec3 L0 = b.O - double(r.integer(-4, 4)) * d;
        if (k > 0) L0 = L0 + off * across(d, r);
        return make(b.q, L0, d);
    }
    case Family::degenerate_frame: {
        // Every degenerate quadric: plane pairs, a line, a point, nothing, a plane in GQ form;
        // lines through its point (or beside it by 2^-k).
        Kind kind = Kind(r.integer(nondegenerate_kinds, kind_count - 1));
        Built b = build(kind, r, rotate);
        Line l = through(b.P, direction(r), r);
        if (r.coin()) l.L0 = l.L0 + off * across(l.v, r);
        return make(b.q, l.L0, l.v);
    }
    case Family::scale: {
        // Half: the same surface written 2^e q (e = +-k): every answer must be the unscaled
        // one's. Half: a surface of size 2^j (j = +-k/2) and its line, scaled with it: f(x / 2^j)
        // times 2^2j keeps the quadratic part and takes the linear part times 2^j, K times 2^2j
        // (exact: powers of two), and the line's t does not change.
        Built b = build(Kind(r.integer(0, kind_count - 2)), r, rotate);
        Line l = through(b.P, direction(r), r);
        bool binary32 = p == Precision::binary32;
        if (r.coin()) {
            // binary32: within float's range for every coefficient (the largest near 2^12).
            int e = std::min(k, binary32 ? 96 : k) * (r.coin() ? 1 : -1);
            for (double& x : b.q.q)
                x = std::ldexp(x, e);
        } else {
            int j = std::min(k / 2, binary32 ? 40 : k / 2) * (r.coin() ? 1 : -1);
            for (int i = 6; i < 10; ++i)
                b.q.q[std::size_t(i)] = std::ldexp(b.q.q[std::size_t(i)], i < 9 ? j : 2 * j);
            l = {std::ldexp(1.0, j) * l.L0, std::ldexp(1.0, j) * l.v};
        }
        return make(b.q, l.L0, l.v);
    }
    case Family::far_origin: {
        // A source 2^k sizes away, aimed through P, or past it by a little.
        Built b = build(any_kind(r), r, rotate);
        Vec3 d = direction(r);
        Vec3 L0 = b.P - std::ldexp(1.0, k) * d;
        if (r.coin()) L0 = L0 + 0.125 * across(d, r);
        return make(b.q, L0, d);
    }
    case Family::inside_start: {
        // From P on the surface, with the caller's word for it (coincident) or without; or
        // from 2^-k off it.
        Built b = build(any_kind(r), r, rotate);
        Vec3 d = r.coin() ? direction(r) : across(b.n, r) + b.n;
        Case c = make(b.q, b.P, d);
        if (k > 0 && r.coin())
            c.line.L0 = b.P + off * b.n;
        else
            std::get<Quadric>(c.shape).coincident = r.coin();
        return c;
    }
    case Family::thin: {
        // An ellipsoid's or a cylinder's axis 2^-k of the others (k <= 20: its coefficient 2^2k
        // times the centre's squares stays an integer below 2^53).
        Built b = build(r.coin() ? Kind::ellipsoid : Kind::cylinder, r, false, std::min(k, 20));
        Line l = through(b.P, direction(r), r);
        return make(b.q, l.L0, l.v);
    }
    default:
        return {};
    }
}

} // namespace surfaces

template <>
bool CaseMaker<Quadric>::applies(Family f) {
    return surfaces::quadric_applies(f);
}

template <>
Case CaseMaker<Quadric>::make(Family f, Rng& r, int k, Frames frames, Precision p) {
    return surfaces::quadric_case(f, r, k, frames, p);
}

} // namespace linequad
