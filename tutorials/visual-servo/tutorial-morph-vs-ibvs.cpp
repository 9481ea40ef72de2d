//! \example tutorial-morph-vs-ibvs.cpp
//! IBVS and the morph servo side by side, from the same start: the camera turned by 160 deg about its optical axis
//! from the desired pose, where IBVS on 4 points with the current interaction matrix drives the camera back along its
//! axis (to 4.2 m from the plane) before it turns. Two free-flying cameras (vpSimulatorCamera) look at the same
//! rendered scene, the key and an AprilTag on a plane: IBVS servoes on the tag's 4 corners (a stock vpServo),
//! vpServoMorph on the key's contour, each from its own images only. With a display: both camera views, the distance to
//! the plane and the pose errors of both (vpPlot), and both camera paths from outside. Prints, for each, the
//! iterations, how far the camera went back and its path.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpMath.h>
#include <visp3/morph_sim/vpMorphPlanarScene.h>
#include <visp3/morph_sim/vpMorphTagPoseEstimator.h>
#include <visp3/morph_vs/vpServoMorph.h>
#include <visp3/robot/vpSimulatorCamera.h>
#include <visp3/visual_features/vpFeatureBuilder.h>
#include <visp3/visual_features/vpFeaturePoint.h>
#include <visp3/vs/vpServo.h>
#include <visp3/vs/vpServoDisplay.h>

#include "tutorial-display.h"
#include "tutorial-external-view.h"

namespace
{
//! What one controller did: its camera's path, how far it went from the plane, its last pose error.
struct Run
{
  vpSimulatorCamera robot;
  std::string state = "moving";
  unsigned int iterations = 0;
  double path = 0, maxDepth = 0, errDeg = 0, errMm = 0;
  bool done = false;

  void start(const vpHomogeneousMatrix &cMo, double dt)
  {
    robot.setSamplingTime(dt);
    robot.setMaxTranslationVelocity(100.0); // no saturation: the velocity is the control law's
    robot.setMaxRotationVelocity(100.0);
    robot.setPosition(cMo.inverse()); // world frame = object frame
  }
  vpHomogeneousMatrix cMo() const { return robot.getPosition().inverse(); }
  //! The errors and the depth at the current pose (the simulator's truth, for the plot and the summary).
  void measure(const vpHomogeneousMatrix &cdMo)
  {
    const vpHomogeneousMatrix c = cMo(), cdMc = cdMo * c.inverse();
    errDeg = vpMath::deg(vpThetaUVector(cdMc.getRotationMatrix()).getTheta());
    errMm = cdMc.getTranslationVector().frobeniusNorm() * 1000;
    maxDepth = std::max(maxDepth, c[2][3]);
  }
  void move(const vpColVector &v)
  {
    const vpTranslationVector before = robot.getPosition().getTranslationVector();
    robot.setVelocity(vpRobot::CAMERA_FRAME, v);
    path += (robot.getPosition().getTranslationVector() - before).frobeniusNorm();
    ++iterations;
  }
};
} // namespace

