// Shapes and perturbations shared by the morph unit tests (seeded, so every run sees the same inputs).
#ifndef VP_MORPH_TEST_SHAPES_H
#define VP_MORPH_TEST_SHAPES_H

#include <random>
#include <utility>
#include <vector>

#include <visp3/morph/vpMorphContour.h>
#include <visp3/morph/vpMorphCorrespondence.h>

namespace vpMorphTest
{
//! The contour with Gaussian noise of standard deviation \e sigma added to every coordinate.
inline vpMorphContour noisy(const vpMorphContour &c, std::mt19937 &rng, double sigma)
{
  std::normal_distribution<double> g(0.0, sigma);
  std::vector<double> x = c.xs(), y = c.ys();
  for (std::size_t k = 0; k < x.size(); ++k) {
    x[k] += g(rng);
    y[k] += g(rng);
  }
  return vpMorphContour(x, y, c.units());
}

//! Identity correspondence with the target's numbering shifted: input vertex k goes with target (k + shift) % n.
inline vpMorphCorrespondence shiftedIdentity(std::size_t n, std::size_t shift)
{
  std::vector<std::pair<std::size_t, std::size_t>> p;
  for (std::size_t k = 0; k < n; ++k)
    p.emplace_back(k, (k + shift) % n);
  return vpMorphCorrespondence(n, n, p, 0.0, 0.0);
}
} // namespace vpMorphTest

#endif
