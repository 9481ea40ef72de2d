#include <visp3/morph/vpMorphRigidCheck.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/Dense>

#include <visp3/morph/vpMorphException.h>

#include "vpMorphEdgeFit.h"
#include "vpMorphRigidShapeData.h"

namespace
{
using vpMorphEdgeFit::tukeyLoss;
using vpMorphEdgeFit::tukeyWeight;
typedef Eigen::Matrix3d Mat3;
typedef Eigen::Matrix<double, 8, 8> Mat8;
typedef Eigen::Matrix<double, 8, 1> Vec8;

constexpr int kIterations = 8;        // Gauss-Newton steps
constexpr std::size_t kFitStride = 4; // the fit uses every 4th fine sample: 64 a side
constexpr double kFirstCutOff = 0.05; // the Tukey cut-off's start, in target sizes (a coarse alignment's error)
constexpr double kShrink = 0.6;       // and its decrease a step, down to twice the tolerance
constexpr double kMaxTilt = 45.0 * M_PI / 180.0; // the steepest view of a part that the check admits

// The input and the target as check() from \e start compares them, both at one blur: the sharper laid at the other's,
// the start's scale converting between their pixels.
const vpMorphRigidShape &laidInput(const vpMorphRigidShape &input, const vpMorphRigidShape &target,
                                   const vpMorphRigidTransform &start)
{
  const double scale = start.scale();
  return scale > 0.0 && std::isfinite(scale) ? input.atBlur(target.contour().outlineBlur() / scale) : input;
}

const vpMorphRigidShape &laidTarget(const vpMorphRigidShape &input, const vpMorphRigidShape &target,
                                    const vpMorphRigidTransform &start)
{
  const double scale = start.scale();
  return scale > 0.0 && std::isfinite(scale) ? target.atBlur(input.contour().outlineBlur() * scale) : target;
}

// Maps (x, y) by H; false at infinity.
inline bool project(const Mat3 &H, double x, double y, double &X, double &Y, double &w)
{
  w = H(2, 0) * x + H(2, 1) * y + H(2, 2);
  if (!(std::fabs(w) > 1e-12))
    return false;
  const double iw = 1.0 / w;
  X = (H(0, 0) * x + H(0, 1) * y + H(0, 2)) * iw;
  Y = (H(1, 0) * x + H(1, 1) * y + H(1, 2)) * iw;
  return std::isfinite(X) && std::isfinite(Y);
}

// Normalised frames: input u = (p - ci) / si, target U = (P - ct) / st; G maps u to U.
struct Frames
{
  double ci_x, ci_y, si, ct_x, ct_y, st;
  Mat3 toPixels(const Mat3 &G) const
  {
    Mat3 A, B;
    A << 1.0 / si, 0, -ci_x / si, 0, 1.0 / si, -ci_y / si, 0, 0, 1;
    B << st, 0, ct_x, 0, st, ct_y, 0, 0, 1;
    return B * G * A;
  }
};

/*
  One Gauss-Newton step of G (h33 = 1) on the point-to-edge distances of the input's samples mapped onto the target
  and of the target's samples mapped back onto the input, Tukey-weighted at cut-off c (target sizes); false when the
  system is singular or a point maps to infinity. Given \e objective, G is left as it is and the mean Tukey loss of
  those distances (tukeyLoss()) is stored there instead: what the step descends.
*/
bool step(const vpMorphRigidShapeData &in, const vpMorphRigidShapeData &tg, const Frames &f, Mat3 &G, double c,
          double *objective = nullptr)
{
  double loss = 0.0;
  std::size_t samples = 0;
  Mat8 A = Mat8::Zero();
  Vec8 b = Vec8::Zero();
  std::size_t used = 0;
  const double isi = 1.0 / f.si, ist = 1.0 / f.st;
  // Input to target: r = m . (G u - nearest), in target sizes. Only the input's own edges: an occluder's edge or a
  // bridge is no part of the target's outline.
  for (std::size_t i = 0; i < in.fx.size(); i += kFitStride) {
    if (in.marked && !in.fown[i])
      continue;
    const double x = (in.fx[i] - f.ci_x) * isi, y = (in.fy[i] - f.ci_y) * isi;
    double X, Y, w;
    if (!project(G, x, y, X, Y, w))
      return false;
    double mx, my;
    const double r = tg.fineEdges.within(f.ct_x + X * f.st, f.ct_y + Y * f.st, c * f.st, mx, my) * ist;
    if (objective) {
      loss += tukeyLoss(r, c);
      ++samples;
      continue;
    }
    const double wt = std::isfinite(r) ? tukeyWeight(std::fabs(r), c) : 0.0;
    if (wt <= 0.0)
      continue;
    // d(X, Y) / d(h11 h12 h13 h21 h22 h23 h31 h32)
    const double ax = mx / w, ay = my / w, az = -(mx * X + my * Y) / w;
    const Vec8 J = (Vec8() << ax * x, ax * y, ax, ay * x, ay * y, ay, az * x, az * y).finished();
    A.noalias() += wt * J * J.transpose();
    b.noalias() -= wt * r * J;
    ++used;
  }
  // Target to input through G^-1: d(G^-1 U) = -G^-1 dG G^-1 U; r in input sizes, onto the input's own edges.
  const Mat3 Gi = G.inverse();
  for (std::size_t i = 0; i < tg.fx.size(); i += kFitStride) {
    const Eigen::Vector3d U((tg.fx[i] - f.ct_x) * ist, (tg.fy[i] - f.ct_y) * ist, 1.0);
    const Eigen::Vector3d v = Gi * U;
    if (!(std::fabs(v(2)) > 1e-12))
      return false;
    const double iz = 1.0 / v(2), x = v(0) * iz, y = v(1) * iz;
    double mx, my;
    const double r = in.ownEdges().within(f.ci_x + x * f.si, f.ci_y + y * f.si, c * f.si, mx, my) * isi;
    if (objective) {
      loss += tukeyLoss(r, c);
      ++samples;
      continue;
    }
    const double wt = std::isfinite(r) ? tukeyWeight(std::fabs(r), c) : 0.0;
    if (wt <= 0.0)
      continue;
    Vec8 J;
    for (int k = 0; k < 8; ++k) {
      const int row = k / 3, col = k % 3; // parameter k is G(row, col)
      const Eigen::Vector3d dv = -Gi.col(row) * v(col);
      J(k) = (mx * (dv(0) - x * dv(2)) + my * (dv(1) - y * dv(2))) * iz;
    }
    A.noalias() += wt * J * J.transpose();
    b.noalias() -= wt * r * J;
    ++used;
  }
  if (objective) {
    *objective = samples > 0 ? loss / static_cast<double>(samples) : 1.0;
    return true;
  }
  if (used < 8)
    return false;
  A.diagonal() *= 1.0 + 1e-6; // Levenberg's damping: directions the outlines do not fix stay put
  const Vec8 d = A.ldlt().solve(b);
  if (!d.allFinite())
    return false;
  for (int k = 0; k < 8; ++k)
    G(k / 3, k % 3) += d(k);
  return true;
}

/*
  Whether G (normalised frames) is a view of a flat part at most kMaxTilt from the target's: the local affine map's
  singular values differ at most by the cosine of the tilt (a disc seen tilted is an ellipse of that aspect), keep the
  orientation, and its area scale varies across the input by at most a factor 2 (the perspective of a part whose depth
  varies by a fifth). A homography fitted freely can squash an outline onto a few edges of another, which no camera
  sees.
*/
bool admissible(const Mat3 &G, const vpMorphRigidShapeData &in, const Frames &f)
{
  auto jacobian = [&G](double x, double y, double &det, double &ratio) {
    double X, Y, w;
    if (!project(G, x, y, X, Y, w))
      return false;
    const double a = (G(0, 0) - X * G(2, 0)) / w, b = (G(0, 1) - X * G(2, 1)) / w;
    const double c = (G(1, 0) - Y * G(2, 0)) / w, d = (G(1, 1) - Y * G(2, 1)) / w;
    det = a * d - b * c;
    // Singular values of [a b; c d]: s1 s2 = |det|, s1^2 + s2^2 = |J|_F^2.
    const double fro = a * a + b * b + c * c + d * d, disc = std::sqrt(std::max(0.0, fro * fro - 4.0 * det * det));
    const double s1 = std::sqrt(0.5 * (fro + disc)), s2 = std::sqrt(std::max(0.0, 0.5 * (fro - disc)));
    ratio = s1 > 0.0 ? s2 / s1 : 0.0;
    return std::isfinite(det) && det > 0.0;
  };
  double det0, ratio;
  if (!jacobian(0.0, 0.0, det0, ratio) || ratio < std::cos(kMaxTilt))
    return false;
  for (std::size_t i = 0; i < in.fx.size(); i += kFitStride) {
    double det;
    if (!jacobian((in.fx[i] - f.ci_x) / f.si, (in.fy[i] - f.ci_y) / f.si, det, ratio) || det > 2.0 * det0 ||
        det < 0.5 * det0)
      return false;
  }
  return true;
}

// \e side's fine sample \e i mapped by H to (X, Y), and \e e its distance to \e other's outline (+inf beyond 2 tol);
// false when it maps to infinity.
inline bool mapped(const vpMorphRigidShapeData &side, const vpMorphRigidShapeData &other, const Mat3 &H, double tol,
                   std::size_t i, double &X, double &Y, double &e)
{
  double w, mx, my;
  if (!project(H, side.fx[i], side.fy[i], X, Y, w))
    return false;
  e = std::fabs(other.fineEdges.within(X, Y, 2.0 * tol, mx, my));
  return true;
}

/*
  Share of \e side's fine samples within tol of the other curve once mapped by H (pixels), their mean truncated
  quadratic distance, (when \e outside is given) the share beyond 2 tol outside the other curve and (when \e
  unexplained is given) the share on its own edge (vpMorphContour::ownEdge()) beyond tol. With \e base (the other side's
  mean, 0 for the first side) and \e abandonAbove >= 0: false as soon as the check's cost, 0.5 (base + mean), is sure to
  exceed abandonAbove, \e cost then that bound (a partial sum of terms >= 0 never exceeds the sum, rounding included,
  and the operations after it are monotone).
*/
bool measure(const vpMorphRigidShapeData &side, const vpMorphRigidShapeData &other, const Mat3 &H, double tol,
             double &share, double &cost, double *outside = nullptr, double *unexplained = nullptr, double base = 0.0,
             double abandonAbove = -1.0)
{
  std::size_t on = 0, out = 0, own = 0;
  double sum = 0.0;
  const bool sign = outside != nullptr;
  const double n = static_cast<double>(side.fx.size());
  for (std::size_t i = 0; i < side.fx.size(); ++i) {
    if (abandonAbove >= 0.0 && 0.5 * (base + sum / n) > abandonAbove) {
      cost = 0.5 * (base + sum / n);
      return false;
    }
    double X, Y, e, d = 2.0 * tol; // beyond tol: unexplained
    if (mapped(side, other, H, tol, i, X, Y, e)) {
      if (e <= tol) {
        d = e;
        ++on;
      } else if (sign && e > 2.0 * tol && !other.fineInside(X, Y)) {
        ++out;
      }
    }
    own += d > tol && side.fown[i];
    d = std::min(d, tol);
    sum += (d * d) / (tol * tol);
  }
  share = static_cast<double>(on) / n;
  cost = sum / n;
  if (outside)
    *outside = static_cast<double>(out) / n;
  if (unexplained)
    *unexplained = static_cast<double>(own) / n;
  return true;
}
} // namespace

