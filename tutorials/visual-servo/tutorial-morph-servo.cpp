//! \example tutorial-morph-servo.cpp
//! vpServoMorph: the camera of a robot is servoed through the virtual contours (sub-goals) of the morph from the
//! current view to the taught one, while the hand-eye transform, started 15 deg and 30 mm off with intrinsics
//! 20 % off, is estimated on line. Prints the pose error after every move, like Figure 2 of the paper; with a display,
//! shows the camera's view with vpServoMorph::display(), the residuals and the velocity (vpPlot), and the camera's path
//! from outside.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <vector>

#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpVelocityTwistMatrix.h>
#include <visp3/morph_vs/vpServoMorph.h>
#include <visp3/robot/vpSimulatorCamera.h>

#include "tutorial-display.h"
#include "tutorial-external-view.h"
#include "tutorial-morph-part.h"
#include "tutorial-servo-windows.h"

namespace
{
// Angle (deg) and distance (mm) of a transform.
void errorOf(const vpHomogeneousMatrix &M, double &deg, double &mm)
{
  deg = vpMath::deg(vpThetaUVector(M.getRotationMatrix()).getTheta());
  mm = M.getTranslationVector().frobeniusNorm() * 1000;
}
} // namespace

int main(int argc, char **argv)
{
  std::vector<std::string> args;
  tutorial::Viewer viewer(argc, argv, args);
  if (!tutorial::Viewer::accepts(args, 0, argv[0]))
    return EXIT_FAILURE;
  try {
    // The truth, known only to the simulation: camera, hand-eye transform, desired and start poses.
    const vpCameraParameters camTrue(800, 800, 320, 240);
    const vpHomogeneousMatrix eMcTrue(0.01, 0.05, 0.12, 0, 0, vpMath::rad(90));
    const vpHomogeneousMatrix cdMo(0.01, 0, 0.5, 0, 0, vpMath::rad(20));
    const vpHomogeneousMatrix cMo(0.06, -0.03, 0.5, 0, 0, vpMath::rad(190));

    //! [Setup]
    // What the controller is told: intrinsics 20 % off, eMc 15 deg and 30 mm off.
    const vpHomogeneousMatrix eMcGuess =
        eMcTrue * vpHomogeneousMatrix(0.024, -0.018, 0, 0, 0, vpMath::rad(15)).inverse();
    vpServoMorph servo;
    servo.setCameraParameters(vpCameraParameters(960, 960, 320, 240));
    servo.set_eMc(eMcGuess);
    servo.getPlanner().setSubGoalCount(10); // 10 virtual images; 0 = the goal only
    servo.setSubGoalThresholds(0.10, 5.0);  // the paper's switching thresholds (rad, px)
    servo.setSamplingTime(0.1);
    servo.setGain(0.5);                                     // half of the Eq. 11 step per period
    servo.setTarget(tutorial::project(cdMo, camTrue), 0.5); // taught view, taken 0.5 m above the part
    //! [Setup]

    vpSimulatorCamera robot; // a free-flying camera; the end effector is eMcTrue^-1 away
    robot.setSamplingTime(0.1);
    robot.setMaxTranslationVelocity(10.0);
    robot.setMaxRotationVelocity(100.0);
    robot.setPosition(cMo.inverse());
    const vpVelocityTwistMatrix cVe(eMcTrue.inverse());

    //! [Display]
    // The camera's view (the part's contour on white), the plot, and the camera's path seen from outside.
    vpImage<unsigned char> I(480, 640, 255), Iext(480, 640, 255);
    viewer.open(I, 0, 0, "Camera: contour (red), sub-goal (orange), target (green)", "camera");
    tutorial::ServoPlot plot(viewer, 660, 0);
    viewer.open(Iext, 0, 540, "External view: the camera's path (red), desired camera (green)", "external");
    tutorial::ExternalView external(tutorial::part(), {}, cdMo);
    //! [Display]

    double deg, mm;
    errorOf(eMcTrue.inverse() * eMcGuess, deg, mm);
    std::printf("hand-eye estimate error at start: %.2f deg, %.1f mm\n", deg, mm);
    std::printf("move  sub-goal  residual(rad)  residual(px)  pose error to goal (deg, mm)\n");
    //! [Loop]
    bool ok = false;
    for (int move = 0; move < 200; ++move) {
      const vpHomogeneousMatrix cMo_now = robot.getPosition().inverse();
      const vpColVector ve = servo.computeControlLaw(tutorial::project(cMo_now, camTrue)); // end-effector velocity
      //! [Show]
      vpDisplay::display(I);
      servo.display(I, vpColor::red, vpColor::orange, vpColor::green, 2);
      vpDisplay::flush(I);
      //! [Show]
      plot.add(move, servo);
      external.add(0, cMo_now, vpColor::red);
      vpDisplay::display(Iext);
      external.display(Iext);
      vpDisplay::flush(Iext);
      viewer.pace(40);
      errorOf(cdMo * cMo_now.inverse(), deg, mm);
      std::printf("%4d  %2zu/%zu     %8.4f      %8.2f      %7.2f  %7.2f   %s\n", move, servo.getSubGoalIndex() + 1,
                  servo.getSubGoals().size(), servo.getRotationResidual(), servo.getTranslationResidual(), deg, mm,
                  vpServoMorph::statusName(servo.getStatus()));
      if (servo.getStatus() == vpServoMorph::CONVERGED) {
        errorOf(eMcTrue.inverse() * servo.get_eMc(), deg, mm);
        std::printf("converged after %d moves; hand-eye estimate error %.3f deg, %.2f mm; projection scale %.4f "
                    "(true 1.2)\n",
                    move, deg, mm, servo.getHandEyeEstimator().translationScale());
        ok = true;
        break;
      }
      if (servo.getStatus() != vpServoMorph::MOVING && servo.getStatus() != vpServoMorph::SUBGOAL_REACHED)
        break; // lost target, degenerate contour or unreliable correspondence: the velocity is zero
      if (viewer.clicked(I))
        break; // a click in the camera window stops the servo
      robot.setVelocity(vpRobot::CAMERA_FRAME, cVe * ve);
    }
    //! [Loop]
    if (!ok)
      std::cout << "not converged: " << vpServoMorph::statusName(servo.getStatus()) << std::endl;
    plot.expect(viewer, "camera", servo, I.getWidth(), I.getHeight());
    viewer.save();
    viewer.waitClick(I);
    return ok ? EXIT_SUCCESS : EXIT_FAILURE;
  } catch (const vpException &e) {
    std::cerr << "error: " << e.getMessage() << std::endl;
    return EXIT_FAILURE;
  }
}
