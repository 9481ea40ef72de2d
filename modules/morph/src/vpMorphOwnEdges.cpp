#include "vpMorphOwnEdges.h"

#include <cmath>

#include <Eigen/Dense>
#include <opencv2/imgproc.hpp>

#include "vpMorphAffineLevel.h"
#include "vpMorphLevelSpread.h"

std::vector<bool> vpMorphOwnEdges(const cv::Mat &g, const cv::Mat &object, const cv::Point &tl,
                                  const std::vector<cv::Point2d> &points, const std::vector<cv::Point2d> &outward,
                                  double beyond, double reach)
{
  const std::size_t n = points.size();
  // A patch lies up to beyond + 1 px past its point, and the object pixels within reach of it count: both views are
  // widened by that much into the images they were cut from (a box drawn close about the object would cut off the
  // patches of its outermost points, which only the image's own border may do).
  const int r = int(std::ceil(reach)), m = int(std::ceil(beyond)) + 2 + r;
  cv::Mat G = g, O = object;
  G.adjustROI(m, m, m, m);
  O.adjustROI(m, m, m, m);
  cv::Size whole;
  cv::Point at, atWide, atObject, atObjectWide;
  g.locateROI(whole, at);
  G.locateROI(whole, atWide);
  object.locateROI(whole, atObject);
  O.locateROI(whole, atObjectWide);
  const cv::Point shift = at - atWide; // where g lies in G
  if (O.size() != G.size() || atObject - atObjectWide != shift) {
    O = cv::Mat::zeros(G.size(), CV_8UC1); // not cut alike: no object pixel known beyond the box
    object.copyTo(O(cv::Rect(shift, object.size())));
  }
  const cv::Point tlWide = tl - shift;
  cv::Mat near;
  cv::dilate(O, near, cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * r + 1, 2 * r + 1)));
  enum { OFF_IMAGE, OBJECT, MEASURED };
  std::vector<int> state(n, OFF_IMAGE);
  std::vector<double> mean(n, 0.0);
  for (std::size_t k = 0; k < n; ++k) {
    const int c0 = int(std::lround(points[k].x + beyond * outward[k].x)) - tlWide.x,
              r0 = int(std::lround(points[k].y + beyond * outward[k].y)) - tlWide.y;
    if (c0 < 1 || r0 < 1 || c0 + 1 >= G.cols || r0 + 1 >= G.rows)
      continue;
    int sum = 0;
    state[k] = MEASURED;
    for (int y = r0 - 1; y <= r0 + 1; ++y)
      for (int x = c0 - 1; x <= c0 + 1; ++x) {
        sum += G.at<unsigned char>(y, x);
        if (near.at<unsigned char>(y, x))
          state[k] = OBJECT;
      }
    mean[k] = sum / 9.0;
  }
  // The measured means' residuals about a level, and their 4 sigma.
  std::vector<double> res(n, 0.0);
  auto residuals = [&](const Eigen::Vector3d &p) {
    std::vector<double> below, above;
    for (std::size_t k = 0; k < n; ++k)
      if (state[k] == MEASURED) {
        res[k] = mean[k] - (p(0) + p(1) * points[k].x + p(2) * points[k].y);
        (res[k] < 0.0 ? below : above).push_back(std::fabs(res[k]));
      }
    return vpMorphLevelSpread::fourSigma(vpMorphLevelSpread::oneSidedMad(vpMorphLevelSpread::median(below), false,
                                                                         vpMorphLevelSpread::median(above), false));
  };
  std::vector<double> measured;
  for (std::size_t k = 0; k < n; ++k)
    if (state[k] == MEASURED)
      measured.push_back(mean[k]);
  std::vector<bool> own(n);
  for (std::size_t k = 0; k < n; ++k)
    own[k] = state[k] == OBJECT;
  if (measured.empty())
    return own;
  Eigen::Vector3d level(vpMorphLevelSpread::median(measured), 0.0, 0.0);
  double within = residuals(level);
  for (int pass = 0; pass < 2; ++pass) {
    vpMorphAffineLevel::Sums sums;
    for (std::size_t k = 0; k < n; ++k)
      if (state[k] == MEASURED && std::fabs(res[k]) <= within)
        sums.add(points[k].x, points[k].y, mean[k]);
    Eigen::Vector3d p;
    if (!vpMorphAffineLevel::slope(sums, 1.0, p))
      p = Eigen::Vector3d(sums.g / sums.n, 0.0, 0.0); // the median's own mean is within: n > 0
    level = p;
    within = residuals(level);
  }
  for (std::size_t k = 0; k < n; ++k)
    if (state[k] == MEASURED)
      own[k] = std::fabs(res[k]) <= within;
  return own;
}
