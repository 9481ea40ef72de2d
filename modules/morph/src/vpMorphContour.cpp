#include <visp3/morph/vpMorphContour.h>

#include "vpMorphRegionOverlap.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <visp3/core/vpMath.h>
#include <visp3/morph/vpMorphException.h>

namespace
{
[[noreturn]] void fail(const std::string &what)
{
  throw vpMorphException(vpMorphException::badContourError, "vpMorphContour: " + what);
}

// Orientation of the triangle (p, q, r): > 0 for a left turn.
double cross(double px, double py, double qx, double qy, double rx, double ry)
{
  return (qx - px) * (ry - py) - (qy - py) * (rx - px);
}

bool onSegment(double px, double py, double qx, double qy, double rx, double ry)
{
  return std::min(px, qx) <= rx && rx <= std::max(px, qx) && std::min(py, qy) <= ry && ry <= std::max(py, qy);
}

bool segmentsIntersect(double ax, double ay, double bx, double by, double cx, double cy, double dx, double dy)
{
  const double d1 = cross(cx, cy, dx, dy, ax, ay), d2 = cross(cx, cy, dx, dy, bx, by);
  const double d3 = cross(ax, ay, bx, by, cx, cy), d4 = cross(ax, ay, bx, by, dx, dy);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0)))
    return true;
  return (d1 == 0 && onSegment(cx, cy, dx, dy, ax, ay)) || (d2 == 0 && onSegment(cx, cy, dx, dy, bx, by)) ||
         (d3 == 0 && onSegment(ax, ay, bx, by, cx, cy)) || (d4 == 0 && onSegment(ax, ay, bx, by, dx, dy));
}
} // namespace

vpMorphContour::vpMorphContour(const std::vector<double> &x, const std::vector<double> &y, Units units)
  : m_x(x), m_y(y), m_units(units)
{
  if (x.size() != y.size()) {
    std::ostringstream os;
    os << "x and y have different sizes (" << x.size() << " and " << y.size() << ")";
    fail(os.str());
  }
  validate();
}

vpMorphContour::vpMorphContour(const std::vector<vpImagePoint> &points, Units units) : m_units(units)
{
  m_x.reserve(points.size());
  m_y.reserve(points.size());
  for (const vpImagePoint &p : points) {
    m_x.push_back(p.get_u());
    m_y.push_back(p.get_v());
  }
  validate();
}

void vpMorphContour::validate() const
{
  const std::size_t n = m_x.size();
  if (n < 3) {
    std::ostringstream os;
    os << "a polygon needs at least 3 vertices (got " << n << ")";
    fail(os.str());
  }
  for (std::size_t k = 0; k < n; ++k) {
    if (!std::isfinite(m_x[k]) || !std::isfinite(m_y[k])) {
      std::ostringstream os;
      os << "vertex " << k << " is not finite (" << m_x[k] << ", " << m_y[k] << ")";
      fail(os.str());
    }
    // Second-order moments (orientation(), the rigid fits) sum fourth powers of coordinates: beyond 1e75 they
    // overflow and the centroid or a fitted transform becomes infinite (found by fuzz_polygon_correspondence).
    if (std::fabs(m_x[k]) > maxCoordinate() || std::fabs(m_y[k]) > maxCoordinate()) {
      std::ostringstream os;
      os << "vertex " << k << " (" << m_x[k] << ", " << m_y[k] << ") is beyond " << maxCoordinate()
         << " in magnitude: its moments would overflow double precision";
      fail(os.str());
    }
  }
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t p = (k + n - 1) % n;
    if (m_x[k] == m_x[p] && m_y[k] == m_y[p]) {
      std::ostringstream os;
      os << "vertices " << p << " and " << k << " are repeated (" << m_x[k] << ", " << m_y[k] << ")";
      fail(os.str());
    }
  }
  // Distinct vertices can still be too close or too far apart for double arithmetic: an edge length that
  // underflows to 0 (coordinates differing by 1e-200) or a length or area that overflows (coordinates beyond
  // 1e154) gives every algorithm downstream 0/0 or inf - inf, i.e. NaN work and out-of-band paths in the matcher.
  for (std::size_t k = 0; k < n; ++k) {
    const double len = edgeLength(k);
    if (!(len > 0.0) || !std::isfinite(len)) {
      std::ostringstream os;
      os << "edge " << k << " has length " << len << " in double precision (vertices (" << m_x[(k + n - 1) % n]
         << ", " << m_y[(k + n - 1) % n] << ") and (" << m_x[k] << ", " << m_y[k]
         << ")): coordinates too close or too large";
      fail(os.str());
    }
  }
  // Zero area relative to the squared perimeter: all vertices collinear.
  const double a = std::fabs(signedArea()), l = perimeter();
  if (!std::isfinite(a) || !std::isfinite(l) || !std::isfinite(l * l)) {
    std::ostringstream os;
    os << "area (" << a << ") or perimeter (" << l << ") overflows double precision: coordinates too large";
    fail(os.str());
  }
  if (!(a > 1e-12 * l * l))
    fail("the vertices are collinear (zero area)");
}

