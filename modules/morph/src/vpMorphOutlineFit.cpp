#include <visp3/morph/vpMorphOutlineFit.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include <Eigen/Dense>

#include <visp3/core/vpException.h>
#include <visp3/morph/vpMorphException.h>

#include "vpMorphEdgeFit.h"
#include "vpMorphNearestEdge.h"

using namespace vpMorphEdgeFit;

namespace
{
[[noreturn]] void badParameter(const std::string &msg)
{
  throw vpMorphException(vpMorphException::badParameterError, "vpMorphOutlineFit: " + msg);
}

// Points of the outlines whose regions' overlap compares the hypotheses of search() (a few pixels apart).
const std::size_t kOverlapPoints = 128;

// Turns of search()'s start tried: every twelfth of a turn, each lobe of a part nearly symmetric of order 2, 3, 4 or 6
// started exactly (the correspondence may start a lobe off), a fifth within its basin.
const int kSearchTurns = 12;

// A normal distribution's standard deviation over its median absolute deviation: the robust scale's factor.
constexpr double kMadToSigma = 1.4826;

/*
  The noise of residuals taken in order along an outline, whatever the pose they were measured at: 1.4826 MAD of
  their second differences over sqrt(3/2) (the second difference of white noise of deviation s has deviation
  s sqrt(3/2)), floored. A pose error or a bend moves neighbouring samples alike and cancels there; a corner of the
  goal, where the nearest edge changes, is one of the MAD's outliers.
*/
double differenceScale(const std::vector<double> &r, double floor)
{
  std::vector<double> d;
  for (std::size_t k = 1; k + 1 < r.size(); ++k)
    if (std::isfinite(r[k - 1]) && std::isfinite(r[k]) && std::isfinite(r[k + 1]))
      d.push_back(std::fabs(r[k] - 0.5 * (r[k - 1] + r[k + 1])));
  return d.empty() ? floor : std::max(kMadToSigma * median(d) / std::sqrt(1.5), floor);
}

} // namespace

struct vpMorphOutlineFit::Goal
{
  vpMorphNearestEdge nearest;                    // the goal's edges
  std::vector<Eigen::Vector2d> samples, normals; // its samples and their left normals, for the reverse rows
  vpMorphContour region;                         // its outline resampled for the overlaps of search()

  Goal(const vpMorphContour &goal, std::size_t count)
    : nearest(goal), region(goal.size() > kOverlapPoints ? goal.resampled(kOverlapPoints) : goal)
  {
    const vpMorphContour g = goal.size() > count ? goal.resampled(count) : goal;
    const std::size_t n = g.size();
    samples.resize(n);
    normals.resize(n);
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t a = (k + n - 1) % n, b = (k + 1) % n;
      const Eigen::Vector2d t(g.x(b) - g.x(a), g.y(b) - g.y(a));
      const double l = t.norm();
      samples[k] = Eigen::Vector2d(g.x(k), g.y(k));
      normals[k] = l > 0.0 ? Eigen::Vector2d(-t.y() / l, t.x() / l) : Eigen::Vector2d(0.0, 0.0);
    }
  }
};

vpMorphOutlineFit::vpMorphOutlineFit(const vpMorphContour &goal) : m_covariance(4, 4, 0.0)
{
  if (goal.empty())
    throw vpMorphException(vpMorphException::badContourError, "vpMorphOutlineFit: empty goal");
  m_goal = goal.outline();
  m_goalCcw = m_goal.isCounterClockwise();
  m_goalData = std::make_shared<const Goal>(m_goal, m_samples);
}

void vpMorphOutlineFit::setMinimumSigma(double sigma)
{
  if (!std::isfinite(sigma) || sigma < 0.0)
    badParameter("the minimum sigma must be finite and >= 0");
  m_minSigma = sigma;
}

void vpMorphOutlineFit::setFineWidth(double width)
{
  if (!std::isfinite(width) || width < 0.0)
    badParameter("the fine width must be finite and >= 0");
  m_fineWidth = width;
}

void vpMorphOutlineFit::setMaximumSigma(double sigma)
{
  if (!(sigma > 0.0))
    badParameter("the maximum sigma must be > 0");
  m_maxSigma = sigma;
}

