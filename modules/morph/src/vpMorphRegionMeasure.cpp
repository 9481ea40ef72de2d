#include "vpMorphRegionMeasure.h"
#include "vpMorphAffineLevel.h"
#include "vpMorphEdgeOutline.h"
#include "vpMorphLevelSpread.h"

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
using vpMorphEdgeOutline::edgeOutline;
using vpMorphEdgeOutline::edgeProfile;
using vpMorphEdgeOutline::gradient;
using vpMorphLevelSpread::fourSigma;
using vpMorphLevelSpread::median;
using vpMorphLevelSpread::medianOf;
using vpMorphLevelSpread::oneSidedMad;
using vpMorphLevelSpread::quantizedDeviationMedian;

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
    beside the object) lies on one side and would widen the window over its own levels. The deviations are the
    levels' rounded ones (quantizedDeviationMedian()).
  */
  void window(int &med, double &halfWidth) const
  {
    med = static_cast<int>(medianOf(h));
    std::array<long, 256> below{}, above{}; // histograms of the deviations on each side, the median's own in both
    for (int v = 0; v < 256; ++v)
      (v <= med ? below : above)[std::abs(v - med)] += h[v];
    above[0] += h[med];
    halfWidth =
        fourSigma(oneSidedMad(quantizedDeviationMedian(below), h[0] > 0, quantizedDeviationMedian(above), h[255] > 0));
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

/*
  The object's level for a region without a plateau (nowhere more than 2 B + 1 px wide: a wire): all its pixels are
  edge, their levels between the object's and the background's, so \e own, read on them, lies towards the
  background the more the thinner the part and the wider the blur, and the edge's middle with it. A blurred step's
  profile is antisymmetric about the step's middle whatever the blur (edgeProfile()), so the object's level is the one
  whose middle with the background's is that level: 2 L - bg, L in proportion to own + bg along the edge (a light that
  falls off scales both). \e own when no such level is found between \e own and the background. gx, gy: the gradient.
*/
Level levelFromEdge(const cv::Mat &g, const cv::Mat &gx, const cv::Mat &gy, const cv::Mat &band, const Level &own,
                    const Level &bg, const cv::Point &tl)
{
  Level middle = own;
  middle.a = 0.5 * (own.a + bg.a);
  middle.au = 0.5 * (own.au + bg.au);
  middle.av = 0.5 * (own.av + bg.av);
  const double uc = tl.x + 0.5 * (g.cols - 1), vc = tl.y + 0.5 * (g.rows - 1);
  const double ownc = own.at(uc, vc), bgc = bg.at(uc, vc), midc = middle.at(uc, vc);
  double level, slope;
  if (!(midc > 0.0) || !edgeProfile(g, gx, gy, band, std::fabs(ownc - bgc) / 8.0, level, slope, &middle, tl) ||
      !((level - ownc) * (bgc - level) > 0.0))
    return own;
  const double k = 2.0 * level / midc; // fg = k middle - bg
  Level fg = own;
  fg.a = k * middle.a - bg.a;
  fg.au = k * middle.au - bg.au;
  fg.av = k * middle.av - bg.av;
  return fg;
}

} // namespace

void vpMorphRegionMeasure::measure(const cv::Mat &grey, const cv::Mat &bin, Region &reg, const Region *levelsFrom,
                                   bool levelsOnly)
{
  const int B = 3;
  static_assert(kReach == B + 3, "the band, and the ring 2 px beyond it");
  cv::Rect box = cv::boundingRect(reg.chain);
  box.x -= kReach;
  box.y -= kReach;
  box.width += 2 * kReach;
  box.height += 2 * kReach;
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
  Level fg = given ? levelsFrom->fg
                   : (innerLevels.n > 0 ? affineLevel(g, plateau, box.tl(), innerLevels)
                                        : affineLevel(g, own, box.tl(), LevelHistogram(g, own)));
  const Level bg = given ? levelsFrom->bg : affineLevel(g, ring, box.tl(), ringLevels);
  // The levels at the box's centre tell the contrast and the polarity.
  const double uc = box.x + 0.5 * (box.width - 1), vc = box.y + 0.5 * (box.height - 1);
  auto contrast = [&] { return fg.valid && bg.valid ? std::fabs(fg.at(uc, vc) - bg.at(uc, vc)) : 0.0; };
  const double minContrast = 8.0; // grey levels: below, the levels are not told apart (the binary region is used)
  cv::Mat gx, gy;                 // computed once for the edge's level, profile and outline
  if (!given && innerLevels.n == 0 && contrast() >= minContrast) {
    gradient(g, gx, gy);
    fg = levelFromEdge(g, gx, gy, band, fg, bg, box.tl());
  }
  reg.fg = fg;
  reg.bg = bg;
  if (levelsOnly)
    return;
  // Raw moments about the box corner (well conditioned), centred at the end.
  double m00 = 0.0, m10 = 0.0, m01 = 0.0, m20 = 0.0, m11 = 0.0, m02 = 0.0;
  const double fgc = fg.valid ? fg.at(uc, vc) : -1.0, bgc = bg.valid ? bg.at(uc, vc) : -1.0;
  const bool grades = contrast() >= minContrast;
  // A level clipped by the sensor (a bright background at 255 under a brighter light) flattens the far half of the
  // edge: the linear weights then lose that half's share and the region shrinks by a few tenths of a pixel all
  // round. There, the pixels count by their distance to the edge, (level - g) / slope, the edge's slope read where
  // the gradient peaks and its level where the edge profiles are antisymmetric, which clipping beyond the middle of
  // the step does not move (edgeProfile()). Half of the far level's pixels at the limit (its median there) marks it as
  // clipped: a level under the limit whose noise reaches it is not.
  double edgeLevel = 0.0, edgeSlope = 0.0;
  if (grades && gx.empty())
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