std::vector<vpImagePoint> vpMorphContour::points() const
{
  std::vector<vpImagePoint> p;
  p.reserve(size());
  for (std::size_t k = 0; k < size(); ++k)
    p.push_back(point(k));
  return p;
}

double vpMorphContour::signedArea() const
{
  const std::size_t n = size();
  double a = 0.0;
  for (std::size_t k = 0, p = n - 1; k < n; p = k++)
    a += m_x[p] * m_y[k] - m_x[k] * m_y[p];
  return 0.5 * a;
}

double vpMorphContour::area() const { return std::fabs(signedArea()); }

double vpMorphContour::perimeter() const
{
  double l = 0.0;
  for (std::size_t k = 0; k < size(); ++k)
    l += edgeLength(k);
  return l;
}

double vpMorphContour::overlapArea(const vpMorphContour &other) const
{
  if (empty() || other.empty())
    throw vpMorphException(vpMorphException::badContourError, "vpMorphContour::overlapArea: empty contour");
  if (units() != other.units())
    throw vpMorphException(vpMorphException::badParameterError,
                           "vpMorphContour::overlapArea: the two contours have different units");
  return vpMorphOverlapArea(vpMorphOverlapPolygon(vpMorphPoints(*this)), vpMorphOverlapPolygon(vpMorphPoints(other)));
}

double vpMorphContour::edgeLength(std::size_t k) const
{
  const std::size_t p = (k + size() - 1) % size();
  const double dx = m_x[k] - m_x[p], dy = m_y[k] - m_y[p];
  return std::sqrt(dx * dx + dy * dy); // no hypot: its overflow care is not needed here and it is slow
}

double vpMorphContour::turningAngle(std::size_t k) const
{
  const std::size_t n = size(), p = (k + n - 1) % n, q = (k + 1) % n;
  const double ux = m_x[k] - m_x[p], uy = m_y[k] - m_y[p];
  const double vx = m_x[q] - m_x[k], vy = m_y[q] - m_y[k];
  return std::atan2(ux * vy - uy * vx, ux * vx + uy * vy);
}

void vpMorphContour::centroid(double &cx, double &cy) const
{
  const std::size_t n = size();
  // Shifted to vertex 0 to keep the shoelace sums well conditioned far from the origin.
  const double ox = m_x[0], oy = m_y[0];
  double a = 0.0, sx = 0.0, sy = 0.0;
  for (std::size_t k = 0, p = n - 1; k < n; p = k++) {
    const double xp = m_x[p] - ox, yp = m_y[p] - oy, xk = m_x[k] - ox, yk = m_y[k] - oy;
    const double c = xp * yk - xk * yp;
    a += c;
    sx += (xp + xk) * c;
    sy += (yp + yk) * c;
  }
  cx = ox + sx / (3.0 * a);
  cy = oy + sy / (3.0 * a);
}

void vpMorphContour::polygonMoments(double &mu20, double &mu11, double &mu02) const
{
  double cx, cy;
  centroid(cx, cy);
  // Second-order central moments of the polygon region (Green's theorem), per unit area (a: twice the signed area).
  double a = 0.0, mxx = 0.0, myy = 0.0, mxy = 0.0;
  const std::size_t n = size();
  for (std::size_t k = 0, p = n - 1; k < n; p = k++) {
    const double x0 = m_x[p] - cx, y0 = m_y[p] - cy, x1 = m_x[k] - cx, y1 = m_y[k] - cy;
    const double c = x0 * y1 - x1 * y0;
    a += c;
    mxx += (x0 * x0 + x0 * x1 + x1 * x1) * c;
    myy += (y0 * y0 + y0 * y1 + y1 * y1) * c;
    mxy += (x0 * y1 + 2 * x0 * y0 + 2 * x1 * y1 + x1 * y0) * c;
  }
  mu20 = mxx / (6.0 * a);
  mu02 = myy / (6.0 * a);
  mu11 = mxy / (12.0 * a);
}

