#include <visp3/morph_vs/vpFeatureMorph.h>

#include <cmath>
#include <iostream>
#include <sstream>

#include <visp3/core/vpMath.h>
#include <visp3/morph/vpMorphException.h>

#include "vpMorphRegionCheck.h"

namespace
{
// Regions, deformed view, overlap and undeformed part: the constants shared with vpServoMorph (see
// vpMorphRegionCheck); the part's outline sampled as vpServoMorph samples it (twice the overlap's points).
constexpr double kRegionMismatch = vpMorphRegionCheck::kRegionMismatch;
constexpr double kDeformedOutside = vpMorphRegionCheck::kDeformedOutside;
constexpr std::size_t kOutsidePoints = vpMorphRegionCheck::kOverlapPoints, kPartSamples = 2 * kOutsidePoints;
constexpr double kPartTolerancePx = vpMorphRegionCheck::kRigidPartTolerancePx;
constexpr double kPartMinShare = vpMorphRegionCheck::kRigidPartMinShare;
constexpr unsigned int kPartPeriod = vpMorphRegionCheck::kRigidPartPeriod;
// Rotation of the fit to the goal under which a view not alike is judged hidden or bent.
const double kDecideTurn = 5.0 * M_PI / 180.0;

// Region moments of a polygon (Green's theorem): area a, centroid, normalised centred moments mu_ij / a.
void regionMoments(const vpMorphContour &c, double &a, double &xg, double &yg, double &n20, double &n02, double &n11)
{
  double A = 0, sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0;
  const std::size_t n = c.size();
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t j = (i + 1) % n;
    const double x0 = c.x(i), y0 = c.y(i), x1 = c.x(j), y1 = c.y(j);
    const double cr = x0 * y1 - x1 * y0;
    A += cr;
    sx += (x0 + x1) * cr;
    sy += (y0 + y1) * cr;
    sxx += (x0 * x0 + x0 * x1 + x1 * x1) * cr;
    syy += (y0 * y0 + y0 * y1 + y1 * y1) * cr;
    sxy += (x0 * y1 + 2 * x0 * y0 + 2 * x1 * y1 + x1 * y0) * cr;
  }
  A *= 0.5; // signed; the ratios below do not depend on the orientation
  xg = sx / (6 * A);
  yg = sy / (6 * A);
  n20 = sxx / (12 * A) - xg * xg;
  n02 = syy / (12 * A) - yg * yg;
  n11 = sxy / (24 * A) - xg * yg;
  a = std::fabs(A);
}
} // namespace

vpFeatureMorph::vpFeatureMorph() : vpBasicFeature() { init(); }

void vpFeatureMorph::init()
{
  dim_s = 4;
  nbParameters = 1;
  s.resize(dim_s);
  s = 0.0;
  if (flags == NULL)
    flags = new bool[nbParameters];
  flags[0] = false;
  m_contour = vpMorphContour();
  m_Z = 1.0;
  m_A = m_B = 0.0;
  m_C = 1.0;
  m_n20 = m_n02 = m_n11 = 0.0;
  m_tracker.reset();
  m_fit = vpMorphRigidTransform();
  m_regions = REGIONS_UNDECIDED;
  m_regionsChecked = false;
  m_bentCount = 0;
  m_partKnown = false;
  m_partOffset = vpMorphRigidTransform();
  m_scaleBias = 1.0;
}

void vpFeatureMorph::buildFrom(const vpMorphContour &contour, const vpCameraParameters &cam, double Z)
{
  if (contour.empty())
    throw vpMorphException(vpMorphException::badContourError, "vpFeatureMorph::buildFrom: empty contour");
  m_cam = cam;
  buildFrom(contour.units() == vpMorphContour::PIXEL ? contour.toNormalized(cam) : contour, Z);
}

