#include "vpMorphEdgeOutline.h"
#include "vpMorphLevelSpread.h"
#include "vpMorphOwnEdges.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include <opencv2/imgproc.hpp>

using vpMorphRegionMeasure::Level;

namespace
{
using vpMorphLevelSpread::median;

// Bilinear interpolation of a one-channel image of T at (x, y), clamped to the image.
template <typename T> double bilinear(const cv::Mat &m, double x, double y)
{
  x = std::min(std::max(x, 0.0), double(m.cols - 1));
  y = std::min(std::max(y, 0.0), double(m.rows - 1));
  const int x0 = std::max(0, std::min(int(x), m.cols - 2)), y0 = std::max(0, std::min(int(y), m.rows - 2));
  const int x1 = std::min(x0 + 1, m.cols - 1), y1 = std::min(y0 + 1, m.rows - 1);
  const double a = x - x0, b = y - y0;
  return (1 - a) * (1 - b) * m.at<T>(y0, x0) + a * (1 - b) * m.at<T>(y0, x1) + (1 - a) * b * m.at<T>(y1, x0) +
         a * b * m.at<T>(y1, x1);
}

/*
  The level about which the edge profiles through \e profiles (pixel, gradient direction) are antisymmetric, searched
  within half a step (\e slope per pixel) of \e level0: a blurred step g(x0 + u) + g(x0 - u) = 2 g(x0) whatever the
  blur, and on that level, x0 is the edge. Only samples off the sensor's limits count, so a side clipped beyond the
  middle of the step does not move it; the gradient peak does, through the 3x3 support of its derivative.
  Returns \e level0 when too few samples are left. Profile k's level is the level times \e scale[k] (1 for every
  profile of an evenly lit edge; under a light that falls off, the shading there).
*/
double antisymmetricLevel(const cv::Mat &g, const std::vector<cv::Vec4d> &profiles, double level0, double slope,
                          const std::vector<double> &scale)
{
  const int half = 12; // samples each side, a quarter pixel apart: +-3 px
  const double h = 0.25, umax = 1.5;
  // Interpolated samples are clipped as soon as one of their four pixels is.
  cv::Mat limit = (g == 0) | (g == 255), near;
  cv::dilate(limit, near, cv::Mat::ones(2, 2, CV_8UC1), cv::Point(0, 0));
  // At most 512 profiles, spread along the edge: the level is one number for the whole edge.
  const std::size_t stride = (profiles.size() + 511) / 512;
  std::vector<std::array<double, 2 * half + 1>> prof;
  std::vector<double> profScale;
  for (std::size_t k = 0; k < profiles.size(); k += stride) {
    prof.emplace_back();
    profScale.push_back(scale[k]);
    for (int i = -half; i <= half; ++i) {
      const double x = std::min(std::max(profiles[k][0] + i * h * profiles[k][2], 0.0), double(g.cols - 1)),
                   y = std::min(std::max(profiles[k][1] + i * h * profiles[k][3], 0.0), double(g.rows - 1));
      const int x0 = std::max(0, std::min(int(x), g.cols - 2)), y0 = std::max(0, std::min(int(y), g.rows - 2));
      prof.back()[i + half] = near.at<unsigned char>(y0, x0) ? NAN : bilinear<unsigned char>(g, x, y);
    }
  }
  auto sample = [&](const std::array<double, 2 * half + 1> &p, double t, double &v) {
    const double f = t / h + half;
    if (!(f >= 0.0)) // then the truncation below is the floor
      return false;
    const int i = static_cast<int>(f);
    if (i + 1 > 2 * half)
      return false;
    v = p[i] + (f - i) * (p[i + 1] - p[i]);
    return std::isfinite(v);
  };
  // The mean squared asymmetry of the profiles about their level L (\e level times the profile's scale), +inf when
  // under half of them can be compared.
  auto asymmetry = [&](double level) {
    double cost = 0.0;
    std::size_t n = 0;
    for (std::size_t j = 0; j < prof.size(); ++j) {
      const auto &p = prof[j];
      const double L = level * profScale[j];
      // The crossing of L nearest the maximum (g rises along the profile), searched outwards: ring k holds the two
      // intervals whose crossings lie k to k + 1 steps from it, so once one is found strictly nearer than k steps,
      // ring k cannot do better (a crossing on a ring's boundary is found in the inner ring): the same crossing as a
      // scan of all 24 intervals, from the few nearest.
      double x0 = INFINITY;
      auto crossing = [&](int i) {
        if (std::isfinite(p[i]) && std::isfinite(p[i + 1]) && (p[i] - L) * (p[i + 1] - L) <= 0.0 && p[i] != p[i + 1]) {
          const double t = (i - half + (L - p[i]) / (p[i + 1] - p[i])) * h;
          if (std::fabs(t) < std::fabs(x0))
            x0 = t;
        }
      };
      for (int k = 0; k < half && k * h <= 1.0 && !(std::fabs(x0) < k * h); ++k) {
        crossing(half - 1 - k);
        crossing(half + k);
      }
      if (!std::isfinite(x0) || std::fabs(x0) > 1.0)
        continue;
      for (double u = 0.5; u <= umax; u += 0.5) {
        double a, b;
        if (!sample(p, x0 + u, a) || !sample(p, x0 - u, b))
          continue;
        const double e = std::min(std::fabs(a + b - 2.0 * L), 0.5 * slope); // corners: bounded
        cost += e * e;
        ++n;
      }
    }
    return n >= prof.size() / 2 ? cost / n : INFINITY;
  };
  // Coarse to fine: 33 levels across +-half a step, then 17 about the best.
  double bestLevel = level0, bestCost = INFINITY;
  const double coarse = slope / 32.0;
  for (int pass = 0; pass < 2; ++pass) {
    const double centre = bestLevel, step = pass == 0 ? coarse : coarse / 8.0;
    for (int j = -16; j <= 16; ++j) {
      if (pass == 1 && (std::abs(j) > 8 || j == 0)) // the centre's cost is known
        continue;
      const double L = centre + j * step, c = asymmetry(L);
      if (c < bestCost) {
        bestCost = c;
        bestLevel = L;
      }
    }
  }
  return bestLevel;
}

} // namespace

