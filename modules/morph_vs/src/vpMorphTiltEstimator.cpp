#include <visp3/morph_vs/vpMorphTiltEstimator.h>

#include "vpMorphParameterCheck.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <visp3/core/vpException.h>
#include <visp3/core/vpRotationMatrix.h>
#include <visp3/core/vpThetaUVector.h>
#include <visp3/morph/vpMorphException.h>

namespace
{
// Outline points of a homography fit.
const unsigned int kSamples = vpMorphHomography::kDefaultSamples;

// The largest standard deviation of a 2x2 covariance [c00 c01; c01 c11].
double largestDeviation(double c00, double c01, double c11)
{
  return std::sqrt(std::max(0.0, 0.5 * (c00 + c11) + std::sqrt(0.25 * (c00 - c11) * (c00 - c11) + c01 * c01)));
}

// The tilt (angle, axis (ax, ay) of norm sa = sin(angle)) as a rotation vector (ex, ey); zero when untilted.
void tiltVector(double angle, double ax, double ay, double sa, double &ex, double &ey)
{
  ex = sa > 1e-12 ? angle * ax / sa : 0.0;
  ey = sa > 1e-12 ? angle * ay / sa : 0.0;
}

/*
  The tilt to command from the estimate e, given a second estimate f and the covariance S of one period's estimate:
  along each principal axis of S, what both e and f show on the same side beyond k standard deviations (and at least
  floor), the smaller of the two; nothing on an axis where they disagree. Per axis, because a thin object's tilt about
  its long axis is seen far worse than about its short one.
*/
void beyondDeadZone(double ex, double ey, double fx, double fy, double s00, double s01, double s11, double floor,
                    double k, double &cx, double &cy)
{
  const double mean = 0.5 * (s00 + s11), half = std::sqrt(0.25 * (s00 - s11) * (s00 - s11) + s01 * s01);
  const double th = 0.5 * std::atan2(2.0 * s01, s00 - s11); // the axis of the larger variance
  const double variance[2] = {mean + half, std::max(0.0, mean - half)};
  const double axis[2][2] = {{std::cos(th), std::sin(th)}, {-std::sin(th), std::cos(th)}};
  cx = cy = 0.0;
  for (int i = 0; i < 2; ++i) {
    const double a = ex * axis[i][0] + ey * axis[i][1], b = fx * axis[i][0] + fy * axis[i][1];
    const double beyond = std::min(std::fabs(a), std::fabs(b)) - std::max(floor, k * std::sqrt(variance[i]));
    if (a * b > 0.0 && beyond > 0.0) {
      cx += std::copysign(beyond, a) * axis[i][0];
      cy += std::copysign(beyond, a) * axis[i][1];
    }
  }
}
} // namespace

void vpMorphTiltEstimator::setPixelSize(double unitsPerPixel)
{
  vpMorphParameterCheck::positive(unitsPerPixel, "vpMorphTiltEstimator::setPixelSize", "the pixel size");
  m_pixel = unitsPerPixel;
}

void vpMorphTiltEstimator::setDeadZone(double rad)
{
  vpMorphParameterCheck::nonNegative(rad, "vpMorphTiltEstimator", "the dead zone");
  m_deadZone = rad;
}

void vpMorphTiltEstimator::setOutlineDeadZone(double rad)
{
  vpMorphParameterCheck::nonNegative(rad, "vpMorphTiltEstimator", "the outline dead zone");
  m_outlineDeadZone = rad;
}

void vpMorphTiltEstimator::setFinalThreshold(double rad)
{
  vpMorphParameterCheck::positive(rad, "vpMorphTiltEstimator", "the final tilt threshold");
  m_final = rad;
}

void vpMorphTiltEstimator::reset()
{
  m_haveWarm = m_latched = m_estimated = false;
  m_residual = 0.0;
  m_deviation = std::numeric_limits<double>::infinity();
  m_deadZoneUsed = m_deadZone;
  m_cMcd.eye();
  m_sumX = m_sumY = 0.0;
  m_window.clear();
  m_kappa = 1.0;
  m_scatterKnown = false;
}

