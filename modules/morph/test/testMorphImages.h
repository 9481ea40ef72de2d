// Images shared by the morph unit tests: the largest object's boundary and the benchmark scene's square occluder.
// Include after catch.hpp.
#ifndef VP_MORPH_TEST_IMAGES_H
#define VP_MORPH_TEST_IMAGES_H

#include <algorithm>
#include <cstdlib>
#include <vector>

#include <opencv2/imgproc.hpp>

namespace vpMorphTest
{
//! The pixel boundary of the largest dark object.
inline std::vector<cv::Point> largestBoundary(const cv::Mat &src)
{
  cv::Mat bin = src < 128;
  std::vector<std::vector<cv::Point>> cs;
  cv::findContours(bin, cs, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE);
  REQUIRE_FALSE(cs.empty());
  return *std::max_element(cs.begin(), cs.end(),
                           [](const auto &a, const auto &b) { return cv::contourArea(a) < cv::contourArea(b); });
}

/*!
  Hides \e share of the object's outline behind a grey square (neither background nor object) centred on the
  outline point at \e where (fraction of the perimeter), grown until that share of the outline lies inside it: the
  benchmark scene's occluder, which bites a notch into a straight side instead of cutting it off.
*/
inline cv::Mat squareOccluder(const cv::Mat &src, double where, double share)
{
  const std::vector<cv::Point> c = largestBoundary(src);
  const cv::Point o = c[static_cast<std::size_t>(where * c.size()) % c.size()];
  int h = 1;
  for (;; ++h) {
    std::size_t in = 0;
    for (const cv::Point &p : c)
      in += (std::abs(p.x - o.x) <= h && std::abs(p.y - o.y) <= h) ? 1 : 0;
    if (in >= share * c.size())
      break;
  }
  cv::Mat out = src.clone();
  cv::rectangle(out, cv::Point(o.x - h, o.y - h), cv::Point(o.x + h, o.y + h), cv::Scalar(170), cv::FILLED);
  return out;
}
} // namespace vpMorphTest

#endif
