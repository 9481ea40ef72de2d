/*!
  \file fuzz_servo.cpp
  \brief Fuzz target: vpServoMorph and vpFeatureMorph fed arbitrary contours, in a short control loop.

  Input: a flags byte (control law, rigid path, online calibration, jitter), the desired depth, gain and
  sub-goal count, the target polygon (3 to 32 vertices, vpFuzzInput::coordinate), then up to 8 iterations, each a
  mode byte and its data: the target lost (empty contour), an arbitrary polygon, or the target moved by a
  similarity (any rotation, translation, scale 0.5-2.5) with optional per-vertex jitter, as a real loop sees it.
  A vpException from a setter or from a contour constructor is a correct outcome. The documented contract of
  vpServoMorph must hold at every iteration: a 6-vector, finite ("zero, never NaN"), zero whenever the status
  is not MOVING or SUBGOAL_REACHED (a hold or a stop), and a finite hand-eye estimate.
  vpFeatureMorph built on the same contours must give a finite 4-vector error and a finite 4x6 interaction
  matrix, or refuse the contour with an exception.
*/
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <vector>

#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpColVector.h>
#include <visp3/core/vpException.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpMatrix.h>
#include <visp3/morph/vpMorphContour.h>
#include <visp3/morph_vs/vpFeatureMorph.h>
#include <visp3/morph_vs/vpServoMorph.h>

#include "vpFuzzInput.h"

namespace
{
bool allFinite(const vpColVector &v)
{
  for (unsigned int i = 0; i < v.getRows(); ++i)
    if (!std::isfinite(v[i]))
      return false;
  return true;
}

bool allFinite(const vpMatrix &M)
{
  for (unsigned int i = 0; i < M.getRows(); ++i)
    for (unsigned int j = 0; j < M.getCols(); ++j)
      if (!std::isfinite(M[i][j]))
        return false;
  return true;
}

bool readPolygon(vpFuzzInput &in, std::size_t count, double scale, vpMorphContour &c)
{
  std::vector<double> x(count), y(count);
  for (std::size_t k = 0; k < count; ++k) {
    x[k] = 320.0 + in.coordinate(scale);
    y[k] = 240.0 + in.coordinate(scale);
  }
  try {
    c = vpMorphContour(x, y);
  } catch (const vpException &) {
    return false;
  }
  return true;
}

void checkFeature(const vpMorphContour &current, const vpFeatureMorph &sd, const vpCameraParameters &cam, double Z)
{
  vpFeatureMorph s;
  try {
    s.buildFrom(current, cam, Z);
  } catch (const vpException &) {
    return; // refused with a message
  }
  vpColVector e;
  vpMatrix L;
  try {
    e = s.error(sd);
    L = s.interaction();
  } catch (const vpException &) {
    return;
  }
  if (e.getRows() == 4 && !allFinite(e))
    std::fprintf(stderr, "error (%g, %g, %g, %g), fit theta %g scale %g\n", e[0], e[1], e[2], e[3],
                 s.getAlignment().transform.theta(), s.getAlignment().transform.scale());
  VP_FUZZ_CHECK(e.getRows() == 4 && allFinite(e), "vpFeatureMorph::error() is a finite 4-vector");
  VP_FUZZ_CHECK(L.getRows() == 4 && L.getCols() == 6 && allFinite(L),
                "vpFeatureMorph::interaction() is a finite 4x6 matrix");
}
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  vpFuzzInput in(data, size);
  const uint8_t flags = in.byte();
  static const double depths[] = {0.5, 0.3, 1.0, 2.0, 1e-6, 1e6, 0.0, -0.5};
  const double Zd = depths[in.byte() % 8];
  const double gain = (1 + in.byte()) / 256.0;
  const std::size_t nSub = in.range(0, 12);
  const double scale = in.scale();
  const vpCameraParameters cam(800, 800, 320, 240);

  vpMorphContour target;
  if (!readPolygon(in, in.range(3, 32), scale, target))
    return 0;

  vpServoMorph servo;
  servo.setCameraParameters(cam);
  servo.set_eMc(vpHomogeneousMatrix(0.01, -0.02, 0.1, 0.0, 0.0, 0.1));
  servo.setControlLaw((flags & 1) ? vpServoMorph::STOCK_VPSERVO : vpServoMorph::HOMOGENEOUS_TRANSFORMS);
  servo.getPlanner().setRigidPath((flags & 2) ? vpMorphSubGoalPlanner::ABOUT_OBJECT_CENTROID
                                              : vpMorphSubGoalPlanner::CAMERA_STRAIGHT_LINE);
  servo.setOnlineCalibration((flags & 4) == 0);
  servo.getPlanner().setSubGoalCount(nSub);
  servo.setGain(gain);
  try {
    servo.setTarget(target, Zd);
  } catch (const vpException &) {
    return 0; // bad depth
  }
  vpFeatureMorph sd;
  try {
    sd.buildFrom(target, cam, Zd);
  } catch (const vpException &) {
    sd = vpFeatureMorph(); // refused: the feature checks below are skipped
  }

  const std::size_t iterations = in.range(1, 8);
  for (std::size_t it = 0; it < iterations; ++it) {
    const uint8_t mode = in.byte();
    vpMorphContour current;
    if (mode % 8 == 0) {
      // target lost: the empty contour
    } else if (mode % 8 == 1) {
      if (!readPolygon(in, in.range(3, 32), scale, current))
        continue;
    } else {
      const double theta = in.byte() * (2.0 * M_PI / 256.0);
      const double tx = static_cast<int8_t>(in.byte()) * 2.0, ty = static_cast<int8_t>(in.byte()) * 2.0;
      const double s = 0.5 + in.byte() / 128.0;
      try {
        current = target.transformed(theta, tx, ty, s);
        if (flags & 8) {
          std::vector<double> x = current.xs(), y = current.ys();
          for (std::size_t k = 0; k < x.size(); ++k) {
            x[k] += static_cast<int8_t>(in.byte()) / 32.0;
            y[k] += static_cast<int8_t>(in.byte()) / 32.0;
          }
          current = vpMorphContour(x, y);
        }
      } catch (const vpException &) {
        continue;
      }
    }
    const vpColVector v = servo.computeControlLaw(current);
    VP_FUZZ_CHECK(v.getRows() == 6, "the velocity has 6 components");
    VP_FUZZ_CHECK(allFinite(v), "vpServoMorph never returns a non-finite velocity");
    VP_FUZZ_CHECK(allFinite(servo.getCameraVelocity()), "the camera velocity is finite");
    const vpServoMorph::Status st = servo.getStatus();
    if (st != vpServoMorph::MOVING && st != vpServoMorph::SUBGOAL_REACHED)
      VP_FUZZ_CHECK(v.frobeniusNorm() == 0.0, "the velocity is zero when the servo stops");
    const vpHomogeneousMatrix eMc = servo.get_eMc();
    for (unsigned int i = 0; i < 4; ++i)
      for (unsigned int j = 0; j < 4; ++j)
        VP_FUZZ_CHECK(std::isfinite(eMc[i][j]), "the hand-eye estimate stays finite");
    if (!current.empty() && sd.isBuilt())
      checkFeature(current, sd, cam, Zd);
  }
  return 0;
}