bool vpMorphTiltEstimator::isVerified(double sigmas) const
{
  return m_estimated && m_residual + sigmas * m_deviation <= m_final;
}

bool vpMorphTiltEstimator::homography(const vpMorphContour &currentN, const vpMorphContour &targetN,
                                      const vpMorphHomography &start, double minInliers, double maxResidualPx,
                                      vpMorphHomography &G) const
{
  // The robust scale floored as the view aligner's (the edges' noise); measured outlines sampled twice as densely as
  // polygons (every few pixels of a tool's outline: what the tilt's second-order effect needs), with a common edge
  // offset where a clipped level may have moved them (vpMorphViewAligner::edgesMayBeOffset()).
  const bool dense = currentN.hasOutline() && targetN.hasOutline();
  try {
    G = vpMorphHomography::refine(
        currentN.outline(), targetN.outline(), start,
        (dense ? vpMorphViewAligner::outlineSigmaFloorPx() : vpMorphViewAligner::polygonSigmaFloorPx()) * m_pixel,
        dense ? 2 * kSamples : kSamples, vpMorphHomography::kDefaultIterations,
        vpMorphViewAligner::edgesMayBeOffset(currentN, targetN));
  } catch (const vpException &) {
    return false;
  }
  return G.inlierShare() >= minInliers && G.residual() <= maxResidualPx * m_pixel;
}
void vpMorphTiltEstimator::fuse(const vpMatrix &C, double &angle, double &ax, double &ay, double &sa)
{
  // This period's tilt as a rotation vector e and its covariance (the perspective part (d6, d7) of the homography is
  // the plane normal's (n0, n1) near the goal, and e = (-n1, n0)).
  Sample cur;
  tiltVector(angle, ax, ay, sa, cur.ex, cur.ey);
  cur.c00 = C[7][7];
  cur.c01 = -C[6][7];
  cur.c11 = C[6][6];
  cur.sx = m_sumX;
  cur.sy = m_sumY;
  cur.deadZone = m_deadZoneUsed;
  // An earlier period stands for the tilt now once the commands executed since are taken off, while they are smaller
  // than its dead zone (an execution off by a few percent then moves it by a few percent of its noise).
  m_window.erase(
      std::remove_if(m_window.begin(), m_window.end(),
                     [&](const Sample &s) { return !(std::hypot(cur.sx - s.sx, cur.sy - s.sy) <= s.deadZone); }),
      m_window.end());
  m_window.push_back(cur);
  if (m_window.size() > getWindow())
    m_window.erase(m_window.begin(), m_window.end() - static_cast<std::ptrdiff_t>(getWindow()));
  // Information-weighted mean.
  double i00 = 0, i01 = 0, i11 = 0, b0 = 0, b1 = 0;
  std::vector<std::array<double, 5>> info; // e (compensated), information matrix
  for (const Sample &s : m_window) {
    const double det = s.c00 * s.c11 - s.c01 * s.c01;
    if (!(det > 0.0))
      continue;
    const double j00 = s.c11 / det, j01 = -s.c01 / det, j11 = s.c00 / det;
    const double ex = s.ex - (cur.sx - s.sx), ey = s.ey - (cur.sy - s.sy);
    info.push_back({ex, ey, j00, j01, j11});
    i00 += j00;
    i01 += j01;
    i11 += j11;
    b0 += j00 * ex + j01 * ey;
    b1 += j01 * ex + j11 * ey;
  }
  const double det = i00 * i11 - i01 * i01;
  if (info.empty() || !(det > 0.0))
    return;
  const double mx = (i11 * b0 - i01 * b1) / det, my = (-i01 * b0 + i00 * b1) / det;
  // The outlines' covariance counts only the noise a fit's residuals show, not what changes from one view to the next
  // (the pixel grid's phase under the edges): the scatter of the periods about their mean scales it.
  m_scatterKnown = info.size() >= 3;
  if (m_scatterKnown) {
    double chi2 = 0.0;
    for (const auto &q : info) {
      const double dx = q[0] - mx, dy = q[1] - my;
      chi2 += q[2] * dx * dx + 2.0 * q[3] * dx * dy + q[4] * dy * dy;
    }
    m_kappa = std::max(1.0, chi2 / (2.0 * double(info.size() - 1)));
  }
  angle = std::hypot(mx, my);
  sa = std::sin(angle);
  ax = angle > 0.0 ? sa * mx / angle : 0.0;
  ay = angle > 0.0 ? sa * my / angle : 0.0;
}

