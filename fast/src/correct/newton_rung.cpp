// The Newton rung of the correct solver (see newton_rung.hpp for the method). Every bound is
// rigorous at any size of the scene (underflow enters as an absolute floor; overflow makes a bound
// infinite, which proves nothing), and every decision is taken only when a bound proves it.
#include "correct/newton_rung.hpp"

#include "correct/newton_steps.hpp"

#include <cmath>
#include <optional>
#include <type_traits>
#include <utility>

namespace linequad::detail {

namespace {

using namespace newton;

template <int SigmaZ>
Local<double> local_at(const LineForm& f, double c) {
    const double at[1] = {c};
    Local<double> out[1];
    newton::local_at<SigmaZ>(f, at, out);
    return out[0];
}

// The enclosure of the root next to c, when the local quadratic proves one.
LINEQUAD_INLINE std::optional<Enclosure<double>> root_near(const Local<double>& L,
                                                           const Leading<double>& A, double c) {
    Enclosure<double> en = newton::root_near(L, A, c);
    if (!en.proven) return std::nullopt;
    return en;
}

// No real root, near the vertex c; local_at: the precise expansion or the hit test's quick one.
template <class LocalAt>
bool no_root_proven(const Leading<double>& A, double c, LocalAt local_at) {
    if (!std::isfinite(c)) return false;
    return newton::no_root_proven(A, c, local_at(c));
}

// 1: the root is inside the extent and the range; 0: outside; -1: the bounds cannot tell.
LINEQUAD_INLINE int kept(const LineForm& f, const Unit& unit, const Enclosure<double>& en) {
    Kept<double> k = newton::kept(f, unit.line.range, en);
    return k.outside ? 0 : k.inside ? 1 : -1;
}

// The hit, t and its point correctly rounded to Target in the caller's units; false when a bound
// does not prove a rounding.
template <class Target>
LINEQUAD_INLINE bool add_hit(const Enclosure<double>& en, const Unit& unit, const Line& caller,
                             Query q, Result& r) {
    if constexpr (std::is_same_v<Target, Binary32>) {
        // A float's rounding cell is 2^29 times a double's: t = c + x and each coordinate
        // fma(t, v_k, L0_k) in double, each with one rounding added to its bound, nearly always
        // prove it.
        double t = en.c + en.x, e_t = en.e + u * std::fabs(t);
        std::optional<double> rounded =
            round_proven<Target>({t, 0, e_t * F::cover(4) + F::denorm_min}, unit.t_factor);
        if (!rounded) return false;
        Hit& h = r.hits[r.count];
        h.t = *rounded, h.kind = HitKind::cross, h.part = Part::lateral, h.p = {};
        if (q.points) {
            double p[3];
#pragma GCC unroll 3
            for (int k = 0; k < 3; ++k) {
                if (caller.v[k] == 0) { // an exact zero is +0, as the oracle's
                    p[k] = caller.L0[k] + 0.0;
                    continue;
                }
                double v = unit.line.v[k], pk = std::fma(t, v, unit.line.L0[k]);
                double e =
                    (std::fabs(v) * e_t + u * std::fabs(pk)) * F::cover(8) + F::underflow_floor;
                std::optional<double> rk = round_proven<Target>({pk, 0, e}, unit.pos_factor);
                if (!rk) return false;
                p[k] = *rk;
            }
            h.p = {p[0], p[1], p[2]};
        }
        ++r.count;
        return true;
    } else {
        Rounded<double> t = rounded_t(en, unit.t_factor);
        if (!t.proven) return false;
        Hit& h = r.hits[r.count];
        h.t = t.value;
        h.kind = HitKind::cross;
        h.part = Part::lateral;
        h.p = {};
        if (q.points) {
            double p[3];
#pragma GCC unroll 3
            for (int k = 0; k < 3; ++k) {
                // L0_k + t v_k is L0_k exactly when v_k = 0 (an exact zero is +0, as the oracle's).
                if (caller.v[k] == 0) {
                    p[k] = caller.L0[k] + 0.0;
                    continue;
                }
                Rounded<double> pk =
                    rounded_point(en, unit.line.L0[k], unit.line.v[k], unit.pos_factor);
                if (!pk.proven) return false;
                p[k] = pk.value;
            }
            h.p = {p[0], p[1], p[2]};
        }
        ++r.count;
        return true;
    }
}

} // namespace

namespace {

// G in double-double (the precise line form), or in double from the quick line form: enough for
// a float rounding, which has 29 bits more room.
template <int SigmaZ, Residual R>
Local<double> local_near(const LineForm& f, double c) {
    if constexpr (R == Residual::quick)
        return quick_local_at<SigmaZ>(f, c);
    else
        return local_at<SigmaZ>(f, c);
}

template <int SigmaZ, class Target, Residual R>
bool solve(const LineForm& f, const Unit& unit, const Line& caller, Query query, Result& r) {
    Leading<double> A = leading<SigmaZ>(f);
    if (!(std::fabs(A.A) > A.e)) return false; // nearly parallel to the axis or to a generator
    Estimates<double> est = estimates<SigmaZ>(f, A);
    if (!est.real)
        return no_root_proven(A, est.vertex, [&](double c) { return local_near<SigmaZ, R>(f, c); });
    double estimate[2] = {est.root[0], est.root[1]};
    if (estimate[1] < estimate[0]) std::swap(estimate[0], estimate[1]);
    // Both roots at once when both are needed; otherwise the second only if the first is not kept.
    Local<double> local[2];
    bool both = R == Residual::double_double && query.need == Need::all;
    if (both) newton::local_at<SigmaZ>(f, estimate, local);
    for (int i = 0; i < 2; ++i) {
        if (!both) local[i] = local_near<SigmaZ, R>(f, estimate[i]);
        std::optional<Enclosure<double>> en = root_near(local[i], A, estimate[i]);
        if (!en || en->smaller != (i == 0)) return false;
        int inside = kept(f, unit, *en);
        if (inside < 0) return false;
        if (inside == 0) continue;
        if (!add_hit<Target>(*en, unit, caller, query, r)) return false;
        if (query.need != Need::all) break; // the smaller root first: also the nearest
    }
    return true;
}

// ---- The hit test ----

// Any root proven inside the extent and the range is a hit, whichever it is: the first one
// found is the answer. No hit needs both roots proven outside, or none proven real.
template <int SigmaZ>
bool hit_test(const LineForm& f, const Unit& unit, Result& r) {
    Leading<double> A = leading<SigmaZ>(f);
    if (!(std::fabs(A.A) > A.e)) return false;
    auto local = [&](double c) { return quick_local_at<SigmaZ>(f, c); };
    Estimates<double> est = estimates<SigmaZ>(f, A);
    if (!est.real) return no_root_proven(A, est.vertex, local); // r has no hit
    bool outside[2] = {false, false}; // the smaller, the larger root proven outside
    for (double c : est.root) {
        std::optional<Enclosure<double>> en = root_near(local(c), A, c);
        if (!en) continue;
        int inside = kept(f, unit, *en);
        if (inside == 1) {
            // t = c + x rounded once: within e + u |t| of the root (the sum's rounding).
            double t = en->c + en->x;
            r.hits[0] = {t,
                         {},
                         (en->e + u * std::fabs(t)) * F::cover(8) + F::denorm_min,
                         HitKind::cross,
                         Part::lateral,
                         true};
            r.count = 1;
            return true;
        }
        if (inside == 0) outside[en->smaller ? 0 : 1] = true;
    }
    return outside[0] && outside[1];
}

} // namespace

bool hit_test_rung(const LineForm& f, const Unit& unit, Result& r) {
    return with_sigma_z(
        f.sigma_z, [&](auto sigma_z) { return hit_test<decltype(sigma_z)::value>(f, unit, r); });
}

template <class Target, Residual R>
bool newton_rung(const LineForm& f, const Unit& unit, const Line& caller, Query query, Result& r) {
    return with_sigma_z(f.sigma_z, [&](auto sigma_z) {
        return solve<decltype(sigma_z)::value, Target, R>(f, unit, caller, query, r);
    });
}

template bool newton_rung<Binary64, Residual::double_double>(const LineForm&, const Unit&,
                                                             const Line&, Query, Result&);
template bool newton_rung<Binary32, Residual::double_double>(const LineForm&, const Unit&,
                                                             const Line&, Query, Result&);
template bool newton_rung<Binary32, Residual::quick>(const LineForm&, const Unit&, const Line&,
                                                     Query, Result&);

} // namespace linequad::detail
