#include "vpMorphGreyClasses.h"
#include "vpMorphAffineLevel.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include <Eigen/Dense>
#include <opencv2/imgproc.hpp>

// A run of 8 equal pixels counts at once, and the others go to 4 interleaved tables, so that a background of one level
// does not chain every increment on one counter.
vpMorphGreyClasses::Histogram vpMorphGreyClasses::histogram(const unsigned char *p, std::size_t n)
{
  std::array<Histogram, 4> h{};
  std::size_t i = 0;
  for (; i + 8 <= n; i += 8) {
    std::uint64_t w;
    std::memcpy(&w, p + i, 8);
    if (w == p[i] * 0x0101010101010101ULL) {
      h[0][p[i]] += 8;
      continue;
    }
    for (std::size_t k = 0; k < 8; ++k)
      ++h[k & 3][p[i + k]];
  }
  for (; i < n; ++i)
    ++h[0][p[i]];
  for (std::size_t v = 0; v < 256; ++v)
    h[0][v] += h[1][v] + h[2][v] + h[3][v];
  return h[0];
}

// cv::threshold()'s THRESH_OTSU computation, operation for operation (the same double sums in the same order), so the
// split is the one it gives (test_morph checks it).
int vpMorphGreyClasses::otsu(const Histogram &h, long total)
{
  const double scale = 1.0 / static_cast<double>(total);
  double mu = 0.0;
  for (int i = 0; i < 256; ++i)
    mu += i * static_cast<double>(h[i]);
  mu *= scale;
  double mu1 = 0.0, q1 = 0.0, maxSigma = 0.0;
  int best = 0;
  for (int i = 0; i < 256; ++i) {
    const double p = static_cast<double>(h[i]) * scale;
    mu1 *= q1;
    q1 += p;
    const double q2 = 1.0 - q1;
    if (std::min(q1, q2) < FLT_EPSILON || std::max(q1, q2) > 1.0 - FLT_EPSILON)
      continue;
    mu1 = (mu1 + i * p) / q1;
    const double mu2 = (mu - q1 * mu1) / q2, sigma = q1 * q2 * (mu1 - mu2) * (mu1 - mu2);
    if (sigma > maxSigma) {
      maxSigma = sigma;
      best = i;
    }
  }
  return best;
}

namespace
{
// The samples the levels are fitted on, at x = (u - cu) / scale, y = (v - cv) / scale (well conditioned).
struct Lattice
{
  int step, nu, nv;
  double cu, cv, scale;
  std::vector<double> xs, ys;
  std::vector<unsigned char> g;

  explicit Lattice(const cv::Mat &grey)
    : step(std::max(1, static_cast<int>(std::sqrt(double(grey.rows) * double(grey.cols) / 4096.0)))),
      nu((grey.cols + step - 1) / step), nv((grey.rows + step - 1) / step), cu(0.5 * (grey.cols - 1)),
      cv(0.5 * (grey.rows - 1)), scale(std::max(0.5 * std::max(grey.cols, grey.rows), 1.0)),
      xs(static_cast<std::size_t>(nu)), ys(static_cast<std::size_t>(nv)), g(std::size_t(nu) * std::size_t(nv))
  {
    for (int j = 0; j < nu; ++j)
      xs[std::size_t(j)] = (j * step - cu) / scale;
    for (int i = 0; i < nv; ++i) {
      ys[std::size_t(i)] = (i * step - cv) / scale;
      const unsigned char *row = grey.ptr<unsigned char>(i * step);
      for (int j = 0; j < nu; ++j)
        g[std::size_t(i) * std::size_t(nu) + std::size_t(j)] = row[j * step];
    }
  }
  double x(std::size_t k) const { return xs[k % std::size_t(nu)]; }
  double y(std::size_t k) const { return ys[k / std::size_t(nu)]; }
};

double levelAt(const Eigen::Vector3d &p, double x, double y) { return p(0) + p(1) * x + p(2) * y; }

// Sample g's deviation from a level: a sample at a sensor's limit (0, 255) only bounds its value, and deviates by how
// far the level lies beyond that bound on its own side.
double deviation(unsigned char g, double level)
{
  const double r = g - level;
  return g == 255 ? std::max(r, 0.0) : (g == 0 ? std::min(r, 0.0) : r);
}

// Two classes of the lattice (label 1: the light one) and their levels.
struct Split
{
  std::vector<unsigned char> label;
  Eigen::Vector3d dark, light;
  double lowest = std::numeric_limits<double>::infinity(); // criterion() of the split a descent ended with

