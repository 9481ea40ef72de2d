#include <visp3/morph/vpMorphHomography.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include <visp3/morph/vpMorphException.h>
#include <visp3/morph/vpMorphRigidTransform.h>

#include "vpMorphNearestEdge.h"

namespace
{
using Mat3 = Eigen::Matrix3d;
using Vec3 = Eigen::Vector3d;
using Mat8 = Eigen::Matrix<double, 8, 8>;
using Mat9 = Eigen::Matrix<double, 9, 9>;
using Vec9 = Eigen::Matrix<double, 9, 1>;

struct Point
{
  double x, y;
};

Mat3 toEigen(const vpMatrix &M)
{
  Mat3 E;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      E(r, c) = M[r][c];
  return E;
}

vpMatrix toVisp(const Mat3 &E)
{
  vpMatrix M(3, 3);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      M[r][c] = E(r, c);
  return M;
}

bool finite(const Mat3 &M) { return M.allFinite(); }

// Unit Frobenius norm, positive determinant: one representative of the projective class.
Mat3 normalise(const Mat3 &M)
{
  const double n = M.norm();
  Mat3 N = M / n;
  if (N.determinant() < 0)
    N = -N;
  return N;
}

bool project(const Mat3 &M, double x, double y, double &xo, double &yo)
{
  const Vec3 u = M * Vec3(x, y, 1.0);
  if (!(std::fabs(u[2]) > 1e-12 * u.norm()))
    return false;
  xo = u[0] / u[2];
  yo = u[1] / u[2];
  return std::isfinite(xo) && std::isfinite(yo);
}

// n points evenly spaced along the closed polygon, starting at vertex 0, and (when \e normals is given) the unit left
// normal (-dy, dx) of the edge each lies on.
std::vector<Point> sampleOutline(const vpMorphContour &c, unsigned int n, std::vector<Point> *normals = nullptr)
{
  const double L = c.perimeter();
  std::vector<Point> out;
  out.reserve(n);
  std::size_t k = 0; // current edge from vertex k to k+1
  double s0 = 0.0;   // arc length at vertex k
  for (unsigned int i = 0; i < n; ++i) {
    const double s = L * double(i) / double(n);
    double len = c.edgeLength((k + 1) % c.size());
    while (s > s0 + len && k + 1 < c.size()) {
      s0 += len;
      ++k;
      len = c.edgeLength((k + 1) % c.size());
    }
    const std::size_t l = (k + 1) % c.size();
    const double t = len > 0 ? std::min(1.0, (s - s0) / len) : 0.0;
    out.push_back({c.x(k) + t * (c.x(l) - c.x(k)), c.y(k) + t * (c.y(l) - c.y(k))});
    if (normals)
      normals->push_back(len > 0 ? Point{-(c.y(l) - c.y(k)) / len, (c.x(l) - c.x(k)) / len} : Point{0.0, 0.0});
  }
  return out;
}

double median(std::vector<double> v)
{
  if (v.empty())
    return 0.0;
  const std::size_t m = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + m, v.end());
  return v[m];
}

// Tukey's biweight constant (95 % efficiency under Gaussian noise): a residual of kTukey robust scales weighs nothing.
constexpr double kTukey = 4.685;

/*
  The robust scale of the residuals \e r, 1.4826 MAD floored at \e minSigma and at rounding (1e-13 \e scale), where
  those beyond \e reach were not searched (+inf). That is the exhaustive scale when the median lies within reach
  (every residual beyond is beyond it too). Where Tukey's cut-off of that scale lies beyond reach, \e requery(k,
  within) searches each of them again within the cut-off (r[k] then exact, or +inf beyond it, where it weighs
  nothing); where the median does, exhaustively, and the scale is taken again.
*/
template <typename F> double robustScale(std::vector<double> &r, double reach, double minSigma, double scale, F requery)
{
  auto scaleOf = [&](double &m) {
    std::vector<double> a(r.size());
    for (std::size_t k = 0; k < r.size(); ++k)
      a[k] = std::fabs(r[k]);
    m = median(a);
    return std::max({minSigma, 1.4826 * m, 1e-13 * scale});
  };
  double m = 0.0;
  const double sigma = scaleOf(m);
  if (!(kTukey * sigma > reach))
    return sigma;
  const double within = m <= reach ? kTukey * sigma : std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < r.size(); ++k)
    if (std::isinf(r[k]))
      requery(k, within);
  return m <= reach ? sigma : scaleOf(m);
}

