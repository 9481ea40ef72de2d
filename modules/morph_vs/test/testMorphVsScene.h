// Synthetic planar scene shared by the morph_vs tests: an asymmetric planar object polygon (about 15 cm) in the
// plane z = 0 of its frame, projected through a pinhole camera (640x480, px = py = 800), no rendering.
#ifndef TEST_MORPH_VS_SCENE_H
#define TEST_MORPH_VS_SCENE_H

#include <cmath>
#include <vector>

#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpThetaUVector.h>
#include <visp3/morph/vpMorphContour.h>

namespace vpMorphVsTest
{
//! The intrinsics of the benchmark protocol (DESIGN.md).
inline vpCameraParameters camera() { return vpCameraParameters(800, 800, 320, 240); }

//! Object vertices (metres, z = 0): an L-shaped bracket with a chamfer, no symmetry.
inline std::vector<vpColVector> objectPoints()
{
  const double xy[][2] = {{-0.07, -0.05}, {0.08, -0.05}, {0.08, -0.01}, {0.02, -0.01}, {0.02, 0.04},
                          {-0.01, 0.07},  {-0.03, 0.07}, {-0.03, 0.02}, {-0.07, 0.02}};
  std::vector<vpColVector> P;
  for (const auto &p : xy) {
    vpColVector X(4);
    X[0] = p[0];
    X[1] = p[1];
    X[2] = 0;
    X[3] = 1;
    P.push_back(X);
  }
  return P;
}

//! Camera looking straight at the object plane at depth Z, object rotated by thetaDeg about the optical axis
//! and offset by (tx, ty) in the camera frame.
inline vpHomogeneousMatrix planarPose(double thetaDeg, double tx, double ty, double Z = 0.5)
{
  return vpHomogeneousMatrix(tx, ty, Z, 0, 0, vpMath::rad(thetaDeg));
}

//! Normalised contour of the object seen from cMo; empty if a vertex is not in front of the camera.
inline vpMorphContour projectNormalized(const vpHomogeneousMatrix &cMo)
{
  std::vector<double> x, y;
  for (const vpColVector &P : objectPoints()) {
    const vpColVector X = cMo * P;
    if (X[2] <= 1e-6)
      return vpMorphContour();
    x.push_back(X[0] / X[2]);
    y.push_back(X[1] / X[2]);
  }
  return vpMorphContour(x, y, vpMorphContour::NORMALIZED);
}

//! Pixel contour of the object seen from cMo with the (true) intrinsics \e cam.
inline vpMorphContour projectPixels(const vpHomogeneousMatrix &cMo, const vpCameraParameters &cam = camera())
{
  const vpMorphContour n = projectNormalized(cMo);
  return n.empty() ? n : n.toPixels(cam);
}

//! Depth of the object frame origin in the camera frame.
inline double depth(const vpHomogeneousMatrix &cMo) { return cMo[2][3]; }

//! Pose error between two camera poses (translation in metres, rotation in degrees).
inline void poseError(const vpHomogeneousMatrix &cMo, const vpHomogeneousMatrix &cdMo, double &t, double &rDeg)
{
  const vpHomogeneousMatrix cdMc = cdMo * cMo.inverse();
  t = cdMc.getTranslationVector().frobeniusNorm();
  rDeg = vpMath::deg(vpThetaUVector(cdMc.getRotationMatrix()).getTheta());
}
} // namespace vpMorphVsTest

#endif
