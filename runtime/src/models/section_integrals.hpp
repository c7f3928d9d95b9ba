// A profile variant's run-time section integrals (generated_abi.h's SectionIntegral; docs/model.md section 11.2):
// the table's distributions, linear between its stations, times the variant's shape functions, integrated on the
// common refinement of the stations and the bases' intervals: exact to round-off for polynomial bases, converged for
// AMM. What the generator integrated exactly when stations were structure, computed once per parameter set.
#pragma once

#include <vector>

#include "generated_abi.h"
#include "interface.hpp"
#include "variant.hpp"

namespace hubbeam {

/// The distribution d (SectionDistribution) of a profile at each of its stations, from p.stations and p.profile.
std::vector<double> section_distribution(const VariantKey& key, const Parameters& p, SectionDistribution d);

/// Entry n: int_0^1 xi^power d(xi) prod(factors)(xi) dxi of list[n], for the bases of key and the profile of p.
std::vector<double> section_integrals(const VariantKey& key, const generated::SectionIntegral* list, int count,
                                      const Parameters& p);

}  // namespace hubbeam
