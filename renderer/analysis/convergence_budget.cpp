#include "renderer/analysis/convergence_budget.h"

#include <algorithm>
#include <cmath>

namespace kiln {

ReferencePlan plan_reference(double share_seconds, uint32_t pilot_spp, double pilot_seconds, double seconds_per_spp,
                             uint32_t max_spp, uint32_t requested_spp) {
  const double cost = std::max(seconds_per_spp, 0.0);
  ReferencePlan plan;
  if (requested_spp > 0) {
    plan.spp = std::max(requested_spp, pilot_spp);
  } else {
    const double left = kPlanningMargin * share_seconds - pilot_seconds;
    const double affordable = cost > 0.0 ? std::floor(std::max(left, 0.0) / cost) : double(max_spp);
    plan.spp = uint32_t(std::clamp(double(pilot_spp) + affordable, double(pilot_spp), double(std::max(max_spp, pilot_spp))));
  }
  plan.estimated_seconds = pilot_seconds + double(plan.spp - pilot_spp) * cost;
  plan.fits = plan.estimated_seconds <= share_seconds;
  return plan;
}

double strategies_budget(double budget_seconds, double reference_seconds) {
  return std::max(budget_seconds - reference_seconds, (1.0 - kReferenceShare) * budget_seconds);
}

}  // namespace kiln
