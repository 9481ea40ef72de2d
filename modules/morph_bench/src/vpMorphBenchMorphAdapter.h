/*
  \file vpMorphBenchMorphAdapter.h
  \brief Internal to the morph_bench module (not installed): what the two VISPMorph adapters share (the recognition
  at the first frame, the target check and the re-recognition).
*/
#ifndef VP_MORPH_BENCH_MORPH_ADAPTER_H
#define VP_MORPH_BENCH_MORPH_ADAPTER_H

#include <algorithm>
#include <string>
#include <vector>

#include <visp3/core/vpExponentialMap.h>
#include <visp3/morph/vpMorphException.h>
#include <visp3/morph/vpMorphHomography.h>
#include <visp3/morph_vs/vpMorphJointVelocity.h>

#include "vpMorphBenchAdapter.h"

//! Recognition at the first frame, the target check and the re-recognition, shared by the two VISPMorph adapters.
class vpMorphBenchMorphAdapter : public vpMorphBenchAdapter
{
public:
  std::string recognizedObject() const override { return m_object; }

protected:
  //! Factor on a template's acceptance threshold for vpServoMorph's own target check: a slack over recognition's
  //! threshold, as a view seen during the servo is not the first view (a last line of defence, see mismatch()).
  static constexpr double kCheckSlack = 1.25;
  //! The recognition is checked on the first image and then every kCheckPeriod measured images (1 s at 25 Hz).
  static constexpr unsigned int kCheckPeriod = 25;
  //! Another template replaces the current one only when the current one costs this much more work.
  static constexpr double kSwitchRatio = 1.2; // vpMorphServoGuard::getMismatchRatio()

  //! The share of its displacement a VISPMorph law executes a period: lambda dt, the exponential rate of the stock
  //! laws' constant gain.
  double lawShare() const { return std::min(1.0, m_ctx.lambda * m_ctx.samplingTime); }

