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
#include "vpMorphRegionJoin.h"
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

// Wraps the ViSP buffer (row-major, 8 bits) without copying; it is only read.
cv::Mat greyOf(const vpImage<unsigned char> &I)
{
  return cv::Mat(static_cast<int>(I.getHeight()), static_cast<int>(I.getWidth()), CV_8UC1,
                 const_cast<unsigned char *>(I.bitmap));
}

// The rectangle of the whole image.
cv::Rect wholeOf(const vpImage<unsigned char> &I)
{
  return cv::Rect(0, 0, static_cast<int>(I.getWidth()), static_cast<int>(I.getHeight()));
}

// The object's class in an image: the two grey classes (vpMorphGreyClasses) fitted on the whole image, and which of
// them is the object (the border-minority polarity rule).
struct Segmentation
{
  vpMorphGreyClasses classes;
  bool objectIsBright;
};

// \e rect of the image classified into the same rectangle of \e bin (image coordinates): 255 for the object's class.
void classify(const cv::Mat &grey, const Segmentation &s, const cv::Rect &rect, cv::Mat &bin)
{
  cv::Mat dst = bin(rect);
  s.classes.bright(grey(rect), dst, rect.tl());
  if (!s.objectIsBright)
    cv::bitwise_not(dst, dst);
}

Segmentation segmentation(const vpImage<unsigned char> &I)
{
  if (I.getSize() == 0 || I.bitmap == nullptr)
    fail("the image is empty");
  const unsigned int minSide = vpMorphContourExtractor::minImageSize();
  if (I.getWidth() < minSide || I.getHeight() < minSide) {
    std::ostringstream os;
    os << "the image is " << I.getWidth() << "x" << I.getHeight() << ", smaller than the minimum " << minSide << "x"
       << minSide;
    fail(os.str());
  }
  const cv::Mat grey = greyOf(I);
  const long total = static_cast<long>(I.getSize());
  const vpMorphGreyClasses::Histogram h = vpMorphGreyClasses::histogram(I.bitmap, I.getSize());
  const auto lo = std::find_if(h.begin(), h.end(), [](long c) { return c > 0; });
  if (*lo == total) {
    std::ostringstream os;
    os << "the image is uniform (every pixel is " << (lo - h.begin()) << "): no contrast to separate an object";
    fail(os.str());
  }
  Segmentation s{vpMorphGreyClasses(grey, vpMorphGreyClasses::otsu(h, total)), true};
  // Polarity: the class that dominates the border is the background.
  const int rows = grey.rows, cols = grey.cols;
  auto bright = [&grey, &s](const cv::Rect &part) {
    cv::Mat dst(part.size(), CV_8UC1);
    s.classes.bright(grey(part), dst, part.tl());
    return static_cast<long>(cv::countNonZero(dst));
  };
  long count = 0, border = 0;
  for (const cv::Rect &side : {cv::Rect(0, 0, cols, 1), cv::Rect(0, rows - 1, cols, 1), cv::Rect(0, 1, 1, rows - 2),
                               cv::Rect(cols - 1, 1, 1, rows - 2)}) {
    count += bright(side);
    border += side.area();
  }
  s.objectIsBright = 2 * count != border ? 2 * count < border : 2 * bright(cv::Rect(0, 0, cols, rows)) < total;
  return s;
}

/*
  The object mask of \e rect (image coordinates) in \e padded, which has one pixel of background all round the image
  (what findContours() needs to close objects that touch the border): its view of the image, of which \e rect alone is
  written, and the ring of pixels round \e rect set to background.
*/
cv::Mat mask(const cv::Mat &grey, const Segmentation &s, const cv::Rect &rect, cv::Mat &padded)
{
  const int rows = grey.rows, cols = grey.cols;
  padded.create(rows + 2, cols + 2, CV_8UC1);
  const cv::Rect ring(rect.x, rect.y, rect.width + 2, rect.height + 2); // in padded coordinates
  padded(cv::Rect(ring.x, ring.y, ring.width, 1)).setTo(0);
  padded(cv::Rect(ring.x, ring.br().y - 1, ring.width, 1)).setTo(0);
  for (int r = ring.y + 1; r < ring.br().y - 1; ++r) { // a column's setTo() goes through OpenCV's generic iteration
    unsigned char *row = padded.ptr<unsigned char>(r);
    row[ring.x] = row[ring.br().x - 1] = 0;
  }
  cv::Mat bin = padded(cv::Rect(1, 1, cols, rows));
  classify(grey, s, rect, bin);
  return bin;
}

