/*!
  \file vpMorphBenchPlane.h
  \brief Internal: where a pixel's ray meets the object's plane.
*/
#ifndef VP_MORPH_BENCH_PLANE_H
#define VP_MORPH_BENCH_PLANE_H

#include <cmath>

#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpColVector.h>
#include <visp3/core/vpHomogeneousMatrix.h>

namespace vpMorphBenchPlane
{
//! Where the ray of pixel (u, v) meets the plane z = 0 of the object seen from cMo (object frame, m); false when
//! it does not, in front of the camera.
inline bool onPlane(const vpHomogeneousMatrix &cMo, const vpCameraParameters &cam, double u, double v, double &x,
                    double &y)
{
  const vpHomogeneousMatrix oMc = cMo.inverse();
  vpColVector ray(3);
  ray[0] = (u - cam.get_u0()) / cam.get_px();
  ray[1] = (v - cam.get_v0()) / cam.get_py();
  ray[2] = 1.0;
  const vpColVector d = oMc.getRotationMatrix() * ray;
  const vpTranslationVector o = oMc.getTranslationVector();
  if (std::fabs(d[2]) < 1e-12)
    return false;
  const double t = -o[2] / d[2];
  x = o[0] + t * d[0];
  y = o[1] + t * d[1];
  return t > 0;
}
} // namespace vpMorphBenchPlane

#endif
