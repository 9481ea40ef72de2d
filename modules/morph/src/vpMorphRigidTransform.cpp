#include <visp3/morph/vpMorphRigidTransform.h>

#include "vpMorphEdgeFit.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

#include <Eigen/Dense>

#include <visp3/morph/vpMorphException.h>

namespace
{
using namespace vpMorphEdgeFit;

double wrapAngle(double a)
{
  a = std::remainder(a, 2.0 * M_PI); // [-pi, pi]
  if (a <= -M_PI)
    a += 2.0 * M_PI;
  return a;
}

[[noreturn]] void badParameter(const std::string &msg)
{
  throw vpMorphException(vpMorphException::badParameterError, msg);
}

// Corresponded point sets P_k = A_{i_k}, Q_k = B_{j_k} with their per-pair length weights.
struct PairSet
{
  std::vector<Eigen::Vector2d> P, Q;
  std::vector<double> w;
};

PairSet buildPairs(const vpMorphContour &A, const vpMorphContour &B, const vpMorphCorrespondence &c)
{
  PairSet s;
  std::vector<std::pair<std::size_t, std::size_t>> pairs = c.pairs();
  // A list that repeats its starting pair at the end is the same cycle.
  if (pairs.size() > 1 && pairs.back() == pairs.front())
    pairs.pop_back();
  const std::size_t K = pairs.size();
  s.P.reserve(K);
  s.Q.reserve(K);
  for (const auto &p : pairs) {
    s.P.emplace_back(A.x(p.first), A.y(p.first));
    s.Q.emplace_back(B.x(p.second), B.y(p.second));
  }
  // Length of the corresponded segment from pair k to pair k+1 on each side (0 when that side repeats).
  std::vector<double> dP(K), dQ(K);
  double LP = 0.0, LQ = 0.0;
  for (std::size_t k = 0; k < K; ++k) {
    const std::size_t k1 = (k + 1) % K;
    dP[k] = (s.P[k1] - s.P[k]).norm();
    dQ[k] = (s.Q[k1] - s.Q[k]).norm();
    LP += dP[k];
    LQ += dQ[k];
  }
  s.w.resize(K);
  for (std::size_t k = 0; k < K; ++k) {
    const std::size_t km = (k + K - 1) % K;
    const double wp = LP > 0 ? 0.5 * (dP[km] + dP[k]) / LP : 1.0 / K;
    const double wq = LQ > 0 ? 0.5 * (dQ[km] + dQ[k]) / LQ : 1.0 / K;
    s.w[k] = 0.5 * (wp + wq);
  }
  return s;
}

// Similarity x' = s R(theta) (x - muP) + muQ.
struct Similarity
{
  double theta = 0.0, scale = 1.0;
  Eigen::Vector2d muP = Eigen::Vector2d::Zero(), muQ = Eigen::Vector2d::Zero();
  Eigen::Vector2d operator()(const Eigen::Vector2d &x) const
  {
    return scale * Eigen::Rotation2Dd(theta).toRotationMatrix() * (x - muP) + muQ;
  }
};

void weightedMeans(const PairSet &s, const std::vector<double> &w, Eigen::Vector2d &muP, Eigen::Vector2d &muQ)
{
  double W = 0.0;
  muP.setZero();
  muQ.setZero();
  for (std::size_t k = 0; k < w.size(); ++k) {
    muP += w[k] * s.P[k];
    muQ += w[k] * s.Q[k];
    W += w[k];
  }
  muP /= W;
  muQ /= W;
}

// Closed-form weighted 2-D Procrustes (Umeyama without reflection): the rotation maximises
// sum w (R p').q', i.e. theta = atan2(sum w p' x q', sum w p'.q'); the scale is the least-squares one.
Similarity procrustes(const PairSet &s, const std::vector<double> &w, bool withScale)
{
  Similarity T;
  weightedMeans(s, w, T.muP, T.muQ);
  double sdot = 0.0, scross = 0.0, varP = 0.0;
  for (std::size_t k = 0; k < w.size(); ++k) {
    const Eigen::Vector2d p = s.P[k] - T.muP, q = s.Q[k] - T.muQ;
    sdot += w[k] * p.dot(q);
    scross += w[k] * (p.x() * q.y() - p.y() * q.x());
    varP += w[k] * p.squaredNorm();
  }
  T.theta = std::atan2(scross, sdot);
  if (withScale && varP > 0.0) {
    const double s_ = std::hypot(sdot, scross) / varP;
    if (s_ > 0.0 && std::isfinite(s_))
      T.scale = s_;
  }
  return T;
}

// Robust scale of the residuals: 1.4826 MAD of the pooled x and y residual components.
double robustSigma(const PairSet &s, const Similarity &T)
{
  std::vector<double> e;
  e.reserve(2 * s.P.size());
  for (std::size_t k = 0; k < s.P.size(); ++k) {
    const Eigen::Vector2d r = T(s.P[k]) - s.Q[k];
    e.push_back(r.x());
    e.push_back(r.y());
  }
  const double med = median(e);
  for (double &v : e)
    v = std::fabs(v - med);
  return 1.4826 * median(e);
}

vpMorphRigidTransform toTransform(const Similarity &T, const vpMorphContour &input)
{
  // Written about the input's area centroid c: x' = sR(x - c) + c + t with t = sR(c - muP) + muQ - c.
  double cx, cy;
  input.centroid(cx, cy);
  const Eigen::Vector2d c(cx, cy);
  const Eigen::Vector2d t = T(c) - c;
  return vpMorphRigidTransform(T.theta, t.x(), t.y(), T.scale, cx, cy);
}

// A shape's elongation vector: the centroid and principal axis of the region its contour encloses, from the region's
// moments (the measured ones when the contour carries them: vpMorphContour::hasRegion()), which neither the vertices'
// placement along an edge nor the outline's pixel-scale detail moves. \e anisotropy: (l1 - l2) / (l1 + l2);
// \e spread2: the trace of the covariance (the square of the shape's size up to a constant).
void elongation(const vpMorphContour &c, Eigen::Vector2d &mu, double &angle, double &anisotropy, double &spread2)
{
  double cx, cy, m20, m11, m02;
  c.regionCentroid(cx, cy);
  c.regionMoments(m20, m11, m02);
  mu = Eigen::Vector2d(cx, cy);
  angle = 0.5 * std::atan2(2.0 * m11, m20 - m02);
  const double tr = m20 + m02;
  anisotropy = tr > 0.0 ? std::hypot(m20 - m02, 2.0 * m11) / tr : 0.0;
  spread2 = tr;
}
} // namespace

