// vpMorphOutlineFit's model statistics: the runs of outliers along the input that are parts of the view the goal does
// not have (vpMorphOutlineFit::getOutsideShare(), getInsideShare()).
#include <visp3/morph/vpMorphOutlineFit.h>

#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

void vpMorphOutlineFit::structuredOutliers(const std::vector<double> &w)
{
  // Runs of consecutive outliers along the input (cyclic). Outliers of the noise come alone: at the rate p of the
  // isolated ones, a run of m happens by chance with probability about n p^m, so only runs longer than the m that makes
  // it 1e-3 are parts of the view the goal does not have.
  const std::size_t n = m_residuals.size();
  m_outsideShare = m_insideShare = 0.0;
  std::vector<std::pair<std::size_t, std::size_t>> runs; // (start, length)
  std::size_t first = n;
  for (std::size_t k = 0; k < n; ++k)
    if (w[k] > 0.0) {
      first = k;
      break;
    }
  if (first == n) { // no inlier: one run, the whole outline
    double out = 0.0;
    for (double r : m_residuals)
      out += r > 0.0 ? 1.0 : 0.0;
    (out > 0.5 * double(n) ? m_outsideShare : m_insideShare) = 1.0;
    return;
  }
  for (std::size_t i = 1; i <= n; ++i) {
    const std::size_t k = (first + i) % n;
    if (w[k] > 0.0)
      continue;
    if (!runs.empty() && (runs.back().first + runs.back().second) % n == k)
      ++runs.back().second;
    else
      runs.emplace_back(k, 1);
  }
  std::size_t singles = 0;
  for (const auto &run : runs)
    singles += run.second == 1 ? 1 : 0;
  const double p = std::max(double(singles), 0.5) / double(n);
  const double m = std::max(2.0, std::ceil(std::log(1e-3 / double(n)) / std::log(p)));
  for (const auto &run : runs) {
    if (double(run.second) < m)
      continue;
    std::size_t out = 0;
    for (std::size_t j = 0; j < run.second; ++j)
      out += m_residuals[(run.first + j) % n] > 0.0 ? 1 : 0;
    (2 * out > run.second ? m_outsideShare : m_insideShare) += double(run.second) / double(n);
  }
}
