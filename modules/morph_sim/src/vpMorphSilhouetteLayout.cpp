#include <visp3/morph_sim/vpMorphSilhouetteLayout.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include <opencv2/imgproc.hpp>

#include <visp3/core/vpImageConvert.h>
#include <visp3/io/vpImageIo.h>
#include <visp3/morph/vpMorphException.h>

#include "vpMorphCoverage.h"

namespace
{
const int kSupersampling = 4; // the shape is cut at 4 x the output resolution, then averaged down

void badImage(const std::string &msg) { throw vpMorphException(vpMorphException::badImageError, msg); }

//! The object's region of \e I (0/1): the largest 8-connected region of the class that does not dominate the border.
cv::Mat1b objectMask(const vpImage<unsigned char> &I, cv::Rect &box)
{
  if (I.getWidth() < 2 || I.getHeight() < 2)
    badImage("vpMorphSilhouetteLayout: the image is empty");
  cv::Mat src;
  vpImageConvert::convert(I, src);
  double lo = 0.0, hi = 0.0;
  cv::minMaxLoc(src, &lo, &hi);
  if (hi == lo)
    badImage("vpMorphSilhouetteLayout: the image is uniform: no object");
  cv::Mat1b bin;
  cv::threshold(src, bin, 0, 1, cv::THRESH_BINARY | cv::THRESH_OTSU);
  const int w = bin.cols, h = bin.rows;
  long border = 0, ones = 0;
  for (int x = 0; x < w; ++x)
    ones += bin(0, x) + bin(h - 1, x), border += 2;
  for (int y = 1; y < h - 1; ++y)
    ones += bin(y, 0) + bin(y, w - 1), border += 2;
  const unsigned char objectClass = 2 * ones > border ? 0 : 1; // the class that does not dominate the border
  cv::Mat1b object = bin == objectClass;
  cv::Mat labels, stats, centroids;
  const int n = cv::connectedComponentsWithStats(object, labels, stats, centroids, 8, CV_32S);
  int best = 0, bestArea = 0;
  for (int k = 1; k < n; ++k)
    if (stats.at<int>(k, cv::CC_STAT_AREA) > bestArea) {
      bestArea = stats.at<int>(k, cv::CC_STAT_AREA);
      best = k;
    }
  // Fewer pixels than a 3 x 3 square is no shape to servo on.
  if (best == 0 || bestArea < 9)
    badImage("vpMorphSilhouetteLayout: no object region in the image");
  box = cv::Rect(stats.at<int>(best, cv::CC_STAT_LEFT), stats.at<int>(best, cv::CC_STAT_TOP),
                 stats.at<int>(best, cv::CC_STAT_WIDTH), stats.at<int>(best, cv::CC_STAT_HEIGHT));
  cv::Mat1b out = labels == best;
  return out / 255;
}

} // namespace

vpMorphSilhouetteLayout::vpMorphSilhouetteLayout(const vpImage<unsigned char> &source, unsigned int objectPixels,
                                                 unsigned int margin)
  : m_objectPixels(objectPixels), m_margin(margin), m_srcWidth(source.getWidth()), m_srcHeight(source.getHeight())
{
  if (objectPixels < 16 || objectPixels > 4000 || margin > 1000)
    throw vpMorphException(
        vpMorphException::badParameterError,
        "vpMorphSilhouetteLayout: the object's side must be 16..4000 px and the margin at most 1000");
  cv::Rect box;
  objectMask(source, box);
  m_scale = static_cast<double>(objectPixels) / std::max(box.width, box.height);
  // Continuous coordinates (a pixel spans [i, i + 1)): the box's centre goes to the canvas's.
  const double side = objectPixels + 2.0 * margin;
  m_offsetX = 0.5 * side - m_scale * (box.x + 0.5 * box.width);
  m_offsetY = 0.5 * side - m_scale * (box.y + 0.5 * box.height);
  m_image = apply(source);
}

