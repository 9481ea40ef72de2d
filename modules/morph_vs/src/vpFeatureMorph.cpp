#include <visp3/morph_vs/vpFeatureMorph.h>

#include <cmath>
#include <iostream>
#include <sstream>

#include <visp3/core/vpMath.h>
#include <visp3/morph/vpMorphException.h>

namespace
{
// Whether two contours have the same vertices (a desired feature rebuilt from the same contour keeps its goal).
bool sameContour(const vpMorphContour &a, const vpMorphContour &b)
{
  return a.size() == b.size() && a.xs() == b.xs() && a.ys() == b.ys();
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
  m_aligner = vpMorphViewAligner();
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
  // The region measured on the image where there is one (see vpMorphContour::hasRegion(): the polygon's area and
  // centroid move by a percent when a vertex appears or shifts from one image to the next), else the polygon's.
  const double a = normalized.regionArea();
  double xg, yg, n20, n02, n11;
  normalized.regionCentroid(xg, yg);
  normalized.regionMoments(n20, n11, n02);
  const double Z = 1.0 / (A * xg + B * yg + C);
  // A valid contour can still be too small for its moments in normalised coordinates (a polygon of 1e-160: the
  // area underflows to 0, the centroid divides by it): refuse it rather than give vpServo an infinite error
  // (found by fuzz_servo).
  // The interaction matrix sums cubes of the vertex offsets: below 1e-50 normalised units (a 1e-50 rad object,
  // far below any image) they underflow and ViSP divides by zero.
  if (!(std::sqrt(a) >= 1e-50) || !std::isfinite(a) || !std::isfinite(xg) || !std::isfinite(yg) ||
      !std::isfinite(n20) || !std::isfinite(n02) || !std::isfinite(n11) || !std::isfinite(Z) ||
      !std::isfinite(std::log(a))) {
    std::ostringstream os;
    os << "vpFeatureMorph::buildFrom: the contour's moments are not finite in normalised coordinates (area " << a
       << ", centroid (" << xg << ", " << yg
       << ")): the polygon is too small (below 1e-50 normalised units) or too large";
    throw vpMorphException(vpMorphException::badContourError, os.str());
  }
  m_contour = normalized;
  m_A = A;
  m_B = B;
  m_C = C;
  m_n20 = n20;
  m_n02 = n02;
  m_n11 = n11;
  m_Z = Z;
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
  // One measurement, vpServoMorph's: the similarity that lays this view on the desired one (a new desired contour
  // is a new goal).
  if (!m_aligner.hasGoal() || !sameContour(m_aligner.getGoalNormalized(), sd->m_contour)) {
    m_aligner.setCameraParameters(m_cam);
    m_aligner.setGoal(sd->m_contour);
  }
  const vpMorphViewAlignment a = m_aligner.align(m_contour);
  double full[4] = {0.0, 0.0, 0.0, 0.0};
  if (a.explained()) {
    // The desired values are where the alignment lays the current centroid and at what size: for a view with a part
    // hidden or bent, the visible part's own centroid and area at the goal, not the desired region's.
    double gx, gy;
    a.transform.apply(s[0], s[1], gx, gy);
    s[2] = -a.transform.theta();
    full[0] = s[0] - gx;
    full[1] = s[1] - gy;
    full[2] = s[2];
    full[3] = -std::log(a.transform.scale());
  }
  // An unexplained view (another shape, a view the measurement cannot place): a zero error, which a stock vpServo
  // turns into a zero velocity; getAlignment() says why.
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