double vpMorphRigidCheck::tolerance(const vpMorphContour &input, const vpMorphContour &target)
{
  const double px = input.hasOutline() && target.hasOutline() ? 0.5 : 1.5;
  return target.units() == vpMorphContour::PIXEL ? px : px * std::sqrt(target.regionArea()) / 128.0;
}

vpMorphRigidCheck::Result vpMorphRigidCheck::check(const vpMorphRigidShape &input, const vpMorphRigidShape &target,
                                                   const vpMorphRigidTransform &start)
{
  return checkFrom(input, target, start, -1.0);
}

namespace
{
// The similarity \e start (input pixels to target pixels) in the normalised frames: U = (T(p) - ct) / st with
// p = ci + si u.
Mat3 normalised(const vpMorphRigidTransform &start, const vpMorphRigidShapeData &in, const vpMorphRigidShapeData &tg)
{
  double ox, oy;
  start.apply(in.cx, in.cy, ox, oy);
  const double k = start.scale() * in.size / tg.size, c = std::cos(start.theta()), s = std::sin(start.theta());
  Mat3 G;
  G << k * c, -k * s, (ox - tg.cx) / tg.size, k * s, k * c, (oy - tg.cy) / tg.size, 0, 0, 1;
  return G;
}
} // namespace

bool vpMorphRigidCheck::laid(const vpMorphRigidShape &input, const vpMorphRigidShape &target,
                             const vpMorphRigidTransform &start, const vpMorphRigidShapeData *&in,
                             const vpMorphRigidShapeData *&tg)
{
  if (input.empty() || target.empty())
    throw vpMorphException(vpMorphException::badParameterError, "vpMorphRigidCheck: empty shape");
  // A start off the sizes a view of the target can have (as the coarse stage's: vpMorphRigidShape) is no view of it,
  // and laying either at the other's blur through it would blur a part out of all measure.
  const double sizes = start.scale() * input.m_data->size / target.m_data->size;
  if (!(sizes >= 0.5 && sizes <= 2.0))
    return false;
  in = laidInput(input, target, start).m_data.get();
  tg = laidTarget(input, target, start).m_data.get();
  if (in->contour.units() != tg->contour.units())
    throw vpMorphException(vpMorphException::badParameterError, "vpMorphRigidCheck: the contours' units differ");
  return true;
}

