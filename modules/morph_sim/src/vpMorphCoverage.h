/*!
  \file vpMorphCoverage.h
  \brief Internal: an object image (black on white) as the share of each pixel the object covers, and back.
*/
#ifndef VP_MORPH_COVERAGE_H
#define VP_MORPH_COVERAGE_H

#include <algorithm>
#include <cmath>

#include <opencv2/core.hpp>

#include <visp3/core/vpImage.h>

namespace vpMorphCoverage
{
//! The share in [0, 1] of each pixel that a black-on-white image's object covers.
inline cv::Mat1f fromImage(const vpImage<unsigned char> &I)
{
  cv::Mat1f c(static_cast<int>(I.getHeight()), static_cast<int>(I.getWidth()));
  for (int y = 0; y < c.rows; ++y)
    for (int x = 0; x < c.cols; ++x)
      c(y, x) = 1.0f - I[y][x] / 255.0f;
  return c;
}

//! The black-on-white image of a coverage map (clamped to [0, 1]).
inline vpImage<unsigned char> toImage(const cv::Mat1f &c)
{
  vpImage<unsigned char> I(static_cast<unsigned int>(c.rows), static_cast<unsigned int>(c.cols));
  for (int y = 0; y < c.rows; ++y)
    for (int x = 0; x < c.cols; ++x)
      I[y][x] = static_cast<unsigned char>(std::lround(255.0 * (1.0 - std::min(1.0f, std::max(0.0f, c(y, x))))));
  return I;
}
} // namespace vpMorphCoverage

#endif