// Robust weight of a residual in units of sigma: Huber (c = 1.345) or Tukey biweight (c = kTukey).
double robustWeight(double r, double sigma, bool tukey)
{
  const double u = std::fabs(r) / sigma;
  if (tukey) {
    const double c = kTukey;
    if (u >= c)
      return 0.0;
    const double a = 1.0 - (u / c) * (u / c);
    return a * a;
  }
  const double c = 1.345;
  return u <= c ? 1.0 : c / u;
}

// Hartley normalisation: centroid to the origin, mean distance sqrt(2).
Mat3 hartley(const std::vector<Point> &P, const std::vector<double> &w)
{
  double sw = 0, mx = 0, my = 0;
  for (std::size_t k = 0; k < P.size(); ++k) {
    sw += w[k];
    mx += w[k] * P[k].x;
    my += w[k] * P[k].y;
  }
  mx /= sw;
  my /= sw;
  double md = 0;
  for (std::size_t k = 0; k < P.size(); ++k)
    md += w[k] * std::hypot(P[k].x - mx, P[k].y - my);
  md /= sw;
  const double s = md > 0 ? std::sqrt(2.0) / md : 1.0;
  Mat3 T;
  T << s, 0, -s * mx, 0, s, -s * my, 0, 0, 1;
  return T;
}

// Weighted DLT from point pairs (Hartley-normalised); returns false on a rank-deficient system.
bool dlt(const std::vector<Point> &A, const std::vector<Point> &B, const std::vector<double> &w, Mat3 &G)
{
  const Mat3 Ta = hartley(A, w), Tb = hartley(B, w);
  Eigen::Matrix<double, 9, 9> M = Eigen::Matrix<double, 9, 9>::Zero();
  for (std::size_t k = 0; k < A.size(); ++k) {
    if (!(w[k] > 0))
      continue;
    const Vec3 a = Ta * Vec3(A[k].x, A[k].y, 1.0), b = Tb * Vec3(B[k].x, B[k].y, 1.0);
    Eigen::Matrix<double, 9, 1> r1, r2;
    r1 << 0, 0, 0, -a[0], -a[1], -a[2], b[1] * a[0], b[1] * a[1], b[1] * a[2];
    r2 << a[0], a[1], a[2], 0, 0, 0, -b[0] * a[0], -b[0] * a[1], -b[0] * a[2];
    M += w[k] * (r1 * r1.transpose() + r2 * r2.transpose());
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 9, 9>> es(M);
  if (es.info() != Eigen::Success)
    return false;
  const Eigen::Matrix<double, 9, 1> ev = es.eigenvalues();
  // A unique solution: one (near) zero eigenvalue, the next one clearly above it.
  if (!(ev[1] > 1e-12 * ev[8]))
    return false;
  const Eigen::Matrix<double, 9, 1> h = es.eigenvectors().col(0);
  Mat3 Gn;
  Gn << h[0], h[1], h[2], h[3], h[4], h[5], h[6], h[7], h[8];
  G = Tb.inverse() * Gn * Ta;
  return finite(G) && std::fabs(G.determinant()) > 0;
}

/*
  Distance from (x, y) to the edges of \e nearest moved by delta along their left normals, as the level delta of the
  polygon's distance: an outline grown (or shrunk) all round is that level set, with rounded corners as a blurred edge
  makes them. \e side is -d(distance)/d(delta): +1 where the point lies on the side the normals point to, -1 opposite.
*/
double offsetDistance(const vpMorphNearestEdge &nearest, double x, double y, double delta, double &mx, double &my,
                      double &side, double reach = std::numeric_limits<double>::infinity())
{
  double along = 0.0;
  // The level delta lies within |delta| of the edges: beyond reach + |delta| of them, it is beyond reach.
  const double r = nearest.within(x, y, reach + std::fabs(delta), mx, my, &along);
  if (std::isinf(r))
    return r;
  side = along > 0.0 ? 1.0 : (along < 0.0 ? -1.0 : 0.0);
  return r - side * delta;
}

[[noreturn]] void degenerate(const std::string &msg)
{
  throw vpMorphException(vpMorphException::badContourError, "vpMorphHomography: " + msg);
}

// The checks shared by fit() and refine(); who names the caller in the messages.
void checkFitInput(const vpMorphContour &input, const vpMorphContour &target, double minSigma, unsigned int samples,
                   unsigned int maxIterations, const std::string &who)
{
  if (!std::isfinite(minSigma) || minSigma < 0.0) {
    std::ostringstream os;
    os << who + ": minSigma must be finite and >= 0, got " << minSigma;
    throw vpMorphException(vpMorphException::badParameterError, os.str());
  }
  if (samples < 16 || maxIterations < 1) {
    std::ostringstream os;
    os << who + ": need samples >= 16 and maxIterations >= 1, got " << samples << " and " << maxIterations;
    throw vpMorphException(vpMorphException::badParameterError, os.str());
  }
  if (input.size() < 4 || target.size() < 4) {
    std::ostringstream os;
    os << who + ": a homography needs outlines of at least 4 vertices (a triangle's edges let points slide "
                "along them), got "
       << input.size() << " and " << target.size();
    throw vpMorphException(vpMorphException::badContourError, os.str());
  }
  if (input.units() != target.units())
    throw vpMorphException(vpMorphException::badParameterError,
                           who + ": the two contours are in different units (pixels and normalised coordinates)");
}
} // namespace

