// Shared by the tutorials that reproduce the paper's figures (tutorials/paper/): command line, the simulated
// bench (scene, Viper850, controller) and the real image pipeline. Header-only, tutorial code, not a library.
#ifndef TUTORIAL_PAPER_COMMON_H
#define TUTORIAL_PAPER_COMMON_H

#include <cmath>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpImage.h>
#include <visp3/core/vpImageConvert.h>
#include <visp3/core/vpImageDraw.h>
#include <visp3/core/vpIoTools.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpThetaUVector.h>
#include <visp3/morph/vpMorph.h>
#include <visp3/morph/vpMorphDrawing.h>
#include <visp3/morph/vpMorphException.h>
#include <visp3/morph_sim/vpMorphPlanarScene.h>
#include <visp3/morph_sim/vpMorphSimRobot.h>
#include <visp3/morph_sim/vpMorphTagPoseEstimator.h>
#include <visp3/morph_vs/vpServoMorph.h>

#include "tutorial-display.h"
#include "tutorial-servo-windows.h"

namespace paper
{
//! Takes "[--out DIR]" from the arguments tutorial::Viewer left (its -c, -d, --save-display taken out). Returns false
//! (after printing the usage) on anything else; creates DIR.
inline bool parseArgs(const char *program, const std::vector<std::string> &args, std::string &out)
{
  out = ".";
  for (std::size_t i = 0; i < args.size(); ++i) {
    if (args[i] == "--out" && i + 1 < args.size()) {
      out = args[++i];
      continue;
    }
    std::cout << "Usage: " << program << " " << tutorial::Viewer::options()
              << " [--out DIR]  (PNG and CSV files go to DIR, default .)" << std::endl;
    return false;
  }
  vpIoTools::makeDirectory(out);
  return true;
}

//! The desired pose of every figure: optical axis normal to the object plane, 0.5 m away, object upright.
inline vpHomogeneousMatrix desiredPose() { return vpHomogeneousMatrix(0, 0, 0.5, 0, 0, 0); }

/*!
  The real pipeline of the bench, from a camera pose to the contour the controller gets: render the camera image,
  detect the AprilTag, paint it out (it is a larger dark region than the object), extract the largest object's
  contour. \e I receives the rendered (unmasked) image, for pictures. The simulator's truth is never used here.
*/
inline vpMorphContour observe(const vpMorphPlanarScene &scene, const vpMorphTagPoseEstimator &tag,
                              const vpHomogeneousMatrix &cMo, vpImage<unsigned char> &I)
{
  scene.render(cMo, I);
  vpHomogeneousMatrix cMo_tag;
  std::vector<vpImagePoint> corners;
  tag.estimate(I, cMo_tag, &corners);                     // not found: nothing to mask
  return vpMorphTagPoseEstimator::silhouette(I, corners); // empty when no object: the servo reports TARGET_LOST
}

//! Rotation residual (rad, signed) and translation residual (px) of a real contour to a (virtual) goal contour,
//! measured by a fresh morph between them (the paper's pose difference "from the morphs"): its correspondence,
//! then the robust similarity fit with the half-pixel resolution of contours extracted from images.
inline void morphResidual(const vpMorphContour &real, const vpMorphContour &goal, double &rad, double &px)
{
  const vpMorph morph(real, goal);
  const vpMorphRigidTransform T = vpMorphRigidTransform::fitLeastSquares(real, goal, morph.correspondence(), true,
                                                                         vpMorphRigidTransform::TUKEY, 30, 0.5);
  rad = T.theta();
  px = std::hypot(T.tx(), T.ty());
}

/*!
  Pose error against the desired pose, from the simulator's truth, measured at the object (where the tool acts):
  the displacement of the object origin between the two camera frames, split into its part in the image plane
  (mm) and along the optical axis (depth, mm), and the angle of the relative rotation (deg).
*/
struct PoseError
{
  double inPlaneMm = 0, depthMm = 0, deg = 0;
};
inline PoseError truthError(const vpHomogeneousMatrix &cMo, const vpHomogeneousMatrix &cdMo)
{
  PoseError e;
  const vpTranslationVector d = cMo.getTranslationVector() - cdMo.getTranslationVector();
  e.inPlaneMm = std::hypot(d[0], d[1]) * 1000.0;
  e.depthMm = std::fabs(d[2]) * 1000.0;
  e.deg = vpMath::deg(vpThetaUVector((cdMo * cMo.inverse()).getRotationMatrix()).getTheta());
  return e;
}

/*!
  The acceptance test of every figure: converged, and within 1 mm in the image plane and 0.5 deg of the desired
  pose (simulator truth). Depth is held to 3 mm only: it is observed through the contour's scale, and contours
  extracted from images (vertices on the pixel grid) resolve the scale of a 15 cm object at 0.5 m to about
  0.4 %, i.e. 2 mm of depth (measured: a 1 mm depth change can give a scale of the wrong sign).
*/
inline bool aligned(const vpServoMorph &servo, const PoseError &e)
{
  return servo.getStatus() == vpServoMorph::CONVERGED && e.inPlaneMm < 1.0 && e.deg < 0.5 && e.depthMm < 3.0;
}

//! The controller of every figure: the paper's, 8 virtual images, switching at 0.10 rad and 5 px (the defaults),
//! half of the Eq. 11 step per period, and a hand-eye estimate 5 deg and 14 mm off (in the plane of the task, the
//! part its moves observe), corrected on line.
inline void setUpController(vpServoMorph &servo, const vpMorphSimRobot &robot, const vpCameraParameters &cam,
                            const vpMorphContour &storedView, double Zd, double dt)
{
  servo.setCameraParameters(cam);
  servo.set_eMc(robot.eMcTrue() * vpHomogeneousMatrix(0.01, -0.01, 0, 0, 0, vpMath::rad(5)));
  servo.getPlanner().setSubGoalCount(8);
  servo.setGain(0.5);
  servo.setSamplingTime(dt);
  servo.setTarget(storedView, Zd);
}

/*!
  The simulated bench of the paper's experiments: the object (15 cm) and an AprilTag on a plane, a Viper850 whose
  camera sees them from the desired pose in its reference configuration, and the stored view (the goal): the
  contour extracted from the image taken there. The camera gives an image every dt; the robot's own controller
  resolves the commanded end-effector twist into joint velocities ten times faster (as real arms do), so that the
  executed move follows the commanded screw (one Euler step of 0.1 s over an 18 deg turn tilts the camera, which
  the planar task can neither see nor correct).
*/
struct Bench
{
  static constexpr double dt = 0.1;
  static constexpr int substeps = 10;