void vpFeatureMorph::buildFrom(const vpMorphContour &normalizedContour, double Z)
{
  if (normalizedContour.empty())
    throw vpMorphException(vpMorphException::badContourError, "vpFeatureMorph::buildFrom: empty contour");
  if (normalizedContour.units() != vpMorphContour::NORMALIZED)
    throw vpMorphException(vpMorphException::badParameterError,
                           "vpFeatureMorph::buildFrom: a pixel contour needs the camera parameters");
  if (!std::isfinite(Z) || Z <= 0.0) {
    std::ostringstream os;
    os << "vpFeatureMorph::buildFrom: the depth Z must be finite and > 0, got " << Z;
    throw vpMorphException(vpMorphException::badParameterError, os.str());
  }
  setContour(normalizedContour, 0.0, 0.0, 1.0 / Z);
}

void vpFeatureMorph::buildFrom(const vpMorphContour &contour, const vpCameraParameters &cam, double A, double B,
                               double C)
{
  if (contour.empty())
    throw vpMorphException(vpMorphException::badContourError, "vpFeatureMorph::buildFrom: empty contour");
  if (!std::isfinite(A) || !std::isfinite(B) || !std::isfinite(C))
    throw vpMorphException(vpMorphException::badParameterError,
                           "vpFeatureMorph::buildFrom: the plane coefficients must be finite");
  const vpMorphContour n = contour.units() == vpMorphContour::PIXEL ? contour.toNormalized(cam) : contour;
  for (std::size_t k = 0; k < n.size(); ++k)
    if (!(A * n.x(k) + B * n.y(k) + C > 0.0)) {
      std::ostringstream os;
      os << "vpFeatureMorph::buildFrom: the plane 1/Z = " << A << " x + " << B << " y + " << C
         << " is not in front of the camera at vertex " << k;
      throw vpMorphException(vpMorphException::badParameterError, os.str());
    }
  m_cam = cam;
  setContour(n, A, B, C);
}

void vpFeatureMorph::setContour(const vpMorphContour &normalized, double A, double B, double C)
{
  double a, xg, yg, n20, n02, n11;
  regionMoments(normalized, a, xg, yg, n20, n02, n11);
  const double Z = 1.0 / (A * xg + B * yg + C);
  // A valid contour can still be too small for its moments in normalised coordinates (a polygon of 1e-160: the
  // area underflows to 0, the centroid divides by it): refuse it rather than give vpServo an infinite error
  // (found by fuzz_servo).
  // The interaction matrix sums cubes of the vertex offsets: below 1e-50 normalised units (a 1e-50 rad object,
  // far below any image) they underflow and ViSP divides by zero.
  if (!(std::sqrt(a) >= 1e-50) || !std::isfinite(a) || !std::isfinite(xg) || !std::isfinite(yg) || !std::isfinite(n20) ||
      !std::isfinite(n02) || !std::isfinite(n11) || !std::isfinite(Z) || !std::isfinite(std::log(a))) {
    std::ostringstream os;
    os << "vpFeatureMorph::buildFrom: the contour's moments are not finite in normalised coordinates (area " << a
       << ", centroid (" << xg << ", " << yg << ")): the polygon is too small (below 1e-50 normalised units) or too large";
    throw vpMorphException(vpMorphException::badContourError, os.str());
  }
  m_contour = normalized;
  m_A = A;
  m_B = B;
  m_C = C;
  m_polyS[0] = xg;
  m_polyS[1] = yg;
  m_polyS[2] = 0.5 * std::log(a);
  if (normalized.hasRegion()) {
    // The region measured on the image (see vpMorphContour::hasRegion()): the polygon's area and centroid move by a
    // percent when a vertex appears or shifts from one image to the next.
    a = normalized.regionArea();
    normalized.regionCentroid(xg, yg);
    normalized.regionMoments(n20, n11, n02);
  }
  m_n20 = n20;
  m_n02 = n02;
  m_n11 = n11;
  m_Z = 1.0 / (A * xg + B * yg + C);
  s[0] = xg;
  s[1] = yg;
  s[3] = 0.5 * std::log(a);
  flags[0] = true;
}

