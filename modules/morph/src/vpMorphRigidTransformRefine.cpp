// vpMorphRigidTransform's fits without a correspondence: on the target's edges (point-to-edge ICP, refineOnOutline())
// and on the overlap of the two regions (refineOnOverlap(), fitOnOverlap()).
#include <visp3/morph/vpMorphRigidTransform.h>

#include "vpMorphEdgeFit.h"
#include "vpMorphNearestEdge.h"
#include "vpMorphRegionOverlap.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include <visp3/morph/vpMorphException.h>

namespace
{
using namespace vpMorphEdgeFit;

[[noreturn]] void badParameter(const std::string &msg)
{
  throw vpMorphException(vpMorphException::badParameterError, msg);
}

// The checks shared by the refinements of a transform between two contours.
void checkContourPair(const vpMorphContour &input, const vpMorphContour &target, unsigned int maxIterations,
                      const char *who)
{
  if (input.empty() || target.empty())
    throw vpMorphException(vpMorphException::badContourError, std::string(who) + ": empty contour");
  if (input.units() != target.units())
    badParameter(std::string(who) + ": the two contours have different units");
  if (maxIterations < 1)
    badParameter(std::string(who) + ": maxIterations must be >= 1");
}

/*
  One round of edgeIcp(): the weighted normal equations of the pairs (nearest points Q, normals N, distances d) for
  the 4 unknowns (a, b, tx, ty), solved into \e x. False when no pair is kept.
*/
bool edgeIcpRound(const std::vector<Eigen::Vector2d> &P, const std::vector<Eigen::Vector2d> &Q,
                  const std::vector<Eigen::Vector2d> &N, const std::vector<double> &d, double cut, Eigen::Vector4d &x)
{
  Eigen::Matrix4d A = Eigen::Matrix4d::Zero();
  Eigen::Vector4d rhs = Eigen::Vector4d::Zero();
  PointToPointSums pp;
  for (std::size_t k = 0; k < P.size(); ++k) {
    const double w = tukeyWeight(d[k], cut);
    if (w == 0.0)
      continue;
    const double px = P[k].x(), py = P[k].y();
    const Eigen::Vector2d &nk = N[k];
    const Eigen::Vector4d J(nk.x() * px + nk.y() * py, nk.y() * px - nk.x() * py, nk.x(), nk.y());
    A.selfadjointView<Eigen::Lower>().rankUpdate(J, w);
    rhs += (w * nk.dot(Q[k])) * J;
    pp.add(w, px, py, Q[k].x(), Q[k].y());
  }
  if (!(pp.sw > 0.0))
    return false;
  A.triangularView<Eigen::StrictlyUpper>() = A.transpose();
  pp.addTo(A, rhs);
  x = A.ldlt().solve(rhs);
  return true;
}

/*
  The same with a fifth unknown, the offset delta of the edges along their normals (\e along of
  vpMorphNearestEdge): m . (M p + t) - along delta = m . q. The point-edge rows are stacked and multiplied at once
  and the point-point terms summed in closed form (one 5 x 5 outer product per pair made the whole fit a tenth
  slower).
*/
bool edgeIcpRoundWithOffset(const std::vector<Eigen::Vector2d> &P, const std::vector<Eigen::Vector2d> &Q,
                            const std::vector<Eigen::Vector2d> &N, const std::vector<double> &d,
                            const std::vector<double> &along, double cut, Eigen::Matrix<double, 5, 1> &z)
{
  Eigen::Matrix<double, Eigen::Dynamic, 5> J(P.size(), 5);
  Eigen::VectorXd w(P.size()), b(P.size());
  PointToPointSums pp;
  Eigen::Index n = 0;
  for (std::size_t k = 0; k < P.size(); ++k) {
    const double wk = tukeyWeight(d[k], cut);
    if (wk == 0.0)
      continue;
    const double px = P[k].x(), py = P[k].y(), qx = Q[k].x(), qy = Q[k].y();
    const Eigen::Vector2d &nk = N[k];
    J.row(n) << nk.x() * px + nk.y() * py, nk.y() * px - nk.x() * py, nk.x(), nk.y(), -along[k];
    w[n] = wk;
    b[n] = nk.dot(Q[k]);
    ++n;
    pp.add(wk, px, py, qx, qy);
  }
  if (n == 0)
    return false;
  const auto Jn = J.topRows(n);
  Eigen::Matrix<double, 5, 5> A = Jn.transpose() * w.head(n).asDiagonal() * Jn;
  Eigen::Matrix<double, 5, 1> rhs = Jn.transpose() * w.head(n).cwiseProduct(b.head(n));
  pp.addTo(A, rhs);
  // A faint pull of the offset to 0: on a disc, growing the outline and scaling it are the same.
  A(4, 4) += 1e-9 * pp.sw;
  z = A.ldlt().solve(rhs);
  return true;
}

/*
  Trimmed point-to-edge ICP of the points P (relative to the input's centre) on the edges behind \e nearest, from
  x = (a, b, tx, ty) of the map p -> [a -b; b a] p + t. Tukey weights at 5 sigma, sigma = sigmaFixed when > 0, else
  1.4826 MAD of the distances floored at sigmaMin. With \e offset (in: its start, out: the fitted value), the
  target's edges are also moved along their normals by one common offset, fitted with the map: an outline measured
  grown or shrunk all round (a biased edge level) then does not bias the scale. Returns the refined x (not checked
  for a positive scale).
*/
Eigen::Vector4d edgeIcp(const std::vector<Eigen::Vector2d> &P, const vpMorphNearestEdge &nearest, Eigen::Vector4d x,
                        bool withScale, double sigmaMin, double sigmaFixed, unsigned int iterations, double spread,
                        double *offset = nullptr)
{
  std::vector<Eigen::Vector2d> Q(P.size()), N(P.size());
  std::vector<double> d(P.size()), along(P.size(), 1.0);
  double delta = offset ? *offset : 0.0;
  for (unsigned int it = 0; it < iterations; ++it) {
    for (std::size_t k = 0; k < P.size(); ++k) {
      const Eigen::Vector2d p = linearMap(x, P[k]);
      // The nearest point q = p - r m of the target's edges: r the signed distance, m the edge's normal (towards p
      // at a vertex).
      double mx, my;
      const double r = offset ? nearest(p.x(), p.y(), mx, my, along[k]) : nearest(p.x(), p.y(), mx, my);
      N[k] = Eigen::Vector2d(mx, my);
      Q[k] = p - r * N[k];
      d[k] = std::fabs(r - along[k] * delta);
    }
    // Distances are norms (>= 0): their median stands for the MAD of a residual centred on 0. Tukey weights
    // from the distance trim what the target does not have; the fit itself is point-to-edge, which slides
    // along the edges in one round instead of creeping, plus a small point-to-point term that keeps it posed
    // where every kept point lies on one straight edge.
    const double sigma = sigmaFixed > 0.0 ? sigmaFixed : std::max(1.4826 * median(d), sigmaMin), cut = 5.0 * sigma;
    Eigen::Vector4d xn;
    const double deltaBefore = delta;
    if (offset) {
      Eigen::Matrix<double, 5, 1> z;
      if (!edgeIcpRoundWithOffset(P, Q, N, d, along, cut, z) || !z.allFinite())
        break;
      xn = z.head<4>();
      delta = z[4];
    } else if (!edgeIcpRound(P, Q, N, d, cut, xn)) {
      break;
    }
    if (!xn.allFinite())
      break;
    if (!withScale)
      xn.head<2>() /= xn.head<2>().norm();
    // How far the round moved the points, at most: (a, b) times the target's spread, t and the offset as they are.
    // Under a billionth of the spread (a ten-millionth of a pixel on a 100 px object) the fit has settled: the rounds
    // that follow a part from the last image stop there within 10 of their 20 (the bound used to be 1e-12 in the
    // contours' units, which normalised coordinates never reach).
    const Eigen::Vector4d step = xn - x;
    const double moved = std::max({step.head<2>().cwiseAbs().maxCoeff() * spread, step.tail<2>().cwiseAbs().maxCoeff(),
                                   std::fabs(delta - deltaBefore)});
    x = xn;
    if (moved < 1e-9 * spread)
      break;
  }
  if (offset)
    *offset = delta;
  return x;
}

} // namespace