vpMorphRigidTransform::vpMorphRigidTransform(double theta, double tx, double ty, double scale, double cx, double cy)
  : m_theta(wrapAngle(theta)), m_tx(tx), m_ty(ty), m_scale(scale), m_cx(cx), m_cy(cy)
{
  if (!std::isfinite(theta) || !std::isfinite(tx) || !std::isfinite(ty) || !std::isfinite(scale) ||
      !std::isfinite(cx) || !std::isfinite(cy) || !(scale > 0.0)) {
    std::ostringstream os;
    os << "vpMorphRigidTransform: parameters must be finite with scale > 0 (theta " << theta << ", t (" << tx << ", "
       << ty << "), scale " << scale << ", centre (" << cx << ", " << cy << "))";
    badParameter(os.str());
  }
}

void vpMorphRigidTransform::apply(double x, double y, double &xo, double &yo) const
{
  const double c = m_scale * std::cos(m_theta), s = m_scale * std::sin(m_theta);
  const double dx = x - m_cx, dy = y - m_cy;
  xo = c * dx - s * dy + m_cx + m_tx;
  yo = s * dx + c * dy + m_cy + m_ty;
}

vpImagePoint vpMorphRigidTransform::apply(const vpImagePoint &p) const
{
  double x, y;
  apply(p.get_u(), p.get_v(), x, y);
  return vpImagePoint(y, x);
}

vpMorphContour vpMorphRigidTransform::apply(const vpMorphContour &contour) const
{
  if (contour.empty())
    throw vpMorphException(vpMorphException::badContourError, "vpMorphRigidTransform::apply: empty contour");
  std::vector<double> x(contour.size()), y(contour.size());
  for (std::size_t k = 0; k < contour.size(); ++k)
    apply(contour.x(k), contour.y(k), x[k], y[k]);
  vpMorphContour out(x, y, contour.units());
  if (contour.hasRegion() || contour.hasOutline()) { // they move with their polygon: x' = s R (x - c) + c + t
    if (contour.hasRegion()) {
      double cx, cy, mu20, mu11, mu02;
      contour.regionCentroid(cx, cy);
      contour.regionMoments(mu20, mu11, mu02);
      out.setRegion(contour.regionArea(), cx, cy, mu20, mu11, mu02);
    }
    if (contour.hasOutline())
      out.setOutline(contour.outline(), contour.outlineBlur());
    const double a = m_scale * std::cos(m_theta), b = m_scale * std::sin(m_theta);
    out.mapRegion(a, -b, b, a, m_cx + m_tx - a * m_cx + b * m_cy, m_cy + m_ty - b * m_cx - a * m_cy);
  }
  return out;
}