void vpMorphEdgeOutline::gradient(const cv::Mat &g, cv::Mat &gx, cv::Mat &gy)
{
  cv::Sobel(g, gx, CV_32F, 1, 0, 3, 1.0 / 8.0, 0.0, cv::BORDER_REPLICATE);
  cv::Sobel(g, gy, CV_32F, 0, 1, 3, 1.0 / 8.0, 0.0, cv::BORDER_REPLICATE);
}

bool vpMorphEdgeOutline::edgeProfile(const cv::Mat &g, const cv::Mat &gx, const cv::Mat &gy, const cv::Mat &band,
                                     double minSlope, double &level, double &slope, const Level *shading,
                                     const cv::Point &tl)
{
  // Each maximum's level over the shading there, relative to the box's centre.
  const double reference = shading ? shading->at(tl.x + 0.5 * (g.cols - 1), tl.y + 0.5 * (g.rows - 1)) : 1.0;
  auto shade = [&](int c, int r) { return shading ? shading->at(tl.x + c, tl.y + r) / reference : 1.0; };
  cv::Mat mag;
  cv::magnitude(gx, gy, mag);
  auto at = [&mag](double x, double y) { return bilinear<float>(mag, x, y); };
  std::vector<double> levels, slopes, scales;
  std::vector<cv::Vec4d> profiles; // each maximum and its gradient direction
  for (int r = 0; r < g.rows; ++r)
    for (int c = 0; c < g.cols; ++c) {
      const double m0 = mag.at<float>(r, c);
      if (!band.at<unsigned char>(r, c) || !(m0 > minSlope))
        continue;
      const double nx = gx.at<float>(r, c) / m0, ny = gy.at<float>(r, c) / m0;
      const double mm = at(c - nx, r - ny), mp = at(c + nx, r + ny);
      if (!(m0 >= mm && m0 > mp))
        continue;
      const double den = mm - 2.0 * m0 + mp;
      const double d = den < 0.0 ? std::min(0.5, std::max(-0.5, 0.5 * (mm - mp) / den)) : 0.0;
      scales.push_back(shade(c, r));
      levels.push_back((g.at<unsigned char>(r, c) + d * m0) / scales.back()); // g rises along the gradient at m0 / px
      slopes.push_back(m0 - 0.25 * (mm - mp) * d);
      profiles.push_back(cv::Vec4d(c, r, nx, ny));
    }
  if (levels.size() < 16)
    return false;
  level = median(levels);
  slope = median(slopes);
  if (!(slope > 0.0))
    return false;
  level = antisymmetricLevel(g, profiles, level, slope, scales);
  return true;
}

