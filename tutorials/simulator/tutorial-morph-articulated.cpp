//! \example tutorial-morph-articulated.cpp
//! An articulated template: the pliers, taught closed together with their two arms and the pin (a joint file),
//! recognise the pliers opened by 32 deg, pose themselves at that opening, and vpServoMorph aligns a simulated
//! free-flying camera with the opened pliers. Writes OUTDIR/morph-articulated.png (default: the current folder): the
//! morph from the first view to the template posed at its opening. With a display, shows the servo as it runs
//! (vpServoMorph::display(), its residuals and velocity, the camera's path from outside). Usage: OUTDIR [-c] [-d]
//! [--save-display FILE].
#include <cstdio>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include <visp3/core/vpMath.h>
#include <visp3/morph/vpMorph.h>
#include <visp3/morph/vpMorphDatabase.h>
#include <visp3/morph/vpMorphDrawing.h>
#include <visp3/morph/vpMorphJointFile.h>
#include <visp3/morph_sim/vpMorphPlanarScene.h>
#include <visp3/morph_sim/vpMorphSimRobot.h>
#include <visp3/morph_sim/vpMorphTagPoseEstimator.h>
#include <visp3/morph_vs/vpServoMorph.h>

#include "tutorial-display.h"
#include "tutorial-servo-windows.h"

