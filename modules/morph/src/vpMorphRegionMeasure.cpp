#include "vpMorphRegionMeasure.h"
#include "vpMorphAffineLevel.h"
#include "vpMorphLevelSpread.h"
#include "vpMorphOwnEdges.h"

#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include <Eigen/Dense>
#include <opencv2/imgproc.hpp>

using vpMorphRegionMeasure::Level;
using vpMorphRegionMeasure::Region;

namespace
{
using vpMorphLevelSpread::fourSigma;
using vpMorphLevelSpread::median;
using vpMorphLevelSpread::medianOf;
using vpMorphLevelSpread::oneSidedMad;

/*
  The histogram of the grey levels under a mask: built once per mask, it gives the level under it, the share of it at
  a saturated level and the least-squares sums of any window of levels (each a whole pass over the region's box
  otherwise). Positions (x, y) are about the box's centre.
*/
struct LevelHistogram
{
  std::array<long, 256> h{};
  std::array<std::array<double, 5>, 256> moments{}; // per level: sum x, y, x^2, x y, y^2
  long n = 0;
  double cx, cy;

  LevelHistogram(const cv::Mat &grey, const cv::Mat &m) : cx(0.5 * (m.cols - 1)), cy(0.5 * (m.rows - 1))
  {
    for (int r = 0; r < m.rows; ++r) {
      const unsigned char *pm = m.ptr<unsigned char>(r), *pg = grey.ptr<unsigned char>(r);
      const double y = r - cy;
      int c = 0;
      auto add = [&](int end) {
        for (; c < end; ++c)
          if (pm[c]) {
            ++h[pg[c]];
            ++n;
            const double x = c - cx;
            std::array<double, 5> &q = moments[pg[c]];
            q[0] += x;
            q[1] += y;
            q[2] += x * x;
            q[3] += x * y;
            q[4] += y * y;
          }
      };
      // 8 pixels at a time past the mask's empty words (a band's or ring's box is mostly empty).
      for (; c + 8 <= m.cols;) {
        std::uint64_t w;
        std::memcpy(&w, pm + c, 8);
        if (w == 0)
          c += 8;
        else
          add(c + 8);
      }
      add(m.cols);
    }
  }

  /*
    The histogram's median (the lowest level with half the counts at or under it) and a window about it of 4 sigma
    (at least half a grey level): the levels of the mask's main surface. n > 0. Sigma is 1.4826 times the median
    deviation of the side of the median that deviates less (oneSidedMad()): another surface in the mask (a card
    beside the object) lies on one side and would widen the window over its own levels.
  */
  void window(int &med, double &halfWidth) const
  {
    med = static_cast<int>(medianOf(h));
    std::array<long, 256> below{}, above{}; // histograms of the deviations on each side, the median's own in both
    for (int v = 0; v < 256; ++v)
      (v <= med ? below : above)[std::abs(v - med)] += h[v];
    above[0] += h[med];
    halfWidth = fourSigma(oneSidedMad(medianOf(below), h[0] > 0, medianOf(above), h[255] > 0));
  }

  /*
    The grey level, or -1 when the mask is empty: the mean of the levels within the window about their median, so that
    another surface in the mask (a card beside the object) does not count, but the noise does, clipped as it is. Why
    not the median: on a background a few grey levels under the sensor's limit, the noise's upper tail is clipped and
    the pixels' mean falls under their median; the edge pixels' weights, read against the median, then count a sliver
    of background as object all round.
  */
  double level() const
  {
    if (n == 0)
      return -1.0;
    int med;
    double halfWidth;
    window(med, halfWidth);
    double sum = 0.0;
    long kept = 0;
    for (int v = std::max(0, int(std::ceil(med - halfWidth))); v <= std::min(255, int(std::floor(med + halfWidth)));
         ++v) {
      sum += double(v) * double(h[v]);
      kept += h[v];
    }
    return sum / double(kept); // kept > 0: the median's own bin is in the window
  }