bool vpMorphTiltEstimator::estimate(const vpMorphContour &currentN, const vpMorphContour &targetN, double Zd,
                                    const vpMorphRigidTransform &currentToTarget, bool rigid, bool final, double gain,
                                    vpHomogeneousMatrix &cMct, double &Zp)
{
  m_estimated = false;
  m_residual = 0.0;
  m_deviation = std::numeric_limits<double>::infinity();
  m_cMcd.eye();
  cMct.eye();
  // A target measured on its image, a current contour not (an outline joined across an occluder's cut): part of it
  // was bridged, not seen, so no perspective can be read in it.
  if (m_latched || (targetN.hasRegion() && !currentN.hasRegion()))
    return false;
  try {
    const bool dense = currentN.hasOutline() && targetN.hasOutline();
    const double minInliers = rigid ? getMinInlierShare() : getMinInlierShareNotRigid();
    const double maxResidual = rigid ? getMaxResidualPx() : 0.5 * getMaxResidualPx();
    vpMorphHomography G;
    bool ok = m_haveWarm && homography(currentN, targetN, m_warm, minInliers, maxResidual, G);
    if (!ok)
      ok = homography(currentN, targetN, vpMorphHomography(currentToTarget.toMatrix()), minInliers, maxResidual, G);
    m_haveWarm = ok;
    if (!ok)
      return false;
    m_warm = G;
    m_deadZoneUsed = m_deadZone;
    if (dense) {
      const vpMatrix &C = G.covariance();
      m_deadZoneUsed = std::max(m_outlineDeadZone, getSigmas() * largestDeviation(C[6][6], C[6][7], C[7][7]));
    }
    const vpHomogeneousMatrix cMcd = G.inputMtarget(Zd);
    const vpColVector n = cMcd.getRotationMatrix().getCol(2); // plane normal in the current camera frame
    const vpTranslationVector t = cMcd.getTranslationVector();
    const double dc = Zd + n[0] * t[0] + n[1] * t[1] + n[2] * t[2]; // distance of the camera to the plane
    double cx, cy;
    currentN.regionCentroid(cx, cy);
    const double nr = n[0] * cx + n[1] * cy + n[2];
    if (!(dc > 0.0) || !(nr > 1e-3))
      return false;
    const double lambda = dc / nr; // depth of P
    const vpColVector P = vpColVector({lambda * cx, lambda * cy, lambda});
    double angle = std::acos(std::max(-1.0, std::min(1.0, n[2])));
    double ax = -n[1], ay = n[0], sa = std::hypot(ax, ay); // the tilt's axis (in the image plane), |.| = sin(angle)
    double tx = 0.0, ty = 0.0;                             // the tilt commanded, as a rotation vector
    double deviation = m_deadZoneUsed / getSigmas();       // a polygon's tilt is known to its dead zone
    if (dense) {
      const vpMatrix &C = G.covariance();
      double ex, ey, mx, my; // this period's estimate, and the one commanded from (fused on the final approach)
      tiltVector(angle, ax, ay, sa, ex, ey);
      if (final)
        fuse(C, angle, ax, ay, sa);
      // The dead zone is one period's deviation (scaled by the periods' scatter), not the mean's: near the goal the
      // views barely change, share their pixel phase, and their errors do not average out.
      const double kappa = final ? m_kappa : 1.0;
      tiltVector(angle, ax, ay, sa, mx, my);
      beyondDeadZone(mx, my, ex, ey, kappa * C[7][7], -kappa * C[6][7], kappa * C[6][6], m_outlineDeadZone, getSigmas(),
                     tx, ty);
      const double c = std::hypot(tx, ty);
      m_deadZoneUsed = c > 0.0 ? std::max(0.0, angle - c) : std::max(angle, m_deadZoneUsed);
      // One period's deviation about the worse-seen axis, scaled by the periods' scatter once three show it (the
      // fit's covariance alone misses what changes from one view to the next).
      deviation = final && m_scatterKnown ? std::sqrt(kappa) * largestDeviation(C[6][6], C[6][7], C[7][7])
                                          : std::numeric_limits<double>::infinity();
    } else {
      // Polygons: within the dead zone on the final approach, what they show is their polygonisation, and a camera
      // that followed it would random-walk: the planar law finishes alone.
      if (m_deadZoneUsed > 0.0 && angle <= m_deadZoneUsed && final) {
        m_latched = true;
        m_residual = angle;
        m_deviation = deviation;
        m_estimated = true;
        return false;
      }
      if (sa > 1e-12) {
        const double cmd = std::max(0.0, angle - m_deadZoneUsed);
        tx = cmd * ax / sa;
        ty = cmd * ay / sa;
      }
    }
    const double cmd = std::hypot(tx, ty);
    if (final && cmd > 0.0) { // executed as a gain share of it per period: the fused estimates are compensated by it
      m_sumX += gain * tx;
      m_sumY += gain * ty;
    }
    vpRotationMatrix Rt; // identity when already aligned
    if (cmd > 0.0)
      Rt = vpRotationMatrix(vpThetaUVector(tx, ty, 0.0));
    const vpColVector RP = vpMatrix(Rt) * P;
    const vpTranslationVector tt(P[0] - RP[0], P[1] - RP[1], P[2] - RP[2]);
    if (!std::isfinite(lambda) || !std::isfinite(angle) || !std::isfinite(tt[0]) || !std::isfinite(tt[1]) ||
        !std::isfinite(tt[2]))
      return false;
    cMct = vpHomogeneousMatrix(tt, Rt);
    m_cMcd = cMcd;
    m_residual = angle;
    m_deviation = deviation;
    m_estimated = true;
    Zp = lambda;
    return true;
  } catch (const vpException &) {
    cMct.eye();
    return false;
  }
}

