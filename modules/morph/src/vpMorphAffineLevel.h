/*
  \file vpMorphAffineLevel.h
  \brief Internal to the morph module (not installed): a grey level as an affine function of the image position, fitted
  by least squares (vpMorphGreyClasses, vpMorphRegionMeasure).
*/
#ifndef VP_MORPH_AFFINE_LEVEL_H
#define VP_MORPH_AFFINE_LEVEL_H

#include <cmath>

#include <Eigen/Dense>

namespace vpMorphAffineLevel
{
// Least-squares sums of levels g at positions (x, y).
struct Sums
{
  double n = 0.0, x = 0.0, y = 0.0, xx = 0.0, xy = 0.0, yy = 0.0, g = 0.0, xg = 0.0, yg = 0.0, gg = 0.0;

  void add(double px, double py, double pg)
  {
    n += 1.0;
    x += px;
    y += py;
    xx += px * px;
    xy += px * py;
    yy += py * py;
    g += pg;
    xg += px * pg;
    yg += py * pg;
    gg += pg * pg;
  }
};

/*
  The affine level [a bx by] (a + bx x + by y) of the sums, when their slope is both seen and worth its two parameters:
  the positions spread at least \e pixel (a pixel in the units of x, y) in every direction, and the fit passes the
  Bayesian information criterion (n ln(RSS_constant / RSS_affine) > 2 ln n), so that the noise of a small or uniformly
  lit surface is not read as a fall-off of its light. False otherwise (\e out untouched): the caller's constant level
  stands.
*/
// Whether the sums' positions spread at least \e pixel in every direction (a slope across them is seen).
inline bool spread(const Sums &s, double pixel)
{
  const double n = s.n;
  if (!(n > 0.0))
    return false;
  const Eigen::Vector2d mean(s.x / n, s.y / n);
  Eigen::Matrix2d cov;
  cov << s.xx / n - mean(0) * mean(0), s.xy / n - mean(0) * mean(1), s.xy / n - mean(0) * mean(1),
      s.yy / n - mean(1) * mean(1);
  return Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(cov, Eigen::EigenvaluesOnly).eigenvalues()(0) >= pixel * pixel;
}

inline bool slope(const Sums &s, double pixel, Eigen::Vector3d &out)
{
  const double n = s.n;
  if (!spread(s, pixel))
    return false;
  Eigen::Matrix3d A;
  A << n, s.x, s.y, s.x, s.xx, s.xy, s.y, s.xy, s.yy;
  const Eigen::Vector3d b(s.g, s.xg, s.yg);
  const Eigen::Vector3d p = A.ldlt().solve(b);
  const double rssConstant = s.gg - s.g * s.g / n, rssAffine = s.gg - b.dot(p);
  const bool worth = rssAffine <= 0.0 ? rssConstant > 0.0 : n * std::log(rssConstant / rssAffine) > 2.0 * std::log(n);
  if (!p.allFinite() || !worth || (p(1) == 0.0 && p(2) == 0.0))
    return false;
  out = p;
  return true;
}
} // namespace vpMorphAffineLevel

#endif