  // The within-class squared deviation from the classes' levels: the criterion both descents lower.
  double criterion(const Lattice &L) const
  {
    double sum = 0.0;
    for (int i = 0; i < L.nv; ++i) {
      const std::size_t row = std::size_t(i) * std::size_t(L.nu);
      const double y = L.ys[std::size_t(i)];
      // Along the row, each level is its value at the row's start plus its x slope.
      const double d0 = dark(0) + dark(2) * y, l0 = light(0) + light(2) * y;
      for (int j = 0; j < L.nu; ++j) {
        const double x = L.xs[std::size_t(j)];
        const double level = label[row + std::size_t(j)] ? l0 + light(1) * x : d0 + dark(1) * x;
        const double r = deviation(L.g[row + std::size_t(j)], level);
        sum += r * r;
      }
    }
    return sum;
  }
  // Two surfaces under one light stay apart everywhere in the image (an affine contrast does at the image's corners);
  // else the two classes are not that.
  bool apartEverywhere(const Lattice &L) const
  {
    const Eigen::Vector3d contrast = light - dark;
    for (double x : {-L.cu / L.scale, L.cu / L.scale})
      for (double y : {-L.cv / L.scale, L.cv / L.scale})
        if (!(levelAt(contrast, x, y) > 0.0))
          return false;
    return true;
  }
};

// A split's sums: per class, the count of its samples and their sums of g, x and y, and the least-squares sums of its
// own surface (\e own): off the limits, and away from the other class (a sample whose lattice neighbours are all of its
// class), where the pixels the edge mixes are not. A class's slope is read there.
struct ClassSums
{
  vpMorphAffineLevel::Sums own[2];
  double n[2] = {0.0, 0.0}, g[2] = {0.0, 0.0}, x[2] = {0.0, 0.0}, y[2] = {0.0, 0.0};

