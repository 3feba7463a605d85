// Monte Carlo against the MPM: after a closed-form sweep, the MPM is run on the samples that sit
// at chosen quantiles of one closed-form output (study key `mpm_at_quantiles`), and its results
// are reported beside the closed forms' with their relative errors. A few MPM runs check the
// tails of a distribution that only the closed forms could afford to sample.
#pragma once
#include <nlohmann/json.hpp>

#include "model/study.hpp"
#include "model/sweep_table.hpp"

namespace lsi {

// For each quantile q of study.mpm_at_quantiles: the ok sample whose value of method/output is
// nearest to the type-7 quantile of that column (the lowest index on ties), its inputs, the
// closed-form outputs of every method, the MPM's outputs, status and wall time, and the relative
// error (closed form - MPM) / MPM of each closed-form output. Returns null if the study has no
// such request. MPM runs that stop unstable are reported with their status and no errors.
nlohmann::json mpm_at_quantiles(const Study& study, const SweepTable& table);

// The human-readable table of mpm_at_quantiles' JSON.
std::string mpm_at_quantiles_table(const nlohmann::json& j);

}  // namespace lsi