std::vector<cv::Point2d> vpMorphEdgeOutline::edgeOutline(const cv::Mat &g, const cv::Mat &gx, const cv::Mat &gy,
                                                         const std::vector<cv::Point> &chain, const cv::Point &tl,
                                                         const Level &fg, const Level &bg, bool whole,
                                                         double clippedLevel, const cv::Mat &object,
                                                         std::vector<bool> &own, double *blur)
{
  // The object's share of pixel (c, r) of the box, from the levels there.
  auto weight = [&](int c, int r) {
    const double u = tl.x + c, v = tl.y + r, b = bg.at(u, v);
    return (g.at<unsigned char>(r, c) - b) / (fg.at(u, v) - b);
  };
  // The object's extent along a row (alongRow) or column through pixel p: false where the 7 pixels do not hold one
  // whole step from object to background.
  auto integral = [&](const cv::Point &p, bool alongRow, double &pos, double &spread) {
    const int W = 3, i0 = alongRow ? p.x : p.y, n = alongRow ? g.cols : g.rows;
    if (i0 - W < 0 || i0 + W >= n)
      return false;
    double w[2 * W + 1], sum = 0.0;
    spread = 0.0;
    for (int k = -W; k <= W; ++k) {
      w[k + W] = alongRow ? weight(i0 + k, p.y) : weight(p.x, i0 + k);
      sum += w[k + W];
      spread += w[k + W] * (1.0 - w[k + W]);
    }
    const double lo = w[0], hi = w[2 * W];
    if (lo > 0.75 && hi < 0.25)
      pos = i0 - W - 0.5 + sum; // object on the low side
    else if (hi > 0.75 && lo < 0.25)
      pos = i0 + W + 0.5 - sum;
    else
      return false;
    return std::fabs(pos - i0) <= 1.5;
  };

  auto at = [&g](double x, double y) { return bilinear<unsigned char>(g, x, y); };
  std::vector<cv::Point2d> out;
  out.reserve(chain.size());
  // Neighbouring pixels may measure the same crossing (two pixels of one row, or where the chain turns at a narrow
  // groove's lip), equal but for rounding: one point for both. Kept twice, a change of units can make them one
  // repeated vertex, an invalid outline.
  constexpr double kSamePoint = 1e-9; // px: far above the rounding of coordinates under 1e4 px, far below edge noise
  auto same = [](const cv::Point2d &a, const cv::Point2d &b) { return std::hypot(a.x - b.x, a.y - b.y) <= kSamePoint; };
  // Per point: its outward normal (towards the background), and whether chain pixels were skipped before it.
  std::vector<cv::Point2d> outward;
  std::vector<bool> gapBefore;
  // A bridge's pixel skipped since the last point; the last pixel gave a point or is the object's.
  bool gap = false, measured = true;
  auto add = [&](const cv::Point2d &q, double nx, double ny) {
    if (out.empty() || !same(q, out.back())) {
      out.push_back(q);
      outward.emplace_back(nx, ny);
      gapBefore.push_back(gap);
    }
    gap = false;
    measured = true;
  };
  const int steps = 8;
  const double h = 0.25;
  std::vector<double> spreads; // each row's (or column's) edge spread, along the edge's normal
  for (const cv::Point &p0 : chain) {
    const cv::Point p = p0 - tl;
    gap = gap || !measured;
    measured = false;
    if (p.x < 0 || p.y < 0 || p.x >= g.cols || p.y >= g.rows)
      continue;
    measured = object.at<unsigned char>(p.y, p.x) != 0; // an object pixel without a point (noise) is no bridge
    const double fgp = fg.at(p0.x, p0.y), bgp = bg.at(p0.x, p0.y);
    const double level = whole ? 0.5 * (fgp + bgp) : clippedLevel;
    const double ex = gx.at<float>(p.y, p.x), ey = gy.at<float>(p.y, p.x), m = std::hypot(ex, ey);
    if (!(m > std::fabs(fgp - bgp) / 16.0))
      continue;
    const double outScale = bgp > fgp ? 1.0 / m : -1.0 / m; // the gradient rises towards the brighter side
    const bool alongRow = std::fabs(ex) >= std::fabs(ey);
    double pos, spread;
    if (whole && integral(p, alongRow, pos, spread)) {
      add(alongRow ? cv::Point2d(pos + tl.x, p0.y) : cv::Point2d(p0.x, pos + tl.y), ex * outScale, ey * outScale);
      spreads.push_back(std::sqrt(M_PI) * spread * (alongRow ? std::fabs(ex) : std::fabs(ey)) / m);
      continue;
    }
    const double nx = ex / m, ny = ey / m;
    double best = INFINITY;
    double prev = at(p.x - steps * h * nx, p.y - steps * h * ny) - level;
    for (int k = -steps + 1; k <= steps; ++k) {
      const double cur = at(p.x + k * h * nx, p.y + k * h * ny) - level;
      if ((prev <= 0.0) != (cur <= 0.0)) {
        const double s = h * (k - 1 + prev / (prev - cur));
        if (std::fabs(s) < std::fabs(best))
          best = s;
      }
      prev = cur;
    }
    if (!std::isfinite(best))
      continue;
    add(cv::Point2d(p0.x + best * nx, p0.y + best * ny), ex * outScale, ey * outScale);
  }
  const bool gapAtEnd = gap || !measured;
  while (out.size() > 1 && same(out.front(), out.back())) {
    out.pop_back();
    outward.pop_back();
    gapBefore.pop_back();
  }
  // The blur: the median spread. A Gaussian step of std s, integrated over pixels, has weights whose w (1 - w) sum to
  // sqrt(s^2 + 1/12) / sqrt(pi) along the normal (1 / cos of the row's angle to it along a row), and zero-mean noise
  // lowers the sum by only the weights' variance.
  double edgeBlur = 0.0;
  if (!spreads.empty()) {
    std::nth_element(spreads.begin(), spreads.begin() + long(spreads.size() / 2), spreads.end());
    edgeBlur = std::max(0.0, spreads[spreads.size() / 2]);
    if (blur != nullptr)
      *blur = edgeBlur;
  }
  const double reach = std::max(1.0, std::ceil(3.0 * edgeBlur));
  const std::vector<bool> seen = vpMorphOwnEdges(g, object, tl, out, outward, reach + 2.5, reach);
  own.assign(out.size(), false);
  for (std::size_t k = 0; k < out.size(); ++k) {
    const std::size_t l = (k + 1) % out.size();
    own[k] = seen[k] && seen[l] && !(l == 0 ? gapBefore[0] || gapAtEnd : gapBefore[l]);
  }
  return out;
}
