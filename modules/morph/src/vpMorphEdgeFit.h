/*
  \file vpMorphEdgeFit.h
  \brief Internal to the morph module (not installed): the pieces of the point-to-edge fits of one outline on another
  (vpMorphOutlineFit, vpMorphRigidTransform's rigid part).
*/
#ifndef VP_MORPH_EDGE_FIT_H
#define VP_MORPH_EDGE_FIT_H

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Dense>

#include <visp3/morph/vpMorphContour.h>
#include <visp3/morph/vpMorphRigidTransform.h>

namespace vpMorphEdgeFit
{
inline double median(std::vector<double> v)
{
  if (v.empty())
    return 0.0;
  const std::size_t h = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + h, v.end());
  double m = v[h];
  if (v.size() % 2 == 0) {
    m = 0.5 * (m + *std::max_element(v.begin(), v.begin() + h));
  }
  return m;
}

// Input samples every perimeter / n along its edges, vertices included, relative to its centroid (cx, cy), in
// order along the outline.
inline std::vector<Eigen::Vector2d> edgeSamples(const vpMorphContour &input, double &cx, double &cy,
                                                std::size_t n = 256)
{
  input.centroid(cx, cy);
  const Eigen::Vector2d c(cx, cy);
  std::vector<Eigen::Vector2d> P;
  const double step = input.perimeter() / double(n);
  const std::size_t m = input.size();
  for (std::size_t k = 0; k < m; ++k) {
    const Eigen::Vector2d a(input.x(k), input.y(k)), b(input.x((k + 1) % m), input.y((k + 1) % m));
    const std::size_t s = std::max<std::size_t>(1, static_cast<std::size_t>(std::ceil((b - a).norm() / step)));
    for (std::size_t j = 0; j < s; ++j)
      P.push_back(a + (double(j) / double(s)) * (b - a) - c);
  }
  return P;
}

// \e T as the map x' = M (x - c) + t, M = [a -b; b a] (linear in (a, b, t), one linear solve an ICP round), and the
// target's spread about t (a scale for the convergence tests).
inline Eigen::Vector4d linearParameters(const vpMorphRigidTransform &T, double cx, double cy,
                                        const vpMorphContour &target, double &spread)
{
  double tx, ty;
  T.apply(cx, cy, tx, ty);
  const Eigen::Vector4d x(T.scale() * std::cos(T.theta()), T.scale() * std::sin(T.theta()), tx, ty);
  spread = 0.0;
  for (std::size_t k = 0; k < target.size(); ++k)
    spread = std::max(spread, (Eigen::Vector2d(target.x(k), target.y(k)) - x.tail<2>()).norm());
  return x;
}

// The transform of linearParameters() x, about (cx, cy): x' = s R (x - c) + t = s R (x - c) + c + (t - c).
inline vpMorphRigidTransform fromLinearParameters(const Eigen::Vector4d &x, double cx, double cy)
{
  return vpMorphRigidTransform(std::atan2(x[1], x[0]), x[2] - cx, x[3] - cy, x.head<2>().norm(), cx, cy);
}

// The map of linearParameters() x applied to p: [a -b; b a] p + t.
inline Eigen::Vector2d linearMap(const Eigen::Vector4d &x, const Eigen::Vector2d &p)
{
  return Eigen::Vector2d(x[0] * p.x() - x[1] * p.y() + x[2], x[1] * p.x() + x[0] * p.y() + x[3]);
}

// Tukey's biweight of a residual r at cut-off c: (1 - (r / c)^2)^2 inside, 0 beyond.
inline double tukeyWeight(double r, double c)
{
  const double u = r / c;
  return u < 1.0 ? (1.0 - u * u) * (1.0 - u * u) : 0.0;
}

// Tukey's loss of a residual r at cut-off c, normalised to [0, 1]: 1 - (1 - (r / c)^2)^3 inside, 1 beyond (and for a
// non-finite r).
inline double tukeyLoss(double r, double c)
{
  const double u = r / c;
  if (!(u * u < 1.0))
    return 1.0;
  const double v = 1.0 - u * u;
  return 1.0 - v * v * v;
}

/*
  The point-to-point terms of an ICP round (weight 1e-3 w per pair, rows (px, -py, 1, 0) -> qx and (py, px, 0, 1) ->
  qy), summed over the pairs in closed form and added to the first four unknowns' normal equations: two 4 x 4 outer
  products per pair were most of a round's own time.
*/
struct PointToPointSums
{
  double sw = 0.0, swx = 0.0, swy = 0.0, swr = 0.0, sqx = 0.0, sqy = 0.0, sa = 0.0, sb = 0.0;
  void add(double w, double px, double py, double qx, double qy)
  {
    sw += w;
    swx += w * px;
    swy += w * py;
    swr += w * (px * px + py * py);
    sqx += w * qx;
    sqy += w * qy;
    sa += w * (px * qx + py * qy);
    sb += w * (px * qy - py * qx);
  }
  template <typename Matrix, typename Vector> void addTo(Matrix &A, Vector &rhs) const
  {
    const double e = 1e-3;
    A(0, 0) += e * swr;
    A(1, 1) += e * swr;
    A(0, 2) += e * swx;
    A(2, 0) += e * swx;
    A(0, 3) += e * swy;
    A(3, 0) += e * swy;
    A(1, 2) -= e * swy;
    A(2, 1) -= e * swy;
    A(1, 3) += e * swx;
    A(3, 1) += e * swx;
    A(2, 2) += e * sw;
    A(3, 3) += e * sw;
    rhs[0] += e * sa;
    rhs[1] += e * sb;
    rhs[2] += e * sqx;
    rhs[3] += e * sqy;
  }
};
} // namespace vpMorphEdgeFit

#endif
