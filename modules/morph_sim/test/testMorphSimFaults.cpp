// Scene- and robot-level faults used by the benchmark's timed events: a frame without the object
// (Faults::objectHidden) and a sudden displacement of the camera (vpMorphSimRobot::displaceCamera()).
#include <catch2/catch.hpp>

#include <cmath>

#include <visp3/core/vpMath.h>
#include <visp3/core/vpThetaUVector.h>
#include <visp3/morph_sim/vpMorphPlanarScene.h>
#include <visp3/morph_sim/vpMorphSimRobot.h>
#include <visp3/morph_sim/vpMorphTagPoseEstimator.h>

namespace
{
const std::string kData = VISPMORPH_DATA_DIR;

void poseDiff(const vpHomogeneousMatrix &a, const vpHomogeneousMatrix &b, double &t, double &r)
{
  const vpHomogeneousMatrix d = a.inverse() * b;
  t = d.getTranslationVector().frobeniusNorm();
  r = vpThetaUVector(d.getRotationMatrix()).getTheta();
}
} // namespace

TEST_CASE("a frame without the object: tag still there, no silhouette", "[morph_sim][faults]")
{
  vpMorphPlanarScene scene(kData + "/objects/key.png");
  const vpHomogeneousMatrix cMo(0.01, -0.01, 0.5, 0, 0, vpMath::rad(30));
  vpImage<unsigned char> I, J;
  scene.render(cMo, I);
  vpMorphPlanarScene::Faults f;
  f.objectHidden = true;
  scene.setFaults(f);
  scene.render(cMo, J);
  const vpMorphTagPoseEstimator est = scene.tagPoseEstimator();
  vpHomogeneousMatrix cMoI, cMoJ;
  std::vector<vpImagePoint> ci, cj;
  REQUIRE(est.estimate(I, cMoI, &ci));
  REQUIRE(est.estimate(J, cMoJ, &cj));
  CHECK_FALSE(vpMorphTagPoseEstimator::silhouette(I, ci).empty());
  CHECK(vpMorphTagPoseEstimator::silhouette(J, cj).empty());
  f.objectHidden = false; // back: the same image as before, bit for bit
  scene.setFaults(f);
  scene.render(cMo, J);
  const bool same = J == I;
  CHECK(same);
}

TEST_CASE("a sudden displacement of the camera, on every robot, outside the path", "[morph_sim][faults]")
{
  const vpHomogeneousMatrix cdMo(0, 0, 0.5, 0, 0, 0);
  const vpHomogeneousMatrix cMcp(0.02, 0.0, 0.0, 0, 0, vpMath::rad(10));
  for (auto kind : {vpMorphSimRobot::FREE_CAMERA, vpMorphSimRobot::VIPER850, vpMorphSimRobot::AFMA6}) {
    vpMorphSimRobot robot(kind, 0.04);
    robot.setDesiredPose(cdMo);
    REQUIRE(robot.initialiseCameraRelativeToDesired(vpHomogeneousMatrix(0.01, 0.01, 0, 0, 0, vpMath::rad(20))));
    vpColVector v(6, 0.0);
    v[0] = 0.01;
    robot.setVelocity(vpRobot::CAMERA_FRAME, v);
    const double path = robot.cameraPathLength();
    const vpHomogeneousMatrix fMc = robot.get_fMc();
    INFO(vpMorphSimRobot::kindName(kind));
    REQUIRE(robot.displaceCamera(cMcp));
    double t, r;
    poseDiff(fMc * cMcp, robot.get_fMc(), t, r);
    CHECK(t < 1e-6);
    CHECK(r < 1e-6);
    CHECK(robot.cameraPathLength() == path); // not a commanded motion
    CHECK(robot.status() == vpMorphSimRobot::OK);
    // Out of reach (the arms): not moved.
    if (kind != vpMorphSimRobot::FREE_CAMERA) {
      const vpHomogeneousMatrix before = robot.get_fMc();
      CHECK_FALSE(robot.displaceCamera(vpHomogeneousMatrix(0, 0, -5.0, 0, 0, 0)));
      poseDiff(before, robot.get_fMc(), t, r);
      CHECK(t == 0);
    }
  }
}
