//! \example tutorial-morph-feature-vpServo.cpp
//! vpFeatureMorph in a stock vpServo loop: a free-flying camera aligns itself with a planar object that it first
//! sees rotated by 170 deg, a start where 4-point IBVS makes the camera retreat.
#include <cmath>
#include <cstring>
#include <iostream>
#include <vector>

#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpImage.h>
#include <visp3/morph_vs/vpFeatureMorph.h>
#include <visp3/robot/vpSimulatorCamera.h>
#include <visp3/vs/vpServo.h>

namespace
{
// The contour of a planar L-shaped part (z = 0 in its frame) as the camera at cMo sees it, in pixels.
vpMorphContour project(const vpHomogeneousMatrix &cMo, const vpCameraParameters &cam)
{
  const double P[][2] = {{-0.07, -0.05}, {0.08, -0.05}, {0.08, -0.01}, {0.02, -0.01}, {0.02, 0.04},
                         {-0.01, 0.07},  {-0.03, 0.07}, {-0.03, 0.02}, {-0.07, 0.02}};
  std::vector<double> x, y;
  for (const auto &p : P) {
    const vpColVector X = cMo * vpColVector({p[0], p[1], 0, 1});
    x.push_back(X[0] / X[2]);
    y.push_back(X[1] / X[2]);
  }
  return vpMorphContour(x, y, vpMorphContour::NORMALIZED).toPixels(cam);
}
} // namespace

int main(int argc, char **argv)
{
  for (int i = 1; i < argc; ++i)
    if (std::strcmp(argv[i], "-c") && std::strcmp(argv[i], "-d")) {
      std::cout << "Usage: " << argv[0] << " [-c] [-d]  (headless: nothing is displayed)" << std::endl;
      return EXIT_FAILURE;
    }
  try {
    const vpCameraParameters cam(800, 800, 320, 240);
    const vpHomogeneousMatrix cdMo(0.01, 0, 0.5, 0, 0, vpMath::rad(20));     // desired pose: 0.5 m above the part
    const vpHomogeneousMatrix cMo(-0.06, 0.05, 0.5, 0, 0, vpMath::rad(190)); // start: rotated by 170 deg

    //! [Features]
    // The desired feature is built once from the goal view; its depth Zd is known (the taught pose).
    const double Zd = 0.5;
    const vpMorphContour goal = project(cdMo, cam);
    vpFeatureMorph s, s_star;
    s_star.buildFrom(goal, cam, Zd);
    s.buildFrom(project(cMo, cam), cam, Zd);
    //! [Features]

    //! [Task]
    vpServo task;
    task.setServo(vpServo::EYEINHAND_CAMERA);
    task.setInteractionMatrixType(vpServo::CURRENT); // DESIRED and MEAN work too
    task.setLambda(5.0);
    task.addFeature(s, s_star); // always with a built s_star: vpServo keeps pointers to both
    // (xg, yg, theta, ln sqrt(a)) constrain the planar task: leave the camera tilt velocities at zero.
    vpColVector dof(6, 1.0);
    dof[3] = dof[4] = 0;
    task.setCameraDoF(dof);
    //! [Task]

    vpSimulatorCamera robot;
    robot.setSamplingTime(0.1);
    robot.setMaxTranslationVelocity(10.0); // no saturation: the velocity is the control law's
    robot.setMaxRotationVelocity(100.0);
    robot.setPosition(cMo.inverse()); // world frame = object frame

    //! [Loop]
    for (int iter = 0; iter < 300; ++iter) {
      const vpHomogeneousMatrix cMo_now = robot.getPosition().inverse();
      const vpMorphContour c = project(cMo_now, cam);
      // Depth of the plane from the area ratio with the goal view: no 3-D measurement needed.
      s.buildFrom(c, cam, Zd * std::sqrt(goal.area() / c.area()));
      const vpColVector v = task.computeControlLaw(); // s.error() tracks the correspondence from the last call
      if (task.getError().frobeniusNorm() < 1e-5) {
        const vpHomogeneousMatrix cdMc = cdMo * cMo_now.inverse();
        std::cout << "converged after " << iter << " iterations: position error "
                  << cdMc.getTranslationVector().frobeniusNorm() * 1000 << " mm, rotation error "
                  << vpMath::deg(vpThetaUVector(cdMc.getRotationMatrix()).getTheta()) << " deg, "
                  << s.tracker().fullMatchCount() << " full correspondence search(es), "
                  << s.tracker().trackedMatchCount() << " tracked" << std::endl;
        return EXIT_SUCCESS;
      }
      if (iter % 10 == 0)
        std::cout << "iteration " << iter << ": |e| = " << task.getError().frobeniusNorm()
                  << ", theta error = " << vpMath::deg(s.get_theta()) << " deg" << std::endl;
      robot.setVelocity(vpRobot::CAMERA_FRAME, v);
    }
    //! [Loop]
    std::cout << "not converged" << std::endl;
    return EXIT_FAILURE;
  } catch (const vpException &e) {
    std::cerr << "error: " << e.getMessage() << std::endl;
    return EXIT_FAILURE;
  }
}
