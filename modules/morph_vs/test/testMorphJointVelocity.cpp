// Tests of vpMorphJointVelocity: on ViSP's Afma6 and Viper850 models, joint velocities held over each period follow
// a long turn about the optical axis far closer than the plain conversion, exactly when solved on the model, from the
// first period on; history and bad input.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

#include <visp3/core/vpMath.h>
#include <visp3/core/vpThetaUVector.h>
#include <visp3/core/vpVelocityTwistMatrix.h>
#include <visp3/morph/vpMorphException.h>
#include <visp3/morph_vs/vpMorphJointVelocity.h>
#include <visp3/robot/vpAfma6.h>
#include <visp3/robot/vpViper850.h>

namespace
{
constexpr double kDt = 0.04;

// Angle (deg) between the optical axes of two camera poses, and the distance (m) between their centres.
void poseError(const vpHomogeneousMatrix &fMa, const vpHomogeneousMatrix &fMb, double &tiltDeg, double &shift)
{
  const vpRotationMatrix Ra = fMa.getRotationMatrix(), Rb = fMb.getRotationMatrix();
  const double c = Ra[0][2] * Rb[0][2] + Ra[1][2] * Rb[1][2] + Ra[2][2] * Rb[2][2];
  tiltDeg = vpMath::deg(std::acos(std::min(1.0, c)));
  shift = (fMa.getTranslationVector() - fMb.getTranslationVector()).frobeniusNorm();
}

enum Conversion { PLAIN, EXTRAPOLATED, MODEL };

template <class Robot> vpMorphJointVelocity::KinematicModel modelOf(const Robot &robot)
{
  return {[&robot](const vpColVector &q) {
            vpHomogeneousMatrix fMe;
            robot.get_fMe(q, fMe);
            return fMe;
          },
          [&robot](const vpColVector &q) {
            vpMatrix eJe;
            robot.get_eJe(q, eJe);
            return eJe;
          }};
}

// Turns the camera by 60 deg about its optical axis in \e periods periods, each period's joint velocity held
// (q += qdot dt), converted as \e how; returns the tilt and shift against the turn.
template <class Robot>
void turn(Robot &robot, const vpHomogeneousMatrix &eMc, vpColVector q, Conversion how, double &tiltDeg, double &shift,
          int periods = 80)
{
  vpHomogeneousMatrix fMc0;
  robot.get_fMc(q, fMc0);
  vpColVector vc(6, 0.0);
  vc[5] = vpMath::rad(60.0) / (periods * kDt);
  const vpColVector ve = vpVelocityTwistMatrix(eMc) * vc;
  vpMorphJointVelocity conv(kDt);
  if (how == MODEL)
    conv.setKinematicModel(modelOf(robot));
  for (int k = 0; k < periods; ++k) {
    vpMatrix eJe;
    robot.get_eJe(q, eJe);
    q += (how == PLAIN ? eJe.pseudoInverse(1e-6) * ve : conv.compute(eJe, q, ve)) * kDt;
  }
  vpHomogeneousMatrix fMc;
  robot.get_fMc(q, fMc);
  poseError(fMc, fMc0 * vpHomogeneousMatrix(0, 0, 0, 0, 0, vpMath::rad(60.0)), tiltDeg, shift);
}

// The benchmark's reference configurations of the two arms.
vpColVector afmaReference()
{
  vpColVector q(6, 0.0);
  q[0] = 0.05;
  q[1] = -0.04;
  q[4] = vpMath::rad(45);
  return q;
}
vpColVector viperReference()
{
  vpColVector q(6, 0.0);
  q[1] = vpMath::rad(-120);
  q[2] = vpMath::rad(220);
  q[4] = vpMath::rad(-45);
  return q;
}
} // namespace

TEST_CASE("vpMorphJointVelocity: a long turn about the optical axis held period by period stays a turn",
          "[joint_velocity]")
{
  vpAfma6 afma;
  const vpColVector qa = afmaReference();
  double plainTilt, plainShift, tilt, shift;
  turn(afma, afma.get_eMc(), qa, PLAIN, plainTilt, plainShift);
  turn(afma, afma.get_eMc(), qa, EXTRAPOLATED, tilt, shift);
  INFO("Afma6: plain " << plainTilt << " deg, " << 1000 * plainShift << " mm; predicted " << tilt << " deg, "
                       << 1000 * shift << " mm");
  CHECK(plainTilt > 0.3); // the drift the class is for (0.39 deg measured)
  CHECK(tilt < 0.05 * plainTilt);
  CHECK(shift < 0.1 * plainShift);

  vpViper850 viper;
  const vpColVector qv = viperReference();
  vpHomogeneousMatrix eMcViper;
  viper.get_eMc(eMcViper);
  turn(viper, eMcViper, qv, PLAIN, plainTilt, plainShift);
  turn(viper, eMcViper, qv, EXTRAPOLATED, tilt, shift);
  INFO("Viper850: plain " << plainTilt << " deg, " << 1000 * plainShift << " mm; predicted " << tilt << " deg, "
                          << 1000 * shift << " mm");
  CHECK(tilt <= plainTilt);
  CHECK(shift <= plainShift);
}