double vpMorphRigidCheck::startCost(const vpMorphRigidShape &input, const vpMorphRigidShape &target,
                                    const vpMorphRigidTransform &start)
{
  const vpMorphRigidShapeData *in = nullptr, *tg = nullptr;
  if (!laid(input, target, start, in, tg))
    return 1.0;
  Mat3 G = normalised(start, *in, *tg);
  double objective = 1.0;
  return step(*in, *tg, Frames{in->cx, in->cy, in->size, tg->cx, tg->cy, tg->size}, G, kFirstCutOff, &objective)
             ? objective
             : 1.0;
}

vpMorphRigidCheck::Result vpMorphRigidCheck::checkFrom(const vpMorphRigidShape &input, const vpMorphRigidShape &target,
                                                       const vpMorphRigidTransform &start, double abandonAbove)
{
  const vpMorphRigidShapeData *pin = nullptr, *ptg = nullptr;
  if (!laid(input, target, start, pin, ptg))
    return Result();
  const vpMorphRigidShapeData &in = *pin, &tg = *ptg;
  const Frames f{in.cx, in.cy, in.size, tg.cx, tg.cy, tg.size};
  Mat3 G = normalised(start, in, tg);
  Result r;
  const double tol = tolerance(in.contour, tg.contour);
  double cut = kFirstCutOff;
  for (int it = 0; it < kIterations; ++it, cut = std::max(2.0 * tol / tg.size, cut * kShrink))
    if (!step(in, tg, f, G, cut))
      return r;
  if (!admissible(G, in, f))
    return r;
  const Mat3 H = f.toPixels(G);
  double ci = 1.0, ct = 1.0;
  // A silhouette joined across its occluder (no measured region) has bridges, which may pass outside the target.
  // Abandoned: the result is the bound on the cost that exceeds abandonAbove.
  Result abandoned;
  if (!measure(in, tg, H, tol, r.inputShare, abandoned.cost, in.contour.hasRegion() ? &r.outsideShare : nullptr,
               &r.unexplainedShare, 0.0, abandonAbove))
    return abandoned;
  ci = abandoned.cost;
  // A view whose outline is its own edge all round (vpMorphContour::ownEdge(): no occluder, nor the image's border,
  // cuts it) hides nothing: the target's outline it leaves outside its region is absent. Otherwise it does not tell.
  const bool hidesNothing = in.marked && !in.ownOnly;
  if (!measure(tg, in, H.inverse(), tol, r.targetShare, abandoned.cost, hidesNothing ? &r.absentShare : nullptr,
               nullptr, ci, abandonAbove))
    return abandoned;
  ct = abandoned.cost;
  r.cost = 0.5 * (ci + ct);
  vpMatrix M(3, 3);
  for (unsigned int i = 0; i < 3; ++i)
    for (unsigned int j = 0; j < 3; ++j)
      M[i][j] = H(i, j);
  try {
    r.homography = vpMorphHomography(M);
  } catch (const vpException &) {
    return Result(); // singular: no fit
  }
  r.start = start;
  r.fitted = true;
  return r;
}