vpMorphRigidTransform vpMorphRigidTransform::refineOnOutline(const vpMorphContour &input, const vpMorphContour &target,
                                                             const vpMorphRigidTransform &initial, bool withScale,
                                                             double minSigma, unsigned int maxIterations,
                                                             double *edgeOffset)
{
  const char *who = "vpMorphRigidTransform::refineOnOutline";
  checkContourPair(input, target, maxIterations, who);
  if (!std::isfinite(minSigma) || minSigma < 0.0)
    badParameter(std::string(who) + ": minSigma must be finite and >= 0");

  double cx, cy, spread;
  const std::vector<Eigen::Vector2d> P = edgeSamples(input, cx, cy);
  Eigen::Vector4d x = linearParameters(initial, cx, cy, target, spread);
  const double sigmaMin = std::max(1e-9 * std::max(spread, 1e-300), minSigma);

  const vpMorphNearestEdge nearest(target); // a grid over a dense target's edges
  double offset = 0.0;
  x = edgeIcp(P, nearest, x, withScale, sigmaMin, 0.0, maxIterations, spread, edgeOffset ? &offset : nullptr);
  if (!(x.head<2>().norm() > 0.0) || !x.allFinite()) {
    if (edgeOffset)
      *edgeOffset = 0.0;
    return initial;
  }
  if (edgeOffset)
    *edgeOffset = offset;
  return fromLinearParameters(x, cx, cy);
}