void vpFeatureMorph::planeFromPose(const vpHomogeneousMatrix &cMo, double &A, double &B, double &C)
{
  // Plane n . X = d in the camera frame, n the object z axis: 1/Z = (n_x x + n_y y + n_z) / d.
  const double nx = cMo[0][2], ny = cMo[1][2], nz = cMo[2][2];
  const double d = nx * cMo[0][3] + ny * cMo[1][3] + nz * cMo[2][3];
  if (std::fabs(d) < 1e-12)
    throw vpMorphException(vpMorphException::badParameterError,
                           "vpFeatureMorph::planeFromPose: the camera centre lies in the object plane");
  A = nx / d;
  B = ny / d;
  C = nz / d;
}

void vpFeatureMorph::checkBuilt(const char *caller) const
{
  if (m_contour.empty()) {
    std::ostringstream os;
    os << "vpFeatureMorph::" << caller
       << ": the feature has no contour; call buildFrom() first (and use vpServo::addFeature(s, s_star) with a "
          "built s_star)";
    throw vpMorphException(vpMorphException::badParameterError, os.str());
  }
}

vpMatrix vpFeatureMorph::interaction(unsigned int select)
{
  checkBuilt("interaction");
  const double xg = s[0], yg = s[1], iZ = 1.0 / m_Z, A = m_A, B = m_B, C = m_C;
  vpMatrix L(0, 6);
  if (select & selectXg()) {
    vpMatrix r(1, 6);
    r[0][0] = -iZ;
    r[0][1] = 0;
    r[0][2] = xg * iZ + 4 * (A * m_n20 + B * m_n11);
    r[0][3] = xg * yg + 4 * m_n11;
    r[0][4] = -(1 + xg * xg + 4 * m_n20);
    r[0][5] = yg;
    L = vpMatrix::stack(L, r);
  }
  if (select & selectYg()) {
    vpMatrix r(1, 6);
    r[0][0] = 0;
    r[0][1] = -iZ;
    r[0][2] = yg * iZ + 4 * (A * m_n11 + B * m_n02);
    r[0][3] = 1 + yg * yg + 4 * m_n02;
    r[0][4] = -xg * yg - 4 * m_n11;
    r[0][5] = -xg;
    L = vpMatrix::stack(L, r);
  }
  if (select & selectTheta()) {
    // Weighted mean angular velocity of the vertices about their weighted mean (weights: half adjacent edges).
    const std::size_t n = m_contour.size();
    std::vector<double> w(n);
    double W = 0, cx = 0, cy = 0;
    for (std::size_t i = 0; i < n; ++i) {
      w[i] = 0.5 * (m_contour.edgeLength(i) + m_contour.edgeLength((i + 1) % n));
      W += w[i];
      cx += w[i] * m_contour.x(i);
      cy += w[i] * m_contour.y(i);
    }
    cx /= W;
    cy /= W;
    vpMatrix r(1, 6);
    double N = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const double x = m_contour.x(i), y = m_contour.y(i), ax = x - cx, ay = y - cy;
      const double iZi = A * x + B * y + C; // 1 / depth of the vertex on the plane
      const double Lx[6] = {-iZi, 0, x * iZi, x * y, -(1 + x * x), y};
      const double Ly[6] = {0, -iZi, y * iZi, 1 + y * y, -x * y, -x};
      for (unsigned int k = 0; k < 6; ++k)
        r[0][k] += w[i] * (ax * Ly[k] - ay * Lx[k]);
      N += w[i] * (ax * ax + ay * ay);
    }
    // Element by element: vpMatrix::operator/= refuses divisors below machine epsilon, i.e. any contour smaller
    // than about 1e-5 normalised units (N is a cube of its size), which buildFrom() accepts (found by fuzzing).
    for (unsigned int k = 0; k < 6; ++k)
      r[0][k] /= N;
    L = vpMatrix::stack(L, r);
  }
  if (select & selectScale()) {
    vpMatrix r(1, 6);
    r[0][0] = -0.5 * A;
    r[0][1] = -0.5 * B;
    r[0][2] = 0.5 * (3 * iZ - C);
    r[0][3] = 1.5 * yg;
    r[0][4] = -1.5 * xg;
    L = vpMatrix::stack(L, r);
  }
  return L;
}