TEST_CASE("vpMorphJointVelocity: solved on the robot's model, a turn is a turn from its first period",
          "[joint_velocity]")
{
  vpAfma6 afma;
  const vpColVector qa = afmaReference();
  vpViper850 viper;
  const vpColVector qv = viperReference();
  vpHomogeneousMatrix eMcViper;
  viper.get_eMc(eMcViper);
  // 60 deg in 80 periods, and in 2 (a half turn's first periods at the bench's top rate are 16 deg each).
  for (int periods : {80, 2}) {
    double plainTilt, plainShift, tilt, shift;
    turn(afma, afma.get_eMc(), qa, PLAIN, plainTilt, plainShift, periods);
    turn(afma, afma.get_eMc(), qa, MODEL, tilt, shift, periods);
    INFO(periods << " periods, Afma6: plain " << plainTilt << " deg, " << 1000 * plainShift << " mm; on the model "
                 << tilt << " deg, " << 1000 * shift << " mm");
    CHECK(plainTilt > 0.3);
    CHECK(tilt < 1e-3); // kPoseTolerance a period: micro-radians
    CHECK(shift < 1e-5);
    turn(viper, eMcViper, qv, PLAIN, plainTilt, plainShift, periods);
    turn(viper, eMcViper, qv, MODEL, tilt, shift, periods);
    INFO(periods << " periods, Viper850: plain " << plainTilt << " deg, " << 1000 * plainShift << " mm; on the model "
                 << tilt << " deg, " << 1000 * shift << " mm");
    CHECK(tilt < 1e-3);
    CHECK(shift < 1e-5);
  }

  vpMorphJointVelocity conv(kDt);
  vpMorphJointVelocity::KinematicModel half = modelOf(afma);
  half.eJe = nullptr;
  CHECK_THROWS_AS(conv.setKinematicModel(half), vpMorphException);
  CHECK_FALSE(conv.getKinematicModel().isSet());
  conv.setKinematicModel(modelOf(afma));
  CHECK(conv.getKinematicModel().isSet());
  conv.setKinematicModel({});
  CHECK_FALSE(conv.getKinematicModel().isSet());

  // A model that does not fit the robot: a clear error, not a wrong velocity.
  vpMorphJointVelocity::KinematicModel wrong = modelOf(afma);
  wrong.eJe = [](const vpColVector &) { return vpMatrix(5, 6, 0.0); };
  conv.setKinematicModel(wrong);
  vpMatrix J;
  afma.get_eJe(qa, J);
  vpColVector ve(6, 0.0);
  ve[0] = 0.05;
  ve[3] = 1.0;
  ve[5] = 1.0;
  CHECK_THROWS_AS(conv.compute(J, qa, ve), vpMorphException);
}

TEST_CASE("vpMorphJointVelocity: the plain conversion without a usable last step, and bad input", "[joint_velocity]")
{
  vpAfma6 afma;
  vpColVector q(6, 0.0);
  q[4] = vpMath::rad(45);
  vpMatrix J;
  afma.get_eJe(q, J);
  vpColVector ve(6, 0.0);
  ve[3] = 0.1;
  ve[0] = 0.01;
  const vpColVector plain = J.pseudoInverse(1e-6) * ve;
  vpMorphJointVelocity conv(kDt);
  CHECK((conv.compute(J, q, ve) - plain).frobeniusNorm() < 1e-12); // first period: nothing to extrapolate from
  CHECK((conv.compute(J, q, ve) - plain).frobeniusNorm() < 1e-12); // no motion since: the same
  // After a step along plain, the coming step continues it: the Jacobian is extrapolated.
  vpColVector q1 = q + plain * kDt;
  vpMatrix J1;
  afma.get_eJe(q1, J1);
  const vpColVector v1 = conv.compute(J1, q1, ve);
  CHECK((v1 - J1.pseudoInverse(1e-6) * ve).frobeniusNorm() > 1e-9);
  conv.reset();
  CHECK((conv.compute(J1, q1, ve) - J1.pseudoInverse(1e-6) * ve).frobeniusNorm() < 1e-12);

  CHECK_THROWS_AS(vpMorphJointVelocity(0.0), vpMorphException);
  CHECK_THROWS_AS(vpMorphJointVelocity(std::numeric_limits<double>::quiet_NaN()), vpMorphException);
  CHECK_THROWS_AS(conv.compute(J, vpColVector(5, 0.0), ve), vpMorphException);
  CHECK_THROWS_AS(conv.compute(J, q, vpColVector(3, 0.0)), vpMorphException);
  vpColVector bad = ve;
  bad[2] = std::numeric_limits<double>::infinity();
  CHECK_THROWS_AS(conv.compute(J, q, bad), vpMorphException);
}
