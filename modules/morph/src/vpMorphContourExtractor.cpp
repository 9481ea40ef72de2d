#include <visp3/morph/vpMorphContourExtractor.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <sstream>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <visp3/core/vpImageConvert.h>
#include <visp3/morph/vpMorphException.h>
#include <visp3/morph/vpMorphPolygonApproximation.h>

#include "vpMorphGreyClasses.h"
#include "vpMorphRegionMeasure.h"

using vpMorphRegionMeasure::measure;
using vpMorphRegionMeasure::Region;

namespace
{
[[noreturn]] void fail(const std::string &what)
{
  throw vpMorphException(vpMorphException::badImageError, "vpMorphContourExtractor: " + what);
}

vpImage<unsigned char> toGrey(const vpImage<vpRGBa> &I)
{
  vpImage<unsigned char> g;
  if (I.getSize() > 0)
    vpImageConvert::convert(I, g);
  return g;
}

/*
  Object mask (255 = object) from the two grey classes (vpMorphGreyClasses) and the border-minority polarity rule. It
  is a view of \e padded, which has one pixel of background all round (what findContours() needs to close objects that
  touch the border), written in place rather than copied into it.
*/
cv::Mat mask(const vpImage<unsigned char> &I, cv::Mat &padded)
{
  if (I.getSize() == 0 || I.bitmap == nullptr)
    fail("the image is empty");
  const unsigned int minSide = vpMorphContourExtractor::minImageSize();
  if (I.getWidth() < minSide || I.getHeight() < minSide) {
    std::ostringstream os;
    os << "the image is " << I.getWidth() << "x" << I.getHeight() << ", smaller than the minimum " << minSide
       << "x" << minSide;
    fail(os.str());
  }
  // Wraps the ViSP buffer (row-major, 8 bits) without copying; it is only read.
  const cv::Mat grey(static_cast<int>(I.getHeight()), static_cast<int>(I.getWidth()), CV_8UC1,
                     const_cast<unsigned char *>(I.bitmap));
  const long total = static_cast<long>(I.getSize());
  const vpMorphGreyClasses::Histogram h = vpMorphGreyClasses::histogram(I.bitmap, I.getSize());
  const auto lo = std::find_if(h.begin(), h.end(), [](long c) { return c > 0; });
  if (*lo == total) {
    std::ostringstream os;
    os << "the image is uniform (every pixel is " << (lo - h.begin()) << "): no contrast to separate an object";
    fail(os.str());
  }
  const int rows = grey.rows, cols = grey.cols;
  padded.create(rows + 2, cols + 2, CV_8UC1);
  padded.row(0).setTo(0);
  padded.row(rows + 1).setTo(0);
  for (int r = 1; r <= rows; ++r) { // a column's setTo() goes through OpenCV's generic strided iteration
    unsigned char *row = padded.ptr<unsigned char>(r);
    row[0] = row[cols + 1] = 0;
  }
  cv::Mat bin = padded(cv::Rect(1, 1, cols, rows));
  vpMorphGreyClasses(grey, vpMorphGreyClasses::otsu(h, total)).bright(grey, bin);

  // Polarity: the class that dominates the border is the background.
  long bright = 0, border = 0;
  const unsigned char *top = bin.ptr<unsigned char>(0), *bottom = bin.ptr<unsigned char>(rows - 1);
  for (int c = 0; c < cols; ++c) {
    bright += (top[c] != 0) + (bottom[c] != 0);
    border += 2;
  }
  for (int r = 1; r < rows - 1; ++r) {
    const unsigned char *row = bin.ptr<unsigned char>(r);
    bright += (row[0] != 0) + (row[cols - 1] != 0);
    border += 2;
  }
  const bool objectIsBright = 2 * bright != border ? 2 * bright < border : 2 * cv::countNonZero(bin) < total;
  if (!objectIsBright)
    cv::bitwise_not(bin, bin);
  return bin;
}

// The first \e measured regions (largest first) also get their grey-level area and centroid. \e binOut, if not
// null, receives the object mask they were found in.
std::vector<Region> regions(const vpImage<unsigned char> &I, std::size_t measured = 0, cv::Mat *binOut = nullptr)
{
  cv::Mat padded;
  const cv::Mat bin = mask(I, padded);
  if (binOut)
    *binOut = bin;
  std::vector<std::vector<cv::Point> > contours;
  cv::findContours(padded, contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE);

  std::vector<Region> out;
  for (std::vector<cv::Point> &c : contours) {
    const double a = cv::contourArea(c);
    if (a < vpMorphContourExtractor::minRegionArea())
      continue;
    Region r{std::move(c), a, cv::Point()};
    for (cv::Point &p : r.chain)
      p -= cv::Point(1, 1);
    r.first = *std::min_element(r.chain.begin(), r.chain.end(), [](const cv::Point &p, const cv::Point &q) {
      return p.y < q.y || (p.y == q.y && p.x < q.x);
    });
    out.push_back(std::move(r));
  }
  if (out.empty()) {
    std::ostringstream os;
    os << "no object found in the " << I.getWidth() << "x" << I.getHeight() << " image (" << contours.size()
       << " region(s), all enclosing less than the validity floor of " << vpMorphContourExtractor::minRegionArea()
       << " square pixels)";
    fail(os.str());
  }
  std::sort(out.begin(), out.end(), [](const Region &a, const Region &b) {
    if (a.area != b.area)
      return a.area > b.area;
    return a.first.y < b.first.y || (a.first.y == b.first.y && a.first.x < b.first.x);
  });
  const cv::Mat grey(static_cast<int>(I.getHeight()), static_cast<int>(I.getWidth()), CV_8UC1,
                     const_cast<unsigned char *>(I.bitmap));
  for (std::size_t k = 0; k < std::min(measured, out.size()); ++k)
    measure(grey, bin, out[k]);
  return out;
}

std::vector<vpImagePoint> toVisp(const std::vector<cv::Point> &c)
{
  std::vector<vpImagePoint> out;
  out.reserve(c.size());
  for (const cv::Point &p : c)
    out.emplace_back(p.y, p.x);
  return out;
}
vpMorphContour polygon(const Region &r)
{
  vpMorphContour c = vpMorphPolygonApproximation::approximate(toVisp(r.chain));
  if (r.subArea > 0.0) {
    try {
      c.setRegion(r.subArea, r.cx, r.cy, r.mu20, r.mu11, r.mu02);
    } catch (const vpMorphException &) {
      // Not a valid region (grey levels inconsistent with the mask): the contour keeps its polygon measures.
    }
  }
  if (r.outline.size() >= 4) {
    std::vector<double> x, y;
    x.reserve(r.outline.size());
    y.reserve(r.outline.size());
    for (const cv::Point2d &p : r.outline) {
      x.push_back(p.x);
      y.push_back(p.y);
    }
    try {
      c.setOutline(vpMorphContour(x, y));
    } catch (const vpMorphException &) {
      // Not a valid outline (a sliver): the contour goes without.
    }
  }
  return c;
}

// Closest pair of pixels between two chains (brute force: chains are a few thousand pixels at most).
double closestPair(const std::vector<cv::Point> &a, const std::vector<cv::Point> &b, cv::Point &pa, cv::Point &pb)
{
  long best = LONG_MAX;
  for (const cv::Point &p : a)
    for (const cv::Point &q : b) {
      const long dx = p.x - q.x, dy = p.y - q.y, d2 = dx * dx + dy * dy;
      if (d2 < best) {
        best = d2;
        pa = p;
        pb = q;
      }
    }
  return best == LONG_MAX ? INFINITY : std::sqrt(double(best));
}

// Distance between two rectangles (0 when they overlap): a lower bound of the distance between what they hold.
double rectGap(const cv::Rect &a, const cv::Rect &b)
{
  const int dx = std::max({0, b.x - (a.x + a.width - 1), a.x - (b.x + b.width - 1)});
  const int dy = std::max({0, b.y - (a.y + a.height - 1), a.y - (b.y + b.height - 1)});
  return std::hypot(double(dx), double(dy));
}

// The pixels of a chain within r of a point.
void near(const std::vector<cv::Point> &chain, const cv::Point &c, double r, std::vector<cv::Point> &out)
{
  for (const cv::Point &p : chain)
    if (std::abs(p.x - c.x) <= r && std::abs(p.y - c.y) <= r && std::hypot(double(p.x - c.x), double(p.y - c.y)) <= r)
      out.push_back(p);
}

// The pixels of a chain within r of c that lie within \e reach of the other chain.
void cutEdge(const std::vector<cv::Point> &chain, const cv::Point &c, double r, const std::vector<cv::Point> &other,
             double reach, std::vector<cv::Point> &out)
{
  std::vector<cv::Point> candidates, others;
  near(chain, c, r, candidates);
  if (candidates.empty())
    return;
  // Only the other chain's pixels within r + reach of c can be within reach of a candidate: a few dozen instead of
  // the whole chain for each candidate (the same pixels result).
  near(other, c, r + reach, others);
  const double reach2 = reach * reach;
  for (const cv::Point &p : candidates)
    for (const cv::Point &q : others) {
      const double dx = p.x - q.x, dy = p.y - q.y;
      if (dx * dx + dy * dy <= reach2) {
        out.push_back(p);
        break;
      }
    }
}
} // namespace