  ClassSums(const Lattice &L, const std::vector<unsigned char> &label)
  {
    const int nu = L.nu, nv = L.nv;
    for (int i = 0; i < nv; ++i) {
      const std::size_t row = std::size_t(i) * std::size_t(nu);
      const unsigned char *Lb = &label[row], *G = &L.g[row];
      const unsigned char *U = i > 0 ? Lb - nu : Lb, *D = i + 1 < nv ? Lb + nu : Lb;
      // Per class along the row: count, sum x, x^2, g, x g, g^2 of the own samples, and count, sum g, x of all (the
      // row's y added after).
      double r[2][6] = {}, all[2][3] = {};
      for (int j = 0; j < nu; ++j) {
        const unsigned char cls = Lb[j], gj = G[j];
        const double xj = L.xs[std::size_t(j)];
        double *t = all[cls];
        t[0] += 1.0;
        t[1] += gj;
        t[2] += xj;
        const unsigned char left = j > 0 ? Lb[j - 1] : cls, right = j + 1 < nu ? Lb[j + 1] : cls;
        if (gj == 0 || gj == 255 || left != cls || right != cls || U[j] != cls || D[j] != cls)
          continue;
        double *q = r[cls];
        q[0] += 1.0;
        q[1] += xj;
        q[2] += xj * xj;
        q[3] += gj;
        q[4] += xj * gj;
        q[5] += double(gj) * gj;
      }
      const double yi = L.ys[std::size_t(i)];
      for (int c = 0; c < 2; ++c) {
        n[c] += all[c][0];
        g[c] += all[c][1];
        x[c] += all[c][2];
        y[c] += all[c][0] * yi;
        const double *q = r[c];
        vpMorphAffineLevel::Sums &f = own[c];
        f.n += q[0];
        f.x += q[1];
        f.y += q[0] * yi;
        f.xx += q[2];
        f.xy += q[1] * yi;
        f.yy += q[0] * yi * yi;
        f.g += q[3];
        f.xg += q[4];
        f.yg += q[3] * yi;
        f.gg += q[5];
      }
    }
  }
};

/*
  The levels of two classes under one light: L_c = m_c S, the shading S = 1 + a x + b y shared (a light that falls off
  across the view scales the plane's level and the object's alike), fitted by least squares on the classes' own
  surfaces (\e own, alternating the means and the shading: each step is a linear least squares). A class with no
  sample there gets the mean of all its samples over the shading. False when the shading is not both seen and worth its
  two parameters (as vpMorphAffineLevel::slope(): the positions spread a pixel every way, and the Bayesian information
  criterion), the caller's constant levels standing; else \e level[c] = (m_c, m_c a, m_c b).
*/
bool sharedShading(const ClassSums &cs, double pixel, Eigen::Vector3d level[2])
{
  const vpMorphAffineLevel::Sums *own = cs.own;
  vpMorphAffineLevel::Sums pooled;
  for (const vpMorphAffineLevel::Sums *s : {&own[0], &own[1]}) {
    pooled.n += s->n;
    pooled.x += s->x;
    pooled.y += s->y;
    pooled.xx += s->xx;
    pooled.xy += s->xy;
    pooled.yy += s->yy;
  }
  const double N = pooled.n;
  if (!vpMorphAffineLevel::spread(pooled, pixel))
    return false;
  // Over a class's own samples under the shading (a, b): the sums of S^2 and of g S, the least-squares mean, and the
  // residual sum of squares at mean m.
  auto shadedSquares = [](const vpMorphAffineLevel::Sums &s, double a, double b) {
    return s.n + 2.0 * (a * s.x + b * s.y) + a * a * s.xx + 2.0 * a * b * s.xy + b * b * s.yy;
  };
  auto shadedLevels = [](const vpMorphAffineLevel::Sums &s, double a, double b) { return s.g + a * s.xg + b * s.yg; };
  auto mean = [&](const vpMorphAffineLevel::Sums &s, double a, double b) {
    return shadedLevels(s, a, b) / shadedSquares(s, a, b);
  };
  auto rss = [&](const vpMorphAffineLevel::Sums &s, double m, double a, double b) {
    return s.gg - 2.0 * m * shadedLevels(s, a, b) + m * m * shadedSquares(s, a, b);
  };
  double a = 0.0, b = 0.0, m[2] = {0.0, 0.0};
  const int maxIterations = 100; // a bound for safety: each step lowers the sum of squares, settling in a few
  for (int it = 0; it < maxIterations; ++it) {
    Eigen::Matrix2d A = Eigen::Matrix2d::Zero();
    Eigen::Vector2d r = Eigen::Vector2d::Zero();
    for (int c = 0; c < 2; ++c) {
      if (!(own[c].n > 0.0))
        continue;
      m[c] = mean(own[c], a, b);
      // g - m = m (a x + b y) on the class's samples.
      A += m[c] * m[c] * (Eigen::Matrix2d() << own[c].xx, own[c].xy, own[c].xy, own[c].yy).finished();
      r += m[c] * Eigen::Vector2d(own[c].xg - m[c] * own[c].x, own[c].yg - m[c] * own[c].y);
    }
    const Eigen::Vector2d ab = A.ldlt().solve(r);
    if (!ab.allFinite())
      return false;
    // Settled once the shading moves by a trillionth across the half-image: far under a grey level.
    const bool settled = std::fabs(ab(0) - a) + std::fabs(ab(1) - b) < 1e-12;
    a = ab(0);
    b = ab(1);
    if (settled)
      break;
  }
  double rssConstant = 0.0, rssShaded = 0.0;
  for (int c = 0; c < 2; ++c)
    if (own[c].n > 0.0) {
      m[c] = mean(own[c], a, b);
      rssConstant += own[c].gg - own[c].g * own[c].g / own[c].n;
      rssShaded += rss(own[c], m[c], a, b);
    } else {
      m[c] = cs.g[c] / (cs.n[c] + a * cs.x[c] + b * cs.y[c]);
    }
  const bool worth = rssShaded <= 0.0 ? rssConstant > 0.0 : N * std::log(rssConstant / rssShaded) > 2.0 * std::log(N);
  if (!worth || !std::isfinite(m[0]) || !std::isfinite(m[1]) || (a == 0.0 && b == 0.0))
    return false;
  for (int c = 0; c < 2; ++c)
    level[c] = Eigen::Vector3d(m[c], m[c] * a, m[c] * b);
  return true;
}

enum class Descent { NO_SPLIT, NO_SLOPE, SETTLED };

// Lloyd's descent of the criterion from s.label: the classes' levels fitted, each sample given to the class it deviates
// less from, until none moves. NO_SLOPE when the starting split shows no shading (with constant levels, Otsu's split is
// the best), NO_SPLIT when a class has no sample or the levels fitted are not finite.
Descent descend(const Lattice &L, Split &s)
{
  const int nu = L.nu, nv = L.nv;
  std::vector<unsigned char> &label = s.label;
  Split best;
  double lowest = std::numeric_limits<double>::infinity();
  const int maxIterations = 64; // a bound for safety: each pass but the last lowers the criterion
  for (int it = 0; it < maxIterations; ++it) {
    const ClassSums cs(L, label);
    const double *n = cs.n;
    if (!(n[0] > 0.0 && n[1] > 0.0))
      return Descent::NO_SPLIT;
    // The classes' levels under one shading, or the mean of all each class's pixels (those at the limits included: the
    // mean of a clipped noise is nearer the level than the mean of its unclipped side).
    Eigen::Vector3d fit[2];
    const bool sloped = sharedShading(cs, 1.0 / L.scale, fit);
    if (!sloped)
      for (int c = 0; c < 2; ++c)
        fit[c] = Eigen::Vector3d(cs.g[c] / n[c], 0.0, 0.0);
    if (it == 0 && !sloped)
      return Descent::NO_SLOPE;
    s.dark = fit[0];
    s.light = fit[1];
    // Each sample goes to the class it deviates less from (at a limit, a tie to the class on the limit's side), and
    // the criterion of the new split is summed on the way.
    long changed = 0;
    double c = 0.0;
    for (int i = 0; i < nv; ++i) {
      const std::size_t row = std::size_t(i) * std::size_t(nu);
      const double y = L.ys[std::size_t(i)];
      const double d0 = s.dark(0) + s.dark(2) * y, l0 = s.light(0) + s.light(2) * y;
      for (int j = 0; j < nu; ++j) {
        const std::size_t k = row + std::size_t(j);
        const double x = L.xs[std::size_t(j)];
        const unsigned char g = L.g[k];
        const double toLight = deviation(g, l0 + s.light(1) * x), toDark = deviation(g, d0 + s.dark(1) * x);
        const unsigned char cls =
            g == 255 ? std::fabs(toLight) <= std::fabs(toDark) : std::fabs(toLight) < std::fabs(toDark);
        c += cls ? toLight * toLight : toDark * toDark;
        changed += cls != label[k];
        label[k] = cls;
      }
    }
    // The fits leave out the samples next to the other class: a pass need not lower the criterion (the passes can
    // cycle). The descent ends at the first pass that does not, with the lowest split it visited.
    if (!(c < lowest)) {
      if (best.label.empty())
        return Descent::NO_SPLIT; // not even the first pass has a finite criterion
      break;
    }
    lowest = c;
    best = s;
    best.lowest = c;
    if (changed == 0)
      break;
  }
  s = best;
  return Descent::SETTLED;
}

/*
  The dominant surface's affine level over the samples off the limits (mostly the plane's: a camera frames an object
  inside its background): least squares, then reweighted by Tukey's biweight at the residuals' MAD scale, so that the
  object's samples, outliers to the plane's level, do not tilt it. False when the samples do not pose it.
*/
bool dominantLevel(const Lattice &L, Eigen::Vector3d &p)
{
  std::vector<Eigen::Vector3d> J; // (1, x, y) of each sample off the limits
  std::vector<double> g;
  for (int i = 0; i < L.nv; ++i)
    for (int j = 0; j < L.nu; ++j) {
      const unsigned char v = L.g[std::size_t(i) * std::size_t(L.nu) + std::size_t(j)];
      if (v != 0 && v != 255) {
        J.emplace_back(1.0, L.xs[std::size_t(j)], L.ys[std::size_t(i)]);
        g.push_back(v);
      }
    }
  std::vector<double> w(g.size(), 1.0), r(g.size());
  const double kTukey = 4.685;                     // 95 % efficiency under Gaussian noise
  const double kMadToSigma = 1.4826;               // MAD to standard deviation under Gaussian noise
  const double quantisation = 1.0 / std::sqrt(12); // the deviation of the 8-bit rounding: the scale's floor
  const int maxIterations = 20;                    // a bound for safety: the biweight settles in a few rounds
  for (int it = 0; it < maxIterations; ++it) {
    vpMorphAffineLevel::Sums S; // weighted
    for (std::size_t i = 0; i < g.size(); ++i) {
      const double wi = w[i], x = J[i](1), y = J[i](2), wx = wi * x, wy = wi * y, wg = wi * g[i];
      S.n += wi;
      S.x += wx;
      S.y += wy;
      S.xx += wx * x;
      S.xy += wx * y;
      S.yy += wy * y;
      S.g += wg;
      S.xg += wg * x;
      S.yg += wg * y;
    }
    Eigen::Matrix3d A;
    A << S.n, S.x, S.y, S.x, S.xx, S.xy, S.y, S.xy, S.yy;
    const Eigen::Vector3d b(S.g, S.xg, S.yg);
    const Eigen::LDLT<Eigen::Matrix3d> ldlt(A);
    if (ldlt.info() != Eigen::Success || !(ldlt.vectorD().minCoeff() > 0.0))
      return false;
    const Eigen::Vector3d q = ldlt.solve(b);
    if (!q.allFinite())
      return false;
    // Settled once the level moves by a hundredth of the rounding's deviation.
    const bool settled = it > 0 && (q - p).cwiseAbs().maxCoeff() < 0.01 * quantisation;
    p = q;
    if (settled)
      break;
    for (std::size_t i = 0; i < g.size(); ++i)
      r[i] = std::fabs(g[i] - p.dot(J[i]));
    std::vector<double> sorted = r;
    std::nth_element(sorted.begin(), sorted.begin() + std::ptrdiff_t(sorted.size() / 2), sorted.end());
    const double cut = kTukey * std::max(kMadToSigma * sorted[sorted.size() / 2], quantisation);
    for (std::size_t i = 0; i < g.size(); ++i) {
      const double u = r[i] / cut;
      w[i] = u < 1.0 ? (1.0 - u * u) * (1.0 - u * u) : 0.0;
    }
  }
  return true;
}

/*
  The second start: Otsu's split of the samples with the dominant surface's level removed. Where Otsu's split of the
  levels themselves falls on the plane's ramp, the descent from it settles with the two classes meeting across the
  ramp; from this one it settles on the object.
*/
bool detrendedStart(const Lattice &L, Split &s)
{
  Eigen::Vector3d trend = Eigen::Vector3d::Zero();
  if (!dominantLevel(L, trend))
    return false;
  // The residuals, offset to the middle of the 8-bit range and clamped there (a residual beyond stays on its side).
  std::vector<unsigned char> q(L.g.size());
  for (std::size_t k = 0; k < L.g.size(); ++k)
    q[k] = cv::saturate_cast<unsigned char>(128.0 + deviation(L.g[k], levelAt(trend, L.x(k), L.y(k))));
  const int t = vpMorphGreyClasses::otsu(vpMorphGreyClasses::histogram(q.data(), q.size()), long(q.size()));
  s.label.resize(q.size());
  for (std::size_t k = 0; k < q.size(); ++k)
    s.label[k] = q[k] > t;
  return true;
}
} // namespace