  /*!
    The silhouette of image \e I. On the first one, the database tells which region is the object
    (vpMorphTagPoseEstimator::silhouetteCandidates(), the context's vpMorphPartRecognizer on the list); afterwards the
    silhouette is the one that continues the last (a larger region elsewhere is not the object). False when the caller
    must return \e cmd as it is (hold: no silhouette; stop: rejected); true with cmd.measureMs set.
  */
  bool observe(const vpImage<unsigned char> &I, vpMorphContour &c, Command &cmd)
  {
    double ms = 0;
    const TagView tag = detectTag(I);
    std::string reason;
    if (!m_template) {
      const std::vector<vpMorphContour> candidates = vpMorphTagPoseEstimator::silhouetteCandidates(I, tag.corners, &ms);
      if (candidates.empty()) {
        cmd = holdCommand(ms);
        return false;
      }
      if (!recognize(candidates, c, reason)) {
        cmd = stopCommand(reason);
        return false;
      }
    } else {
      c = vpMorphTagPoseEstimator::silhouette(I, tag.corners, m_previous, &ms);
      if (c.empty()) {
        cmd = holdCommand(ms);
        return false;
      }
    }
    m_previous = c;
    cmd = Command();
    cmd.measureMs = ms;
    return true;
  }
  //! Recognises the object among the first image's \e candidates into \e c; false (and \e reason) if rejected.
  bool recognize(const std::vector<vpMorphContour> &candidates, vpMorphContour &c, std::string &reason)
  {
    if (!m_ctx.database || m_ctx.database->empty())
      throw vpMorphException(vpMorphException::badParameterError, "morph controller: no template database");
    if (!m_ctx.forcedTemplate.empty()) { // fault injection: a recognition error
      m_template = &(*m_ctx.database)[m_ctx.forcedTemplate];
      m_object = m_template->name();
      c = candidates.front();
      return true;
    }
    std::size_t chosen = 0;
    const vpMorphRecognition r = m_ctx.recognizer ? m_ctx.recognizer->recognize(candidates, chosen)
                                                  : m_ctx.database->recognize(candidates, chosen);
    c = candidates[chosen];
    if (r.index == vpMorphRecognition::npos || !r.accepted) {
      reason = "recognition";
      return false;
    }
    m_template = &(*m_ctx.database)[r.index];
    m_object = m_template->name();
    return true;
  }
  /*!
    True when \e c is not the current template's shape (vpServoMorph's target check, for the adapter without
    vpServoMorph): not accepted by the database as that template with kCheckSlack (vpMorphDatabase::accepts():
    beyond its threshold times kCheckSlack, and not an occluded view of it), or the database clearly prefers
    another template (its best, accepted, at least kSwitchRatio times cheaper). The thresholds alone cannot
    tell every pair apart: calibrated on 20 % occlusions, the pliers' threshold (1.57) is above its distance to
    the screwdriver (1.44), so a screwdriver taken for the pliers passes it.
  */
  bool mismatch(const vpMorphContour &c) const
  {
    const vpMorphDatabase &db = *m_ctx.database;
    const std::size_t cur = db.find(m_template->name());
    if (m_ctx.recognizer) { // its rigid stage first, as vpMorphServoGuard's check with a recognizer
      const vpMorphPartRecognizer::Naming n = m_ctx.recognizer->namedAs(c, cur);
      if (n != vpMorphPartRecognizer::UNDECIDED)
        return n == vpMorphPartRecognizer::NAMED_OTHER;
    }
    const vpMorphRecognition r = db.recognize(c);
    if (r.index == vpMorphRecognition::npos || r.index == cur)
      return false;
    double d = 0.0;
    return !db.accepts(c, cur, kCheckSlack, &d) || (r.accepted && d >= kSwitchRatio * r.distance);
  }
  /*!
    The current template was found wrong for \e c: recognises \e c again without the templates already
    rejected (the best, else the runner-up if it is \e c's part: the recognizer's rigid stage decides where it names
    one, as in mismatch(), the database's acceptance elsewhere). False when none is left.
  */
  bool rerecognize(const vpMorphContour &c)
  {
    const vpMorphDatabase &db = *m_ctx.database;
    m_rejected.push_back(db.find(m_template->name()));
    const vpMorphRecognition r = m_ctx.recognizer ? m_ctx.recognizer->recognize(c) : db.recognize(c);
    auto names = [&](std::size_t k) {
      const vpMorphPartRecognizer::Naming n =
          m_ctx.recognizer ? m_ctx.recognizer->namedAs(c, k) : vpMorphPartRecognizer::UNDECIDED;
      return n == vpMorphPartRecognizer::UNDECIDED ? db.accepts(c, k) : n == vpMorphPartRecognizer::NAMED_TEMPLATE;
    };
    const std::size_t idx[2] = {r.index, r.secondIndex};
    for (int k = 0; k < 2; ++k) {
      if (idx[k] == vpMorphRecognition::npos ||
          std::find(m_rejected.begin(), m_rejected.end(), idx[k]) != m_rejected.end() ||
          !(k == 0 ? r.accepted : names(idx[k])))
        continue;
      m_template = &db[idx[k]];
      m_object = m_template->name();
      return true;
    }
    return false;
  }
  /*!
    \e cmd with its end-effector twist sent as the joint velocities that, held for the period, move the end-effector
    by it (vpMorphJointVelocity on the arm's kinematic model), the conversion's time counted in the law's: held from
    the Jacobian at the period's start, a long turn tilts the camera, which a planar law does not take back.
  */
  Command toJoints(Command cmd, const vpMatrix &eJe, const vpColVector &q)
  {
    const Clock::time_point t0 = Clock::now();
    predictPrevious(cmd.v);
    cmd.v = m_joints.compute(eJe, q, cmd.v);
    cmd.controlMs += msSince(t0);
    cmd.frame = vpRobot::JOINT_STATE;
    return cmd;
  }
  //! The hand-eye transform the adapter's law converts with (its controller's estimate where it has one).
  virtual vpHomogeneousMatrix handEye() const { return m_ctx.eMc; }
  /*!
    Moves the last silhouette, which the next image's must overlap (vpMorphContourExtractor::extractJoined()), by the
    camera motion the end-effector twist \e ve commands over the period (through handEye(); the plane
    fronto-parallel at the depth the silhouette's size gives against the template's): in a half turn's period a
    piece an occluder cut off moves farther than its own size, and, not overlapping where it was, would be dropped.
  */
  void predictPrevious(const vpColVector &ve)
  {
    if (m_previous.empty() || !m_template || !finite(ve))
      return;
    const double a = m_previous.area(), ad = m_template->contour().area();
    if (!(a > 0.0) || !(ad > 0.0))
      return;
    const double Z = m_template->cdMo()[2][3] * std::sqrt(ad / a);
    const vpColVector vc = vpVelocityTwistMatrix(handEye().inverse()) * ve;
    // The plane z = Z of this camera, in the next one: x' ~ (R + t n^T / Z) x with n = (0, 0, 1).
    const vpHomogeneousMatrix cnMc = vpExponentialMap::direct(vc, m_ctx.samplingTime).inverse();
    vpMatrix G(3, 3);
    for (unsigned int r = 0; r < 3; ++r) {
      for (unsigned int k = 0; k < 3; ++k)
        G[r][k] = cnMc[r][k];
      G[r][2] += cnMc[r][3] / Z;
    }
    try {
      m_previous = vpMorphHomography(G).apply(m_previous.toNormalized(m_ctx.cam)).toPixels(m_ctx.cam);
    } catch (const vpException &) {
      // A vertex mapped to infinity (the plane seen edge-on): the silhouette as it was.
    }
  }
  void reset() override
  {
    m_joints.setSamplingTime(m_ctx.samplingTime);
    m_joints.reset();
    m_joints.setKinematicModel(m_ctx.robotModel);
    m_template = nullptr;
    m_object.clear();
    m_rejected.clear();
    m_previous = vpMorphContour();
  }

  const vpMorphTemplate *m_template = nullptr;
  std::string m_object;
  std::vector<std::size_t> m_rejected;
  vpMorphContour m_previous; //!< the last silhouette, which the next one continues
  vpMorphJointVelocity m_joints;
};

#endif