vpMorphRigidTransform vpFeatureMorph::fitToDesired(const vpFeatureMorph &sd, const vpMorphCorrespondence &corr)
{
  const vpMorphContour &des = sd.m_contour;
  const bool outlines = m_contour.hasOutline() && des.hasOutline();
  const double tenthPixel = m_cam.get_px() > 0.0 ? 0.1 / m_cam.get_px() : 0.0;
  // Both outlines measured: the fit refined on them, point to edge, robust scale floored at a tenth of a pixel. It does
  // not move with the polygons' vertices as the corresponded vertices' fit does.
  auto onOutlines = [&](const vpMorphRigidTransform &T) {
    try {
      return vpMorphRigidTransform::refineOnOutline(m_contour.outline(), des.outline(), T, true, tenthPixel);
    } catch (const vpException &) {
      return T; // an outline fit that degenerates: the corresponded vertices' fit stands
    }
  };
  const vpMorphRigidTransform plain =
      vpMorphRigidTransform::fitLeastSquares(m_contour, des, corr, true, vpMorphRigidTransform::NO_ROBUST);
  // Decided at the first error() after init(), then only from alike to not alike (an occluder that comes): switching
  // between the regions' and the fit's estimates from one image to the next makes a loop chatter (see vpServoMorph).
  // Only against a desired contour with its measured region (a template): a polygon goal (a morph's frame, a drawn
  // contour) has no region to compare with, and polygons' areas are no test (a thin tool's strays by 2-3 %).
  const bool alike = !des.hasRegion() || vpMorphRegionCheck::alike(des, m_contour, plain.scale(), kRegionMismatch);
  const bool wasHidden = m_regions == REGIONS_HIDDEN;
  if (m_regions == REGIONS_UNDECIDED || (m_regions == REGIONS_ALIKE && !alike))
    m_regions = alike ? REGIONS_ALIKE : REGIONS_NOT_ALIKE;
  // A current contour without its region against a desired one with it is an outline joined across an occluder's cut
  // (vpMorphContourExtractor): it sticks out along its bridge, and is hidden, not bent.
  if (m_regions == REGIONS_NOT_ALIKE && !m_contour.hasRegion())
    m_regions = REGIONS_HIDDEN;
  // Share of the view that F lays outside the desired region (on the outlines when both have them, resampled once).
  vpMorphContour view, goal;
  auto outside = [&](const vpMorphRigidTransform &F) {
    if (view.empty()) {
      view = outlines ? m_contour.outline().resampled(kOutsidePoints) : m_contour;
      goal = outlines ? des.outline().resampled(kOutsidePoints) : des;
    }
    return vpMorphRegionCheck::outsideShare(F, view, goal);
  };
  auto robustFit = [&]() {
    // The corresponded vertices crowd a hidden part onto the cut, and the plain least squares follow them; the robust
    // ones weigh them out.
    const vpMorphRigidTransform T =
        vpMorphRigidTransform::fitLeastSquares(m_contour, des, corr, true, vpMorphRigidTransform::TUKEY);
    return outlines ? onOutlines(T) : T;
  };
  if (m_regions == REGIONS_BENT)
    return outlines ? bentFit(sd, onOutlines(m_fit), true) : plain;
  if (m_regions == REGIONS_ALIKE) {
    const vpMorphRigidTransform T = outlines ? onOutlines(plain) : plain;
    // A small occluder or bend barely changes the regions' invariants, and their centroids and areas then carry the
    // part it hides or moves into the pose (an occluded wrench, key and pliers converging 2.3-11.4 mm off). Checked
    // once near the goal, as a view not alike is: laid by the regions, such a view sticks out of the desired region;
    // laid by the robust fit, a hidden one lies inside, a bent one still sticks out.
    if (!m_regionsChecked && des.hasRegion() && m_contour.hasRegion() && std::fabs(T.theta()) < kDecideTurn) {
      m_regionsChecked = true;
      double cx, cy, gx, gy;
      m_contour.regionCentroid(cx, cy);
      des.regionCentroid(gx, gy);
      const vpMorphRigidTransform byRegions(T.theta(), gx - cx, gy - cy,
                                            std::sqrt(des.regionArea() / m_contour.regionArea()), cx, cy);
      if (outside(byRegions) > kDeformedOutside) {
        const vpMorphRigidTransform Tr = robustFit();
        if (outside(Tr) <= kDeformedOutside) {
          m_regions = REGIONS_HIDDEN;
          return Tr;
        }
        // Out of the desired region either way: bent (a wrench whose handle is bent keeps its regions' invariants
        // within 2 %, and converged 2.1 mm off on them).
        if (outlines) {
          m_regions = REGIONS_BENT;
          return bentFit(sd, T, false);
        }
      }
    }
    return T;
  }

  // Part of the object hidden (or not yet decided).
  vpMorphRigidTransform T = robustFit();
  // A hidden view's fit can have two basins (an outline joined across a card, whose bridge changes from one image to
  // the next: a key's scales 4 % apart, a screwdriver's 7 %), and the correspondence started it in one or the other: a
  // loop chattering until its budget ran out, or a jump. Also refined from the last period's fit; kept, the one whose
  // scale moved less since, as the depth changes little in a period. (The one laying the view more inside the desired
  // region was kept first: shrinking a view always does that, and a screwdriver's scale jumped by 7 %.)
  if (wasHidden && outlines) {
    const vpMorphRigidTransform Tp = onOutlines(m_fit);
    if (std::fabs(std::log(Tp.scale() / m_fit.scale())) < std::fabs(std::log(T.scale() / m_fit.scale())))
      T = Tp;
  }
  // Hidden or bent, decided once the view is near the goal (the fit is then at its most accurate): an occluder only
  // hides, so the view laid by the fit lies inside the desired region; a bend sticks out. A bent view's outline fit
  // has two basins or more (a bent hammer's, 0.25 % apart in scale), and the tracked correspondence started it in one
  // or the other from one image to the next: a loop chattering about a goal 3-14 mm off until its budget ran out. It
  // is laid by its largest overlap instead (bentFit()), or by the regions without outlines.
  if (m_regions == REGIONS_NOT_ALIKE && std::fabs(T.theta()) < kDecideTurn) {
    m_regions = outside(T) > kDeformedOutside ? REGIONS_BENT : REGIONS_HIDDEN;
    if (m_regions == REGIONS_BENT)
      return outlines ? bentFit(sd, T, false) : plain;
  }
  return T;
}