vpMorphGreyClasses::vpMorphGreyClasses(const cv::Mat &grey, int t) : m_t0(t), m_tu(0.0), m_tv(0.0)
{
  const Lattice L(grey);
  Split otsuStart;
  otsuStart.label.resize(L.g.size());
  for (std::size_t k = 0; k < L.g.size(); ++k)
    otsuStart.label[k] = L.g[k] > t;
  // An even light: neither class of Otsu's split shows a slope of its own, and Otsu's split stands.
  const ClassSums cs(L, otsuStart.label);
  Eigen::Vector3d unused;
  if (!vpMorphAffineLevel::slope(cs.own[0], 1.0 / L.scale, unused) &&
      !vpMorphAffineLevel::slope(cs.own[1], 1.0 / L.scale, unused))
    return;
  // Otsu's split with constant levels, each class's mean: the criterion a shaded split has to beat.
  otsuStart.dark = Eigen::Vector3d(cs.g[0] / cs.n[0], 0.0, 0.0);
  otsuStart.light = Eigen::Vector3d(cs.g[1] / cs.n[1], 0.0, 0.0);
  const double constant = otsuStart.criterion(L);
  // The criterion is not convex: descended from Otsu's split and from the detrended one, the lower of the splits that
  // stay two surfaces under one light is kept, where it lowers the criterion by more than the Bayesian information
  // criterion charges for the shading's two parameters (n ln(J_constant / J) > 2 ln n); else Otsu's split stands (a
  // step in the plane's own level, the floor beyond its edge, is not a light falling off).
  const Split *best = nullptr;
  double lowest = std::numeric_limits<double>::infinity();
  auto consider = [&](const Split &s) {
    if (s.apartEverywhere(L) && s.lowest < lowest) {
      lowest = s.lowest;
      best = &s;
    }
  };
  if (descend(L, otsuStart) == Descent::SETTLED)
    consider(otsuStart);
  Split trendStart;
  if (detrendedStart(L, trendStart) && descend(L, trendStart) == Descent::SETTLED)
    consider(trendStart);
  const double n = double(L.g.size());
  if (!best || !(n * std::log(constant / lowest) > 2.0 * std::log(n)))
    return;
  const Eigen::Vector3d mid = 0.5 * (best->dark + best->light);
  m_tu = mid(1) / L.scale;
  m_tv = mid(2) / L.scale;
  m_t0 = mid(0) - m_tu * L.cu - m_tv * L.cv;
}