vpMorphHomography::vpMorphHomography() : m_G(3, 3)
{
  m_G.eye();
  m_G /= std::sqrt(3.0);
}

vpMorphHomography::vpMorphHomography(const vpMatrix &G)
{
  if (G.getRows() != 3 || G.getCols() != 3) {
    std::ostringstream os;
    os << "vpMorphHomography: the matrix must be 3x3, got " << G.getRows() << "x" << G.getCols();
    throw vpMorphException(vpMorphException::badParameterError, os.str());
  }
  const Mat3 E = toEigen(G);
  if (!finite(E) || !(std::fabs(E.determinant()) > 1e-14 * std::pow(E.norm(), 3)))
    throw vpMorphException(vpMorphException::badParameterError,
                           "vpMorphHomography: the matrix must be finite and non-singular");
  m_G = toVisp(normalise(E));
}

bool vpMorphHomography::apply(double x, double y, double &xo, double &yo) const
{
  double a, b;
  if (!project(toEigen(m_G), x, y, a, b))
    return false;
  xo = a;
  yo = b;
  return true;
}

vpMorphContour vpMorphHomography::apply(const vpMorphContour &c) const
{
  std::vector<double> x(c.size()), y(c.size());
  for (std::size_t k = 0; k < c.size(); ++k)
    if (!apply(c.x(k), c.y(k), x[k], y[k]))
      throw vpMorphException(vpMorphException::badContourError,
                             "vpMorphHomography::apply: a vertex maps to infinity (the line at infinity crosses the "
                             "contour)");
  return vpMorphContour(x, y, c.units());
}

vpMorphHomography vpMorphHomography::inverse() const
{
  vpMorphHomography h;
  h.m_G = toVisp(normalise(toEigen(m_G).inverse()));
  h.m_residual = m_residual;
  h.m_inlierShare = m_inlierShare;
  h.m_iterations = m_iterations;
  return h;
}

