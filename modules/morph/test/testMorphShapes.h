// Shapes and perturbations shared by the morph unit tests (seeded, so every run sees the same inputs).
#ifndef VP_MORPH_TEST_SHAPES_H
#define VP_MORPH_TEST_SHAPES_H

#include <cmath>
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

//! \e c with every edge moved by d along its left normal (-dy, dx) / |d|, the vertices where the moved edges meet.
inline vpMorphContour offsetEdges(const vpMorphContour &c, double d)
{
  const std::size_t n = c.size();
  std::vector<double> x(n), y(n);
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t p = (k + n - 1) % n, q = (k + 1) % n;
    const double l1 = std::hypot(c.x(k) - c.x(p), c.y(k) - c.y(p)), l2 = std::hypot(c.x(q) - c.x(k), c.y(q) - c.y(k));
    const double n1x = -(c.y(k) - c.y(p)) / l1, n1y = (c.x(k) - c.x(p)) / l1;
    const double n2x = -(c.y(q) - c.y(k)) / l2, n2y = (c.x(q) - c.x(k)) / l2;
    const double f = d / (1.0 + n1x * n2x + n1y * n2y);
    x[k] = c.x(k) + f * (n1x + n2x);
    y[k] = c.y(k) + f * (n1y + n2y);
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