vpMorphRigidCheck::Result vpMorphRigidCheck::check(const vpMorphRigidShape &input, const vpMorphRigidShape &target,
                                                   const vpMorphRigidShape::Alignment &alignment)
{
  return check(input, target, alignment, -1.0);
}

vpMorphRigidCheck::Result vpMorphRigidCheck::check(const vpMorphRigidShape &input, const vpMorphRigidShape &target,
                                                   const vpMorphRigidShape::Alignment &alignment, double abandonAbove)
{
  Result r = checkFrom(input, target, alignment.transform, abandonAbove);
  // The other hypotheses matter only below the least cost so far.
  auto tryFrom = [&](const vpMorphRigidTransform &start) {
    const double above = abandonAbove >= 0.0 ? std::min(abandonAbove, r.cost) : r.cost;
    const Result a = checkFrom(input, target, start, above);
    if (a.cost < r.cost)
      r = a;
  };
  if (alignment.hasAlternative)
    tryFrom(alignment.alternative);
  for (const vpMorphRigidShape::Hypothesis &h : alignment.symmetric)
    tryFrom(h.transform);
  return r;
}

vpMorphRigidCheck::Result vpMorphRigidCheck::check(const vpMorphContour &input, const vpMorphContour &target,
                                                   const vpMorphRigidTransform &start)
{
  return check(vpMorphRigidShape(input), vpMorphRigidShape(target), start);
}