vpMorphRigidTransform vpFeatureMorph::bentFit(const vpFeatureMorph &sd, const vpMorphRigidTransform &base, bool warm)
{
  const vpMorphContour &des = sd.m_contour;
  const double tolerance = kPartTolerancePx / m_cam.get_px();
  // The scale of the largest part that lies on the template (vpMorphRigidTransform::fitRigidPart: a bent key's bow):
  // a bend drags the outline fit and changes the area by percents. Searched every kPartPeriod periods (milliseconds),
  // followed from its offset to the base fit in between; when none is found, the outlines' length ratio (which a bend
  // nearly keeps) times the last part's ratio to it.
  const vpMorphContour dense = m_contour.outline().resampled(kPartSamples);
  const double lengthScale = des.outline().resampled(kPartSamples).perimeter() / dense.perimeter();
  double share = 0.0;
  const vpMorphRigidTransform R =
      !warm || !m_partKnown || m_bentCount % kPartPeriod == 0
          ? vpMorphRigidTransform::fitRigidPart(dense, des.outline(), base, tolerance, &share)
          : vpMorphRigidTransform::refineRigidPart(dense, des.outline(), m_partOffset * base, tolerance, &share);
  ++m_bentCount;
  m_partKnown = share >= kPartMinShare;
  if (m_partKnown) {
    m_partOffset = R * base.inverse();
    m_scaleBias = R.scale() / lengthScale;
  }
  const double scale = m_scaleBias * lengthScale;
  // Rotation and translation: the placement of largest overlap with the template at that scale (as vpServoMorph's), the
  // pose the bench's truth holds a bent tool to. Searched over +-10 deg at the decision, then refined from the last
  // period's placement.
  const vpMorphContour view = m_contour.outline().resampled(kOutsidePoints);
  const vpMorphContour goal = des.outline().resampled(kOutsidePoints);
  if (!warm) {
    const vpMorphRigidTransform Ts(base.theta(), base.tx(), base.ty(), scale, base.cx(), base.cy());
    return vpMorphRigidTransform::fitOnOverlap(view, goal, Ts, vpMath::rad(10.0), 5, 25);
  }
  const vpMorphRigidTransform last(m_fit.theta(), m_fit.tx(), m_fit.ty(), scale, m_fit.cx(), m_fit.cy());
  return vpMorphRigidTransform::refineOnOverlap(view, goal, last, 6, 0.002);
}

