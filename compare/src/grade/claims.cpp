// What the README claims for each solver, checked by `linequad audit --check` (run in CI).
#include "linequad/audit.hpp"

namespace linequad::audit {

std::vector<std::string> broken_claims(const Report& r) {
    std::vector<std::string> broken;
    for (const auto& entry : r.rows) {
        const RowKey& key = entry.first;
        const Row& row = entry.second;
        const std::string &family = key.family, &solver = key.solver;
        auto claim = [&](bool holds, const std::string& what) {
            if (!holds) broken.push_back(key.name() + ": " + what);
        };
        // Every solver: no NaN or infinity where the oracle has finite values, and the same
        // verdict on bad input (validation is shared and exact).
        claim(row.mismatches[nonfinite] == 0, "returned NaN or infinity");
        if (solver == "certified") {
            // Never wrong when it says it is sure, and every bound holds, on every family.
            claim(row.certain_wrong == 0,
                  std::to_string(row.certain_wrong) + " certain classifications wrong");
            claim(row.bound_violations == 0,
                  std::to_string(row.bound_violations) + " error bounds violated");
        }
        if (solver == "correct" || solver == "correct32") {
            // The oracle's answer bit for bit on every family: classification, t, points and
            // interval ends, and it never refuses what the oracle answers (correct32: the
            // oracle's answer rounded to float, on the binary32 cases).
            claim(row.cases_mismatched == 0,
                  std::to_string(row.cases_mismatched) + " cases classified unlike the oracle");
            claim(row.t_max == 0,
                  "t not correctly rounded (" + std::to_string(row.t_max) + " ulps)");
            claim(row.p_max == 0,
                  "a point not correctly rounded (" + std::to_string(row.p_max) + " ulps)");
            claim(row.uncertain == 0, "a result not marked certain");
        }
        // On generic cases stable classifies like the oracle and its t error has p99 <= 32 ulps,
        // in double and in float. (Its maximum follows the case's condition number, which random
        // cases can make large: a 1-ulp change of the input moves some roots by 10^2 ulps.)
        auto stable_on_generic = [&] {
            claim(row.cases_mismatched == 0,
                  std::to_string(row.cases_mismatched) + " generic cases misclassified");
            double p99 = row.t_error.quantile(0.99);
            claim(p99 <= 32, "t error p99 " + std::to_string(p99) + " ulps > 32 on generic cases");
        };
        if (solver == "stable" || solver == batch_name) {
            // Batch equals stable bit for bit, so it makes stable's claims.
            if (family == "generic") stable_on_generic();
            // It refuses (out_of_range) only inputs whose magnitudes double cannot hold.
            claim(row.mismatches[refused] == 0 || family == "scale",
                  "refused a case within double's range");
        }
        // stable32's refusals are not claimed: its discriminant is a product of up to ten
        // inputs, which leaves float's range in the scale family's far shapes and in the
        // degenerate frames' flat frusta.
        if (solver == "stable32" && family == "generic") stable_on_generic();
    }
    return broken;
}

} // namespace linequad::audit
