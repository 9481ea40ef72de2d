//! \example tutorial-morph-feature-vpServo.cpp
//! vpFeatureMorph in a stock vpServo loop: a free-flying camera aligns itself with a planar object that it first
//! sees rotated by 170 deg, a start where 4-point IBVS makes the camera retreat. With a display, shows the camera's
//! view with the current (red) and desired (green) features, the error and the velocity (vpPlot), and the camera's path
//! from outside.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpImage.h>
#include <visp3/morph_vs/vpFeatureMorph.h>
#include <visp3/robot/vpSimulatorCamera.h>
#include <visp3/vs/vpServo.h>

#include "tutorial-display.h"
#include "tutorial-external-view.h"
#include "tutorial-morph-part.h"

int main(int argc, char **argv)
{
  std::vector<std::string> args;
  tutorial::Viewer viewer(argc, argv, args);
  if (!tutorial::Viewer::accepts(args, 0, argv[0]))
    return EXIT_FAILURE;
  try {
    const vpCameraParameters cam(800, 800, 320, 240);
    const vpHomogeneousMatrix cdMo(0.01, 0, 0.5, 0, 0, vpMath::rad(20));     // desired pose: 0.5 m above the part
    const vpHomogeneousMatrix cMo(-0.06, 0.05, 0.5, 0, 0, vpMath::rad(190)); // start: rotated by 170 deg

    //! [Features]
    // The desired feature is built once from the goal view; its depth Zd is known (the taught pose).
    const double Zd = 0.5;
    const vpMorphContour goal = tutorial::project(cdMo, cam);
    vpFeatureMorph s, s_star;
    s_star.buildFrom(goal, cam, Zd);
    s.buildFrom(tutorial::project(cMo, cam), cam, Zd);
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

    //! [Display]
    // The camera's view (the part's contour on white), the error and velocity plot, the camera's path from outside.
    vpImage<unsigned char> I(480, 640, 255), Iext(480, 640, 255);
    viewer.open(I, 0, 0, "Camera: current feature (red), desired feature (green)", "camera");
    vpPlot *plot = viewer.plot(2, 700, 560, 660, 0, "vpFeatureMorph in vpServo: error, camera velocity", "plot");
    if (plot) {
      plot->initGraph(0, 4);
      plot->setTitle(0, "error s - s*");
      plot->initGraph(1, 6);
      plot->setTitle(1, "camera velocity (m/s, rad/s)");
      const char *e[] = {"xg", "yg", "theta", "sigma"}, *v[] = {"vx", "vy", "vz", "wx", "wy", "wz"};
      for (unsigned int k = 0; k < 6; ++k) {
        if (k < 4)
          plot->setLegend(0, k, e[k]);
        plot->setLegend(1, k, v[k]);
      }
    }
    viewer.open(Iext, 0, 540, "External view: the camera's path (red), desired camera (green)", "external");
    tutorial::ExternalView external(tutorial::part(), {}, cdMo);
    //! [Display]

    //! [Loop]
    bool ok = false;
    std::vector<std::string> status;
    for (int iter = 0; iter < 300; ++iter) {
      const vpHomogeneousMatrix cMo_now = robot.getPosition().inverse();
      const vpMorphContour c = tutorial::project(cMo_now, cam);
      // Depth of the plane from the area ratio with the goal view: no 3-D measurement needed.
      s.buildFrom(c, cam, Zd * std::sqrt(goal.area() / c.area()));
      const vpColVector v = task.computeControlLaw(); // s.error() tracks the correspondence from the last call
      ok = task.getError().frobeniusNorm() < 1e-5;

      //! [Show]
      // The desired feature wider and underneath, so that it stays visible where the current one reaches it.
      char line[120];
      std::snprintf(line, sizeof line, "iteration %d  |e| = %.5f  theta error %.2f deg", iter,
                    task.getError().frobeniusNorm(), vpMath::deg(s.get_theta()));
      status = {ok ? "converged" : "moving", line};
      vpDisplay::display(I);
      s_star.display(cam, I, vpColor::green, 4);
      s.display(cam, I, vpColor::red, 2);
      tutorial::Viewer::caption(I, status);
      vpDisplay::flush(I);
      //! [Show]
      if (plot) {
        plot->plot(0, iter, task.getError());
        plot->plot(1, iter, v);
      }
      external.add(0, cMo_now, vpColor::red);
      vpDisplay::display(Iext);
      external.display(Iext);
      vpDisplay::flush(Iext);
      viewer.pace(40);

      if (ok) {
        const vpHomogeneousMatrix cdMc = cdMo * cMo_now.inverse();
        std::cout << "converged after " << iter << " iterations: position error "
                  << cdMc.getTranslationVector().frobeniusNorm() * 1000 << " mm, rotation error "
                  << vpMath::deg(vpThetaUVector(cdMc.getRotationMatrix()).getTheta()) << " deg, "
                  << s.getAligner().getTracker().fullMatchCount() << " full correspondence search(es), "
                  << s.getAligner().getTracker().trackedMatchCount() << " tracked" << std::endl;
        break;
      }
      if (iter % 10 == 0)
        std::cout << "iteration " << iter << ": |e| = " << task.getError().frobeniusNorm()
                  << ", theta error = " << vpMath::deg(s.get_theta()) << " deg" << std::endl;
      if (viewer.clicked(I))
        break; // a click in the camera window stops the servo
      robot.setVelocity(vpRobot::CAMERA_FRAME, v);
    }
    //! [Loop]
    if (!ok)
      std::cout << "not converged" << std::endl;
    viewer.expectContour("camera", "desired feature", goal.points(), vpColor::green);
    viewer.expectText("camera", "status", tutorial::Viewer::captionBand(status), vpColor::white, status);
    viewer.expectCurves("plot", "error and velocity", {vpColor::blue, vpColor::green, vpColor::red});
    viewer.save();
    viewer.waitClick(I);
    return ok ? EXIT_SUCCESS : EXIT_FAILURE;
  } catch (const vpException &e) {
    std::cerr << "error: " << e.getMessage() << std::endl;
    return EXIT_FAILURE;
  }
}