void vpMorphOutlineFit::setMaxIterations(unsigned int n)
{
  if (n < 1)
    badParameter("at least one iteration is needed");
  m_maxIterations = n;
}

void vpMorphOutlineFit::setSampleCount(unsigned int n)
{
  if (n < 8)
    badParameter("at least 8 samples are needed");
  m_samples = n;
  m_goalData = std::make_shared<const Goal>(m_goal, m_samples);
}

double vpMorphOutlineFit::cost(const std::vector<double> &residuals, double sigma)
{
  if (residuals.empty() || !(sigma > 0.0))
    return 1.0;
  const double c = tukeyConstant() * sigma;
  double sum = 0.0;
  for (double r : residuals)
    sum += tukeyLoss(r, c);
  return sum / double(residuals.size());
}

namespace
{
// The map p -> M p + t of x = (a, b, tx, ty), M = [a -b; b a].
Eigen::Matrix2d linearPart(const Eigen::Vector4d &x)
{
  return (Eigen::Matrix2d() << x[0], -x[1], x[1], x[0]).finished();
}
} // namespace

/*
  The rows of the robust fit at x: the input's samples P on the goal's edges (forward), and with \e inputEdges the
  goal's samples on the input's edges (reverse), each as J z = rhs for z = (a, b, tx, ty[, delta]), with its residual.
*/
struct vpMorphOutlineFit::Solver
{
  // The input's edges, and the centroid its samples are taken about (the grid keeps the outline's own coordinates:
  // shifted, two points a few ulps apart on a rough staircase would become one).
  struct InputEdges
  {
    vpMorphNearestEdge edges;
    double cx, cy;
  };

  struct Rows
  {
    std::vector<Eigen::Vector2d> p, m; // the input point and the goal-frame normal of each row
    std::vector<double> rhs, offset, r, w;
    std::size_t forward = 0;

    void resize(std::size_t n)
    {
      p.resize(n);
      m.resize(n);
      rhs.resize(n);
      offset.resize(n);
      r.resize(n);
      w.assign(n, 0.0);
    }
  };

  /*
    The rows at x and their robust scale: 1.4826 MAD of the residuals within \e cut (the inliers of the last round's
    scale; all of them when cut is not > 0), floored at sigmaFloor. Trimmed to the inliers, the scale stays the noise of
    the part the fit lies on, however much of the view lies elsewhere (a bent limb longer than the part, an occluder).
    A residual of magnitude \e reach or more is given as +inf (its row weighs nothing): the caller needs it only as
    beyond its cut-off, and the nearest-edge search stops there instead of crossing the grid for a far point. With a
    cut and a finite reach (a reweighting round), so is one beyond Tukey's cut-off of the scale returned: the rows are
    measured within the cut first (all the scale needs), then those beyond it again, within that cut-off (a few
    outliers: the searches stay short).
  */
  static double measureRows(const Goal &goal, const std::vector<Eigen::Vector2d> &P, const InputEdges *inputEdges,
                            const Eigen::Vector4d &x, double delta, double sigmaFloor, double cut, Rows &rows,
                            double reach = std::numeric_limits<double>::infinity())
  {
    const std::size_t n = P.size(), ng = inputEdges ? goal.samples.size() : 0;
    rows.resize(n + ng);
    rows.forward = n;
    const double inf = std::numeric_limits<double>::infinity();
    const double s2 = x.head<2>().squaredNorm(), s = std::sqrt(s2);
    const Eigen::Matrix2d M = linearPart(x), Minv = M.transpose() / s2, R = M / s;
    // Row k's residual, +inf when its magnitude is \e within or more.
    auto measure = [&](std::size_t k, double within) {
      if (k < n) {
        const Eigen::Vector2d y = linearMap(x, P[k]);
        double mx, my, along;
        // |r| >= |rk| - |delta|: a distance of within + |delta| or more is a residual of within or more.
        const double rk = goal.nearest.within(y.x(), y.y(), within + std::fabs(delta), mx, my, &along);
        rows.p[k] = P[k];
        rows.m[k] = Eigen::Vector2d(mx, my);
        const bool near = rk != inf;
        rows.rhs[k] = near ? rows.m[k].dot(y) - rk : 0.0; // m . q, q the nearest point of the unmoved edges
        rows.offset[k] = -along;
        rows.r[k] =
            near ? rk - along * delta : inf; // the distance to the goal's edges moved by delta along their normals
        return;
      }
      const std::size_t j = k - n;
      const Eigen::Vector2d &g = goal.samples[j];
      const Eigen::Vector2d u = Minv * (g - x.tail<2>()); // about the input's centroid
      double mx, my;
      // |r| >= s |rj| - |delta|, as above in the input's units.
      const double rj = inputEdges->edges.within(u.x() + inputEdges->cx, u.y() + inputEdges->cy,
                                                 (within + std::fabs(delta)) / s, mx, my);
      const Eigen::Vector2d nIn(mx, my);
      if (rj == inf) {
        rows.p[k] = u;
        rows.m[k] = Eigen::Vector2d::Zero();
        rows.rhs[k] = rows.offset[k] = 0.0;
        rows.r[k] = inf;
        return;
      }
      rows.p[k] = u - rj * nIn;
      rows.m[k] = R * nIn;
      rows.rhs[k] = rows.m[k].dot(g);
      rows.offset[k] = -rows.m[k].dot(goal.normals[j]);
      rows.r[k] = s * rj + delta * rows.m[k].dot(goal.normals[j]);
    };
    // Every residual under the cut is measured at a reach of the cut: the same value (a search within reach finds
    // what a search without one does).
    const bool twoPasses = cut > 0.0 && cut < reach && reach < inf;
    for (std::size_t k = 0; k < n + ng; ++k)
      measure(k, twoPasses ? cut : reach);
    std::vector<double> d;
    d.reserve(n + ng);
    for (double r : rows.r)
      if (!(cut > 0.0) || std::fabs(r) < cut)
        d.push_back(std::fabs(r));
    const double sigma = std::max(kMadToSigma * median(d), sigmaFloor);
    if (twoPasses) {
      const double cutOff = std::min(reach, tukeyConstant() * sigma);
      if (cutOff > cut)
        for (std::size_t k = 0; k < n + ng; ++k)
          if (rows.r[k] == inf)
            measure(k, cutOff);
    }
    return sigma;
  }

