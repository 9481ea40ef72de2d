#include <visp3/morph_bench/vpMorphBenchObservability.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Dense>

#include <visp3/core/vpMath.h>
#include <visp3/core/vpQuaternionVector.h>
#include <visp3/morph/vpMorphException.h>

#include "vpMorphBenchPlane.h"

namespace
{
const double kInf = std::numeric_limits<double>::infinity();
const unsigned int kMaxOrder = 12;                  // k-fold symmetries tried
const double kIrrationalTurnsDeg[] = {13, 43, 101}; // a disc turns onto itself by any of these
const double kScanStepDeg = 2.0;                    // the near-symmetry scan
const double kGroupGuardDeg = 5.0;                  // turns this near a symmetry are the symmetry's
const double kCell = 4.0;                           // px, nearest-point grid
const std::size_t kQueries = 400;                   // outline points moved to measure a residual
const double kReach = 16.0; // px: a point farther from the outline counts as this far (residuals are compared
                            // with fractions of a pixel)

struct Pt
{
  double x, y;
};

//! The closed outline, a point a pixel, with a grid to find the nearest point of it.
class Outline
{
public:
  //! \e centre: the shape's centroid (of its region if measured, else of its points).
  Outline(std::vector<Pt> p, const Pt *centre) : m_p(std::move(p))
  {
    long i1 = m_i0 = cell(m_p[0].x), j1 = m_j0 = cell(m_p[0].y);
    for (const Pt &q : m_p) {
      m_i0 = std::min(m_i0, cell(q.x));
      m_j0 = std::min(m_j0, cell(q.y));
      i1 = std::max(i1, cell(q.x));
      j1 = std::max(j1, cell(q.y));
    }
    m_w = i1 - m_i0 + 1;
    m_h = j1 - m_j0 + 1;
    m_grid.resize(static_cast<std::size_t>(m_w * m_h));
    for (std::size_t i = 0; i < m_p.size(); ++i)
      m_grid[static_cast<std::size_t>((cell(m_p[i].x) - m_i0) + (cell(m_p[i].y) - m_j0) * m_w)].push_back(i);
    double cx = 0, cy = 0;
    for (const Pt &q : m_p) {
      cx += q.x;
      cy += q.y;
    }
    m_c = centre ? *centre : Pt{cx / m_p.size(), cy / m_p.size()};
    // The points moved and compared: at most kQueries, evenly spread (the residuals are means over the outline).
    const std::size_t step = (m_p.size() + kQueries - 1) / kQueries;
    for (std::size_t i = 0; i < m_p.size(); i += step)
      m_q.push_back(m_p[i]);
  }
  const std::vector<Pt> &points() const { return m_q; }
  const Pt &centroid() const { return m_c; }
  //! Normal (unit) of the outline at its point i (of all its points), from its neighbours two points away.
  Pt normal(std::size_t i) const
  {
    const std::size_t n = m_p.size();
    const Pt &a = m_p[(i + n - 2) % n], &b = m_p[(i + 2) % n];
    const double dx = b.x - a.x, dy = b.y - a.y, l = std::hypot(dx, dy);
    return l > 0 ? Pt{-dy / l, dx / l} : Pt{0, 0};
  }
  /*!
    The nearest point of the outline's polyline to q: its distance, the point, the segment's unit normal. Searched
    within kReach pixels: farther, kReach is returned and \e normal is null (a point that far from the outline only
    says that it is far).
  */
  double nearest(const Pt &q, Pt &at, Pt &normal) const
  {
    const long cx = cell(q.x), cy = cell(q.y);
    std::size_t best = m_p.size();
    double bestD = kInf;
    auto visit = [&](long i, long j) {
      if (i < m_i0 || j < m_j0 || i >= m_i0 + m_w || j >= m_j0 + m_h)
        return;
      for (std::size_t k : m_grid[static_cast<std::size_t>((i - m_i0) + (j - m_j0) * m_w)]) {
        const double d = std::hypot(m_p[k].x - q.x, m_p[k].y - q.y);
        if (d < bestD) {
          bestD = d;
          best = k;
        }
      }
    };
    const long reach = static_cast<long>(std::ceil(kReach / kCell)) + 1;
    for (long r = 0; r <= reach && (best == m_p.size() || (r - 1) * kCell < bestD); ++r) {
      if (r == 0) {
        visit(cx, cy);
        continue;
      }
      for (long i = cx - r; i <= cx + r; ++i) {
        visit(i, cy - r);
        visit(i, cy + r);
      }
      for (long j = cy - r + 1; j <= cy + r - 1; ++j) {
        visit(cx - r, j);
        visit(cx + r, j);
      }
    }
    if (best == m_p.size() || bestD > kReach) {
      normal = {0, 0};
      at = q;
      return kReach;
    }
    // Refined on the two segments at that point.
    const std::size_t n = m_p.size();
    double dmin = kInf;
    for (std::size_t s : {(best + n - 1) % n, best}) {
      const Pt &a = m_p[s], &b = m_p[(s + 1) % n];
      const double ex = b.x - a.x, ey = b.y - a.y, l2 = ex * ex + ey * ey;
      const double t = l2 > 0 ? std::min(1.0, std::max(0.0, ((q.x - a.x) * ex + (q.y - a.y) * ey) / l2)) : 0.0;
      const Pt e{a.x + t * ex, a.y + t * ey};
      const double d = std::hypot(q.x - e.x, q.y - e.y);
      if (d < dmin) {
        dmin = d;
        at = e;
        const double l = std::sqrt(l2);
        normal = l > 0 ? Pt{-ey / l, ex / l} : Pt{0, 0};
      }
    }
    return dmin;
  }

private:
  static long cell(double v) { return static_cast<long>(std::floor(v / kCell)); }
  std::vector<Pt> m_p, m_q;
  long m_i0 = 0, m_j0 = 0, m_w = 0, m_h = 0;
  std::vector<std::vector<std::size_t>> m_grid; // the points of each cell of the outline's box
  Pt m_c{0, 0};
};

//! A rigid motion of the image: turn theta about c, then translate by t.
struct Turn
{
  double theta = 0, tx = 0, ty = 0;
  Pt apply(const Pt &p, const Pt &c) const
  {
    const double cs = std::cos(theta), sn = std::sin(theta);
    return {c.x + cs * (p.x - c.x) - sn * (p.y - c.y) + tx, c.y + sn * (p.x - c.x) + cs * (p.y - c.y) + ty};
  }
};

//! RMS distance of the outline moved by T to itself.
double residual(const Outline &o, const Turn &T)
{
  double s = 0;
  Pt at, n;
  for (const Pt &p : o.points()) {
    const double d = o.nearest(T.apply(p, o.centroid()), at, n);
    s += d * d;
  }
  return std::sqrt(s / o.points().size());
}

//! T refined so that the moved outline lies on itself (point-to-edge Gauss-Newton), its turn kept when \e fixedTurn;
//! its RMS residual in \e rms.
Turn refine(const Outline &o, Turn T, double &rms, bool fixedTurn = false)
{
  const Pt &c = o.centroid();
  for (int it = 0; it < 15; ++it) {
    Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
    Eigen::Vector3d b = Eigen::Vector3d::Zero();
    for (const Pt &p : o.points()) {
      const Pt q = T.apply(p, c);
      Pt at, n;
      o.nearest(q, at, n);
      const double r = n.x * (q.x - at.x) + n.y * (q.y - at.y);
      // d q / d theta: q - c - t turned by a quarter turn.
      const double gx = -(q.y - c.y - T.ty), gy = q.x - c.x - T.tx;
      const Eigen::Vector3d J(n.x * gx + n.y * gy, n.x, n.y);
      A += J * J.transpose();
      b += J * r;
    }
    Eigen::Vector3d d = A.ldlt().solve(-b);
    if (fixedTurn) {
      d[0] = 0.0;
      d.tail<2>() = A.block<2, 2>(1, 1).ldlt().solve(-b.tail<2>());
    }
    if (!d.allFinite())
      break;
    T.theta += d[0];
    T.tx += d[1];
    T.ty += d[2];
    if (std::fabs(d[0]) < 1e-9 && std::hypot(d[1], d[2]) < 1e-7)
      break;
  }
  rms = residual(o, T);
  return T;
}

/*!
  Whether the turn by \e theta about the centroid is a symmetry: its translation refined, within 2 sigma RMS. A
  symmetry turns the outline onto itself about its centroid: one that lies more than a pixel off before the
  refinement is none.
*/
bool symmetric(const Outline &o, double theta, Turn *T = nullptr)
{
  double rms = kInf;
  Turn t;
  t.theta = theta;
  if (residual(o, t) > 1.0)
    return false;
  t = refine(o, t, rms, true);
  if (T)
    *T = t;
  return rms <= 2.0 * vpMorphBenchObservability::kPointNoisePx;
}

double wrapDeg(double d) { return d - 360.0 * std::floor(d / 360.0); }

void badParameter(const std::string &msg) { throw vpMorphException(vpMorphException::badParameterError, msg); }
} // namespace

