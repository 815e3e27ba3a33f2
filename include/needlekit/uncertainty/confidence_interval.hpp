// 95 % confidence intervals of sampled estimates.
#pragma once
#include <cstddef>
#include <vector>

namespace needlekit::uncertainty {

struct Interval {
  double lo = 0;
  double hi = 0;
};

// Wilson score interval of a binomial proportion (Wilson, JASA 22, 1927) at 95 % (z = 1.959964): good coverage also
// near 0 and 1, where the normal approximation fails (0 successes in N gives [0, ≈3.84/N]).
Interval wilson_interval(std::size_t successes, std::size_t trials);

// Student-t interval around `center` from independent replicate estimates (their spread, with G − 1 degrees of
// freedom): center ± t_{0.975, G−1}·sd/√G. Used for randomised quasi-Monte Carlo, whose error the binomial formula
// overstates, and for the Sobol' indices. G >= 2.
Interval replicate_interval(double center, const std::vector<double>& replicates);

}  // namespace needlekit::uncertainty
