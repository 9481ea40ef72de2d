#include "vpMorphGreyClasses.h"
#include "vpMorphAffineLevel.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstring>
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

vpMorphGreyClasses::vpMorphGreyClasses(const cv::Mat &grey, int t) : m_t0(t), m_tu(0.0), m_tv(0.0)
{
  const int rows = grey.rows, cols = grey.cols;
  const int step = std::max(1, static_cast<int>(std::sqrt(double(rows) * double(cols) / 4096.0)));
  const int nu = (cols + step - 1) / step, nv = (rows + step - 1) / step;
  // The lattice's coordinates: x = (u - cu) / scale, y = (v - cv) / scale (well conditioned).
  const double cu = 0.5 * (cols - 1), cv = 0.5 * (rows - 1), scale = std::max(0.5 * std::max(cols, rows), 1.0);
  std::vector<double> xs(static_cast<std::size_t>(nu)), ys(static_cast<std::size_t>(nv));
  std::vector<unsigned char> lattice(std::size_t(nu) * std::size_t(nv)), label(lattice.size());
  for (int j = 0; j < nu; ++j)
    xs[std::size_t(j)] = (j * step - cu) / scale;
  for (int i = 0; i < nv; ++i) {
    ys[std::size_t(i)] = (i * step - cv) / scale;
    const unsigned char *row = grey.ptr<unsigned char>(i * step);
    for (int j = 0; j < nu; ++j) {
      const std::size_t k = std::size_t(i) * std::size_t(nu) + std::size_t(j);
      lattice[k] = row[j * step];
      label[k] = lattice[k] > t; // Otsu's split
    }
  }
  Eigen::Vector3d dark, light;  // levels p0 + p1 x + p2 y
  const int maxIterations = 64; // a bound for safety: each pass lowers the within-class deviation
  for (int it = 0; it < maxIterations; ++it) {
    // A class's slope is read on its own surface: off the limits, and away from the other class (a sample whose
    // lattice neighbours are all of its class), where the pixels the edge mixes are not; its count and sum take all
    // its samples.
    vpMorphAffineLevel::Sums fitted[2];
    double n[2] = {0.0, 0.0}, sum[2] = {0.0, 0.0};
    for (int i = 0; i < nv; ++i) {
      const std::size_t row = std::size_t(i) * std::size_t(nu);
      const unsigned char *L = &label[row], *G = &lattice[row];
      const unsigned char *U = i > 0 ? L - nu : L, *D = i + 1 < nv ? L + nu : L;
      // Per class along the row: count, sum x, x^2, g, x g, g^2 of the fitted samples (the row's y added after).
      double r[2][6] = {};
      for (int j = 0; j < nu; ++j) {
        const unsigned char cls = L[j], g = G[j];
        n[cls] += 1.0;
        sum[cls] += g;
        const unsigned char left = j > 0 ? L[j - 1] : cls, right = j + 1 < nu ? L[j + 1] : cls;
        if (g == 0 || g == 255 || left != cls || right != cls || U[j] != cls || D[j] != cls)
          continue;
        const double x = xs[std::size_t(j)];
        double *q = r[cls];
        q[0] += 1.0;
        q[1] += x;
        q[2] += x * x;
        q[3] += g;
        q[4] += x * g;
        q[5] += double(g) * g;
      }
      const double y = ys[std::size_t(i)];
      for (int c = 0; c < 2; ++c) {
        const double *q = r[c];
        vpMorphAffineLevel::Sums &f = fitted[c];
        f.n += q[0];
        f.x += q[1];
        f.y += q[0] * y;
        f.xx += q[2];
        f.xy += q[1] * y;
        f.yy += q[0] * y * y;
        f.g += q[3];
        f.xg += q[4];
        f.yg += q[3] * y;
        f.gg += q[5];
      }
    }
    if (!(n[0] > 0.0 && n[1] > 0.0))
      return; // a class is empty: Otsu's split
    // A class's level: its fitted slope, or the mean of all its pixels (those at the limits included: the mean of a
    // clipped noise is nearer the level than the mean of its unclipped side).
    Eigen::Vector3d fit[2];
    bool sloped = false;
    for (int c = 0; c < 2; ++c) {
      if (vpMorphAffineLevel::slope(fitted[c], 1.0 / scale, fit[c]))
        sloped = true;
      else
        fit[c] = Eigen::Vector3d(sum[c] / n[c], 0.0, 0.0);
    }
    if (it == 0 && !sloped)
      return; // no slope on Otsu's split: it is the best split with constant levels
    dark = fit[0];
    light = fit[1];
    // Each sample goes to the class whose level is nearer: (g - mid) has the sign of the contrast (light - dark).
    const Eigen::Vector3d mid = 0.5 * (dark + light), contrast = light - dark;
    long changed = 0;
    for (int i = 0; i < nv; ++i)
      for (int j = 0; j < nu; ++j) {
        const std::size_t k = std::size_t(i) * std::size_t(nu) + std::size_t(j);
        const double x = xs[std::size_t(j)], y = ys[std::size_t(i)];
        const unsigned char cls =
            (lattice[k] - (mid(0) + mid(1) * x + mid(2) * y)) * (contrast(0) + contrast(1) * x + contrast(2) * y) > 0.0;
        changed += cls != label[k];
        label[k] = cls;
      }
    if (changed == 0)
      break;
  }
  // Two surfaces under one light stay apart everywhere in the image (an affine contrast does at the image's corners);
  // else the two classes are not that, and Otsu's split stands.
  const Eigen::Vector3d contrast = light - dark, mid = 0.5 * (dark + light);
  for (double x : {-cu / scale, cu / scale})
    for (double y : {-cv / scale, cv / scale})
      if (!(contrast(0) + contrast(1) * x + contrast(2) * y > 0.0))
        return;
  m_tu = mid(1) / scale;
  m_tv = mid(2) / scale;
  m_t0 = mid(0) - m_tu * cu - m_tv * cv;
}

void vpMorphGreyClasses::bright(const cv::Mat &grey, cv::Mat &dst) const
{
  if (m_tu == 0.0 && m_tv == 0.0) {
    // One level: a pixel is above it as it is above its floor (levels are integers).
    cv::threshold(grey, dst, std::floor(m_t0), 255, cv::THRESH_BINARY);
    return;
  }
  for (int v = 0; v < grey.rows; ++v) {
    const unsigned char *g = grey.ptr<unsigned char>(v);
    unsigned char *d = dst.ptr<unsigned char>(v);
    const float t = static_cast<float>(m_t0 + m_tv * v), tu = static_cast<float>(m_tu);
    for (int u = 0; u < grey.cols; ++u)
      d[u] = static_cast<float>(g[u]) > t + tu * static_cast<float>(u) ? 255 : 0;
  }
}