  // The least-squares sums of the pixels whose level is within [lo, hi].
  vpMorphAffineLevel::Sums sums(int lo, int hi) const
  {
    vpMorphAffineLevel::Sums s;
    for (int v = std::max(0, lo); v <= std::min(255, hi); ++v) {
      const double k = double(h[v]);
      const std::array<double, 5> &q = moments[v];
      s.n += k;
      s.x += q[0];
      s.y += q[1];
      s.xx += q[2];
      s.xy += q[3];
      s.yy += q[4];
      s.g += v * k;
      s.xg += v * q[0];
      s.yg += v * q[1];
      s.gg += double(v) * v * k;
    }
    return s;
  }

  // Share of the pixels at grey level \e v (a saturated level), 0 when the mask is empty.
  double share(unsigned char v) const { return n > 0 ? double(h[v]) / double(n) : 0.0; }
};

/*
  The level under mask \e m of \e g (a box of the image at \e tl) as an affine function of the position: a light that
  falls off across the view shades a surface so, to first order. Least squares over the pixels within the histogram's
  window about its median (another surface in the mask does not count, LevelHistogram::window()), then again over the
  mask's pixels within 4 sigma (1.4826 MAD, at least half a grey level) of that fit. Without a slope seen or worth its
  parameters (vpMorphAffineLevel::slope()), the histogram's level (LevelHistogram::level()). Invalid on an empty mask.
*/
Level affineLevel(const cv::Mat &g, const cv::Mat &m, const cv::Point &tl, const LevelHistogram &hist)
{
  Level out;
  if (hist.n == 0)
    return out;
  out.a = hist.level();
  out.valid = true;
  int med;
  double halfWidth;
  hist.window(med, halfWidth);
  // Without a slope, the level is the histogram's (the same pixels, read without a fit).
  Eigen::Vector3d p;
  if (!vpMorphAffineLevel::slope(hist.sums(int(std::ceil(med - halfWidth)), int(std::floor(med + halfWidth))), 1.0, p))
    return out;
  const double cx = hist.cx, cy = hist.cy;
  std::vector<double> below, above; // the residuals' magnitudes on each side
  bool belowClipped = false, aboveClipped = false;
  for (int r = 0; r < m.rows; ++r) {
    const unsigned char *pm = m.ptr<unsigned char>(r), *pg = g.ptr<unsigned char>(r);
    for (int c = 0; c < m.cols; ++c)
      if (pm[c]) {
        const double e = pg[c] - p(0) - p(1) * (c - cx) - p(2) * (r - cy);
        (e < 0.0 ? below : above).push_back(std::fabs(e));
        belowClipped = belowClipped || pg[c] == 0;
        aboveClipped = aboveClipped || pg[c] == 255;
      }
  }
  const double within = fourSigma(oneSidedMad(median(below), belowClipped, median(above), aboveClipped));
  vpMorphAffineLevel::Sums s;
  for (int r = 0; r < m.rows; ++r) {
    const unsigned char *pm = m.ptr<unsigned char>(r), *pg = g.ptr<unsigned char>(r);
    for (int c = 0; c < m.cols; ++c)
      if (pm[c] && std::fabs(pg[c] - p(0) - p(1) * (c - cx) - p(2) * (r - cy)) <= within)
        s.add(c - cx, r - cy, pg[c]);
  }
  if (!vpMorphAffineLevel::slope(s, 1.0, p))
    return out;
  out.au = p(1);
  out.av = p(2);
  out.a = p(0) - out.au * (tl.x + cx) - out.av * (tl.y + cy);
  return out;
}

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

// The gradient of g in grey levels per pixel (3x3 Sobel), for edgeProfile() and edgeOutline().
void gradient(const cv::Mat &g, cv::Mat &gx, cv::Mat &gy)
{
  cv::Sobel(g, gx, CV_32F, 1, 0, 3, 1.0 / 8.0, 0.0, cv::BORDER_REPLICATE);
  cv::Sobel(g, gy, CV_32F, 0, 1, 3, 1.0 / 8.0, 0.0, cv::BORDER_REPLICATE);
}

/*
  The level about which the edge profiles through \e profiles (pixel, gradient direction) are antisymmetric, searched
  within half a step (\e slope per pixel) of \e level0: a blurred step g(x0 + u) + g(x0 - u) = 2 g(x0) whatever the
  blur, and on that level, x0 is the edge. Only samples off the sensor's limits count, so a side clipped beyond the
  middle of the step does not move it; the gradient peak does, through the 3x3 support of its derivative (measured:
  10 grey levels low on a step lifted to 285 and clipped at 255 under a 1.2 px blur, the edge 0.15 px out).
  Returns \e level0 when too few samples are left.
*/
double antisymmetricLevel(const cv::Mat &g, const std::vector<cv::Vec4d> &profiles, double level0, double slope)
{
  const int half = 12; // samples each side, a quarter pixel apart: +-3 px
  const double h = 0.25, umax = 1.5;
  // Interpolated samples are clipped as soon as one of their four pixels is.
  cv::Mat limit = (g == 0) | (g == 255), near;
  cv::dilate(limit, near, cv::Mat::ones(2, 2, CV_8UC1), cv::Point(0, 0));
  // At most 512 profiles, spread along the edge: the level is one number for the whole edge.
  const std::size_t stride = (profiles.size() + 511) / 512;
  std::vector<std::array<double, 2 * half + 1>> prof;
  for (std::size_t k = 0; k < profiles.size(); k += stride) {
    prof.emplace_back();
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
  // The mean squared asymmetry of the profiles about L, +inf when under half of them can be compared.
  auto asymmetry = [&](double L) {
    double cost = 0.0;
    std::size_t n = 0;
    for (const auto &p : prof) {
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

/*
  Grey level and slope (grey levels per pixel) of an edge at its gradient maxima: the medians over the
  band's pixels that are a maximum of the gradient magnitude along the gradient direction, each refined to the
  parabola's vertex; the level is then the one about which the profiles through those maxima are antisymmetric
  (antisymmetricLevel()): the peaks' own level is pulled by a clipped far side through the 3x3 derivative. False
  when too few maxima (under 16) are found. gx, gy: the gradient of g (see gradient()).
*/
bool edgeProfile(const cv::Mat &g, const cv::Mat &gx, const cv::Mat &gy, const cv::Mat &band, double minSlope,
                 double &level, double &slope)
{
  cv::Mat mag;
  cv::magnitude(gx, gy, mag);
  auto at = [&mag](double x, double y) { return bilinear<float>(mag, x, y); };
  std::vector<double> levels, slopes;
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
      levels.push_back(g.at<unsigned char>(r, c) + d * m0); // g rises along the gradient at m0 per pixel
      slopes.push_back(m0 - 0.25 * (mm - mp) * d);
      profiles.push_back(cv::Vec4d(c, r, nx, ny));
    }
  if (levels.size() < 16)
    return false;
  level = median(levels);
  slope = median(slopes);
  if (!(slope > 0.0))
    return false;
  level = antisymmetricLevel(g, profiles, level, slope);
  return true;
}

/*
  The edge near each chain pixel, in image coordinates (chain pixel + box corner), one point per pixel.
  - Where the step is whole (fg to bg, not clipped): along the pixel's row, or its column when the edge is closer to
    horizontal, the edge is where the object's share of the 7 pixels about it ends, their weights (g - bg) /
    (fg - bg) (the levels at each pixel) summed from the object's end. Why: a pixel's grey level is the share of its
    area the object covers (then blurred, which keeps areas), so over a row the weights add up to the object's
    extent, averaged over the pixel's height: for a straight edge, exactly the edge at the row's centre, whatever its
    angle and blur. The level crossing of an interpolated profile is off by a pixel-phase-dependent tenth of a pixel
    on slanted edges.
  - Elsewhere (clipped levels, another edge within 3 px, the image border): along the gradient direction (3x3
    Sobel), the crossing nearest the pixel within 2 px of the level halfway between fg and bg there (\e clippedLevel
    when the step is not \e whole), the profile sampled bilinearly every quarter
    pixel and interpolated linearly.
  Pixels without a clear gradient (under the local contrast / 16 per pixel) or without a crossing are skipped.
  \e blur, when given, receives the edge's blur from the whole steps' profiles (left unchanged without any).
  \e own receives, per point, whether the edge from it to the next is the object's own edge: no chain pixel skipped
  between them (a bridge, where there is no edge), and each point's own (vpMorphOwnEdges() on \e object, the object mask
  of the box: beyond the edge's blur reach, 3 blur std, by a pixel and the patch's half diagonal).
*/
std::vector<cv::Point2d> edgeOutline(const cv::Mat &g, const cv::Mat &gx, const cv::Mat &gy,
                                     const std::vector<cv::Point> &chain, const cv::Point &tl, const Level &fg,
                                     const Level &bg, bool whole, double clippedLevel, const cv::Mat &object,
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

} // namespace

void vpMorphRegionMeasure::measure(const cv::Mat &grey, const cv::Mat &bin, Region &reg, const Region *levelsFrom,
                                   bool levelsOnly)
{
  const int B = 3;
  cv::Rect box = cv::boundingRect(reg.chain);
  box.x -= B + 3;
  box.y -= B + 3;
  box.width += 2 * (B + 3);
  box.height += 2 * (B + 3);
  box &= cv::Rect(0, 0, grey.cols, grey.rows);
  const cv::Mat g = grey(box);
  cv::Mat region = cv::Mat::zeros(box.size(), CV_8UC1);
  const std::vector<std::vector<cv::Point>> polys{reg.chain};
  cv::drawContours(region, polys, 0, cv::Scalar(255), cv::FILLED, cv::LINE_8, cv::noArray(), INT_MAX, -box.tl());
  const cv::Mat k3 = cv::getStructuringElement(cv::MORPH_RECT, cv::Size(3, 3));
  cv::Mat others, inner, outer, outerMore, band, ring;
  cv::bitwise_and(bin(box), ~region, others);
  cv::dilate(others, others, k3); // their own edge pixels are not ours either
  cv::erode(region, inner, k3, cv::Point(-1, -1), B, cv::BORDER_CONSTANT, cv::Scalar(0));
  cv::dilate(region, outer, k3, cv::Point(-1, -1), B);
  cv::dilate(outer, outerMore, k3, cv::Point(-1, -1), 2);
  band = outer & ~inner & ~others;
  ring = outerMore & ~outer & ~others;
  // The object's level is read on its own pixels, B deep where it has any: its filled outline less what the mask
  // reads as background inside it (a hole, or what a coiled wire encloses once a blur has closed its coils), whose
  // level is no object's.
  cv::Mat own, plateau;
  cv::bitwise_and(bin(box), region, own);
  cv::erode(own, plateau, k3, cv::Point(-1, -1), B, cv::BORDER_CONSTANT, cv::Scalar(0));
  const bool given = levelsFrom != nullptr && levelsFrom->fg.valid && levelsFrom->bg.valid;
  const LevelHistogram innerLevels(g, plateau), ringLevels(g, ring);
  const Level fg = given ? levelsFrom->fg
                         : (innerLevels.n > 0 ? affineLevel(g, plateau, box.tl(), innerLevels)
                                              : affineLevel(g, own, box.tl(), LevelHistogram(g, own)));
  const Level bg = given ? levelsFrom->bg : affineLevel(g, ring, box.tl(), ringLevels);
  reg.fg = fg;
  reg.bg = bg;
  if (levelsOnly)
    return;
  // Raw moments about the box corner (well conditioned), centred at the end.
  double m00 = 0.0, m10 = 0.0, m01 = 0.0, m20 = 0.0, m11 = 0.0, m02 = 0.0;
  // The levels at the box's centre tell the contrast and the polarity.
  const double uc = box.x + 0.5 * (box.width - 1), vc = box.y + 0.5 * (box.height - 1);
  const double fgc = fg.valid ? fg.at(uc, vc) : -1.0, bgc = bg.valid ? bg.at(uc, vc) : -1.0;
  const bool grades = fg.valid && bg.valid && std::fabs(fgc - bgc) >= 8.0;
  // A level clipped by the sensor (a bright background at 255 under a brighter light) flattens the far half of the
  // edge: the linear weights then lose that half's share and the region shrinks by a few tenths of a pixel all
  // round. There, the pixels count by their distance to the edge, (level - g) / slope, the edge's slope read where
  // the gradient peaks and its level where the edge profiles are antisymmetric, which clipping beyond the middle of
  // the step does not move (edgeProfile()). Half of the far level's pixels at the limit (its median there) marks it as
  // clipped: a level under the limit whose noise reaches it is not.
  double edgeLevel = 0.0, edgeSlope = 0.0;
  cv::Mat gx, gy; // computed once for the edge's profile and outline
  if (grades)
    gradient(g, gx, gy);
  const unsigned char far = fgc < bgc ? 255 : 0, near = fgc < bgc ? 0 : 255;
  const bool clipped = grades && (ringLevels.share(far) >= 0.5 || innerLevels.share(near) >= 0.5) &&
                       edgeProfile(g, gx, gy, band, std::fabs(fgc - bgc) / 8.0, edgeLevel, edgeSlope) &&
                       (edgeLevel - fgc) * (bgc - edgeLevel) > 0.0;
  const double toward = fgc < bgc ? -1.0 : 1.0; // sign of g - edgeLevel inside the object
  const cv::Mat &full = grades ? inner : region;
  // A row's sums (weight, weight x column, weight x column^2) are added to the moments with the row's powers. The
  // whole pixels go 8 at a time (one 64-bit word of the masks): a word of them in closed form, a word with neither
  // whole nor band pixels (outside the object) skipped.
  const int width = box.width;
  for (int r = 0; r < box.height; ++r) {
    const unsigned char *pf = full.ptr<unsigned char>(r), *pb = band.ptr<unsigned char>(r),
                        *pg = g.ptr<unsigned char>(r);
    double s0 = 0.0, s1 = 0.0, s2 = 0.0;
    // The levels along the row: fg0 + fgu c, bg0 + bgu c.
    const double u0 = box.x, v = box.y + r, fg0 = fg.at(u0, v), bg0 = bg.at(u0, v), fgu = fg.au, bgu = bg.au;
    auto pixel = [&](int c) {
      double w = 0.0;
      if (pf[c])
        w = 1.0;
      else if (clipped && pb[c])
        w = std::min(1.0, std::max(0.0, 0.5 + toward * (pg[c] - edgeLevel) / edgeSlope));
      else if (grades && pb[c]) {
        const double b = bg0 + bgu * c;
        w = (pg[c] - b) / (fg0 + fgu * c - b);
      }
      s0 += w;
      s1 += w * c;
      s2 += w * c * c;
    };
    int c = 0;
    for (; c + 8 <= width; c += 8) {
      std::uint64_t f, b;
      std::memcpy(&f, pf + c, 8);
      std::memcpy(&b, pb + c, 8);
      if (f == ~std::uint64_t(0)) { // sum of c..c+7 and of their squares
        s0 += 8.0;
        s1 += 8.0 * c + 28.0;
        s2 += 8.0 * c * c + 56.0 * c + 140.0;
      } else if ((f | b) != 0) {
        for (int k = c; k < c + 8; ++k)
          pixel(k);
      }
    }
    for (; c < width; ++c)
      pixel(c);
    m00 += s0;
    m10 += s1;
    m01 += s0 * r;
    m20 += s2;
    m11 += s1 * r;
    m02 += s0 * r * r;
  }
  if (!(m00 > 0.0))
    return; // left unmeasured: the contour falls back to its polygon
  if (grades)
    reg.outline = edgeOutline(g, gx, gy, reg.chain, box.tl(), fg, bg, !clipped, edgeLevel, bin(box), reg.outlineOwn,
                              &reg.edgeBlur);
  const double xc = m10 / m00, yc = m01 / m00;
  reg.subArea = m00;
  reg.cx = box.x + xc;
  reg.cy = box.y + yc;
  reg.mu20 = m20 / m00 - xc * xc;
  reg.mu11 = m11 / m00 - xc * yc;
  reg.mu02 = m02 / m00 - yc * yc;
}