/*
  The object regions of \e rect (image coordinates; larger than the minimum area, largest first), their chains in image
  coordinates; \e bin receives the object mask they were found in (valid over \e rect). The first \e measured also get
  their grey-level area and centroid. None found throws, unless \e none is given: then set and nothing thrown.
*/
std::vector<Region> regions(const vpImage<unsigned char> &I, const Segmentation &s, const cv::Rect &rect, cv::Mat &bin,
                            std::size_t measured = 0, bool *none = nullptr)
{
  const cv::Mat grey = greyOf(I);
  cv::Mat padded;
  bin = mask(grey, s, rect, padded);
  std::vector<std::vector<cv::Point>> contours;
  cv::findContours(padded(cv::Rect(rect.x, rect.y, rect.width + 2, rect.height + 2)), contours, cv::RETR_EXTERNAL,
                   cv::CHAIN_APPROX_NONE, cv::Point(rect.x - 1, rect.y - 1));

  std::vector<Region> out;
  for (std::vector<cv::Point> &c : contours) {
    const double a = cv::contourArea(c);
    if (a < vpMorphContourExtractor::minRegionArea())
      continue;
    Region r{std::move(c), a, cv::Point()};
    r.first = *std::min_element(r.chain.begin(), r.chain.end(), [](const cv::Point &p, const cv::Point &q) {
      return p.y < q.y || (p.y == q.y && p.x < q.x);
    });
    out.push_back(std::move(r));
  }
  if (out.empty()) {
    if (none) {
      *none = true;
      return out;
    }
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
  for (std::size_t k = 0; k < std::min(measured, out.size()); ++k)
    measure(grey, bin, out[k]);
  return out;
}

// The regions of the whole image, as regions() gives them.
std::vector<Region> regions(const vpImage<unsigned char> &I, std::size_t measured = 0, cv::Mat *binOut = nullptr)
{
  cv::Mat bin;
  std::vector<Region> out = regions(I, segmentation(I), wholeOf(I), bin, measured);
  if (binOut)
    *binOut = bin;
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
      vpMorphContour outline(x, y);
      outline.setOwnEdges(r.outlineOwn);
      c.setOutline(outline, r.edgeBlur);
    } catch (const vpMorphException &) {
      // Not a valid outline (a sliver): the contour goes without.
    }
  }
  return c;
}

/*
  The silhouette of \e seed: alone, or joined with those of \e pieces near it (vpMorphRegionJoin, gaps up to
  joinedMaxGap() times the seed's bounding-box diagonal). A joined outline's edge is measured with the seed's grey
  levels: the bridge's pixels (background, occluder) would move the object's median and every edge with it. It
  carries no measured region: part of its area is a bridge, not the object's grey levels. \e joined, if not null,
  tells whether a piece was joined.
*/
vpMorphContour silhouette(const cv::Mat &grey, const cv::Mat &bin, Region &seed,
                          const std::vector<const Region *> &pieces, bool *joined = nullptr)
{
  const cv::Rect box = cv::boundingRect(seed.chain);
  const double maxGap = vpMorphContourExtractor::joinedMaxGap() * std::hypot(double(box.width), double(box.height));
  Region r;
  const bool any = !pieces.empty() && vpMorphRegionJoin::join(seed, pieces, maxGap, r);
  if (joined)
    *joined = any;
  if (!any) {
    measure(grey, bin, seed);
    return polygon(seed);
  }
  measure(grey, bin, seed, nullptr, true);
  measure(grey, bin, r, &seed);
  r.subArea = 0.0;
  return polygon(r);
}

// The regions, other than regs[seed], of at least joinedMinShare() of its area: the pieces it may be joined with.
std::vector<const Region *> piecesOf(const std::vector<Region> &regs, std::size_t seed, bool smallerOnly)
{
  std::vector<const Region *> out;
  for (std::size_t k = 0; k < regs.size(); ++k)
    if (k != seed && regs[k].area >= vpMorphContourExtractor::joinedMinShare() * regs[seed].area &&
        (!smallerOnly || k > seed))
      out.push_back(&regs[k]);
  return out;
}