double vpMorphRigidCheck::similarityDeviation(const vpMorphContour &input, const vpMorphContour &target,
                                              double quantile)
{
  if (input.units() != target.units())
    throw vpMorphException(vpMorphException::badParameterError,
                           "vpMorphRigidCheck::similarityDeviation: the contours' units differ");
  return similarityDeviation(vpMorphRigidShape(input), vpMorphRigidShape(target), quantile);
}

double vpMorphRigidCheck::similarityDeviation(const vpMorphRigidShape &a, const vpMorphRigidShape &b, double quantile)
{
  if (!(quantile >= 0.0 && quantile <= 1.0))
    throw vpMorphException(vpMorphException::badParameterError,
                           "vpMorphRigidCheck::similarityDeviation: the quantile must be in [0, 1]");
  if (a.empty() || b.empty() || a.contour().units() != b.contour().units())
    throw vpMorphException(vpMorphException::badParameterError,
                           "vpMorphRigidCheck::similarityDeviation: empty shapes or units that differ");
  const vpMorphRigidShapeData &in = *a.m_data, &tg = *b.m_data;
  double best = std::numeric_limits<double>::infinity();
  for (const vpMorphRigidTransform &start : {a.alignOn(b, false).transform, b.alignOn(a, false).transform.inverse()}) {
    try {
      const vpMorphRigidTransform T = vpMorphRigidTransform::refineOnOutline(in.fine, tg.fine, start, true, 0.05, 30);
      const vpMorphRigidTransform Ti = T.inverse();
      std::vector<double> d;
      double mx, my, x, y;
      for (std::size_t i = 0; i < in.fx.size(); ++i) {
        T.apply(in.fx[i], in.fy[i], x, y);
        d.push_back(std::fabs(tg.fineEdges(x, y, mx, my)));
      }
      for (std::size_t i = 0; i < tg.fx.size(); ++i) {
        Ti.apply(tg.fx[i], tg.fy[i], x, y);
        d.push_back(std::fabs(in.fineEdges(x, y, mx, my)) * T.scale());
      }
      const std::size_t k = std::min(d.size() - 1, static_cast<std::size_t>(quantile * d.size()));
      std::nth_element(d.begin(), d.begin() + static_cast<long>(k), d.end());
      if (std::isfinite(d[k]))
        best = std::min(best, d[k] / std::max(1.0, T.scale()));
    } catch (const vpException &) {
      // that start degenerated: the other may not have
    }
  }
  return best;
}