double vpMorphContour::orientation() const
{
  double mu20, mu11, mu02;
  polygonMoments(mu20, mu11, mu02);
  double theta = 0.5 * std::atan2(2.0 * mu11, mu20 - mu02);
  if (theta <= -M_PI / 2)
    theta += M_PI;
  return theta;
}

bool vpMorphContour::isSimple() const
{
  const std::size_t n = size();
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t i1 = (i + 1) % n;
    // Adjacent edges fold back onto each other when the turn is exactly pi.
    const std::size_t i2 = (i + 2) % n;
    if (cross(m_x[i], m_y[i], m_x[i1], m_y[i1], m_x[i2], m_y[i2]) == 0.0) {
      const double dot = (m_x[i1] - m_x[i]) * (m_x[i2] - m_x[i1]) + (m_y[i1] - m_y[i]) * (m_y[i2] - m_y[i1]);
      if (dot < 0.0)
        return false;
    }
    for (std::size_t j = i + 2; j < n; ++j) {
      const std::size_t j1 = (j + 1) % n;
      if (j1 == i)
        continue; // adjacent through the closing edge
      if (segmentsIntersect(m_x[i], m_y[i], m_x[i1], m_y[i1], m_x[j], m_y[j], m_x[j1], m_y[j1]))
        return false;
    }
  }
  return true;
}

void vpMorphContour::setRegion(double area, double cx, double cy, double mu20, double mu11, double mu02)
{
  const bool finite = std::isfinite(area) && std::isfinite(cx) && std::isfinite(cy) && std::isfinite(mu20) &&
                      std::isfinite(mu11) && std::isfinite(mu02);
  // Positive semi-definite up to rounding: mu20, mu02 >= 0 and mu11^2 <= mu20 mu02.
  const double tol = 1e-9 * (std::fabs(mu20) + std::fabs(mu02));
  if (!finite || !(area > 0.0) || mu20 < -tol || mu02 < -tol || mu11 * mu11 > mu20 * mu02 + tol * tol + tol) {
    std::ostringstream os;
    os << "vpMorphContour::setRegion: the region needs a finite positive area, a finite centroid and finite "
          "positive semi-definite moments (area "
       << area << ", centroid (" << cx << ", " << cy << "), moments (" << mu20 << ", " << mu11 << ", " << mu02
       << "))";
    throw vpMorphException(vpMorphException::badParameterError, os.str());
  }
  m_regionArea = area;
  m_regionCx = cx;
  m_regionCy = cy;
  m_regionMu20 = mu20;
  m_regionMu11 = mu11;
  m_regionMu02 = mu02;
}

void vpMorphContour::regionCentroid(double &cx, double &cy) const
{
  if (!hasRegion()) {
    centroid(cx, cy);
    return;
  }
  cx = m_regionCx;
  cy = m_regionCy;
}

void vpMorphContour::regionMoments(double &mu20, double &mu11, double &mu02) const
{
  if (!hasRegion()) {
    polygonMoments(mu20, mu11, mu02);
    return;
  }
  mu20 = m_regionMu20;
  mu11 = m_regionMu11;
  mu02 = m_regionMu02;
}

void vpMorphContour::setOutline(const vpMorphContour &outline, double blur)
{
  if (outline.empty() || outline.size() < 4 || outline.units() != m_units)
    throw vpMorphException(vpMorphException::badParameterError,
                           "vpMorphContour::setOutline: the outline must be a contour of at least 4 vertices in the "
                           "polygon's units");
  if (!(blur >= 0.0) || !std::isfinite(blur))
    throw vpMorphException(vpMorphException::badParameterError,
                           "vpMorphContour::setOutline: the blur must be finite and >= 0");
  vpMorphContour o(outline.m_x, outline.m_y, outline.m_units); // without region or outline of its own
  o.m_ownEdges = outline.m_ownEdges;
  m_outline = std::make_shared<const vpMorphContour>(std::move(o));
  m_outlineBlur = blur;
}

void vpMorphContour::setOwnEdges(const std::vector<bool> &marks)
{
  if (!marks.empty() && marks.size() != size()) {
    std::ostringstream os;
    os << "vpMorphContour::setOwnEdges: " << marks.size() << " marks for " << size() << " vertices";
    throw vpMorphException(vpMorphException::badParameterError, os.str());
  }
  m_ownEdges.assign(marks.begin(), marks.end());
}