  static bool solveRows(Rows &rows, const Eigen::Vector4d &x, double delta, double cut, bool withOffset,
                        Eigen::MatrixXd *information, Eigen::VectorXd &z)
  {
    const int dim = withOffset ? 5 : 4;
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(dim, dim);
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(dim), J(dim);
    PointToPointSums pp;
    for (std::size_t k = 0; k < rows.r.size(); ++k) {
      const double r = rows.r[k];
      rows.w[k] = std::isfinite(r) && std::isfinite(rows.rhs[k]) ? tukeyWeight(std::fabs(r), cut) : 0.0;
      if (rows.w[k] == 0.0)
        continue;
      const Eigen::Vector2d &p = rows.p[k], &m = rows.m[k];
      J.head<4>() << m.x() * p.x() + m.y() * p.y(), m.y() * p.x() - m.x() * p.y(), m.x(), m.y();
      if (withOffset)
        J[4] = rows.offset[k];
      A.selfadjointView<Eigen::Lower>().rankUpdate(J, rows.w[k]);
      rhs += rows.w[k] * rows.rhs[k] * J;
      if (k < rows.forward) {
        const Eigen::Vector2d q = linearMap(x, p) - (r - rows.offset[k] * delta) * m;
        pp.add(rows.w[k], p.x(), p.y(), q.x(), q.y());
      }
    }
    A.triangularView<Eigen::StrictlyUpper>() = A.transpose();
    if (!(pp.sw > 0.0))
      return false;
    if (information)
      *information = A;
    // A faint point-to-point pull keeps the fit posed where every kept sample lies on one straight edge.
    Eigen::Matrix4d A4 = A.topLeftCorner<4, 4>();
    Eigen::Vector4d r4 = rhs.head<4>();
    pp.addTo(A4, r4);
    A.topLeftCorner<4, 4>() = A4;
    rhs.head<4>() = r4;
    if (withOffset)
      A(4, 4) += 1e-9 * pp.sw; // on a disc, growing the outline and scaling it are one motion
    z = A.ldlt().solve(rhs);
    return z.allFinite();
  }