int main(int argc, char **argv)
{
  std::vector<std::string> args;
  tutorial::Viewer viewer(argc, argv, args);
  if (!tutorial::Viewer::accepts(args, 1, argv[0], "[OUTDIR]"))
    return EXIT_FAILURE;
  const std::string out = args.empty() ? "." : args[0];
  const std::string data = VISPMORPH_DATA_DIR;
  try {
    //! [Teach]
    // Each tool taught from the same desired pose: 0.5 m above the plane, turned by 20 deg. The pliers also get
    // their arms, each seen alone from there, and the pin (data/joints/pliers.json: the arms' drawings, the pin and
    // the range of the opening in the drawing's frame).
    const vpHomogeneousMatrix cdMo(0.01, 0, 0.5, 0, 0, vpMath::rad(20));
    const vpMorphJointFile joint = vpMorphJointFile::read(data + "/joints/pliers.json");
    vpMorphDatabase db;
    for (const std::string name : {"hammer", "key", "pliers", "screwdriver", "wedge", "wrench"}) {
      const std::string image = data + "/objects/" + name + ".png";
      const vpMorphPlanarScene scene(image);
      vpMorphTemplate t(name, scene.silhouette(cdMo), image, cdMo);
      if (name == "pliers")
        t.setArticulation(scene.articulation(joint, cdMo));
      db.add(t);
    }
    db.calibrate();
    //! [Teach]

    //! [World]
    // The pliers on the bench are the opened drawing, whose arms vispmorph-make-data turned about the pin (the joint
    // file's "deformed_turns_deg"), laid with arm 0 where the template has it: the goal is cdMo. Laid by arm 1, it
    // would be cdMo * W (the alternative placement): the view tells the two apart by the arm it keeps still.
    std::ifstream f(data + "/joints/pliers.json");
    const std::vector<double> turns = nlohmann::json::parse(f).at("deformed_turns_deg").get<std::vector<double>>();
    const double pu = joint.pivot().get_u(), pv = joint.pivot().get_v();
    vpMorphPlanarScene world(data + "/objects/pliers-deformed.png");
    world.setReferenceImage(data + "/objects/pliers.png"); // one texture frame for both drawings
    world.setReferenceAlignment(vpMorphRigidTransform(-vpMath::rad(turns[0]), 0, 0, 1, pu, pv),
                                {vpMorphRigidTransform(-vpMath::rad(turns[1]), 0, 0, 1, pu, pv)});
    const vpHomogeneousMatrix goals[2] = {cdMo, cdMo * world.alternativePlacements()[0]};
    //! [World]

    //! [Start]
    // A free-flying camera 40 mm and 70 deg away. The controller believes its mount 1 cm off along each axis and
    // turned by 3 deg about the optical axis: the online hand-eye estimation takes it up. (A mount tilted as well
    // would tilt the camera along the turn: vpServoMorph::setTiltCorrection() levels it where the outline bounds the
    // tilt, which a thin part's does only to tenths of a degree.)
    vpMorphSimRobot robot(vpMorphSimRobot::FREE_CAMERA);
    robot.setCameraMount(robot.eMcTrue(),
                         robot.eMcTrue() * vpHomogeneousMatrix(0.01, 0.01, 0.01, 0, 0, vpMath::rad(3)));
    robot.setDesiredPose(cdMo);
    if (!robot.initialiseCameraRelativeToObject(vpHomogeneousMatrix(0.04, 0, 0, 0, 0, vpMath::rad(70)).inverse() *
                                                cdMo)) {
      std::cerr << "start pose out of reach" << std::endl;
      return EXIT_FAILURE;
    }
    // The camera's view: rendered, the tag found by the detector and masked, the pliers' silhouette extracted.
    const vpMorphTagPoseEstimator tags = world.tagPoseEstimator();
    vpImage<unsigned char> I;
    auto look = [&]() {
      world.render(robot.get_cMo(), I);
      vpHomogeneousMatrix cMo_tag;
      std::vector<vpImagePoint> corners;
      if (!tags.estimate(I, cMo_tag, &corners))
        corners.clear();
      return vpMorphTagPoseEstimator::silhouette(I, corners);
    };
    //! [Start]

    //! [Recognize]
    const vpMorphContour first = look();
    const vpMorphRecognition r = db.recognize(first);
    std::printf("first view: %s %s, opened %.0f deg (the pose nearest; poses every 4 deg), distance %.3f "
                "(threshold %.3f)\n",
                r.accepted ? "recognised as" : "rejected, nearest", db[r.index].name().c_str(),
                vpMath::deg(r.articulation), r.distance, r.threshold);
    if (!r.accepted)
      return EXIT_FAILURE;
    // The goal of this view: the template at the opening it shows, the arm that needs the smaller turn kept still.
    double opening = 0.0;
    unsigned int fixedPart = 0;
    const vpMorphContour goal = db[r.index].viewFor(first, &opening, &fixedPart);
    const vpMorph morph(first, goal), rigid(first, db[r.index].contour());
    std::printf("opening %.2f deg, arm %u kept still; D_morph to the posed template %.3f, to the closed one %.3f\n",
                vpMath::deg(opening), fixedPart, morph.distance(), rigid.distance());
    vpMorphDrawing::write(vpMorphDrawing::sequenceStrip(morph, 8, 160, 0), out + "/morph-articulated.png");
    //! [Recognize]

    //! [Servo]
    // The target is the template: vpServoMorph poses it at the opening of the view at the start of each sequence.
    vpServoMorph servo;
    servo.setCameraParameters(world.camera());
    servo.set_eMc(robot.eMcNominal());
    servo.getPlanner().setSubGoalCount(10);
    servo.setSamplingTime(robot.samplingTime());
    servo.setGain(0.1);
    servo.setTarget(db[r.index]);
    tutorial::ServoWindows windows(viewer, world.imageWidth(), world.imageHeight(), world.objectContour3D(),
                                   world.tagCorners3D(), cdMo, "Free camera");
    int it = 0;
    for (; it < 600 && servo.getStatus() != vpServoMorph::CONVERGED && !windows.stopped(); ++it) {
      const vpColVector ve = servo.computeControlLaw(look());
      windows.setDesiredPose(goals[servo.getTargetFixedPart()]); // the arm kept still decides the goal
      windows.show(I, servo, it, robot.get_cMo());
      if (servo.getStatus() != vpServoMorph::CONVERGED && servo.getStatus() != vpServoMorph::MOVING &&
          servo.getStatus() != vpServoMorph::SUBGOAL_REACHED && servo.getStatus() != vpServoMorph::REPLANNED)
        break; // lost, degenerate or unreliable: the velocity is zero, stop here
      robot.setVelocity(vpRobot::END_EFFECTOR_FRAME, ve);
    }
    //! [Servo]
    double t, rot;
    vpMorphTagPoseEstimator::poseDifference(robot.get_cMo(), goals[servo.getTargetFixedPart()], t, rot);
    std::printf("%s after %d iterations (%s): target posed at %.2f deg, arm %u still; %.2f mm and %.3f deg from the "
                "goal\n",
                servo.getStatus() == vpServoMorph::CONVERGED ? "converged" : "stopped", it,
                vpServoMorph::statusName(servo.getStatus()), vpMath::deg(servo.getTargetOpening()),
                servo.getTargetFixedPart(), t * 1000, vpMath::deg(rot));
    std::cout << "wrote " << out + "/morph-articulated.png" << std::endl;
    windows.end(servo);
    return servo.getStatus() == vpServoMorph::CONVERGED ? EXIT_SUCCESS : EXIT_FAILURE;
  } catch (const vpException &e) {
    std::cerr << "error: " << e.getStringMessage() << std::endl;
    return EXIT_FAILURE;
  }
}