bool vpMorphTiltEstimator::read(const vpMorphContour &currentN, const vpMorphContour &targetN, double Zd, double turn,
                                const vpMorphRigidTransform &currentToTarget, Reading &r)
{
  try {
    if (!currentN.hasOutline() || !targetN.hasOutline() || !currentN.hasRegion())
      return false;
    // From the last reading's homography turned by the turn commanded since (a turn about the optical axis maps the
    // normalised image by that rotation): the readings follow the view at a fraction of a cold fit's cost.
    vpMorphHomography G;
    bool ok = false;
    if (m_readWarm) {
      const vpMorphHomography start(m_readG.matrix() * vpMorphRigidTransform(turn, 0, 0, 1, 0, 0).toMatrix());
      ok = homography(currentN, targetN, start, getMinInlierShareNotRigid(), getMaxResidualPx(), G);
    }
    if (!ok)
      ok = homography(currentN, targetN, vpMorphHomography(currentToTarget.toMatrix()), getMinInlierShareNotRigid(),
                      getMaxResidualPx(), G);
    m_readWarm = ok;
    if (!ok)
      return false;
    m_readG = G;
    const vpColVector n = G.inputMtarget(Zd).getRotationMatrix().getCol(2);
    const vpMatrix &C = G.covariance();
    r.nx = n[0];
    r.ny = n[1];
    r.c00 = C[6][6];
    r.c01 = C[6][7];
    r.c11 = C[7][7];
    return std::isfinite(r.nx) && std::isfinite(r.ny) && r.c00 > 0.0 && r.c00 * r.c11 - r.c01 * r.c01 > 0.0;
  } catch (const vpException &) {
    return false;
  }
}