  // Reweighting rounds from x at the robust scale \e sigma (in: the start's, 0 for the MAD of all residuals; out: the
  // last one), never above sigmaCap. False when no round could be solved.
  static bool irls(const Goal &goal, const std::vector<Eigen::Vector2d> &P, const InputEdges *inputEdges,
                   Eigen::Vector4d &x, double &delta, double &sigma, bool withScale, bool withOffset,
                   unsigned int iterations, double sigmaFloor, double spread,
                   double sigmaCap = std::numeric_limits<double>::infinity())
  {
    Rows rows;
    Eigen::VectorXd z;
    bool solved = false;
    for (unsigned int it = 0; it < iterations; ++it) {
      // This round's scale is under kMadToSigma times the cut (the median of residuals within it) or at its floor, so a
      // residual beyond the Tukey cut-off of that bound weighs nothing in this round's solve either.
      const double cut = tukeyConstant() * sigma;
      const double reach = cut > 0.0 ? tukeyConstant() * std::max(kMadToSigma * cut, sigmaFloor)
                                     : std::numeric_limits<double>::infinity();
      sigma = std::min(measureRows(goal, P, inputEdges, x, delta, sigmaFloor, cut, rows, reach),
                       std::max(sigmaCap, sigmaFloor));
      if (!solveRows(rows, x, delta, tukeyConstant() * sigma, withOffset, nullptr, z))
        break;
      Eigen::Vector4d xn = z.head<4>();
      if (!withScale)
        xn.head<2>() *= x.head<2>().norm() / xn.head<2>().norm();
      const double deltaNew = withOffset ? z[4] : 0.0;
      if (!(xn.head<2>().norm() > 0.0) || !xn.allFinite())
        break;
      const Eigen::Vector4d step = xn - x;
      const double moved = std::max({step.head<2>().cwiseAbs().maxCoeff() * spread,
                                     step.tail<2>().cwiseAbs().maxCoeff(), std::fabs(deltaNew - delta)});
      x = xn;
      delta = deltaNew;
      solved = true;
      // Settled once a round moves the samples by a hundredth of their noise (or a billionth of the spread).
      if (moved < std::max(0.01 * sigma, 1e-9 * spread))
        break;
    }
    return solved;
  }

  // irls() continued at scales halved from \e sigma down to \e maximum when it settled above (graduated
  // non-convexity); the solution is kept from the last stage that could be solved.
  static void graduate(const Goal &goal, const std::vector<Eigen::Vector2d> &P, const InputEdges *inputEdges,
                       Eigen::Vector4d &x, double &delta, double &sigma, bool withScale, bool withOffset,
                       unsigned int iterations, double sigmaFloor, double maximum, double spread)
  {
    while (sigma > maximum) {
      const double cap = std::max(0.5 * sigma, maximum);
      Eigen::Vector4d xs = x;
      double ds = delta, ss = cap;
      if (!irls(goal, P, inputEdges, xs, ds, ss, withScale, withOffset, iterations, sigmaFloor, spread, cap))
        return;
      x = xs;
      delta = ds;
      sigma = cap;
    }
  }

  static std::vector<Eigen::Vector2d> inputSamples(const vpMorphContour &input, const vpMorphContour &goalOutline,
                                                   std::size_t count, bool symmetric, double &cx, double &cy,
                                                   std::unique_ptr<InputEdges> &edges)
  {
    if (input.empty())
      throw vpMorphException(vpMorphException::badContourError, "vpMorphOutlineFit::fit: empty input");
    if (input.units() != goalOutline.units())
      badParameter("fit: the input and the goal have different units");
    const vpMorphContour &outline = input.outline();
    // Samples in order along the outline: a dense outline resampled evenly, a polygon along its edges.
    std::vector<Eigen::Vector2d> P;
    if (outline.size() > count) {
      const vpMorphContour sampled = outline.resampled(count);
      sampled.centroid(cx, cy);
      for (std::size_t k = 0; k < sampled.size(); ++k)
        P.emplace_back(sampled.x(k) - cx, sampled.y(k) - cy);
    } else {
      P = edgeSamples(outline, cx, cy, count);
    }
    if (symmetric) // the input's edges, for the reverse rows
      edges.reset(new InputEdges{vpMorphNearestEdge(outline), cx, cy});
    return P;
  }