void vpMorphGreyClasses::bright(const cv::Mat &grey, cv::Mat &dst, const cv::Point &origin) const
{
  if (m_tu == 0.0 && m_tv == 0.0) {
    // One level: a pixel is above it as it is above its floor (levels are integers).
    cv::threshold(grey, dst, std::floor(m_t0), 255, cv::THRESH_BINARY);
    return;
  }
  // Pixel u of row v is above the float threshold T = t + tu u exactly when its grey level, an integer, is above T's
  // integer part. A level of 0 is never above and one of 255 always (a pixel at a limit goes to the class on its side,
  // the levels never crossing in the image by apartEverywhere()): both hold with T clamped to 0 to 254 first (a NaN to
  // 254: above nothing, as in the float comparison). Two loops a row that vectorise, the levels' and the pixels'.
  const float tu = static_cast<float>(m_tu);
  std::vector<float> slope(static_cast<std::size_t>(grey.cols));
  for (int u = 0; u < grey.cols; ++u)
    slope[std::size_t(u)] = tu * static_cast<float>(origin.x + u);
  std::vector<unsigned char> level(slope.size());
  for (int v = 0; v < grey.rows; ++v) {
    const unsigned char *g = grey.ptr<unsigned char>(v);
    unsigned char *d = dst.ptr<unsigned char>(v);
    const float t = static_cast<float>(m_t0 + m_tv * (origin.y + v));
    for (std::size_t u = 0; u < slope.size(); ++u)
      level[u] = static_cast<unsigned char>(static_cast<int>(std::max(0.0f, std::min(254.0f, t + slope[u]))));
    for (std::size_t u = 0; u < slope.size(); ++u)
      d[u] = g[u] > level[u] ? 255 : 0;
  }
}