// The polygon (x, y) clipped to the rectangle [lo, hi]^2 per axis (Sutherland-Hodgman): what of it can overlap an
// image, in coordinates that fit the raster's integers whatever the input's magnitude.
std::vector<cv::Point> clippedPixels(std::vector<cv::Point2d> poly, const cv::Point2d &lo, const cv::Point2d &hi)
{
  for (int side = 0; side < 4 && !poly.empty(); ++side) {
    const bool isX = side % 2 == 0, isLow = side < 2;
    const double bound = isX ? (isLow ? lo.x : hi.x) : (isLow ? lo.y : hi.y);
    auto in = [&](const cv::Point2d &p) { return isLow ? (isX ? p.x : p.y) >= bound : (isX ? p.x : p.y) <= bound; };
    std::vector<cv::Point2d> out;
    for (std::size_t k = 0; k < poly.size(); ++k) {
      const cv::Point2d &a = poly[(k + poly.size() - 1) % poly.size()], &b = poly[k];
      if (in(a) != in(b)) {
        const double t = ((isX ? a.x : a.y) - bound) / ((isX ? a.x : a.y) - (isX ? b.x : b.y));
        out.push_back(a + t * (b - a));
      }
      if (in(b))
        out.push_back(b);
    }
    poly.swap(out);
  }
  std::vector<cv::Point> px;
  for (const cv::Point2d &p : poly)
    px.emplace_back(static_cast<int>(std::lround(p.x)), static_cast<int>(std::lround(p.y)));
  return px;
}

// Per region, how many of its pixels lie inside the polygon \e poly (pixels, its box \e pbox in the image).
std::vector<long> overlaps(const std::vector<Region> &regs, const std::vector<cv::Point> &poly, const cv::Rect &pbox)
{
  std::vector<long> inside(regs.size(), 0);
  if (pbox.area() == 0)
    return inside;
  cv::Mat was = cv::Mat::zeros(pbox.size(), CV_8UC1);
  cv::fillPoly(was, std::vector<std::vector<cv::Point>>{poly}, cv::Scalar(255), cv::LINE_8, 0, -pbox.tl());
  for (std::size_t k = 0; k < regs.size(); ++k) {
    const cv::Rect box = cv::boundingRect(regs[k].chain);
    const cv::Rect common = box & pbox;
    if (common.area() == 0)
      continue;
    cv::Mat is = cv::Mat::zeros(box.size(), CV_8UC1);
    cv::drawContours(is, std::vector<std::vector<cv::Point>>{regs[k].chain}, 0, cv::Scalar(255), cv::FILLED, cv::LINE_8,
                     cv::noArray(), INT_MAX, -box.tl());
    inside[k] = cv::countNonZero(is(common - box.tl()) & was(common - pbox.tl()));
  }
  return inside;
}
} // namespace

vpMorphContour vpMorphContourExtractor::extractJoined(const vpImage<unsigned char> &I) const
{
  cv::Mat bin;
  std::vector<Region> regs = regions(I, 0, &bin); // measured by silhouette(): whole, or its levels only when joined
  return silhouette(greyOf(I), bin, regs.front(), piecesOf(regs, 0, true));
}

std::vector<vpMorphContour> vpMorphContourExtractor::extractCandidates(const vpImage<unsigned char> &I) const
{
  cv::Mat bin;
  std::vector<Region> regs = regions(I, 0, &bin);
  const cv::Mat grey = greyOf(I);
  std::vector<vpMorphContour> out;
  auto add = [&](std::size_t k) {
    bool joined = false;
    out.push_back(silhouette(grey, bin, regs[k], piecesOf(regs, k, true), &joined));
    if (joined)
      out.push_back(silhouette(grey, bin, regs[k], {}));
  };
  std::size_t k = 0;
  for (; k < regs.size() && regs[k].area >= joinedMinShare() * regs.front().area; ++k)
    add(k);
  // The largest region seen whole too, whatever its size: the largest may be one the image's border cuts (the floor
  // beyond the plane's edge), whose area says nothing of the object's.
  const cv::Rect image(0, 0, bin.cols, bin.rows);
  const auto whole = std::find_if(regs.begin(), regs.end(), [&image](const Region &r) {
    const cv::Rect box = cv::boundingRect(r.chain);
    return box.x > image.x && box.y > image.y && box.br().x < image.br().x && box.br().y < image.br().y;
  });
  if (whole != regs.end() && static_cast<std::size_t>(whole - regs.begin()) >= k)
    add(static_cast<std::size_t>(whole - regs.begin()));
  return out;
}

std::vector<vpMorphContour> vpMorphContourExtractor::extractCandidates(const vpImage<vpRGBa> &I) const
{
  return extractCandidates(toGrey(I));
}

