//! \example tutorial-paper-translation.cpp
//! The paper's Figure 3: translational alignment with the wedge by a simulated Viper850. The camera starts 70 mm
//! away in the object plane (same depth and orientation); vpServoMorph servoes it through the virtual contours of
//! the morph to the stored view, from rendered images only, with a hand-eye estimate 5 deg and 14 mm off that it
//! corrects on line. Writes, in --out DIR:
//! - fig3-moves.csv: after each move, the error in the image (translation of the morph from the real contour to
//!   the stored view, px), in the world (simulator truth, mm) and the camera position in the plane (mm);
//! - fig3-subgoals.csv: for each virtual image, the translation between it and the real contour seen when it was
//!   reached (px), and where the camera was then.
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
    paper::Bench bench("wedge");
    // Start: the camera 70 mm away in the plane parallel to the object (a pure translation, as in Figure 3).
    if (!bench.start(vpHomogeneousMatrix(0.06, -0.036, 0, 0, 0, 0))) {
      std::cerr << "start pose out of reach" << std::endl;
      return EXIT_FAILURE;
    }
    vpServoMorph servo;
    paper::setUpController(servo, bench.robot, bench.scene.camera(), bench.storedView, bench.cdMo[2][3],
                           paper::Bench::dt);
    tutorial::ServoWindows watch(viewer, bench.scene.imageWidth(), bench.scene.imageHeight(),
                                 bench.scene.objectContour3D(), bench.scene.tagCorners3D(), bench.cdMo,
                                 "Viper850 camera"); // windows, when a display is available
    // The camera trajectory is drawn in the desired camera frame: x right, y down, as in the image.
    const vpHomogeneousMatrix cdMf = (bench.cdMo * bench.robot.get_fMo().inverse());
    //! [Bench]

    std::ofstream moves = paper::openCsv(out + "/fig3-moves.csv", "move,subgoal,status,image_error_px,"
                                                                  "world_error_mm,camera_x_mm,camera_y_mm");
    std::ofstream subgoals =
        paper::openCsv(out + "/fig3-subgoals.csv", "subgoal,move,virtual_vs_real_px,camera_x_mm,camera_y_mm");
    vpImage<unsigned char> I;
    paper::PoseError e;
    //! [Loop]
    unsigned int move = 0;
    for (; move < 200; ++move) {
      const vpMorphContour seen = bench.look(I);
      const std::size_t before = servo.getSubGoalIndex();
      const vpColVector ve = servo.computeControlLaw(seen);
      watch.show(I, servo, move, bench.robot.get_cMo());
      const vpHomogeneousMatrix cdMc = cdMf * bench.robot.get_fMc(); // where the camera is (truth)
      const std::size_t reached =
          servo.getStatus() == vpServoMorph::CONVERGED ? servo.getSubGoals().size() : servo.getSubGoalIndex();
      for (std::size_t k = before; k < reached; ++k) {
        double rad, px;
        paper::morphResidual(seen, servo.getSubGoals()[k], rad, px);
        subgoals << k + 1 << "," << move << "," << px << "," << cdMc[0][3] * 1000 << "," << cdMc[1][3] * 1000 << "\n";
      }
      double rad, imagePx;
      paper::morphResidual(seen, bench.storedView, rad, imagePx); // error in the morph plane
      e = bench.error();
      moves << move << "," << servo.getSubGoalIndex() + 1 << "," << vpServoMorph::statusName(servo.getStatus()) << ","
            << imagePx << "," << std::hypot(e.inPlaneMm, e.depthMm) << "," << cdMc[0][3] * 1000 << ","
            << cdMc[1][3] * 1000 << "\n";
      if (!paper::running(servo) || watch.stopped())
        break;
      bench.move(ve);
    }
    //! [Loop]

    std::printf("wedge, 70 mm in the plane, Viper850: %s after %u moves (%zu virtual images), camera path %.1f mm\n",
                vpServoMorph::statusName(servo.getStatus()), move, servo.getSubGoals().size(),
                bench.robot.cameraPathLength() * 1000);
    std::printf("final pose error (simulator truth): %.3f deg, %.3f mm in the image plane, %.3f mm in depth\n", e.deg,
                e.inPlaneMm, e.depthMm);
    std::printf("wrote %s/fig3-moves.csv, fig3-subgoals.csv\n", out.c_str());
    const bool ok = paper::aligned(servo, e);
    std::printf("%s\n", ok ? "aligned" : "NOT aligned");
    watch.end(servo);
    return ok ? EXIT_SUCCESS : EXIT_FAILURE;
  } catch (const vpException &e) {
    std::cerr << "error: " << e.getStringMessage() << std::endl;
    return EXIT_FAILURE;
  }
}