vpMorphContour vpMorphContourExtractor::extractJoined(const vpImage<unsigned char> &I) const
{
  cv::Mat bin;
  std::vector<Region> regs = regions(I, 0, &bin); // measured below: whole, or its levels only when joined
  Region &largest = regs.front();
  const cv::Mat grey(static_cast<int>(I.getHeight()), static_cast<int>(I.getWidth()), CV_8UC1,
                     const_cast<unsigned char *>(I.bitmap));
  auto alone = [&]() {
    measure(grey, bin, largest);
    return polygon(largest);
  };
  const cv::Rect box = cv::boundingRect(largest.chain);
  const double maxGap = joinedMaxGap() * std::hypot(double(box.width), double(box.height));
  std::vector<const Region *> pieces;
  for (std::size_t k = 1; k < regs.size(); ++k)
    if (regs[k].area >= joinedMinShare() * largest.area)
      pieces.push_back(&regs[k]);
  if (pieces.empty())
    return alone(); // the common case: one piece, no mask to draw
  // The join is drawn over the pieces' box only (a pixel of background all round), not the whole image.
  cv::Rect all = box;
  for (const Region *p : pieces)
    all |= cv::boundingRect(p->chain);
  const cv::Point offset = cv::Point(1, 1) - all.tl();
  cv::Mat joined = cv::Mat::zeros(all.height + 2, all.width + 2, CV_8UC1);
  auto fill = [&joined, &offset](const std::vector<cv::Point> &poly, bool convex) {
    std::vector<cv::Point> shifted(poly);
    for (cv::Point &p : shifted)
      p += offset;
    if (convex)
      cv::fillConvexPoly(joined, shifted, cv::Scalar(255), cv::LINE_8);
    else
      cv::drawContours(joined, std::vector<std::vector<cv::Point> >{shifted}, 0, cv::Scalar(255), cv::FILLED);
  };
  fill(largest.chain, false);
  // Nearest piece first, each gap bridged by the convex hull of both sides' pixels near it (within 1.5 gaps): a
  // cut straight across a limb is closed by the limb's own width, a bite out of a side is not filled beyond it.
  // Each piece keeps its nearest link to the group, updated as pieces join (one chain-to-chain search per pair at
  // most, none for pairs whose boxes are already farther apart: a noisy frame can hold many pieces).
  struct Link
  {
    double d = INFINITY;
    const Region *g = nullptr;
    cv::Point pg, pp;
  };
  std::vector<Link> links(pieces.size());
  std::vector<cv::Rect> boxes;
  for (const Region *p : pieces)
    boxes.push_back(cv::boundingRect(p->chain));
  auto linkTo = [&](const Region *g) {
    const cv::Rect gb = cv::boundingRect(g->chain);
    for (std::size_t k = 0; k < pieces.size(); ++k) {
      if (rectGap(gb, boxes[k]) > std::min(links[k].d, maxGap))
        continue;
      cv::Point a, b;
      const double d = closestPair(g->chain, pieces[k]->chain, a, b);
      if (d < links[k].d)
        links[k] = Link{d, g, a, b};
    }
  };
  linkTo(&largest);
  bool any = false;
  while (!pieces.empty()) {
    std::size_t bestPiece = 0;
    for (std::size_t k = 1; k < pieces.size(); ++k)
      if (links[k].d < links[bestPiece].d)
        bestPiece = k;
    const Link best = links[bestPiece];
    if (!(best.d <= maxGap))
      break;
    // Of the pixels near the gap, those about as close to the other side as the closest pair: the two cut edges
    // (a card's edges are parallel, so each lies at the gap's width from the other) and the start of the limb's
    // sides. Not the rest of a bow or a head within 1.5 gaps of a long cut, whose hull would fill a triangle
    // between them (a key cut along its shaft joined into a blob).
    const double r = std::max(1.5 * best.d, 3.0), slack = std::max(2.0, 0.25 * best.d);
    std::vector<cv::Point> bridge, hull;
    cutEdge(best.g->chain, best.pg, r, pieces[bestPiece]->chain, best.d + slack, bridge);
    cutEdge(pieces[bestPiece]->chain, best.pp, r, best.g->chain, best.d + slack, bridge);
    cv::convexHull(bridge, hull);
    fill(pieces[bestPiece]->chain, false);
    fill(hull, true);
    const Region *joinedPiece = pieces[bestPiece];
    pieces.erase(pieces.begin() + static_cast<std::ptrdiff_t>(bestPiece));
    links.erase(links.begin() + static_cast<std::ptrdiff_t>(bestPiece));
    boxes.erase(boxes.begin() + static_cast<std::ptrdiff_t>(bestPiece));
    linkTo(joinedPiece);
    any = true;
  }
  if (!any)
    return alone();
  std::vector<std::vector<cv::Point> > contours;
  cv::findContours(joined, contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE);
  const auto it = std::max_element(contours.begin(), contours.end(), [](const auto &a, const auto &b) {
    return cv::contourArea(a) < cv::contourArea(b);
  });
  Region r{*it, cv::contourArea(*it), cv::Point()};
  for (cv::Point &p : r.chain)
    p -= offset;
  // The measured edge along the joined boundary: where it runs over the bridge there is no object edge (no
  // gradient, or the occluder's, which an outline fit drops as it drops an occluder's edge on a single piece), the
  // rest is the object's. Its levels are the largest piece's: the bridge's pixels (background, occluder) would
  // move the object's median and every edge with it (measured: 0.6 px outward on a hammer cut from its head, its
  // depth 3.3 mm off). No measured region: part of its area is a bridge, not the object's grey levels.
  measure(grey, bin, largest, nullptr, true);
  measure(grey, bin, r, &largest);
  r.subArea = 0.0;
  return polygon(r);
}