vpMorphRigidTransform vpMorphRigidTransform::refineOnOverlap(const vpMorphContour &input, const vpMorphContour &target,
                                                             const vpMorphRigidTransform &initial,
                                                             unsigned int maxIterations, double initialStep)
{
  const char *who = "vpMorphRigidTransform::refineOnOverlap";
  if (!(initialStep > 0.0 && initialStep <= 1.0))
    badParameter(std::string(who) + ": initialStep must be in (0, 1]");
  checkContourPair(input, target, maxIterations, who);

  // The input moved by initial, about its centroid c; z = (r theta, tx, ty) is the further motion x -> R(theta)
  // (x - c) + c + t, with the angle scaled by the radius of gyration r so that all three are lengths (one step
  // length serves them all).
  const vpMorphContour moved = initial.apply(input);
  const std::vector<Eigen::Vector2d> P = vpMorphPoints(moved);
  double cx, cy;
  moved.centroid(cx, cy);
  const Eigen::Vector2d c(cx, cy);
  double r2 = 0.0;
  for (const Eigen::Vector2d &p : P)
    r2 += (p - c).squaredNorm();
  const double r = std::sqrt(r2 / double(P.size()));
  if (!(r > 0.0) || !std::isfinite(r))
    return initial;
  const vpMorphOverlapPolygon B(vpMorphPoints(target));

  std::vector<Eigen::Vector2d> Q(P.size());
  vpMorphOverlapPolygon A; // the moved input, rebuilt in place at each evaluation
  auto evaluate = [&](const Eigen::Vector3d &z, Eigen::Vector3d &g) {
    const Eigen::Rotation2Dd R(z[0] / r);
    for (std::size_t k = 0; k < P.size(); ++k)
      Q[k] = R * (P[k] - c) + c + z.tail<2>();
    A.assign(Q);
    const double f = vpMorphOverlapArea(A, B, c + z.tail<2>(), &g);
    g[0] /= r;
    return f;
  };

  // Pattern search with an adaptive step, trying the gradient's direction first: the overlap is piecewise smooth,
  // and its local maxima often sit on a kink (edges that coincide, a vertex crossing an edge), where the gradient
  // changes abruptly and a quasi-Newton step or a line search stalls; this one walks along ridges and onto kinks
  // alike. The step doubles after a success and halves after a round without one, down to the tolerance.
  Eigen::Vector3d z = Eigen::Vector3d::Zero(), g;
  double f = evaluate(z, g);
  const double tolerance = 1e-5 * r; // a thousandth of a pixel on a 100-pixel object
  double h = initialStep * r;
  for (unsigned int it = 0; it < maxIterations && h > tolerance; ++it) {
    Eigen::Vector3d dirs[7];
    int nd = 0;
    if (g.norm() > 0.0)
      dirs[nd++] = g / g.norm();
    for (int i = 0; i < 3; ++i) {
      dirs[nd++] = Eigen::Vector3d::Unit(i);
      dirs[nd++] = -Eigen::Vector3d::Unit(i);
    }
    bool improved = false;
    for (int k = 0; k < nd && !improved; ++k) {
      Eigen::Vector3d gn;
      const Eigen::Vector3d zn = z + h * dirs[k];
      const double fn = evaluate(zn, gn);
      if (fn > f && std::isfinite(fn)) {
        z = zn;
        f = fn;
        g = gn;
        improved = true;
      }
    }
    h = improved ? std::min(2.0 * h, 0.05 * r) : 0.5 * h;
  }
  if (!z.allFinite())
    return initial;
  // Further motion M: x -> R(z0 / r) (x - c) + c + t, after initial: M * initial.
  const vpMorphRigidTransform M(z[0] / r, z[1], z[2], 1.0, cx, cy);
  return M * initial;
}

vpMorphRigidTransform vpMorphRigidTransform::fitOnOverlap(const vpMorphContour &input, const vpMorphContour &target,
                                                          const vpMorphRigidTransform &initial, double angleRange,
                                                          unsigned int starts, unsigned int maxIterations)
{
  if (!std::isfinite(angleRange) || angleRange < 0.0)
    badParameter("vpMorphRigidTransform::fitOnOverlap: angleRange must be finite and >= 0");
  if (starts < 1 || starts % 2 == 0)
    badParameter("vpMorphRigidTransform::fitOnOverlap: starts must be odd and >= 1");
  if (input.empty() || target.empty())
    throw vpMorphException(vpMorphException::badContourError, "vpMorphRigidTransform::fitOnOverlap: empty contour");
  double cx, cy;
  initial.apply(input).centroid(cx, cy);
  const int half = int(starts / 2);
  vpMorphRigidTransform best = initial;
  double bestOverlap = -1.0;
  for (int k = -half; k <= half; ++k) {
    const double a = half > 0 ? angleRange * double(k) / double(half) : 0.0;
    const vpMorphRigidTransform T =
        refineOnOverlap(input, target, vpMorphRigidTransform(a, 0.0, 0.0, 1.0, cx, cy) * initial, maxIterations);
    const double f = T.apply(input).overlapArea(target);
    if (f > bestOverlap) {
      bestOverlap = f;
      best = T;
    }
  }
  return best;
}