  static void covarianceFrom(vpMorphOutlineFit &self, const Eigen::MatrixXd &H, const Eigen::Vector4d &x, double sigma)
  {
    const int dim = int(H.rows());
    const double s = x.head<2>().norm(), s2 = s * s;
    // d(theta, tx, ty, ln s) / d(a, b, tx, ty).
    Eigen::Matrix4d G = Eigen::Matrix4d::Zero();
    G(0, 0) = -x[1] / s2;
    G(0, 1) = x[0] / s2;
    G(1, 2) = 1.0;
    G(2, 3) = 1.0;
    G(3, 0) = x[0] / s2;
    G(3, 1) = x[1] / s2;
    Eigen::Matrix4d C;
    if (!self.m_withScale) {
      // The scale is no parameter: (a, b) move along the circle of radius s only.
      Eigen::MatrixXd B = Eigen::MatrixXd::Zero(dim, dim - 1);
      B(0, 0) = -x[1] / s;
      B(1, 0) = x[0] / s;
      for (int i = 2; i < dim; ++i)
        B(i, i - 1) = 1.0;
      const Eigen::MatrixXd Hr = B.transpose() * H * B;
      const Eigen::FullPivLU<Eigen::MatrixXd> lu(Hr);
      if (lu.rank() < Hr.rows())
        return;
      C = (B * (sigma * sigma * lu.inverse()) * B.transpose()).topLeftCorner<4, 4>();
    } else {
      const Eigen::FullPivLU<Eigen::MatrixXd> lu(H);
      if (lu.rank() < dim)
        return;
      C = (sigma * sigma * lu.inverse()).topLeftCorner<4, 4>();
    }
    const Eigen::Matrix4d Cp = G * C * G.transpose();
    for (unsigned int i = 0; i < 4; ++i)
      for (unsigned int j = 0; j < 4; ++j)
        self.m_covariance[i][j] = Cp(i, j);
  }

  // The results of a fit at its solution x (or of none: \e solved false).
  static vpMorphRigidTransform finish(vpMorphOutlineFit &self, const vpMorphContour &input,
                                      const std::vector<Eigen::Vector2d> &P, const InputEdges *inputEdges,
                                      const Eigen::Vector4d &x, double delta, double lastSigma, bool solved,
                                      double sigmaFloor, double cx, double cy, const vpMorphRigidTransform &initial)
  {
    const std::size_t n = P.size();
    self.m_residuals.assign(n, 0.0);
    self.m_covariance = vpMatrix(4, 4, 0.0);
    for (unsigned int i = 0; i < 4; ++i)
      self.m_covariance[i][i] = std::numeric_limits<double>::infinity();
    if (!solved || !x.allFinite() || !(x.head<2>().norm() > 0.0)) {
      self.m_sigma = self.m_offset = 0.0;
      self.m_inlierShare = self.m_outsideShare = self.m_insideShare = self.m_goalCoverage = 0.0;
      self.m_residuals.clear();
      return initial;
    }
    // The final residuals and weights, at the solution.
    Rows rows;
    const double sigma = measureRows(*self.m_goalData, P, inputEdges, x, delta, sigmaFloor,
                                     vpMorphOutlineFit::tukeyConstant() * lastSigma, rows);
    Eigen::MatrixXd H;
    Eigen::VectorXd z;
    const double cut = vpMorphOutlineFit::tukeyConstant() * std::min(sigma, std::max(self.m_maxSigma, sigmaFloor));
    const bool posed = solveRows(rows, x, delta, cut, self.m_withOffset, &H, z);
    // The goal's left normals point inwards on a counter-clockwise outline: a residual along them is inside.
    const double outward = self.m_goalCcw ? -1.0 : 1.0;
    std::size_t inliers = 0, covered = 0;
    for (std::size_t k = 0; k < n; ++k) {
      self.m_residuals[k] = outward * rows.r[k];
      inliers += rows.w[k] > 0.0 ? 1 : 0;
    }
    for (std::size_t k = n; k < rows.r.size(); ++k)
      covered += rows.w[k] > 0.0 ? 1 : 0;
    self.structuredOutliers(std::vector<double>(rows.w.begin(), rows.w.begin() + std::ptrdiff_t(n)), input.outline(),
                            inputEdges ? &inputEdges->edges : nullptr);
    self.m_sigma = sigma;
    self.m_offset = outward * delta; // delta moves the edges along their left normals; reported outwards
    self.m_inlierShare = double(inliers) / double(n);
    const std::size_t ng = rows.r.size() - n;
    self.m_goalCoverage = ng > 0 ? double(covered) / double(ng) : std::numeric_limits<double>::quiet_NaN();
    // Covariance of (a, b, tx, ty) from the Tukey-weighted normal equations (without the point-to-point pull), the
    // offset marginalised, mapped to (theta, tx, ty, ln s), at the residuals' own scale (their weighted mean square
    // over the degrees of freedom left), not the robust one, which is floored for the weights' sake.
    double sw = 0.0, swr2 = 0.0;
    for (std::size_t k = 0; k < rows.r.size(); ++k) {
      sw += rows.w[k];
      swr2 += rows.w[k] * rows.r[k] * rows.r[k];
    }
    const double dof = sw - double(H.rows());
    if (posed && inliers > 5 && dof > 0.0)
      covarianceFrom(self, H, x, std::sqrt(swr2 / dof));
    return fromLinearParameters(x, cx, cy);
  }
}; // Solver

