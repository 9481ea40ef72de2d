#include <visp3/morph_vs/vpMorphServoGuard.h>

#include "vpMorphParameterCheck.h"

#include <cmath>
#include <sstream>

#include <visp3/morph/vpMorphException.h>

void vpMorphServoGuard::setJumpPixels(double px)
{
  vpMorphParameterCheck::positive(px, "vpMorphServoGuard::setJumpPixels", "the jump threshold");
  m_jumpPx = px;
}

void vpMorphServoGuard::setJumpRotation(double rad)
{
  vpMorphParameterCheck::positive(rad, "vpMorphServoGuard::setJumpRotation", "the jump threshold");
  m_jumpRotation = rad;
}

namespace
{
// Template \e name's index in \e db, for a target check with \e slack.
std::size_t targetIndex(const vpMorphDatabase &db, const std::string &name, double slack)
{
  if (!std::isfinite(slack) || slack < 1.0)
    throw vpMorphException(vpMorphException::badParameterError,
                           "vpMorphServoGuard::setTargetCheck: the slack must be finite and >= 1");
  const std::size_t k = db.find(name);
  if (k == vpMorphRecognition::npos)
    throw vpMorphException(vpMorphException::notFoundError,
                           "vpMorphServoGuard::setTargetCheck: no template '" + name + "' in the database");
  return k;
}
} // namespace

void vpMorphServoGuard::setTargetCheck(const vpMorphDatabase &db, const std::string &name, double slack)
{
  m_index = targetIndex(db, name, slack);
  m_db = std::make_shared<const vpMorphDatabase>(db);
  m_recognizer.reset();
  m_slack = slack;
}

void vpMorphServoGuard::setTargetCheck(const vpMorphPartRecognizer &recognizer, const std::string &name, double slack)
{
  m_index = targetIndex(recognizer.getDatabase(), name, slack);
  m_recognizer = std::make_shared<const vpMorphPartRecognizer>(recognizer); // shares its databases
  m_db = std::shared_ptr<const vpMorphDatabase>(m_recognizer, &m_recognizer->getDatabase());
  m_slack = slack;
}

void vpMorphServoGuard::clearTargetCheck()
{
  m_db.reset();
  m_recognizer.reset();
}

const vpMorphDatabase &vpMorphServoGuard::getTargetDatabase() const
{
  static const vpMorphDatabase none;
  return m_db ? *m_db : none;
}

void vpMorphServoGuard::reset()
{
  m_lost = m_replans = 0;
  m_halted = NOT_STARTED;
  m_verification = NOT_VERIFIED;
  m_targetDistance = std::numeric_limits<double>::quiet_NaN();
}

vpMorphServoGuard::Status vpMorphServoGuard::halt(Status s)
{
  m_halted = s;
  return s;
}

vpMorphServoGuard::Status vpMorphServoGuard::hold(Status why)
{
  if (++m_lost > m_maxLost)
    return halt(LOST_TOO_LONG);
  return why;
}

bool vpMorphServoGuard::viewJumped(const vpMorphRigidTransform &T, const vpMorphRigidTransform &previous, double gain,
                                   const vpCameraParameters &cam) const
{
  // A command executes about gain x the residual per period (twice that in translation with a calibration error).
  const double dth = std::fabs(std::remainder(T.theta() - previous.theta(), 2.0 * M_PI));
  if (dth > gain * std::fabs(previous.theta()) + m_jumpRotation)
    return true;
  const double px = cam.get_px(), py = cam.get_py();
  const double dt = std::hypot((T.tx() - previous.tx()) * px, (T.ty() - previous.ty()) * py);
  return dt > 2.0 * gain * std::hypot(previous.tx() * px, previous.ty() * py) + m_jumpPx;
}

bool vpMorphServoGuard::allowReplan()
{
  if (m_replans >= m_maxReplans) {
    halt(TOO_MANY_REPLANS);
    return false;
  }
  ++m_replans;
  return true;
}

bool vpMorphServoGuard::targetMismatch(const vpMorphContour &current, const vpMorphContour &target, bool articulated)
{
  if (!m_db)
    return false;
  const vpMorphDatabase &db = *m_db;
  if (m_recognizer) {
    const vpMorphPartRecognizer::Naming n = m_recognizer->namedAs(current, m_index);
    if (n != vpMorphPartRecognizer::UNDECIDED)
      return n == vpMorphPartRecognizer::NAMED_OTHER;
  }
  const vpMorphRecognition r = db.recognize(current);
  if (articulated) {
    // Its distance to the target posed at one opening varies from one view to the next: the database's, over its
    // poses.
    if (!db.accepts(current, m_index, m_slack, &m_targetDistance))
      return true;
  } else {
    m_targetDistance = db.distance().distance(current, target);
    if (!(m_targetDistance <= m_slack * db.threshold(m_index)) &&
        !(db.support(current, m_index, r.index == m_index && r.mirrored) >= db.minimumSupport()))
      return true; // NaN too; an occluded view of the target (it shows enough of its outline) is not a mismatch
  }
  if (!(r.index != vpMorphRecognition::npos && r.index != m_index && r.accepted &&
        m_targetDistance >= getMismatchRatio() * r.distance))
    return false;
  // Nearer by the distance, another template still does not replace the target when it explains less of the view
  // (a bent view may be nearer another template by the distance).
  return !(std::isfinite(r.support) && db.support(current, m_index, db.distance().mirrors()) > r.support);
}

const char *vpMorphServoGuard::verificationName(Verification v)
{
  switch (v) {
  case NOT_VERIFIED:
    return "not verified";
  case VERIFIED:
    return "verified";
  case UNEXPLAINED:
    return "unexplained";
  case OUTSIDE_THRESHOLDS:
    return "outside thresholds";
  case PART_UNCHECKED:
    return "part unchecked";
  case NOT_PINNED:
    return "not pinned";
  case TILT_UNBOUNDED:
    return "tilt unbounded";
  }
  return "?";
}

vpMorphServoGuard::Status vpMorphServoGuard::verify(const vpMorphViewAlignment &a, double rotationRad,
                                                    double translationPx, double scalePx, double radiusPx,
                                                    double pixelsPerUnit, bool tiltVerified)
{
  m_verification = [&] {
    if (!a.explained())
      return UNEXPLAINED;
    // Within the thresholds by its own residual (a measurement other than the one the servo stopped on may disagree).
    const vpMorphRigidTransform &T = a.transform;
    if (!(std::fabs(T.theta()) < rotationRad && std::hypot(T.tx(), T.ty()) * pixelsPerUnit < translationPx &&
          std::fabs(T.scale() - 1.0) * radiusPx < scalePx))
      return OUTSIDE_THRESHOLDS;
    // A view explained only in part may be another shape with more than half of the target's outline: only the
    // target check can say it is the target.
    if (a.model != vpMorphViewAlignment::RIGID && !hasTargetCheck())
      return PART_UNCHECKED;
    const double k = getVerificationSigmas();
    if (!(k * a.rotationDeviation() <= rotationRad && k * a.translationDeviation() * pixelsPerUnit <= translationPx &&
          k * a.scaleDeviation() * radiusPx <= scalePx))
      return NOT_PINNED;
    return tiltVerified ? VERIFIED : TILT_UNBOUNDED;
  }();
  return m_verification == VERIFIED ? CONVERGED : UNVERIFIED;
}