int main(int argc, char **argv)
{
  std::vector<std::string> args;
  tutorial::Viewer viewer(argc, argv, args);
  if (!tutorial::Viewer::accepts(args, 0, argv[0]))
    return EXIT_FAILURE;
  try {
    //! [Scene]
    // The key (15 cm) and an 8 cm AprilTag on a plane; the desired pose 0.5 m above it, optical axis normal to it.
    const vpMorphPlanarScene scene(std::string(VISPMORPH_DATA_DIR) + "/objects/key.png");
    const vpMorphTagPoseEstimator tag = scene.tagPoseEstimator();
    const vpCameraParameters cam = scene.camera();
    const vpHomogeneousMatrix cdMo(0, 0, 0.5, 0, 0, 0);
    // The start: turned by 160 deg about the optical axis and shifted by 2 cm.
    const vpHomogeneousMatrix cMo = vpHomogeneousMatrix(0.02, -0.01, 0, 0, 0, vpMath::rad(160)).inverse() * cdMo;
    const double dt = 0.1, gain = 0.2; // a fifth of the error corrected per period, for both
    //! [Scene]

    //! [Teach]
    // Teach by showing: the image at the desired pose gives both goals, the tag's corners and the key's contour.
    vpImage<unsigned char> I;
    scene.render(cdMo, I);
    vpHomogeneousMatrix cdMo_tag;
    std::vector<vpImagePoint> cornersD;
    if (!tag.estimate(I, cdMo_tag, &cornersD)) {
      std::cerr << "the tag is not found in the desired view" << std::endl;
      return EXIT_FAILURE;
    }
    const vpMorphContour goal = vpMorphTagPoseEstimator::silhouette(I, cornersD);
    //! [Teach]

    //! [IBVS]
    // ViSP's IBVS on 4 points: the tag corners, their depth from the tag's pose, the current interaction matrix.
    const std::vector<vpPoint> corners3D = scene.tagCorners3D();
    vpFeaturePoint p[4], pd[4];
    vpServo task;
    task.setServo(vpServo::EYEINHAND_CAMERA);
    task.setInteractionMatrixType(vpServo::CURRENT);
    task.setLambda(gain / dt);
    for (unsigned int i = 0; i < 4; ++i) {
      vpFeatureBuilder::create(pd[i], cam, cornersD[i]);
      vpPoint P = corners3D[i];
      P.track(cdMo_tag);
      pd[i].set_Z(P.get_Z());
      p[i] = pd[i];
      task.addFeature(p[i], pd[i]);
    }
    //! [IBVS]

    //! [Morph]
    // vpServoMorph on the key's contour, through 10 sub-goals, the camera's frame as the end effector's.
    vpServoMorph servo;
    servo.setCameraParameters(cam);
    servo.getPlanner().setSubGoalCount(10);
    servo.setGain(gain);
    servo.setSamplingTime(dt);
    servo.setTarget(goal, cdMo[2][3]);
    //! [Morph]

    Run ibvs, morph;
    ibvs.start(cMo, dt);
    morph.start(cMo, dt);

    //! [Display]
    vpImage<unsigned char> Im(I.getHeight(), I.getWidth(), 255), Ii(I.getHeight(), I.getWidth(), 255);
    vpImage<unsigned char> Iext(480, 640, 255);
    viewer.open(Im, 0, 0, "vpServoMorph: contour (red), sub-goal (orange), target (green)", "morph");
    viewer.open(Ii, 660, 0, "IBVS: tag corners (red), desired (green)", "ibvs");
    viewer.open(Iext, 0, 540, "External view: IBVS (red), morph (blue), desired camera (green)", "external");
    vpPlot *plot = viewer.plot(3, 700, 560, 1320, 0, "IBVS (red) and morph (blue)", "plot");
    if (plot) {
      const char *titles[] = {"distance to the plane (m)", "rotation error (deg)", "translation error (mm)"};
      for (unsigned int g = 0; g < 3; ++g) {
        plot->initGraph(g, 2);
        plot->setTitle(g, titles[g]);
        plot->setColor(g, 0, vpColor::red);
        plot->setColor(g, 1, vpColor::blue);
        plot->setLegend(g, 0, "IBVS");
        plot->setLegend(g, 1, "morph");
      }
    }
    // Seen from 9 m away, looking at 2.1 m above the plane: where IBVS takes its camera.
    tutorial::ExternalView external(scene.objectContour3D(), corners3D, cdMo, 9.0, 0.3, 0.7, 2.1);
    //! [Display]

    std::vector<std::string> ibvsText;
    for (unsigned int k = 0; k < 400 && !(ibvs.done && morph.done); ++k) {
      //! [Loop IBVS]
      if (!ibvs.done) {
        scene.render(ibvs.cMo(), Ii);
        vpHomogeneousMatrix cMo_tag;
        std::vector<vpImagePoint> corners;
        if (!tag.estimate(Ii, cMo_tag, &corners)) {
          ibvs.state = "tag lost";
          ibvs.done = true;
        } else {
          for (unsigned int i = 0; i < 4; ++i) {
            vpFeatureBuilder::create(p[i], cam, corners[i]);
            vpPoint P = corners3D[i];
            P.track(cMo_tag);
            p[i].set_Z(P.get_Z());
          }
          const vpColVector v = task.computeControlLaw();
          if (task.getError().frobeniusNorm() < 1e-4) {
            ibvs.state = "converged";
            ibvs.done = true;
          } else {
            ibvs.move(v);
          }
        }
        ibvs.measure(cdMo);
      }
      //! [Loop IBVS]
      //! [Loop morph]
      if (!morph.done) {
        scene.render(morph.cMo(), Im);
        vpHomogeneousMatrix cMo_tag;
        std::vector<vpImagePoint> corners;
        if (!tag.estimate(Im, cMo_tag, &corners))
          corners.clear(); // no tag to mask
        const vpColVector v = servo.computeControlLaw(vpMorphTagPoseEstimator::silhouette(Im, corners));
        if (servo.getStatus() == vpServoMorph::CONVERGED ||
            (servo.getStatus() != vpServoMorph::MOVING && servo.getStatus() != vpServoMorph::SUBGOAL_REACHED))
          morph.done = true;
        else
          morph.move(v); // eMc is the identity: the end effector's velocity is the camera's
        morph.state = vpServoMorph::statusName(servo.getStatus());
        morph.measure(cdMo);
      }
      //! [Loop morph]

      //! [Show]
      vpDisplay::display(Im);
      servo.display(Im, vpColor::red, vpColor::orange, vpColor::green, 2);
      vpDisplay::flush(Im);
      char line[120];
      std::snprintf(line, sizeof line, "iteration %u  |e| = %.4f  distance %.3f m", ibvs.iterations,
                    task.getError().frobeniusNorm(), ibvs.cMo()[2][3]);
      ibvsText = {"IBVS: " + ibvs.state, line};
      vpDisplay::display(Ii);
      vpServoDisplay::display(task, cam, Ii, vpColor::red, vpColor::green, 2);
      tutorial::Viewer::caption(Ii, ibvsText);
      vpDisplay::flush(Ii);
      //! [Show]
      if (plot) {
        const Run *runs[] = {&ibvs, &morph};
        for (unsigned int r = 0; r < 2; ++r) {
          plot->plot(0, r, k, runs[r]->cMo()[2][3]);
          plot->plot(1, r, k, runs[r]->errDeg);
          plot->plot(2, r, k, runs[r]->errMm);
        }
      }
      external.add(0, ibvs.cMo(), vpColor::red);
      external.add(1, morph.cMo(), vpColor::blue);
      vpDisplay::display(Iext);
      external.display(Iext);
      std::snprintf(line, sizeof line, "farthest from the plane: IBVS %.2f m, morph %.2f m", ibvs.maxDepth,
                    morph.maxDepth);
      tutorial::Viewer::caption(Iext, {line});
      vpDisplay::flush(Iext);
      viewer.pace(40);
      if (viewer.clicked(Im) || viewer.clicked(Ii))
        break;
    }

    std::printf("start: 160 deg about the optical axis, 0.5 m from the plane\n");
    std::printf("controller  state          iterations  farthest (m)  path (m)  final error (deg, mm)\n");
    const Run *runs[] = {&ibvs, &morph};
    const char *names[] = {"IBVS", "morph"};
    for (int r = 0; r < 2; ++r)
      std::printf("%-10s  %-13s  %10u  %12.3f  %8.3f  %7.3f %7.2f\n", names[r], runs[r]->state.c_str(),
                  runs[r]->iterations, runs[r]->maxDepth, runs[r]->path, runs[r]->errDeg, runs[r]->errMm);

    viewer.expectContour("morph", "target", servo.getTargetContour().points(), vpColor::green);
    viewer.expectText("morph", "status", vpRect(0, 0, 0.75 * Im.getWidth(), 0.25 * Im.getHeight()), vpColor::yellow,
                      servo.statusText());
    viewer.expectText("ibvs", "status", tutorial::Viewer::captionBand(ibvsText), vpColor::white, ibvsText);
    viewer.expectCurves("plot", "distance and errors", {vpColor::red, vpColor::blue});
    viewer.save();
    viewer.waitClick(Im);
    return servo.getStatus() == vpServoMorph::CONVERGED ? EXIT_SUCCESS : EXIT_FAILURE;
  } catch (const vpException &e) {
    std::cerr << "error: " << e.getStringMessage() << std::endl;
    return EXIT_FAILURE;
  }
}