vpMorphHomography vpMorphHomography::fit(const vpMorphContour &input, const vpMorphContour &target,
                                         const vpMorphCorrespondence &corr, double minSigma, unsigned int samples,
                                         unsigned int maxIterations)
{
  vpMorphRigidTransform::checkCorrespondence(input, target, corr, "vpMorphHomography::fit");
  checkFitInput(input, target, minSigma, samples, maxIterations, "vpMorphHomography::fit");
  const double LI = input.perimeter(), LT = target.perimeter();
  // Scale of the coordinates, for the relative floors below.
  const double scale = 0.5 * (LI + LT);

  // 1. Initial homography: weighted DLT over the corresponded segments sampled in proportion to their length.
  std::vector<Point> A, B;
  std::vector<double> w;
  const auto &pairs = corr.pairs();
  const std::size_t K = pairs.size();
  for (std::size_t k = 0; k < K; ++k) {
    const auto &p0 = pairs[k], &p1 = pairs[(k + 1) % K];
    const double ax = input.x(p0.first), ay = input.y(p0.first), bx = target.x(p0.second), by = target.y(p0.second);
    const double adx = input.x(p1.first) - ax, ady = input.y(p1.first) - ay;
    const double bdx = target.x(p1.second) - bx, bdy = target.y(p1.second) - by;
    const double L = 0.5 * (std::hypot(adx, ady) / LI + std::hypot(bdx, bdy) / LT);
    const unsigned int m = std::max(1u, static_cast<unsigned int>(std::lround(L * samples)));
    for (unsigned int s = 0; s < m; ++s) {
      const double t = double(s) / double(m);
      A.push_back({ax + t * adx, ay + t * ady});
      B.push_back({bx + t * bdx, by + t * bdy});
      w.push_back(std::max(L, 1e-6) / m);
    }
  }
  Mat3 G;
  if (!dlt(A, B, w, G))
    degenerate("the corresponded points do not determine a homography (nearly collinear outline)");
  {
    // Robust reweighting on the transfer error: a target vertex matched to several input vertices pairs points
    // that are not images of each other.
    const std::vector<double> w0 = w;
    std::vector<double> e(A.size());
    for (int it = 0; it < 6; ++it) {
      for (std::size_t k = 0; k < A.size(); ++k) {
        double x, y;
        e[k] = project(G, A[k].x, A[k].y, x, y) ? std::hypot(x - B[k].x, y - B[k].y) : 1e3 * scale;
      }
      const double sigma = std::max({minSigma, 1.4826 * median(e), 1e-12 * scale});
      for (std::size_t k = 0; k < A.size(); ++k)
        w[k] = w0[k] * robustWeight(e[k], sigma, it >= 3);
      Mat3 Gi;
      if (!dlt(A, B, w, Gi))
        break; // keep the previous one
      G = Gi;
    }
  }
  G = normalise(G);
  return refine(input, target, vpMorphHomography(toVisp(G)), minSigma, samples, maxIterations);
}