vpMorphContour vpMorphContourExtractor::extractJoined(const vpImage<vpRGBa> &I) const
{
  return extractJoined(toGrey(I));
}

vpImage<unsigned char> vpMorphContourExtractor::objectMask(const vpImage<unsigned char> &I) const
{
  cv::Mat padded;
  const cv::Mat bin = mask(I, padded);
  vpImage<unsigned char> M(I.getHeight(), I.getWidth());
  for (int r = 0; r < bin.rows; ++r)
    std::copy(bin.ptr<unsigned char>(r), bin.ptr<unsigned char>(r) + bin.cols, M[static_cast<unsigned int>(r)]);
  return M;
}

int vpMorphContourExtractor::otsuThreshold(const vpImage<unsigned char> &I)
{
  if (I.getSize() == 0 || I.bitmap == nullptr)
    fail("the image is empty");
  return vpMorphGreyClasses::otsu(vpMorphGreyClasses::histogram(I.bitmap, I.getSize()), static_cast<long>(I.getSize()));
}

std::vector<std::vector<vpImagePoint> > vpMorphContourExtractor::boundaries(const vpImage<unsigned char> &I) const
{
  std::vector<std::vector<vpImagePoint> > out;
  for (const Region &r : regions(I))
    out.push_back(toVisp(r.chain));
  return out;
}

std::vector<std::vector<vpImagePoint> > vpMorphContourExtractor::boundaries(const vpImage<vpRGBa> &I) const
{
  return boundaries(toGrey(I));
}

std::vector<vpImagePoint> vpMorphContourExtractor::boundary(const vpImage<unsigned char> &I) const
{
  return toVisp(regions(I).front().chain);
}

std::vector<vpImagePoint> vpMorphContourExtractor::boundary(const vpImage<vpRGBa> &I) const
{
  return boundary(toGrey(I));
}

vpMorphContour vpMorphContourExtractor::extract(const vpImage<unsigned char> &I) const
{
  return polygon(regions(I, 1).front());
}

vpMorphContour vpMorphContourExtractor::extract(const vpImage<vpRGBa> &I) const { return extract(toGrey(I)); }

std::vector<vpMorphContour> vpMorphContourExtractor::extractAll(const vpImage<unsigned char> &I) const
{
  std::vector<vpMorphContour> out;
  for (const Region &r : regions(I, SIZE_MAX))
    out.push_back(polygon(r));
  return out;
}

std::vector<vpMorphContour> vpMorphContourExtractor::extractAll(const vpImage<vpRGBa> &I) const
{
  return extractAll(toGrey(I));
}
