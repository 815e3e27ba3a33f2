// Variance-based (Sobol') sensitivity indices from the pick-freeze design of Saltelli et al., "Variance based
// sensitivity analysis of model output. Design and estimator for the total sensitivity index", Comput. Phys.
// Commun. 181, 2010: two independent sample matrices A and B (N × k) and, for each input i, AB_i = A with column i
// taken from B; N·(k + 2) model runs.
//   first order  S_i  = (1/N)·Σ f(B)·(f(AB_i) − f(A)) / V      (Saltelli 2010, Table 2 (b))
//   total        ST_i = (1/2N)·Σ (f(A) − f(AB_i))² / V          (Jansen 1999; Saltelli 2010, Table 2 (f))
// with V the variance of f over A and B. The sums are accumulated on outputs shifted by a constant (which leaves
// the estimators' expectations unchanged and avoids cancellation when the spread is small against the mean).
#pragma once
#include <cstddef>
#include <limits>

namespace needlekit::uncertainty {

// The sums of one output for one input over a set of rows.
struct SobolSums {
  std::size_t rows = 0;        // rows where f(A), f(B) and f(AB_i) are all defined
  double sum_a = 0, sum_b = 0, sum_a2 = 0, sum_b2 = 0;
  double first = 0;            // Σ f(B)·(f(AB_i) − f(A))
  double total = 0;            // Σ (f(A) − f(AB_i))²

  void add(double a, double b, double ab) {
    ++rows;
    sum_a += a;
    sum_b += b;
    sum_a2 += a * a;
    sum_b2 += b * b;
    first += b * (ab - a);
    total += (a - ab) * (a - ab);
  }
  void add(const SobolSums& other) {
    rows += other.rows;
    sum_a += other.sum_a;
    sum_b += other.sum_b;
    sum_a2 += other.sum_a2;
    sum_b2 += other.sum_b2;
    first += other.first;
    total += other.total;
  }
};

// V over the A and B rows; NaN with fewer than 2 rows.
double output_variance(const SobolSums& sums);
// S_i and ST_i; NaN when V = 0 (the output does not vary: no index is defined) or there are no rows.
double first_order_index(const SobolSums& sums);
double total_index(const SobolSums& sums);

}  // namespace needlekit::uncertainty