vpMorphRigidTransform vpMorphRigidTransform::interpolated(double alpha, bool longWay) const
{
  if (!std::isfinite(alpha) || alpha < 0.0 || alpha > 1.0) {
    std::ostringstream os;
    os << "vpMorphRigidTransform::interpolated: alpha must be in [0, 1] (got " << alpha << ")";
    badParameter(os.str());
  }
  const double theta = longWay ? m_theta - std::copysign(2.0 * M_PI, m_theta) : m_theta;
  return vpMorphRigidTransform(alpha * theta, alpha * m_tx, alpha * m_ty, std::pow(m_scale, alpha), m_cx, m_cy);
}

vpMorphRigidTransform vpMorphRigidTransform::inverse() const
{
  return vpMorphRigidTransform(-m_theta, -m_tx, -m_ty, 1.0 / m_scale, m_cx + m_tx, m_cy + m_ty);
}

vpMorphRigidTransform vpMorphRigidTransform::operator*(const vpMorphRigidTransform &b) const
{
  // Image of b's centre under the composite gives the translation about that centre.
  double x, y;
  b.apply(b.m_cx, b.m_cy, x, y);
  double xo, yo;
  apply(x, y, xo, yo);
  return vpMorphRigidTransform(m_theta + b.m_theta, xo - b.m_cx, yo - b.m_cy, m_scale * b.m_scale, b.m_cx, b.m_cy);
}

vpMorphRigidTransform vpMorphRigidTransform::recentred(double cx, double cy) const
{
  double x, y;
  apply(cx, cy, x, y);
  return vpMorphRigidTransform(m_theta, x - cx, y - cy, m_scale, cx, cy);
}

vpMatrix vpMorphRigidTransform::toMatrix() const
{
  vpMatrix M(3, 3, 0.0);
  const double c = m_scale * std::cos(m_theta), s = m_scale * std::sin(m_theta);
  double bx, by;
  apply(0.0, 0.0, bx, by);
  M[0][0] = c;
  M[0][1] = -s;
  M[0][2] = bx;
  M[1][0] = s;
  M[1][1] = c;
  M[1][2] = by;
  M[2][2] = 1.0;
  return M;
}

void vpMorphRigidTransform::checkCorrespondence(const vpMorphContour &input, const vpMorphContour &target,
                                                const vpMorphCorrespondence &corr, const char *caller)
{
  const std::string who(caller);
  if (input.empty() || target.empty())
    throw vpMorphException(vpMorphException::badContourError,
                           who + ": the " + (input.empty() ? "input" : "target") + " contour is empty");
  if (input.units() != target.units())
    badParameter(who + ": the input and target contours have different units (one in pixels, one normalised)");
  std::ostringstream os;
  if (corr.empty()) {
    badParameter(who + ": the correspondence is empty");
  }
  if (corr.inputSize() != input.size() || corr.targetSize() != target.size()) {
    os << who << ": the correspondence is between " << corr.inputSize() << " and " << corr.targetSize()
       << " vertices but the contours have " << input.size() << " and " << target.size();
    badParameter(os.str());
  }
  std::vector<char> seenA(input.size(), 0), seenB(target.size(), 0);
  for (std::size_t k = 0; k < corr.size(); ++k) {
    const auto &p = corr.pairs()[k];
    if (p.first >= input.size() || p.second >= target.size()) {
      os << who << ": pair " << k << " (" << p.first << ", " << p.second << ") is out of range for contours of "
         << input.size() << " and " << target.size() << " vertices";
      badParameter(os.str());
    }
    seenA[p.first] = seenB[p.second] = 1;
  }
  for (std::size_t i = 0; i < seenA.size(); ++i)
    if (!seenA[i]) {
      os << who << ": input vertex " << i << " is not in the correspondence";
      badParameter(os.str());
    }
  for (std::size_t j = 0; j < seenB.size(); ++j)
    if (!seenB[j]) {
      os << who << ": target vertex " << j << " is not in the correspondence";
      badParameter(os.str());
    }
}

