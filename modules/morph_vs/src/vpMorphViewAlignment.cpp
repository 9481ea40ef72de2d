#include <visp3/morph_vs/vpMorphViewAlignment.h>

#include <algorithm>
#include <cmath>

const char *vpMorphViewAlignment::modelName(Model m)
{
  switch (m) {
  case RIGID:
    return "rigid";
  case PART_HIDDEN:
    return "part hidden";
  case PART_BENT:
    return "part bent";
  case UNEXPLAINED:
    return "unexplained";
  }
  return "?";
}

double vpMorphViewAlignment::rotationDeviation() const { return std::sqrt(covariance[0][0]); }

double vpMorphViewAlignment::translationDeviation() const
{
  // The larger eigenvalue of the translation block.
  const double a = covariance[1][1], b = covariance[1][2], c = covariance[2][2];
  if (!std::isfinite(a) || !std::isfinite(c))
    return std::numeric_limits<double>::infinity();
  return std::sqrt(std::max(0.0, 0.5 * (a + c) + std::sqrt(0.25 * (a - c) * (a - c) + b * b)));
}

double vpMorphViewAlignment::scaleDeviation() const { return std::sqrt(covariance[3][3]); }