vpMorphHomography vpMorphHomography::refine(const vpMorphContour &input, const vpMorphContour &target,
                                            const vpMorphHomography &initial, double minSigma, unsigned int samples,
                                            unsigned int maxIterations, bool edgeOffset)
{
  checkFitInput(input, target, minSigma, samples, maxIterations, "vpMorphHomography::refine");
  const double scale = 0.5 * (input.perimeter() + target.perimeter());
  Mat3 G = toEigen(initial.m_G);
  const vpMorphNearestEdge nearestInput(input), nearestTarget(target);
  // 2. Gauss-Newton on point-to-segment distances, both ways, nearest points recomputed at each iteration. The
  // parameters: D (8) of G (I + D), and the common offset delta of the target's edges along their left normals.
  std::vector<Point> NT; // the target samples' edge normals
  const std::vector<Point> SI = sampleOutline(input, samples), ST = sampleOutline(target, samples, &NT);
  const std::size_t N = SI.size() + ST.size();
  std::vector<double> r(N);
  Eigen::Matrix<double, Eigen::Dynamic, 9> J(N, 9), WJ(N, 9); // the rows' Jacobians, and weighted
  Eigen::VectorXd rw(N);
  std::vector<Vec3> U(N);         // the samples mapped at this iteration (homogeneous)
  std::vector<double> X(N), Y(N); // and the same in the other contour's coordinates
  // The offset along the target's left normals, from the initial homography's when it has one (the last image's).
  const bool ccw = target.isCounterClockwise();
  double delta = edgeOffset ? (ccw ? -initial.m_edgeOffset : initial.m_edgeOffset) : 0.0;
  // Sample k mapped into the other contour at (G, delta), homogeneous, and (x, y): a target sample is first moved with
  // its edge.
  auto map = [&](const Mat3 &Gk, const Mat3 &Gik, std::size_t k, double &x, double &y) -> Vec3 {
    const std::size_t j = k - SI.size();
    const Vec3 u = k < SI.size() ? Vec3(Gk * Vec3(SI[k].x, SI[k].y, 1.0))
                                 : Vec3(Gik * Vec3(ST[j].x + delta * NT[j].x, ST[j].y + delta * NT[j].y, 1.0));
    if (!(std::fabs(u[2]) > 1e-12 * u.norm()))
      degenerate("the homography maps part of an outline to infinity");
    x = u[0] / u[2];
    y = u[1] / u[2];
    return u;
  };
  // Residual of sample k mapped at (x, y), +inf beyond reach; m and side as offsetDistance() gives them.
  auto residual = [&](std::size_t k, double x, double y, double reach, double &mx, double &my, double &side) {
    return k < SI.size() ? offsetDistance(nearestTarget, x, y, delta, mx, my, side, reach)
                         : nearestInput.within(x, y, reach, mx, my);
  };
  // Tukey's weights need no residual beyond their cut-off: the nearest edges are searched within the last round's
  // (a sample off a hidden or bent part would spread the search over the whole outline), then beyond it as far as
  // this round's needs (robustScale()).
  auto reachAt = [](double sigma) { return sigma > 0.0 ? kTukey * sigma : std::numeric_limits<double>::infinity(); };
  vpMorphHomography out;
  unsigned int it = 0;
  bool converged = false;
  // The offset is fitted from when G is within the noise with it held (below), or at once from a homography that
  // carries one (refined with its offset on the last image).
  bool offsetFree = edgeOffset && delta != 0.0;
  // At a settled G: whether the fit is done, else the offset is freed (G settled before the offset was).
  auto done = [&]() {
    if (offsetFree || !edgeOffset)
      return true;
    offsetFree = true;
    return false;
  };
  const unsigned int huberIterations = std::min(4u, std::max(1u, maxIterations / 2)); // at most
  Mat9 Minv = Mat9::Zero(); // inverse of the last normal matrix, for the covariance
  double sigma = 0.0;       // the last iteration's robust scale
  // Huber weights until the fit is within the noise, Tukey's after: they tell the inliers from the rest only when
  // the residuals are the noise's. Within the noise means an update that moved no sample by the robust scale.
  bool tukey = false, tukeyMoved = false; // the Tukey phase, and whether the last update was one of its
  for (it = 0; it < maxIterations && !converged; ++it) {
    const Mat3 Gi = G.inverse();
    double moved = 0.0; // the largest move of a mapped sample since the last iteration
    for (std::size_t k = 0; k < N; ++k) {
      double x, y;
      const Vec3 u = map(G, Gi, k, x, y);
      if (it > 0)
        moved = std::max({moved, std::fabs(x - X[k]), std::fabs(y - Y[k])});
      U[k] = u;
      X[k] = x;
      Y[k] = y;
    }
    // Settled once an update (of the Tukey rounds) moves no sample by a hundredth of the edges' noise: what is left
    // is far below the estimate's own deviation. The nearest edges are then not searched again. The offset is held at
    // 0 until an update moves no sample by the noise: the misfit G has yet to remove is then below it.
    if (tukeyMoved && moved < 0.01 * sigma && done())
      break;
    if (edgeOffset && tukeyMoved && moved < sigma)
      offsetFree = true;
    if (it >= huberIterations || (it > 0 && moved < sigma))
      tukey = true;
    // Sample k's residual and Jacobian row; a residual beyond reach is +inf (its row is then never used).
    auto row = [&](std::size_t k, double reach) {
      const bool fwd = k < SI.size();
      const Vec3 &u = U[k];
      const double x = X[k], y = Y[k];
      double mx = 0.0, my = 0.0, side = 0.0;
      r[k] = residual(k, x, y, reach, mx, my, side);
      // d(residual) = m^T dpi, dpi = (1/u3) [1 0 -x; 0 1 -y] du; forward du = G D p, backward du = -D u, and the
      // target's edges moved by d(delta) n: forward -side d(delta), backward du = G^-1 n d(delta).
      Eigen::Matrix<double, 1, 3> g;
      g << mx / u[2], my / u[2], -(mx * x + my * y) / u[2];
      Vec3 q;
      double dDelta;
      if (fwd) {
        q = Vec3(SI[k].x, SI[k].y, 1.0);
        g = g * G;
        dDelta = -side;
      } else {
        const Point &n = NT[k - SI.size()];
        dDelta = (g * Gi * Vec3(n.x, n.y, 0.0)).value();
        g = -g;
        q = u;
      }
      J.row(k) << g[0] * q[0], g[0] * q[1], g[0] * q[2], g[1] * q[0], g[1] * q[1], g[1] * q[2], g[2] * q[0],
          g[2] * q[1], dDelta;
    };
    const double reach = tukey ? reachAt(sigma) : std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < N; ++k)
      row(k, reach);
    sigma = robustScale(r, reach, minSigma, scale, [&](std::size_t k, double within) { row(k, within); });
    tukeyMoved = tukey;
    Eigen::VectorXd wr(N);
    for (std::size_t k = 0; k < N; ++k) {
      rw[k] = robustWeight(r[k], sigma, tukey);
      if (rw[k] > 0) {
        wr[k] = rw[k] * r[k];
      } else { // a far residual weighs nothing, whatever its size
        rw[k] = wr[k] = 0.0;
        J.row(k).setZero();
      }
    }
    WJ.noalias() = rw.asDiagonal() * J;
    Mat9 M = J.transpose() * WJ;
    Vec9 b = -(J.transpose() * wr);
    if (!offsetFree) {
      M.row(8).setZero();
      M.col(8).setZero();
      M(8, 8) = 1.0;
      b[8] = 0.0;
    }
    // Conditioning of G's part on the Jacobi-scaled normal matrix: a sliver or a collapsed outline leaves directions
    // free. Growing an outline all round and scaling it are one motion on a disc: the offset's step has a faint prior
    // at 0.
    Vec9 dg;
    for (int i = 0; i < 9; ++i)
      dg[i] = M(i, i) > 0 ? 1.0 / std::sqrt(M(i, i)) : 0.0;
    Mat9 Ms = dg.asDiagonal() * M * dg.asDiagonal();
    const Eigen::SelfAdjointEigenSolver<Mat8> es(Ms.topLeftCorner<8, 8>(), Eigen::EigenvaluesOnly);
    if (!(dg.minCoeff() > 0) || !(es.eigenvalues()[0] > 1e-10 * es.eigenvalues()[7]))
      degenerate("the outlines leave the homography undetermined (ill-conditioned normal equations)");
    Ms(8, 8) += 1e-9;
    const Eigen::LDLT<Mat9> ldlt(Ms);
    const Vec9 d = dg.asDiagonal() * ldlt.solve(dg.asDiagonal() * b);
    Minv = dg.asDiagonal() * ldlt.solve(Mat9::Identity()) * dg.asDiagonal();
    if (!d.allFinite())
      degenerate("non-finite update");
    Mat3 D;
    D << d[0], d[1], d[2], d[3], d[4], d[5], d[6], d[7], 0.0;
    G = normalise(G * (Mat3::Identity() + D));
    delta += d[8];
    converged = tukey && d.lpNorm<Eigen::Infinity>() < 1e-13 && done();
  }
  if (!finite(G) || !(std::fabs(G.determinant()) > 1e-14))
    degenerate("singular result");

  // Final residuals and inliers at the returned homography.
  {
    const Mat3 Gi = G.inverse();
    // As in the rounds: within the last round's cut-off, then as far as the final scale's needs.
    const double reach = reachAt(sigma);
    auto at = [&](std::size_t k, double within) {
      double x, y, mx, my, side;
      map(G, Gi, k, x, y);
      r[k] = residual(k, x, y, within, mx, my, side);
    };
    for (std::size_t k = 0; k < N; ++k)
      at(k, reach);
    const double sigma = robustScale(r, reach, minSigma, scale, [&](std::size_t k, double within) { at(k, within); });
    double s2 = 0, ws2 = 0, sw = 0;
    std::size_t n = 0;
    for (std::size_t k = 0; k < N; ++k) {
      const double w = robustWeight(r[k], sigma, true);
      if (w > 0) {
        s2 += r[k] * r[k];
        ++n;
        ws2 += w * r[k] * r[k];
        sw += w;
      }
    }
    out.m_residual = n > 0 ? std::sqrt(s2 / n) : 0.0;
    out.m_inlierShare = double(n) / double(N);
    // sigma^2 (J^T W J)^-1 with the offset marginalised (the block of G's part), sigma^2 from the weighted residuals
    // over the degrees of freedom left.
    const double dof = edgeOffset ? 9.0 : 8.0;
    const Mat8 C = (sw > dof ? ws2 / (sw - dof) : 0.0) * Minv.topLeftCorner<8, 8>();
    out.m_covariance.resize(8, 8);
    for (int i = 0; i < 8; ++i)
      for (int j = 0; j < 8; ++j)
        out.m_covariance[i][j] = C(i, j);
  }
  out.m_G = toVisp(G);
  out.m_edgeOffset = ccw ? -delta : delta; // the left normals point in on a CCW outline
  out.m_iterations = it;
  return out;
}