void vpMorphContour::mapRegion(double a11, double a12, double a21, double a22, double b1, double b2)
{
  if (m_outline) {
    vpMorphContour o(*m_outline);
    for (std::size_t k = 0; k < o.size(); ++k) {
      const double x = o.m_x[k], y = o.m_y[k];
      o.m_x[k] = a11 * x + a12 * y + b1;
      o.m_y[k] = a21 * x + a22 * y + b2;
    }
    m_outline = std::make_shared<const vpMorphContour>(std::move(o));
    m_outlineBlur *= std::sqrt(std::fabs(a11 * a22 - a12 * a21));
  }
  if (!hasRegion())
    return;
  const double x = m_regionCx, y = m_regionCy;
  m_regionArea *= std::fabs(a11 * a22 - a12 * a21);
  m_regionCx = a11 * x + a12 * y + b1;
  m_regionCy = a21 * x + a22 * y + b2;
  // M' = A M A^T
  const double m20 = m_regionMu20, m11 = m_regionMu11, m02 = m_regionMu02;
  const double p11 = a11 * m20 + a12 * m11, p12 = a11 * m11 + a12 * m02; // first row of A M
  const double p21 = a21 * m20 + a22 * m11, p22 = a21 * m11 + a22 * m02; // second row of A M
  m_regionMu20 = p11 * a11 + p12 * a12;
  m_regionMu11 = p11 * a21 + p12 * a22;
  m_regionMu02 = p21 * a21 + p22 * a22;
}

vpMorphContour vpMorphContour::rotatedStart(std::size_t k) const
{
  vpMorphContour c(*this);
  const std::size_t n = size();
  if (n == 0)
    return c;
  std::rotate(c.m_x.begin(), c.m_x.begin() + (k % n), c.m_x.end());
  std::rotate(c.m_y.begin(), c.m_y.begin() + (k % n), c.m_y.end());
  if (!c.m_ownEdges.empty())
    std::rotate(c.m_ownEdges.begin(), c.m_ownEdges.begin() + (k % n), c.m_ownEdges.end());
  return c;
}

vpMorphContour vpMorphContour::reversed() const
{
  vpMorphContour c(*this);
  if (size() > 1) {
    std::reverse(c.m_x.begin() + 1, c.m_x.end());
    std::reverse(c.m_y.begin() + 1, c.m_y.end());
  }
  // The edge from new vertex j to j + 1 is the old one from j + 1's old index, n - j - 1, to j's.
  const std::size_t n = size();
  for (std::size_t j = 0; j < c.m_ownEdges.size(); ++j)
    c.m_ownEdges[j] = m_ownEdges[n - 1 - j];
  return c;
}

vpMorphContour vpMorphContour::mirrored() const
{
  double cx, cy;
  centroid(cx, cy);
  vpMorphContour c(*this);
  for (double &x : c.m_x)
    x = 2.0 * cx - x;
  c.mapRegion(-1.0, 0.0, 0.0, 1.0, 2.0 * cx, 0.0);
  return c.reversed();
}

vpMorphContour vpMorphContour::counterClockwise() const { return isCounterClockwise() ? *this : reversed(); }

vpMorphContour vpMorphContour::transformed(double theta, double tx, double ty, double s) const
{
  if (!std::isfinite(theta) || !std::isfinite(tx) || !std::isfinite(ty) || !std::isfinite(s) || s <= 0.0) {
    std::ostringstream os;
    os << "vpMorphContour::transformed: parameters must be finite with scale > 0 (theta " << theta << ", t (" << tx
       << ", " << ty << "), s " << s << ")";
    throw vpMorphException(vpMorphException::badParameterError, os.str());
  }
  double cx, cy;
  centroid(cx, cy);
  const double c = std::cos(theta) * s, sn = std::sin(theta) * s;
  vpMorphContour out(*this);
  for (std::size_t k = 0; k < size(); ++k) {
    const double x = m_x[k] - cx, y = m_y[k] - cy;
    out.m_x[k] = cx + c * x - sn * y + tx;
    out.m_y[k] = cy + sn * x + c * y + ty;
  }
  out.mapRegion(c, -sn, sn, c, cx - c * cx + sn * cy + tx, cy - sn * cx - c * cy + ty);
  out.validate();
  return out;
}