vpMorphContour vpMorphContourExtractor::extractJoined(const vpImage<unsigned char> &I,
                                                      const vpMorphContour &previous) const
{
  if (previous.empty())
    return extractJoined(I);
  if (previous.units() != vpMorphContour::PIXEL)
    throw vpMorphException(vpMorphException::badParameterError,
                           "vpMorphContourExtractor::extractJoined: the previous contour must be in PIXEL units");
  // The previous outline's pixels, over its box clipped to the image (a pixel of margin all round).
  std::vector<cv::Point2d> outline;
  outline.reserve(previous.size());
  for (std::size_t k = 0; k < previous.size(); ++k)
    outline.emplace_back(previous.x(k), previous.y(k));
  const cv::Rect image = wholeOf(I);
  const std::vector<cv::Point> poly = clippedPixels(outline, {-1.0, -1.0}, {double(image.width), double(image.height)});
  const cv::Rect pbox = poly.empty() ? cv::Rect() : cv::boundingRect(poly) & image;
  const Segmentation seg = segmentation(I);
  cv::Mat bin;
  std::vector<Region> regs;
  std::vector<long> inside;
  // First in a window about where the object was (classifying and tracing cost in proportion to the pixels, of which
  // the object's are often a small part), grown by a quarter of the box's diagonal for the motion since and by the
  // reach of the regions' measure. Its answer is the whole image's when every region that overlaps where the object was
  // lies in the window with that reach around it (a region is then the same in both); else the whole image is traced.
  // So the margin sets the cost, never the result.
  const int reach = vpMorphRegionMeasure::kReach;
  const int margin = reach + static_cast<int>(std::ceil(0.25 * std::hypot(double(pbox.width), double(pbox.height))));
  const cv::Rect window =
      pbox.area() > 0
          ? cv::Rect(pbox.x - margin, pbox.y - margin, pbox.width + 2 * margin, pbox.height + 2 * margin) & image
          : image;
  if (window != image) {
    bool none = false;
    regs = regions(I, seg, window, bin, 0, &none);
    inside = overlaps(regs, poly, pbox);
    bool whole = true;
    for (std::size_t k = 0; k < regs.size() && whole; ++k) {
      if (inside[k] == 0)
        continue;
      const cv::Rect box = cv::boundingRect(regs[k].chain);
      const cv::Rect read =
          cv::Rect(box.x - reach, box.y - reach, box.width + 2 * reach, box.height + 2 * reach) & image;
      whole = (read & window) == read;
    }
    if (none || !whole || std::none_of(inside.begin(), inside.end(), [](long n) { return n > 0; }))
      regs.clear();
  }
  if (regs.empty()) {
    regs = regions(I, seg, image, bin);
    inside = overlaps(regs, poly, pbox);
  }
  // The object's regions: those that overlap where it was (a distractor lies elsewhere); the largest is the seed.
  const std::size_t seed = static_cast<std::size_t>(
      std::find_if(inside.begin(), inside.end(), [](long n) { return n > 0; }) - inside.begin());
  if (seed == regs.size())
    fail("no object region where the previous outline was (the object left the view or was lost)");
  std::vector<const Region *> pieces;
  for (const Region *p : piecesOf(regs, seed, true))
    if (inside[static_cast<std::size_t>(p - regs.data())] > 0)
      pieces.push_back(p);
  return silhouette(greyOf(I), bin, regs[seed], pieces);
}

vpMorphContour vpMorphContourExtractor::extractJoined(const vpImage<vpRGBa> &I, const vpMorphContour &previous) const
{
  return extractJoined(toGrey(I), previous);
}

vpMorphContour vpMorphContourExtractor::extractJoined(const vpImage<vpRGBa> &I) const
{
  return extractJoined(toGrey(I));
}

vpImage<unsigned char> vpMorphContourExtractor::objectMask(const vpImage<unsigned char> &I) const
{
  cv::Mat padded;
  const cv::Mat bin = mask(greyOf(I), segmentation(I), wholeOf(I), padded);
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

std::vector<std::vector<vpImagePoint>> vpMorphContourExtractor::boundaries(const vpImage<unsigned char> &I) const
{
  std::vector<std::vector<vpImagePoint>> out;
  for (const Region &r : regions(I))
    out.push_back(toVisp(r.chain));
  return out;
}

std::vector<std::vector<vpImagePoint>> vpMorphContourExtractor::boundaries(const vpImage<vpRGBa> &I) const
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