vpMorphBenchObservability::vpMorphBenchObservability(const vpMorphContour &contour, const vpCameraParameters &cam,
                                                     const vpHomogeneousMatrix &cdMo, double translationTolerance,
                                                     double rotationTolerance)
  : m_tolT(translationTolerance), m_tolR(rotationTolerance), m_cdMo(cdMo)
{
  if (!(translationTolerance > 0) || !(rotationTolerance > 0) || !std::isfinite(translationTolerance) ||
      !std::isfinite(rotationTolerance))
    badParameter("vpMorphBenchObservability: the tolerances must be finite and > 0");
  // The outline in pixels, a point every pixel of its length (so that its mean is the perimeter's centroid, the
  // centre of any rotational symmetry).
  const vpMorphContour &c = contour.outline();
  std::vector<Pt> pts;
  double carry = 0.0; // where the next point falls on the current segment
  for (std::size_t k = 0; k < c.size(); ++k) {
    const std::size_t l = (k + 1) % c.size();
    const double dx = c.x(l) - c.x(k), dy = c.y(l) - c.y(k), len = std::hypot(dx, dy);
    for (; carry < len; carry += 1.0)
      pts.push_back({c.x(k) + dx * carry / len, c.y(k) + dy * carry / len});
    carry -= len;
  }
  if (pts.size() < 8)
    throw vpMorphException(vpMorphException::badContourError,
                           "vpMorphBenchObservability: a contour of 8 points at least");
  // The centre of any rotational symmetry is the region's centroid (measured to hundredths of a pixel), else the
  // perimeter's.
  Pt centre{0, 0};
  if (contour.hasRegion())
    contour.regionCentroid(centre.x, centre.y);
  const Outline o(pts, contour.hasRegion() ? &centre : nullptr);

  // Symmetry: continuous, else the largest k-fold.
  std::vector<Turn> group;
  bool continuous = true;
  for (double deg : kIrrationalTurnsDeg)
    continuous = continuous && symmetric(o, vpMath::rad(deg));
  if (continuous)
    m_order = 0;
  else
    for (unsigned int k = kMaxOrder; k >= 2 && m_order == 1; --k) {
      Turn T;
      if (symmetric(o, 2.0 * M_PI / k, &T)) {
        m_order = k;
        for (unsigned int j = 1; j < k; ++j) {
          Turn Tj;
          symmetric(o, 2.0 * M_PI * j / k, &Tj);
          group.push_back(Tj);
        }
      }
    }

  // Near symmetry: the best turn outside the group.
  m_nearResidual = kInf;
  m_nearTurn = 0.0;
  if (m_order != 0) {
    std::vector<std::pair<double, double>> coarse; // (residual, turn)
    for (double deg = kScanStepDeg; deg < 360.0; deg += kScanStepDeg) {
      bool inGroup = false;
      for (unsigned int j = 0; j < std::max(1u, m_order); ++j) {
        const double g = 360.0 * j / std::max(1u, m_order), d = std::fabs(wrapDeg(deg - g + 180.0) - 180.0);
        inGroup = inGroup || d < kGroupGuardDeg;
      }
      if (inGroup)
        continue;
      Turn t;
      t.theta = vpMath::rad(deg);
      coarse.emplace_back(residual(o, t), t.theta);
    }
    std::sort(coarse.begin(), coarse.end());
    // The best three, each refined over the turn within a scan step (a ternary search, the translation refined at
    // every turn), so that it cannot slide back onto the symmetry.
    auto at = [&o](double theta) {
      double rms = kInf;
      Turn t;
      t.theta = theta;
      refine(o, t, rms, true);
      return rms;
    };
    for (std::size_t k = 0; k < coarse.size() && k < 3; ++k) {
      double lo = coarse[k].second - vpMath::rad(kScanStepDeg), hi = coarse[k].second + vpMath::rad(kScanStepDeg);
      for (int it = 0; it < 8; ++it) {
        const double a = lo + (hi - lo) / 3, b = hi - (hi - lo) / 3;
        if (at(a) < at(b))
          hi = b;
        else
          lo = a;
      }
      const double rms = at(0.5 * (lo + hi));
      if (rms < m_nearResidual) {
        m_nearResidual = rms;
        m_nearTurn = 0.5 * (lo + hi);
      }
    }
  }

  // The symmetries as motions of the object frame, through the plane seen at cdMo: two image points and their images.
  const Pt &ic = o.centroid();
  double c0x = 0, c0y = 0;
  vpMorphBenchPlane::onPlane(cdMo, cam, ic.x, ic.y, c0x, c0y);
  m_centreX = c0x;
  m_centreY = c0y;
  const Pt ia{ic.x + 50.0, ic.y};
  double a0x = 0, a0y = 0;
  vpMorphBenchPlane::onPlane(cdMo, cam, ia.x, ia.y, a0x, a0y);
  for (const Turn &T : group) {
    const Pt jc = T.apply(ic, ic), ja = T.apply(ia, ic);
    double c1x = 0, c1y = 0, a1x = 0, a1y = 0;
    vpMorphBenchPlane::onPlane(cdMo, cam, jc.x, jc.y, c1x, c1y);
    vpMorphBenchPlane::onPlane(cdMo, cam, ja.x, ja.y, a1x, a1y);
    const double angle = std::atan2(a1y - c1y, a1x - c1x) - std::atan2(a0y - c0y, a0x - c0x);
    const double cs = std::cos(angle), sn = std::sin(angle);
    m_placements.emplace_back(c1x - (cs * c0x - sn * c0y), c1y - (sn * c0x + cs * c0y), 0.0, 0.0, 0.0, angle);
  }

  // The Cramer-Rao bound of the camera twist from the outline's normal displacements.
  const vpColVector nz = cdMo.getRotationMatrix().getCol(2);
  const vpTranslationVector to = cdMo.getTranslationVector();
  const double dPlane = nz[0] * to[0] + nz[1] * to[1] + nz[2] * to[2];
  Eigen::Matrix<double, 6, 6> F = Eigen::Matrix<double, 6, 6>::Zero();
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const double x = (pts[i].x - cam.get_u0()) / cam.get_px(), y = (pts[i].y - cam.get_v0()) / cam.get_py();
    const double Z = dPlane / (nz[0] * x + nz[1] * y + nz[2]);
    Eigen::Matrix<double, 2, 6> L;
    L << -1 / Z, 0, x / Z, x * y, -(1 + x * x), y, 0, -1 / Z, y / Z, 1 + y * y, -x * y, -x;
    const Pt n = o.normal(i);
    const Eigen::Matrix<double, 1, 6> g = n.x * cam.get_px() * L.row(0) + n.y * cam.get_py() * L.row(1);
    F += g.transpose() * g;
  }
  F /= kPointNoisePx * kPointNoisePx;
  // Errors at the object: e_t = -v + [P]x w (P the object's origin in the camera), e_r = w.
  Eigen::Matrix<double, 6, 6> A = Eigen::Matrix<double, 6, 6>::Identity();
  A.block<3, 3>(0, 0) = -Eigen::Matrix3d::Identity();
  A.block<3, 3>(0, 3) << 0, -to[2], to[1], to[2], 0, -to[0], -to[1], to[0], 0;
  for (int tilt = 0; tilt < 2; ++tilt) {
    // The estimated degrees of freedom: vx, vy, vz, (wx, wy), (wz unless the symmetry is continuous).
    std::vector<int> dof = {0, 1, 2};
    if (tilt) {
      dof.push_back(3);
      dof.push_back(4);
    }
    if (m_order != 0)
      dof.push_back(5);
    const int n = static_cast<int>(dof.size());
    Eigen::MatrixXd Fs(n, n);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j)
        Fs(i, j) = F(dof[i], dof[j]);
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(Fs);
    double *bound = tilt ? m_bound6 : m_bound4;
    if (eig.eigenvalues().minCoeff() <= 1e-12 * std::max(1.0, eig.eigenvalues().maxCoeff())) {
      for (int k = 0; k < 4; ++k)
        bound[k] = kInf;
      continue;
    }
    const Eigen::MatrixXd Cs =
        eig.eigenvectors() * eig.eigenvalues().cwiseInverse().asDiagonal() * eig.eigenvectors().transpose();
    Eigen::Matrix<double, 6, 6> C = Eigen::Matrix<double, 6, 6>::Zero();
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j)
        C(dof[i], dof[j]) = Cs(i, j);
    const Eigen::Matrix<double, 6, 6> E = A * C * A.transpose();
    const Eigen::Matrix2d inPlane = E.block<2, 2>(0, 0), tiltBlock = E.block<2, 2>(3, 3);
    bound[0] = 3.0 * std::sqrt(std::max(0.0, Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(inPlane).eigenvalues()[1]));
    bound[1] = 3.0 * std::sqrt(std::max(0.0, E(2, 2)));
    bound[2] = 3.0 * std::sqrt(std::max(0.0, E(5, 5)));
    bound[3] =
        3.0 * std::sqrt(std::max(0.0, Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(tiltBlock).eigenvalues()[1]));
  }
}

std::string vpMorphBenchObservability::reason(bool tilt) const
{
  if (nearlySymmetric())
    return "nearly-symmetric";
  if (translationBound(tilt) > m_tolT)
    return "translation";
  if (depthBound(tilt) > m_tolT)
    return "depth";
  if (rotationBound(tilt) > m_tolR)
    return "rotation";
  if (tiltBound(tilt) > m_tolR)
    return "tilt";
  return std::string();
}

vpHomogeneousMatrix vpMorphBenchObservability::nearestDesiredPose(const vpHomogeneousMatrix &cMo) const
{
  if (m_order != 0)
    return m_cdMo;
  // The object's displacement in its own frame, its turn about the plane's normal (the twist of its rotation).
  const vpHomogeneousMatrix W = m_cdMo.inverse() * cMo;
  const vpQuaternionVector q(W.getRotationMatrix());
  const double phi = 2.0 * std::atan2(q.z(), q.w());
  const vpHomogeneousMatrix toCentre(m_centreX, m_centreY, 0, 0, 0, 0);
  return m_cdMo * toCentre * vpHomogeneousMatrix(0, 0, 0, 0, 0, phi) * toCentre.inverse();
}
