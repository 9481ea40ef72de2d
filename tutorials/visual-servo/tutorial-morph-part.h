// Shared by the two visual-servo tutorials: the planar L-shaped part they servo on, and its contour as a camera sees
// it. Header-only, tutorial code, not a library.
#ifndef TUTORIAL_MORPH_PART_H
#define TUTORIAL_MORPH_PART_H

#include <vector>

#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpPoint.h>
#include <visp3/morph/vpMorphContour.h>

namespace tutorial
{
//! The part's corners (metres, z = 0 in its frame).
inline std::vector<vpPoint> part()
{
  const double P[][2] = {{-0.07, -0.05}, {0.08, -0.05}, {0.08, -0.01}, {0.02, -0.01}, {0.02, 0.04},
                         {-0.01, 0.07},  {-0.03, 0.07}, {-0.03, 0.02}, {-0.07, 0.02}};
  std::vector<vpPoint> points;
  for (const auto &p : P)
    points.emplace_back(p[0], p[1], 0);
  return points;
}

//! Its contour as the camera at cMo sees it, in pixels.
inline vpMorphContour project(const vpHomogeneousMatrix &cMo, const vpCameraParameters &cam)
{
  std::vector<double> x, y;
  for (vpPoint p : part()) {
    p.project(cMo);
    x.push_back(p.get_x());
    y.push_back(p.get_y());
  }
  return vpMorphContour(x, y, vpMorphContour::NORMALIZED).toPixels(cam);
}
} // namespace tutorial

#endif