vpMorphContour vpMorphContour::normalized() const
{
  double cx, cy;
  centroid(cx, cy);
  const double s = 1.0 / perimeter();
  vpMorphContour out(*this);
  for (std::size_t k = 0; k < size(); ++k) {
    out.m_x[k] = (m_x[k] - cx) * s;
    out.m_y[k] = (m_y[k] - cy) * s;
  }
  out.mapRegion(s, 0.0, 0.0, s, -cx * s, -cy * s);
  return out;
}

vpMorphContour vpMorphContour::resampled(std::size_t n) const
{
  if (n < 3) {
    std::ostringstream os;
    os << "vpMorphContour::resampled: need at least 3 vertices (asked " << n << ")";
    throw vpMorphException(vpMorphException::badParameterError, os.str());
  }
  const std::size_t m = size();
  const double step = perimeter() / static_cast<double>(n);
  std::vector<double> x, y;
  x.reserve(n);
  y.reserve(n);
  std::vector<bool> marks; // each new vertex's edge: the old edge it lies on
  marks.reserve(m_ownEdges.empty() ? 0 : n);
  std::size_t k = 0;  // current edge goes from vertex k to k+1
  double along = 0.0; // arc length at vertex k
  double elen = edgeLength(1 % m);
  for (std::size_t s = 0; s < n; ++s) {
    const double target = s * step;
    while (along + elen < target && k + 1 < m) {
      along += elen;
      ++k;
      elen = edgeLength((k + 1) % m);
    }
    const std::size_t k1 = (k + 1) % m;
    const double t = elen > 0 ? std::min(1.0, std::max(0.0, (target - along) / elen)) : 0.0;
    x.push_back(m_x[k] + t * (m_x[k1] - m_x[k]));
    y.push_back(m_y[k] + t * (m_y[k1] - m_y[k]));
    if (!m_ownEdges.empty())
      marks.push_back(m_ownEdges[k] != 0);
  }
  vpMorphContour out(x, y, m_units);
  out.setOwnEdges(marks);
  if (hasRegion())
    out.setRegion(m_regionArea, m_regionCx, m_regionCy, m_regionMu20, m_regionMu11, m_regionMu02); // same region
  out.m_outline = m_outline; // same edge
  out.m_outlineBlur = m_outlineBlur;
  return out;
}

vpMorphContour vpMorphContour::toNormalized(const vpCameraParameters &cam) const
{
  if (m_units != PIXEL)
    throw vpMorphException(vpMorphException::badParameterError,
                           "vpMorphContour::toNormalized: the contour is already in normalised coordinates");
  vpMorphContour out(*this);
  out.m_outline.reset(); // converted below
  for (std::size_t k = 0; k < size(); ++k) {
    out.m_x[k] = (m_x[k] - cam.get_u0()) / cam.get_px();
    out.m_y[k] = (m_y[k] - cam.get_v0()) / cam.get_py();
  }
  out.mapRegion(1.0 / cam.get_px(), 0.0, 0.0, 1.0 / cam.get_py(), -cam.get_u0() / cam.get_px(),
                -cam.get_v0() / cam.get_py());
  out.m_units = NORMALIZED;
  if (m_outline) { // mapped once, its units changed with it
    out.m_outline = std::make_shared<const vpMorphContour>(m_outline->toNormalized(cam));
    out.m_outlineBlur = m_outlineBlur / std::sqrt(cam.get_px() * cam.get_py());
  }
  return out;
}

vpMorphContour vpMorphContour::toPixels(const vpCameraParameters &cam) const
{
  if (m_units != NORMALIZED)
    throw vpMorphException(vpMorphException::badParameterError,
                           "vpMorphContour::toPixels: the contour is already in pixel coordinates");
  vpMorphContour out(*this);
  out.m_outline.reset(); // converted below
  for (std::size_t k = 0; k < size(); ++k) {
    out.m_x[k] = cam.get_u0() + m_x[k] * cam.get_px();
    out.m_y[k] = cam.get_v0() + m_y[k] * cam.get_py();
  }
  out.mapRegion(cam.get_px(), 0.0, 0.0, cam.get_py(), cam.get_u0(), cam.get_v0());
  out.m_units = PIXEL;
  if (m_outline) { // mapped once, its units changed with it
    out.m_outline = std::make_shared<const vpMorphContour>(m_outline->toPixels(cam));
    out.m_outlineBlur = m_outlineBlur * std::sqrt(cam.get_px() * cam.get_py());
  }
  return out;
}
