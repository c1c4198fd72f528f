// How `kiln converge` spends its --budget (the rule the CLI help and the README state): the budget is the study's
// whole render time, the reference included.
//  - Without --reference, a reference is rendered first within kReferenceShare of the budget: a pilot of doubling
//    waves (at most kPilotShare of that share) measures its cost per sample, then it takes as many samples per pixel
//    as fit the rest of the share (with kPlanningMargin kept back for the estimate's noise), at most --reference-spp
//    (default kDefaultReferenceMaxSpp). Its spp and estimated time are announced before the bulk of it starts.
//  - An explicit --reference-spp N is rendered in full even when it does not fit; its estimate is announced first
//    (with a warning when it exceeds the share), and the strategies still get (1 - kReferenceShare) of the budget.
//  - The strategies share what the reference left, equally; each stops before a wave that would overrun its part
//    (renderer/render/progressive.h).
// So with the default reference the plan fits the budget, and the render time stays within 1.25x of it: past it
// only by the prediction error of the last wave of each run and the error evaluation between waves. A first 1-spp
// wave per run that alone exceeds its part is warned about before the strategies start (renderer/cli/
// converge_command.cpp). Scene loading and the world build come on top.
#pragma once
#include <cstdint>

namespace kiln {

inline constexpr double kReferenceShare = 0.5;
inline constexpr double kPilotShare = 0.05;
inline constexpr double kPlanningMargin = 0.9;
inline constexpr uint32_t kDefaultReferenceMaxSpp = 4096;

struct ReferencePlan {
  uint32_t spp = 0;                // the reference's samples per pixel, the pilot's included
  double estimated_seconds = 0;    // of the whole reference: the pilot's measured time plus the rest's estimate
  bool fits = true;                // estimated_seconds <= share_seconds
};

// The reference's spp after a pilot of pilot_spp samples that took pilot_seconds, its last wave at seconds_per_spp.
// requested_spp > 0: exactly that many (an explicit --reference-spp); 0: as many as fit share_seconds (with
// kPlanningMargin), at most max_spp, never fewer than the pilot's.
ReferencePlan plan_reference(double share_seconds, uint32_t pilot_spp, double pilot_seconds, double seconds_per_spp,
                             uint32_t max_spp, uint32_t requested_spp);

// The strategies' part of the budget once the reference took reference_seconds (0 when it was given as a file).
double strategies_budget(double budget_seconds, double reference_seconds);

}  // namespace kiln