  explicit Bench(const std::string &object)
    : scene(std::string(VISPMORPH_DATA_DIR) + "/objects/" + object + ".png"), tag(scene.tagPoseEstimator()),
      robot(vpMorphSimRobot::VIPER850, dt / substeps)
  {
    robot.setDesiredPose(cdMo);
    storedView = observe(scene, tag, robot.get_cMo(), storedImage);
  }
  //! Puts the camera at cdMc in the desired camera frame; false if out of reach.
  bool start(const vpHomogeneousMatrix &cdMc) { return robot.initialiseCameraRelativeToDesired(cdMc); }
  //! The current camera image and the contour extracted from it.
  vpMorphContour look(vpImage<unsigned char> &I) const { return observe(scene, tag, robot.get_cMo(), I); }
  //! One control period at the end-effector twist ve.
  void move(const vpColVector &ve)
  {
    for (int i = 0; i < substeps; ++i)
      robot.setVelocity(vpRobot::END_EFFECTOR_FRAME, ve);
  }
  PoseError error() const { return truthError(robot.get_cMo(), cdMo); }

  vpMorphPlanarScene scene;
  vpMorphTagPoseEstimator tag;
  vpMorphSimRobot robot;
  const vpHomogeneousMatrix cdMo = desiredPose();
  vpImage<unsigned char> storedImage;
  vpMorphContour storedView;
};

//! True while the controller is moving (not converged, not stopped by a lost target or an unreliable match).
inline bool running(const vpServoMorph &servo)
{
  return servo.getStatus() == vpServoMorph::MOVING || servo.getStatus() == vpServoMorph::SUBGOAL_REACHED;
}

//! Grey image to colour with the contour drawn over it.
inline vpImage<vpRGBa> withContour(const vpImage<unsigned char> &I, const vpMorphContour &c, const vpColor &col)
{
  vpImage<vpRGBa> C;
  vpImageConvert::convert(I, C);
  if (!c.empty())
    vpImageDraw::drawPolygon(C, c.points(), col, 2, true);
  return C;
}

//! Opens a CSV file for writing, with its header line; throws if it cannot be written.
inline std::ofstream openCsv(const std::string &path, const char *header)
{
  std::ofstream f(path);
  if (!f)
    throw vpException(vpException::ioError, "cannot write " + path);
  f << header << "\n";
  return f;
}
} // namespace paper

#endif