vpColVector vpFeatureMorph::error(const vpBasicFeature &s_star, unsigned int select)
{
  const vpFeatureMorph *sd = dynamic_cast<const vpFeatureMorph *>(&s_star);
  if (sd == nullptr)
    throw vpMorphException(vpMorphException::badParameterError,
                           "vpFeatureMorph::error: the desired feature must be a vpFeatureMorph");
  checkBuilt("error");
  if (sd->m_contour.empty())
    throw vpMorphException(vpMorphException::badParameterError,
                           "vpFeatureMorph::error: the desired feature has no contour; call its buildFrom() "
                           "(vpServo::addFeature(s) alone gives an empty desired feature)");
  m_fit = fitToDesired(*sd, m_tracker.update(m_contour, sd->m_contour));
  s[2] = -m_fit.theta();
  double full[4] = {0.0, 0.0, s[2], 0.0};
  // A bent view without outlines has no fit of its own (see bentFit()): the regions, as for a view alike.
  const bool hasOutlines = m_contour.hasOutline() && sd->m_contour.hasOutline();
  if (m_regions == REGIONS_ALIKE || (m_regions == REGIONS_BENT && !hasOutlines)) {
    // The regions measured on both images, or the polygons' for both (one measured region against a polygon's area
    // would be a bias of the depth).
    const bool regions = m_contour.hasRegion() && sd->m_contour.hasRegion();
    const double *cur = regions ? &s[0] : m_polyS, *des = regions ? &sd->s[0] : sd->m_polyS;
    const double cs = regions ? s[3] : m_polyS[2], ds = regions ? sd->s[3] : sd->m_polyS[2];
    full[0] = cur[0] - des[0];
    full[1] = cur[1] - des[1];
    full[3] = cs - ds;
  } else {
    // Part of the object hidden, or bent: the desired values are where the fit lays the current centroid and at what
    // size. The visible part is a fixed part of the object (an occluder lies on the plane), so at the goal its centroid
    // is seen where the fit puts it, and its area grows by the fit's scale squared; the desired region's own centroid
    // and area (a whole object against a part of it, or a bent one) would be a bias of centimetres.
    double gx, gy;
    m_fit.apply(s[0], s[1], gx, gy);
    full[0] = s[0] - gx;
    full[1] = s[1] - gy;
    full[3] = -std::log(m_fit.scale());
  }
  vpColVector e(0);
  for (unsigned int k = 0; k < 4; ++k)
    if (select & FEATURE_LINE[k])
      e.stack(full[k]);
  return e;
}

vpFeatureMorph *vpFeatureMorph::duplicate() const { return new vpFeatureMorph(*this); }

void vpFeatureMorph::print(unsigned int select) const { print(std::cout, select); }

void vpFeatureMorph::print(std::ostream &os, unsigned int select) const
{
  os << "vpFeatureMorph:";
  const char *names[4] = {"xg", "yg", "theta", "sigma"};
  for (unsigned int k = 0; k < 4; ++k)
    if (select & FEATURE_LINE[k])
      os << " " << names[k] << "=" << s[k];
  os << " Z=" << m_Z << " vertices=" << m_contour.size() << std::endl;
}
