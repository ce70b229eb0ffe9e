// A user's own solver audited in process against the installed package: a textbook nearest-hit
// ray-cylinder test, graded beside linequad's correct on generic cylinders.
#include <linequad/audit_solver.hpp>

#include <cmath>
#include <cstdio>

int main() {
    using namespace linequad;
    audit::ExternalSolver mine;
    mine.name = "mine";
    mine.answers = audit::Answers::nearest;
    mine.points = false;
    mine.on<Cylinder>() = [](const Cylinder& c, const Line& l) -> std::optional<Result> {
        if (c.caps || !c.finite) return std::nullopt; // open finite cylinders only
        Vec3 axis = c.H - c.C;
        double h = norm(axis);
        Vec3 n = (1 / h) * axis, w = l.L0 - c.C;
        double vd = dot(l.v, n), wd = dot(w, n);
        double a = dot(l.v, l.v) - vd * vd, b = 2 * (dot(l.v, w) - vd * wd);
        double disc = b * b - 4 * a * (dot(w, w) - wd * wd - c.r * c.r);
        Result r;
        if (a == 0 || disc < 0) return r;
        for (double t : {(-b - std::sqrt(disc)) / (2 * a), (-b + std::sqrt(disc)) / (2 * a)})
            if (l.range.contains(t) && wd + t * vd >= 0 && wd + t * vd <= h) {
                r.hits[r.count++] = Hit{t, {}, NAN, HitKind::cross, Part::lateral, false};
                break;
            }
        return r;
    };
    audit::Options o;
    o.cases_per_group = 200;
    o.families = {Family::generic};
    o.shapes = {0};
    o.solvers = {"correct", "mine"};
    audit::Report r = audit::run(o, {mine});
    audit::Row own = r.total("correct"), theirs = r.total("mine");
    std::printf("correct: %llu cases, %llu mismatched; mine: %llu cases, %llu mismatched, "
                "t max %llu ulps\n",
                (unsigned long long)own.cases, (unsigned long long)own.cases_mismatched,
                (unsigned long long)theirs.cases, (unsigned long long)theirs.cases_mismatched,
                (unsigned long long)theirs.t_max);
    return own.cases_mismatched == 0 && theirs.cases > 0 && theirs.timed() ? 0 : 1;
}