vpImage<unsigned char> vpMorphSilhouetteLayout::apply(const vpImage<unsigned char> &other) const
{
  if (other.getWidth() != m_srcWidth || other.getHeight() != m_srcHeight)
    throw vpMorphException(vpMorphException::badParameterError,
                           "vpMorphSilhouetteLayout::apply: the image is not of the template's size");
  cv::Rect box;
  cv::Mat1f mask;
  objectMask(other, box).convertTo(mask, CV_32F);
  const int side = static_cast<int>(m_objectPixels + 2 * m_margin), K = kSupersampling;
  cv::Mat1f hi(side * K, side * K, 0.0f);
  const double s = K * m_scale;
  if (s >= 1.0) {
    // Pixel centres: U + 0.5 = s (x + 0.5) + K offset.
    const cv::Matx23d A(s, 0.0, K * m_offsetX + 0.5 * s - 0.5, 0.0, s, K * m_offsetY + 0.5 * s - 0.5);
    cv::warpAffine(mask, hi, A, hi.size(), cv::INTER_LINEAR, cv::BORDER_CONSTANT, 0.0);
  } else {
    // Shrinking: area averaging of the whole source, pasted at its place (rounded to a sub-sample).
    cv::Mat1f small;
    const int sw = std::max(1, static_cast<int>(std::lround(mask.cols * s)));
    const int sh = std::max(1, static_cast<int>(std::lround(mask.rows * s)));
    cv::resize(mask, small, cv::Size(sw, sh), 0, 0, cv::INTER_AREA);
    const int ox = static_cast<int>(std::lround(K * m_offsetX)), oy = static_cast<int>(std::lround(K * m_offsetY));
    const cv::Rect dst = cv::Rect(ox, oy, sw, sh) & cv::Rect(0, 0, hi.cols, hi.rows);
    if (dst.area() > 0)
      small(cv::Rect(dst.x - ox, dst.y - oy, dst.width, dst.height)).copyTo(hi(dst));
  }
  cv::Mat1f cut;
  cv::threshold(hi, cut, 0.5, 1.0, cv::THRESH_BINARY);
  cv::Mat1f coverage;
  cv::resize(cut, coverage, cv::Size(side, side), 0, 0, cv::INTER_AREA);
  return vpMorphCoverage::toImage(coverage);
}

vpImage<unsigned char> vpMorphSilhouetteLayout::roughened(const vpImage<unsigned char> &image, unsigned int lowPixels)
{
  if (lowPixels < 4)
    throw vpMorphException(vpMorphException::badParameterError,
                           "vpMorphSilhouetteLayout::roughened: the low resolution must be at least 4 pixels");
  const cv::Mat1f coverage = vpMorphCoverage::fromImage(image);
  const cv::Mat1b inside = coverage > 0.5f;
  const cv::Rect box = inside.empty() ? cv::Rect() : cv::boundingRect(inside);
  if (static_cast<unsigned int>(std::max(box.width, box.height)) <= lowPixels)
    badImage("vpMorphSilhouetteLayout::roughened: no object larger than the low resolution");
  const double r = static_cast<double>(lowPixels) / std::max(box.width, box.height);
  cv::Mat1f low, cut, back;
  cv::resize(coverage, low, cv::Size(), r, r, cv::INTER_AREA);
  cv::threshold(low, cut, 0.5, 1.0, cv::THRESH_BINARY);
  cv::resize(cut, back, coverage.size(), 0, 0, cv::INTER_NEAREST);
  return vpMorphCoverage::toImage(back);
}

vpImage<unsigned char> vpMorphSilhouetteLayout::read(const std::string &path)
{
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw vpMorphException(vpMorphException::notFoundError, "vpMorphSilhouetteLayout: no image file '" + path + "'");
  vpImage<unsigned char> I;
  try {
    vpImageIo::read(I, path);
  } catch (const vpException &e) {
    throw vpMorphException(vpMorphException::ioError,
                           "vpMorphSilhouetteLayout: cannot read image '" + path + "': " + e.getStringMessage());
  }
  if (I.getSize() == 0)
    throw vpMorphException(vpMorphException::ioError, "vpMorphSilhouetteLayout: cannot read image '" + path + "'");
  return I;
}