vpHomogeneousMatrix vpMorphHomography::inputMtarget(double d) const
{
  if (!std::isfinite(d) || d <= 0.0) {
    std::ostringstream os;
    os << "vpMorphHomography::inputMtarget: the plane depth d must be finite and > 0, got " << d;
    throw vpMorphException(vpMorphException::badParameterError, os.str());
  }
  // H = G^-1 ~ iRt + itt n^T / d, n = e3 (target to input).
  Mat3 H = toEigen(m_G).inverse();
  const double n1 = H.col(0).norm(), n2 = H.col(1).norm();
  if (!(n1 > 1e-12) || !(n2 > 1e-12) || !H.allFinite())
    throw vpMorphException(vpMorphException::badContourError,
                           "vpMorphHomography::inputMtarget: the homography has a null column, no pose");
  // det H = (distance of the input camera to the plane) / d: positive when both cameras see the plane's same side.
  double lambda = 2.0 / (n1 + n2);
  if (H.determinant() < 0)
    lambda = -lambda;
  H *= lambda;
  Eigen::Matrix<double, 3, 2> C = H.leftCols<2>();
  const Eigen::JacobiSVD<Eigen::Matrix<double, 3, 2>> svd(C, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::Matrix<double, 3, 2> R12 = svd.matrixU().leftCols<2>() * svd.matrixV().transpose();
  Mat3 R;
  R.col(0) = R12.col(0);
  R.col(1) = R12.col(1);
  R.col(2) = R12.col(0).cross(R12.col(1));
  const Vec3 t = d * (H.col(2) - R.col(2));
  vpHomogeneousMatrix M;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j)
      M[i][j] = R(i, j);
    M[i][3] = t[i];
  }
  return M;
}
