//! \example tutorial-morph-scene.cpp
//! A simulated benchmark scene: the pliers and an AprilTag on a plane, seen by the camera of a simulated Viper850
//! from a start pose, rendered headless with noise and an occluder; the truth two ways (simulator and tag).
//! Writes OUTDIR/morph-scene.png (default: the current folder). With a display, shows the camera image with the tag's
//! corners and pose as detected, the object's outline projected from the truth (green) and the silhouette extracted
//! from the image (red); and the robot's camera seen from outside. Usage: [OUTDIR] [-c] [-d] [--save-display FILE].
#include <cstdio>
#include <iostream>
#include <string>

#include <visp3/core/vpImage.h>
#include <visp3/core/vpMath.h>
#include <visp3/io/vpImageIo.h>
#include <visp3/morph_sim/vpMorphPlanarScene.h>
#include <visp3/morph_sim/vpMorphSimRobot.h>
#include <visp3/morph_sim/vpMorphTagPoseEstimator.h>

#include "tutorial-display.h"
#include "tutorial-external-view.h"

int main(int argc, char **argv)
{
  std::vector<std::string> args;
  tutorial::Viewer viewer(argc, argv, args);
  if (!tutorial::Viewer::accepts(args, 1, argv[0], "[OUTDIR]"))
    return EXIT_FAILURE;
  const std::string out = args.empty() ? "." : args[0];
  try {
    //! [Scene]
    // The pliers (15 cm long) at the origin of the object frame, an 8 cm AprilTag 36h11 beside them; 10 % of the
    // contour hidden by a card, sensor noise of 2 grey levels (seeded: the same image every run).
    vpMorphPlanarScene scene(VISPMORPH_DATA_DIR "/objects/pliers.png", 0.15, 0, 0.08);
    vpMorphPlanarScene::Faults faults;
    faults.noiseSigma = 2.0;
    faults.occludedShare = 0.1;
    faults.occluderPosition = 0.3;
    faults.seed = 1;
    scene.setFaults(faults);
    //! [Scene]

    //! [Robot]
    // The Viper850 sees the object at the desired pose (0.5 m, turned by 20 deg) in its reference configuration;
    // the start is 40 mm and 120 deg away. Its camera mount is known to the controller only within 1 cm / 3 deg.
    vpMorphSimRobot robot(vpMorphSimRobot::VIPER850);
    robot.setCameraMount(robot.eMcTrue(), vpMorphSimRobot::perturbed(robot.eMcTrue(), 0.01, vpMath::rad(3)));
    const vpHomogeneousMatrix cdMo(0, 0, 0.5, 0, 0, vpMath::rad(20));
    robot.setDesiredPose(cdMo);
    const vpHomogeneousMatrix start = vpHomogeneousMatrix(0.04, 0, 0, 0, 0, vpMath::rad(120)).inverse() * cdMo;
    if (!robot.initialiseCameraRelativeToObject(start)) {
      std::cerr << "start pose out of reach" << std::endl;
      return EXIT_FAILURE;
    }
    //! [Robot]

    //! [Render]
    vpImage<unsigned char> I;
    scene.render(robot.get_cMo(), I);
    vpImageIo::write(I, out + "/morph-scene.png");
    //! [Render]

    //! [Truth]
    vpHomogeneousMatrix cMo_tag;
    std::vector<vpImagePoint> corners;
    if (!scene.tagPoseEstimator().estimate(I, cMo_tag, &corners)) {
      std::cerr << "tag not found" << std::endl;
      return EXIT_FAILURE;
    }
    double t, r;
    vpMorphTagPoseEstimator::poseDifference(cMo_tag, robot.get_cMo(), t, r);
    //! [Truth]

    //! [Display]
    // The image with what the truth and the image each say: the projected outline (green), the silhouette extracted
    // with the tag masked (red), the tag's corners and the object frame from its pose (ViSP's frame colours).
    const vpMorphContour truth = scene.projectedContour(robot.get_cMo());
    const vpMorphContour seen = vpMorphTagPoseEstimator::silhouette(I, corners);
    char line[120];
    std::snprintf(line, sizeof line, "simulator vs AprilTag: %.2f mm, %.3f deg", t * 1000, vpMath::deg(r));
    const std::vector<std::string> caption = {"Viper850 camera, 10 % of the outline hidden, noise 2 grey levels", line};
    vpImage<unsigned char> Iext(480, 640, 255);
    if (viewer.open(I, 0, 0, "Scene: projected outline (green), extracted silhouette (red), tag", "camera")) {
      vpDisplay::display(I);
      vpDisplay::displayPolygon(I, truth.points(), vpColor::green, 3);
      if (!seen.empty())
        vpDisplay::displayPolygon(I, seen.points(), vpColor::red, 1);
      for (const vpImagePoint &c : corners)
        vpDisplay::displayCross(I, c, 14, vpColor::blue, 2);
      vpDisplay::displayFrame(I, cMo_tag, scene.camera(), 0.05, vpColor::none, 2);
      tutorial::Viewer::caption(I, caption);
      vpDisplay::flush(I);
      viewer.open(Iext, 0, 540, "External view: the start camera (red), desired camera (green)", "external");
      tutorial::ExternalView external(scene.objectContour3D(), scene.tagCorners3D(), cdMo);
      external.add(0, robot.get_cMo(), vpColor::red);
      vpDisplay::display(Iext);
      external.display(Iext);
      vpDisplay::flush(Iext);
    }
    //! [Display]
    std::cout << "robot: " << vpMorphSimRobot::kindName(robot.kind()) << ", joints " << robot.getJointPositions().t()
              << std::endl;
    std::cout << "occluded share of the contour: " << scene.occludedShare() << std::endl;
    std::cout << "truth: simulator vs AprilTag " << t * 1000 << " mm, " << vpMath::deg(r) << " deg" << std::endl;
    std::cout << "wrote " << out + "/morph-scene.png" << std::endl;
    viewer.expectContour("camera", "projected outline", truth.points(), vpColor::green);
    viewer.expectText("camera", "caption", tutorial::Viewer::captionBand(caption), vpColor::white, caption);
    viewer.save();
    viewer.waitClick(I);
    return (t < 0.002 && vpMath::deg(r) < 0.5) ? EXIT_SUCCESS : EXIT_FAILURE;
  } catch (const vpException &e) {
    std::cerr << "error: " << e.getStringMessage() << std::endl;
    return EXIT_FAILURE;
  }
}
