#include <visp3/morph/vpMorphContourExtractor.h>

#include <algorithm>
#include <sstream>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <visp3/core/vpImageConvert.h>
#include <visp3/morph/vpMorphException.h>
#include <visp3/morph/vpMorphPolygonApproximation.h>

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

// Object mask (255 = object) from Otsu's threshold and the border-minority polarity rule.
cv::Mat mask(const vpImage<unsigned char> &I)
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
  double lo = 0.0, hi = 0.0;
  cv::minMaxLoc(grey, &lo, &hi);
  if (lo == hi) {
    std::ostringstream os;
    os << "the image is uniform (every pixel is " << lo << "): no contrast to separate an object";
    fail(os.str());
  }
  cv::Mat bin;
  cv::threshold(grey, bin, 0, 255, cv::THRESH_BINARY | cv::THRESH_OTSU);

  // Polarity: the class that dominates the border is the background.
  const int rows = bin.rows, cols = bin.cols;
  long bright = 0, border = 0;
  for (int c = 0; c < cols; ++c) {
    bright += (bin.at<unsigned char>(0, c) != 0) + (bin.at<unsigned char>(rows - 1, c) != 0);
    border += 2;
  }
  for (int r = 1; r < rows - 1; ++r) {
    bright += (bin.at<unsigned char>(r, 0) != 0) + (bin.at<unsigned char>(r, cols - 1) != 0);
    border += 2;
  }
  bool objectIsBright;
  if (2 * bright != border)
    objectIsBright = 2 * bright < border;
  else
    objectIsBright = 2 * static_cast<long>(cv::countNonZero(bin)) < static_cast<long>(rows) * cols;
  if (!objectIsBright)
    cv::bitwise_not(bin, bin);
  return bin;
}

struct Region {
  std::vector<cv::Point> chain;
  double area;
  cv::Point first; // top-most, then left-most pixel: deterministic tie break
};

std::vector<Region> regions(const vpImage<unsigned char> &I)
{
  const cv::Mat bin = mask(I);
  // One pixel of background all round closes objects that touch the border.
  cv::Mat padded;
  cv::copyMakeBorder(bin, padded, 1, 1, 1, 1, cv::BORDER_CONSTANT, cv::Scalar(0));
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
} // namespace

vpImage<unsigned char> vpMorphContourExtractor::objectMask(const vpImage<unsigned char> &I) const
{
  const cv::Mat bin = mask(I);
  vpImage<unsigned char> M(I.getHeight(), I.getWidth());
  for (int r = 0; r < bin.rows; ++r)
    std::copy(bin.ptr<unsigned char>(r), bin.ptr<unsigned char>(r) + bin.cols, M[static_cast<unsigned int>(r)]);
  return M;
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
  return vpMorphPolygonApproximation::approximate(boundary(I));
}

vpMorphContour vpMorphContourExtractor::extract(const vpImage<vpRGBa> &I) const { return extract(toGrey(I)); }

std::vector<vpMorphContour> vpMorphContourExtractor::extractAll(const vpImage<unsigned char> &I) const
{
  std::vector<vpMorphContour> out;
  for (const Region &r : regions(I))
    out.push_back(vpMorphPolygonApproximation::approximate(toVisp(r.chain)));
  return out;
}

std::vector<vpMorphContour> vpMorphContourExtractor::extractAll(const vpImage<vpRGBa> &I) const
{
  return extractAll(toGrey(I));
}