vpMorphRigidTransform vpMorphRigidTransform::fitElongation(const vpMorphContour &input, const vpMorphContour &target,
                                                           const vpMorphCorrespondence &corr, bool withScale,
                                                           double *anisotropy)
{
  checkCorrespondence(input, target, corr, "vpMorphRigidTransform::fitElongation");
  const PairSet s = buildPairs(input, target, corr);
  // Every vertex of both polygons is corresponded: each shape's corresponded points are its whole contour.
  Similarity T;
  double aP, aQ, anP, anQ, vP, vQ;
  elongation(input, T.muP, aP, anP, vP);
  elongation(target, T.muQ, aQ, anQ, vQ);
  if (anisotropy)
    *anisotropy = std::min(anP, anQ);
  if (withScale && vP > 0.0 && vQ > 0.0)
    T.scale = std::sqrt(vQ / vP);
  // An axis has no sign: of theta and theta + pi keep the one that makes the corresponded points agree.
  const double theta0 = aQ - aP;
  double agree = 0.0;
  const Eigen::Matrix2d R = Eigen::Rotation2Dd(theta0).toRotationMatrix();
  for (std::size_t k = 0; k < s.P.size(); ++k)
    agree += s.w[k] * (R * (s.P[k] - T.muP)).dot(s.Q[k] - T.muQ);
  T.theta = agree >= 0.0 ? theta0 : theta0 + M_PI;
  return toTransform(T, input);
}

vpMorphRigidTransform vpMorphRigidTransform::fitLeastSquares(const vpMorphContour &input, const vpMorphContour &target,
                                                             const vpMorphCorrespondence &corr, bool withScale,
                                                             RobustLoss loss, unsigned int maxIterations,
                                                             double minSigma)
{
  checkCorrespondence(input, target, corr, "vpMorphRigidTransform::fitLeastSquares");
  if (maxIterations < 1)
    badParameter("vpMorphRigidTransform::fitLeastSquares: maxIterations must be >= 1");
  if (!std::isfinite(minSigma) || minSigma < 0.0)
    badParameter("vpMorphRigidTransform::fitLeastSquares: minSigma must be finite and >= 0");
  const PairSet s = buildPairs(input, target, corr);
  Similarity T = procrustes(s, s.w, withScale);
  if (loss == NO_ROBUST)
    return toTransform(T, input);

  // Floor for the robust scale: residuals of an exact fit are rounding noise, not a scale.
  Eigen::Vector2d muP, muQ;
  weightedMeans(s, s.w, muP, muQ);
  double spread = 0.0;
  for (const Eigen::Vector2d &q : s.Q)
    spread = std::max(spread, (q - muQ).norm());
  // and the caller's resolution of the coordinates (see minSigma).
  const double sigmaMin = std::max(1e-9 * std::max(spread, 1e-300), minSigma);

  const int stages = loss == TUKEY ? 2 : 1;
  std::vector<double> w(s.w.size());
  for (int stage = 0; stage < stages; ++stage) {
    const bool tukey = stage == 1;
    for (unsigned int it = 0; it < maxIterations; ++it) {
      const double sigma = std::max(robustSigma(s, T), sigmaMin);
      const double c = tukey ? 5.0 * sigma : 2.0 * sigma;
      double W = 0.0;
      for (std::size_t k = 0; k < w.size(); ++k) {
        const double r = (T(s.P[k]) - s.Q[k]).norm();
        double rho;
        if (tukey)
          rho = tukeyWeight(r, c);
        else
          rho = r <= c ? 1.0 : c / r;
        w[k] = s.w[k] * rho;
        W += w[k];
      }
      if (!(W > 0.0))
        break; // keep the previous estimate rather than divide by zero
      const Similarity Tn = procrustes(s, w, withScale);
      const double dTheta = std::fabs(wrapAngle(Tn.theta - T.theta));
      const double dT = (Tn(muP) - T(muP)).norm();
      const double dS = std::fabs(Tn.scale - T.scale);
      T = Tn;
      if (dTheta < 1e-12 && dT < 1e-12 * std::max(spread, 1.0) && dS < 1e-12)
        break;
    }
  }
  return toTransform(T, input);
}
