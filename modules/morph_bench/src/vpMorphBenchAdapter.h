/*
  \file vpMorphBenchAdapter.h
  \brief Internal to the morph_bench module (not installed): the part every controller adapter shares (its context,
  the tag estimator, the stop rule on its own error, the stock vpServo set-ups, the commands that hold or stop).
*/
#ifndef VP_MORPH_BENCH_ADAPTER_H
#define VP_MORPH_BENCH_ADAPTER_H

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include <visp3/core/vpVelocityTwistMatrix.h>
#include <visp3/morph/vpMorphContour.h>
#include <visp3/morph_bench/vpMorphBenchController.h>
#include <visp3/morph_sim/vpMorphTagPoseEstimator.h>
#include <visp3/morph_sim/vpMorphThreadCpuClock.h>
#include <visp3/vs/vpServo.h>

/*
  Common part of every adapter of vpMorphBenchController: the context and the tag estimator built with the
  estimated intrinsics; each adapter resets its own state in reset(). The factories of the two families of adapters,
  the VISPMorph ones (vpMorphBenchMorphAdapters.cpp) and the stock ones (vpMorphBenchStockAdapters.cpp), return null
  for a name that is not theirs.
*/
class vpMorphBenchAdapter : public vpMorphBenchController
{
public:
  void start(const Context &ctx) override
  {
    m_ctx = ctx;
    m_tag.reset(new vpMorphTagPoseEstimator(ctx.tagId, ctx.tagSize, ctx.oMt, ctx.cam));
    m_settled = 0;
    reset();
  }

  //! "morph", "morph-planar", "morph-paper" or "morph-vpservo"; null for another name.
  static std::unique_ptr<vpMorphBenchController> createMorph(const std::string &name);
  //! "ibvs-current", "ibvs-desired", "ibvs-mean", "pbvs", "moments" or "moments-planar"; null for another name.
  static std::unique_ptr<vpMorphBenchController> createStock(const std::string &name);

protected:
  // Compute times are the CPU time of the run's thread: starts run on every core (see vpMorphThreadCpuClock).
  using Clock = vpMorphThreadCpuClock;
  static double msSince(Clock::time_point t0) { return Clock::millisecondsSince(t0); }

  //! The tag seen in an image: its pose (from the estimated intrinsics) and its corners.
  struct TagView
  {
    bool found = false;
    vpHomogeneousMatrix cMo;
    std::vector<vpImagePoint> corners;
  };
  TagView detectTag(const vpImage<unsigned char> &I) const
  {
    TagView t;
    t.found = m_tag->estimate(I, t.cMo, &t.corners);
    return t;
  }

  static bool finite(const vpColVector &v)
  {
    for (unsigned int i = 0; i < v.size(); ++i)
      if (!std::isfinite(v[i]))
        return false;
    return true;
  }

  /*!
    The adapters' stop rule on their own error (Command::converged; vpServoMorph has its own, CONVERGED): the error
    norm, as the RMS image displacement (px) of the points the feature stands for, within 3 times its own noise on
    kConvergedPeriods successive measured periods: below that the error is the measurement's noise. Its noise comes
    from sigma = 0.1 px per edge point (vpMorphBenchObservability's noise model) through the feature's fit:
    - a fit of a similarity (4 parameters) to n outline points moves them by sigma sqrt(4 / n) RMS (outlineNoisePx());
    - a tag corner, where two edges of L pixels fitted by least squares meet, by 2 sigma / sqrt(L) (cornerNoisePx()).
  */
  static constexpr double kEdgeNoisePx = 0.1;
  static constexpr unsigned int kConvergedPeriods = 3;
  static double outlineNoisePx(std::size_t points)
  {
    return kEdgeNoisePx * std::sqrt(4.0 / std::max<std::size_t>(points, 4));
  }
  static double cornerNoisePx(double edgePx) { return 2.0 * kEdgeNoisePx / std::sqrt(std::max(edgePx, 1.0)); }
  //! Counts a period whose error norm is \e rmsPx against the noise \e noisePx; true once the rule holds.
  bool settled(double rmsPx, double noisePx)
  {
    m_settled = std::isfinite(rmsPx) && rmsPx <= 3.0 * noisePx ? m_settled + 1 : 0;
    return m_settled >= kConvergedPeriods;
  }
  //! Mean side (px) of the tag's taught corners: the length of the edges its corners are fitted on.
  double taughtTagSidePx() const
  {
    const std::vector<vpImagePoint> &c = m_ctx.taughtTagCorners;
    double sum = 0.0;
    for (std::size_t i = 0; i < c.size(); ++i)
      sum += vpImagePoint::distance(c[i], c[(i + 1) % c.size()]);
    return c.empty() ? 0.0 : sum / c.size();
  }
  //! RMS distance (px) of the contour's points to their centroid: what a rotation or scale error moves them by.
  static double radiusPx(const vpMorphContour &c)
  {
    double cx = 0.0, cy = 0.0, r2 = 0.0;
    c.centroid(cx, cy);
    for (std::size_t k = 0; k < c.size(); ++k)
      r2 += (c.x(k) - cx) * (c.x(k) - cx) + (c.y(k) - cy) * (c.y(k) - cy);
    return c.size() ? std::sqrt(r2 / c.size()) : 0.0;
  }
  virtual void reset() = 0;
  //! A stock vpServo set up as ViSP's examples do for a robot arm: eye-in-hand, L cVe eJe, constant gain.
  void setupStockTask(vpServo &task, vpServo::vpServoIteractionMatrixType L) const
  {
    task.setServo(vpServo::EYEINHAND_L_cVe_eJe);
    task.setInteractionMatrixType(L, vpServo::PSEUDO_INVERSE);
    task.set_cVe(vpVelocityTwistMatrix(m_ctx.eMc.inverse()));
    task.setLambda(m_ctx.lambda);
  }
  /*!
    A stock vpServo on the camera's planar motions (vx, vy, vz, wz): EYEINHAND_CAMERA, current L, the tilts disabled
    (setCameraDoF), the same gain; the adapter maps its camera velocity with the estimated eMc.
  */
  void setupPlanarTask(vpServo &task) const
  {
    task.setServo(vpServo::EYEINHAND_CAMERA);
    task.setInteractionMatrixType(vpServo::CURRENT, vpServo::PSEUDO_INVERSE);
    task.setLambda(m_ctx.lambda);
    vpColVector dof(6, 1.0);
    dof[3] = dof[4] = 0; // no tilt
    task.setCameraDoF(dof);
  }
  /*!
    The stock task's joint velocity for the features just measured (in \e measureMs), with the time of the law;
    a stop instead of a non-finite command.
  */
  static Command stockLaw(vpServo &task, const vpMatrix &eJe, double measureMs)
  {
    Command cmd;
    cmd.measureMs = measureMs;
    const Clock::time_point t0 = Clock::now();
    task.set_eJe(eJe);
    cmd.v = task.computeControlLaw();
    cmd.controlMs = msSince(t0);
    cmd.frame = vpRobot::JOINT_STATE;
    if (!finite(cmd.v))
      return stopCommand("nan");
    return cmd;
  }
  static Command holdCommand(double measureMs)
  {
    Command c;
    c.measured = false;
    c.measureMs = measureMs;
    return c;
  }
  static Command stopCommand(const std::string &reason)
  {
    Command c;
    c.stop = true;
    c.reason = reason;
    return c;
  }

  Context m_ctx;
  std::unique_ptr<vpMorphTagPoseEstimator> m_tag;
  unsigned int m_settled = 0;
};

#endif