vpMorphRigidTransform vpMorphOutlineFit::fit(const vpMorphContour &input, const vpMorphRigidTransform &initial,
                                             double initialSigma)
{
  if (!std::isfinite(initialSigma) || initialSigma < 0.0)
    badParameter("fit: the initial sigma must be finite and >= 0");
  double cx, cy, spread;
  std::unique_ptr<Solver::InputEdges> edges;
  const std::vector<Eigen::Vector2d> P = Solver::inputSamples(input, m_goal, m_samples, m_symmetric, cx, cy, edges);
  Eigen::Vector4d x = linearParameters(initial, cx, cy, m_goal, spread);
  double delta = 0.0, sigma = initialSigma;
  const double floor = std::max(1e-9 * std::max(spread, 1e-300), m_minSigma);
  const bool solved = Solver::irls(*m_goalData, P, edges.get(), x, delta, sigma, m_withScale, m_withOffset,
                                   m_maxIterations, floor, spread);
  if (solved)
    Solver::graduate(*m_goalData, P, edges.get(), x, delta, sigma, m_withScale, m_withOffset, m_maxIterations, floor,
                     m_maxSigma, spread);
  return Solver::finish(*this, input, P, edges.get(), x, delta, sigma, solved, floor, cx, cy, initial);
}

vpMorphRigidTransform vpMorphOutlineFit::search(const vpMorphContour &input, const vpMorphRigidTransform &initial)
{
  double cx, cy, spread;
  std::unique_ptr<Solver::InputEdges> edges;
  const std::vector<Eigen::Vector2d> P = Solver::inputSamples(input, m_goal, m_samples, m_symmetric, cx, cy, edges);
  const Eigen::Vector4d x0 = linearParameters(initial, cx, cy, m_goal, spread);
  const double floor = std::max(1e-9 * std::max(spread, 1e-300), m_minSigma);
  const std::size_t n = P.size();
  // The scales at which the input's area laid on the goal is within a factor 2 of the goal's: beyond, the larger part
  // of one cannot lie on the other (a hypothesis shrunk onto an edge, or spread over the goal's surroundings).
  const double areaRatio = std::fabs(m_goal.area()) / std::fabs(input.outline().area());
  const bool areaKnown = std::isfinite(areaRatio) && areaRatio > 0.0;
  auto admissible = [&](const Eigen::Vector4d &x) {
    const double s2 = x.head<2>().squaredNorm();
    return !areaKnown || (s2 >= 0.5 * areaRatio && s2 <= 2.0 * areaRatio);
  };
  // Hypotheses at the start's scale (a bend or a hidden part leaves the scale): the start and its turns by twelfths
  // about the input's centroid fitted on the whole input, and each of 12 windows (a sixth of the input, half
  // overlapping) fitted alone from the start, each with its own residuals' scale.
  struct Hypothesis
  {
    Eigen::Vector4d x;
    double sigma;
  };
  std::vector<Hypothesis> hypotheses;
  for (int q = 0; q < kSearchTurns; ++q) {
    Eigen::Vector4d x = x0;
    x.head<2>() = Eigen::Rotation2Dd(2.0 * M_PI * q / kSearchTurns) * x0.head<2>(); // turned about its centroid first
    double delta = 0.0, sigma = 0.0;
    if (Solver::irls(*m_goalData, P, nullptr, x, delta, sigma, false, false, m_maxIterations, floor, spread))
      hypotheses.push_back({x, sigma});
  }
  const std::size_t w = std::max<std::size_t>(4, n / 6);
  std::vector<double> windowSigmas;
  Solver::Rows rows;
  for (std::size_t k = 0; k < 12 && n >= 12; ++k) {
    std::vector<Eigen::Vector2d> window(w);
    for (std::size_t j = 0; j < w; ++j)
      window[j] = P[(k * n / 12 + j) % n];
    Eigen::Vector4d x = x0;
    double delta = 0.0, sigma = 0.0;
    if (Solver::irls(*m_goalData, window, nullptr, x, delta, sigma, false, false, m_maxIterations, floor, spread)) {
      hypotheses.push_back({x, sigma});
      Solver::measureRows(*m_goalData, window, nullptr, x, delta, floor, 0.0, rows);
      windowSigmas.push_back(differenceScale(rows.r, floor));
      // And with its scale free: a curved window finds the scale that a hidden part biased the start's by (a
      // straight one slides or shrinks, and its consensus below says so).
      double ds = 0.0, ss = 0.0;
      if (Solver::irls(*m_goalData, window, nullptr, x, ds, ss, true, false, m_maxIterations, floor, spread))
        hypotheses.push_back({x, ss});
    }
  }
  // Each hypothesis refined locally, its scale free, at the edges' noise (the median over the windows of their
  // residuals' difference scale: a window that spans a bend or a cut, or slid along a smooth arc, leaves residuals
  // that vary smoothly, not a larger noise), then scored by the consensus there: kept, among the admissible scales,
  // the one that lays the most of the input on the goal's edges, the largest rigid part of the view (what an occluder
  // leaves, the part a bend did not move). Then refined to the end.
  const double noise = windowSigmas.empty() ? 0.0 : median(windowSigmas);
  Eigen::Vector4d x = x0;
  double delta = 0.0, sigma = noise, bestCost = std::numeric_limits<double>::infinity();
  // Each from two scales: the edges' noise (it stays on the part it lies on) and the spread of all its residuals (a
  // scale the hypotheses' fixed one left off by percents, as a hidden part biases the correspondence's, is found
  // again).
  for (const Hypothesis &h : hypotheses)
    for (const double start : {noise > 0.0 ? noise : h.sigma, 0.0}) {
      // One way only: the goal's samples would pull the view over a part it does not show; the two ways' consensus
      // below rules out a view shrunk onto an edge.
      Eigen::Vector4d xh = h.x;
      double dh = 0.0, sh = start;
      if (!Solver::irls(*m_goalData, P, nullptr, xh, dh, sh, m_withScale, m_withOffset, 8, floor, spread) ||
          !admissible(xh))
        continue;
      // Both ways: a fit shrunk onto one edge of the goal lays the view on it but leaves the goal bare.
      // (A residual beyond the cost's cut-off costs 1 whatever its size.)
      const double costSigma = noise > 0.0 ? noise : sh;
      Solver::measureRows(*m_goalData, P, edges.get(), xh, dh, floor, 0.0, rows, tukeyConstant() * costSigma);
      const double c = cost(rows.r, costSigma);
      if (c < bestCost) {
        bestCost = c;
        x = xh;
        delta = dh;
        sigma = sh;
      }
    }
  const Eigen::Vector4d xBest = x;
  const double deltaBest = delta, sigmaBest = sigma;
  if (!Solver::irls(*m_goalData, P, edges.get(), x, delta, sigma, m_withScale, m_withOffset, m_maxIterations, floor,
                    spread)) {
    x = xBest;
    delta = deltaBest;
    sigma = sigmaBest;
  }
  Solver::graduate(*m_goalData, P, edges.get(), x, delta, sigma, m_withScale, m_withOffset, m_maxIterations, floor,
                   m_maxSigma, spread);
  return Solver::finish(*this, input, P, edges.get(), x, delta, sigma, true, floor, cx, cy, initial);
}