namespace
{
Mat3 toMat3(const vpMorphHomography &h)
{
  Mat3 H;
  for (unsigned int i = 0; i < 3; ++i)
    for (unsigned int j = 0; j < 3; ++j)
      H(static_cast<int>(i), static_cast<int>(j)) = h.matrix()[i][j];
  return H;
}

// Each of \e in's fine samples mapped by H: its truncated quadratic distance to \e tg's outline, min(d, tol)^2 / tol^2
// (1: not within tol).
std::vector<double> terms(const vpMorphRigidShapeData &in, const vpMorphRigidShapeData &tg, const Mat3 &H, double tol)
{
  std::vector<double> t(in.fx.size(), 1.0);
  double X, Y, d;
  for (std::size_t i = 0; i < t.size(); ++i)
    if (mapped(in, tg, H, tol, i, X, Y, d) && d <= tol)
      t[i] = d * d / (tol * tol);
  return t;
}

// The mean of terms() of \e tg's samples mapped back onto the input (H input to target), a sample the input does not
// show counting 0 when its nearest input sample is an occluder's edge: hidden there, not absent.
double targetSide(const vpMorphRigidShapeData &in, const vpMorphRigidShapeData &tg, const Mat3 &H, double tol,
                  const std::vector<char> &occluderEdge)
{
  const Mat3 Hi = H.inverse();
  const std::vector<double> t = terms(tg, in, Hi, tol);
  double sum = 0.0, X, Y, w;
  for (std::size_t j = 0; j < t.size(); ++j) {
    if (t[j] < 1.0 || !project(Hi, tg.fx[j], tg.fy[j], X, Y, w)) {
      sum += t[j];
      continue;
    }
    std::size_t nearest = 0;
    double d2 = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < in.fx.size(); ++i) {
      const double dx = in.fx[i] - X, dy = in.fy[i] - Y;
      if (dx * dx + dy * dy < d2) {
        d2 = dx * dx + dy * dy;
        nearest = i;
      }
    }
    sum += occluderEdge[nearest] ? 0.0 : 1.0;
  }
  return sum / static_cast<double>(t.size());
}
} // namespace

double vpMorphRigidCheck::evidence(const vpMorphRigidShape &input, const vpMorphRigidShape &a, const Result &ra,
                                   const vpMorphRigidShape &b, const Result &rb)
{
  if (!ra.fitted || !rb.fitted)
    throw vpMorphException(vpMorphException::badParameterError, "vpMorphRigidCheck::evidence: a comparison not fitted");
  // The view as a's check laid it (b's laid it alike unless the view is the sharper of the two and b blurrier than a).
  const vpMorphRigidShapeData &in = *laidInput(input, a, ra.start).m_data;
  const vpMorphRigidShapeData &ta = *laidTarget(input, a, ra.start).m_data,
                              &tb = *laidTarget(input, b, rb.start).m_data;
  const double tolA = tolerance(in.contour, ta.contour), tolB = tolerance(in.contour, tb.contour);
  const Mat3 Ha = toMat3(ra.homography), Hb = toMat3(rb.homography);
  const std::vector<double> termsA = terms(in, ta, Ha, tolA), termsB = terms(in, tb, Hb, tolB);
  // The view's outline that is no edge of its own (measured, else what neither explains): an occluder's edge, behind
  // which either may hide what it lacks.
  std::vector<char> occluderEdge(termsA.size());
  double inputSide = 0.0;
  bool occluded = false;
  for (std::size_t i = 0; i < termsA.size(); ++i) {
    occluderEdge[i] = in.marked ? !in.fown[i] : termsA[i] >= 1.0 && termsB[i] >= 1.0;
    occluded = occluded || occluderEdge[i];
    inputSide += termsB[i] - termsA[i];
  }
  inputSide /= static_cast<double>(termsA.size());
  // An occluder's stretch has two ends on each of the three outlines, each a sample either way.
  const double ends = occluded ? 0.5 * 6.0 / static_cast<double>(termsA.size()) : 0.0;
  return 0.5 * (inputSide + targetSide(in, tb, Hb, tolB, occluderEdge) - targetSide(in, ta, Ha, tolA, occluderEdge)) -
         ends;
}
