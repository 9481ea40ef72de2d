//! \example tutorial-paper-rotation.cpp
//! The paper's Figure 2: rotational alignment of the pliers by a simulated Viper850. The camera starts turned by
//! 150 deg about its optical axis; vpServoMorph servoes it through the virtual contours of the morph to the
//! stored view, from rendered images only (tag masked, contour extracted), with a hand-eye estimate 5 deg and
//! 14 mm off that it corrects on line. Writes, in --out DIR:
//! - fig2-moves.csv: after each move, the angular pose error to the desired pose (simulator truth);
//! - fig2-subgoals.csv: for each virtual image, the rotation between it and the real contour seen when it was
//!   reached (measured by a morph of the one into the other);
//! - fig2-start.png, fig2-final.png: the camera images at start and at the end, stored view drawn in green.
//! Exits with failure unless the controller converged to the desired pose (paper::aligned(): 1 mm, 0.5 deg).
#include <cstdio>

#include "tutorial-paper-common.h"

int main(int argc, char **argv)
{
  std::string out;
  std::vector<std::string> args;
  tutorial::Viewer viewer(argc, argv, args);
  try {
    if (!paper::parseArgs(argv[0], args, out))
      return EXIT_FAILURE;

    //! [Bench]
    paper::Bench bench("pliers");
    // Start: the camera turned by 150 deg about its optical axis (a pure rotation, as in the paper's Figure 2).
    if (!bench.start(vpHomogeneousMatrix(0, 0, 0, 0, 0, vpMath::rad(150)))) {
      std::cerr << "start pose out of reach" << std::endl;
      return EXIT_FAILURE;
    }
    vpServoMorph servo;
    paper::setUpController(servo, bench.robot, bench.scene.camera(), bench.storedView, bench.cdMo[2][3],
                           paper::Bench::dt);
    tutorial::ServoWindows watch(viewer, bench.scene.imageWidth(), bench.scene.imageHeight(),
                                 bench.scene.objectContour3D(), bench.scene.tagCorners3D(), bench.cdMo,
                                 "Viper850 camera"); // windows, when a display is available
    //! [Bench]

    std::ofstream moves = paper::openCsv(out + "/fig2-moves.csv", "move,subgoal,status,rotation_error_deg,"
                                                                  "in_plane_error_mm,depth_error_mm");
    std::ofstream subgoals =
        paper::openCsv(out + "/fig2-subgoals.csv", "subgoal,move,virtual_vs_real_deg,virtual_vs_real_px");
    vpImage<unsigned char> I;
    paper::PoseError e;
    //! [Loop]
    unsigned int move = 0;
    for (; move < 200; ++move) {
      const vpMorphContour seen = bench.look(I);
      if (move == 0)
        vpMorphDrawing::write(paper::withContour(I, bench.storedView, vpColor::green), out + "/fig2-start.png");
      const std::size_t before = servo.getSubGoalIndex();
      const vpColVector ve = servo.computeControlLaw(seen);
      watch.show(I, servo, move, bench.robot.get_cMo());
      // Every sub-goal passed at this iteration was reached by the contour seen now: how far was it from it?
      const std::size_t reached =
          servo.getStatus() == vpServoMorph::CONVERGED ? servo.getSubGoals().size() : servo.getSubGoalIndex();
      for (std::size_t k = before; k < reached; ++k) {
        double rad, px;
        paper::morphResidual(seen, servo.getSubGoals()[k], rad, px);
        subgoals << k + 1 << "," << move << "," << vpMath::deg(std::fabs(rad)) << "," << px << "\n";
      }
      e = bench.error();
      moves << move << "," << servo.getSubGoalIndex() + 1 << "," << vpServoMorph::statusName(servo.getStatus()) << ","
            << e.deg << "," << e.inPlaneMm << "," << e.depthMm << "\n";
      if (!paper::running(servo) || watch.stopped())
        break;
      bench.move(ve);
    }
    //! [Loop]
    vpMorphDrawing::write(paper::withContour(I, bench.storedView, vpColor::green), out + "/fig2-final.png");

    const vpHomogeneousMatrix eMcErr = bench.robot.eMcTrue().inverse() * servo.get_eMc();
    std::printf("pliers, 150 deg about the optical axis, Viper850: %s after %u moves (%zu virtual images)\n",
                vpServoMorph::statusName(servo.getStatus()), move, servo.getSubGoals().size());
    std::printf("final pose error (simulator truth): %.3f deg, %.3f mm in the image plane, %.3f mm in depth\n", e.deg,
                e.inPlaneMm, e.depthMm);
    std::printf("hand-eye estimate error: %.2f deg, %.1f mm (start: 5 deg, 14.1 mm)\n",
                vpMath::deg(vpThetaUVector(eMcErr.getRotationMatrix()).getTheta()),
                eMcErr.getTranslationVector().frobeniusNorm() * 1000);
    std::printf("wrote %s/fig2-moves.csv, fig2-subgoals.csv, fig2-start.png, fig2-final.png\n", out.c_str());
    const bool ok = paper::aligned(servo, e);
    std::printf("%s\n", ok ? "aligned" : "NOT aligned");
    watch.end(servo);
    return ok ? EXIT_SUCCESS : EXIT_FAILURE;
  } catch (const vpException &e) {
    std::cerr << "error: " << e.getStringMessage() << std::endl;
    return EXIT_FAILURE;
  }
}
