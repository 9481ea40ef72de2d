/*!
  \file vpMorphTiltEstimator.h
  \brief The out-of-plane part of the morph servo: the tilt of the camera on the object's plane, from the homography of
  the current outline to the target's.
*/
#ifndef VP_MORPH_TILT_ESTIMATOR_H
#define VP_MORPH_TILT_ESTIMATOR_H

#include <cmath>
#include <limits>
#include <vector>

#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/morph/vpMorphContour.h>
#include <visp3/morph/vpMorphHomography.h>
#include <visp3/morph/vpMorphRigidTransform.h>
#include <visp3/morph_vs/vpMorphViewAligner.h>

/*!
  \class vpMorphTiltEstimator
  \ingroup group_morph_vs
  \brief Estimates the tilt between the current camera and the object's plane, and the rotation that levels the camera
  about the plane point seen at the view's centroid.

  The desired view is fronto-parallel to the plane at depth Zd. The homography from the current outline to the
  target's (normalised coordinates; vpMorphHomography::refine() on the measured edges, started from the last period's
  homography or from the similarity the aligner measured) decomposes into cMcd (vpMorphHomography::inputMtarget()),
  which gives the plane's normal n in the current camera frame and the depth of the plane point P at the current
  centroid. The levelling displacement turns the optical axis onto n about P, \f${}^cM_{c'} = [R_t,\ P - R_t P]\f$:
  the object stays where it is in the image, so it does not fight the planar law.

  <b>What is trusted.</b> A homography is used when it explains the outline: on a view the aligner found rigid, most
  of it (getMinInlierShare()) within getMaxResidualPx() RMS; on a view it did not (a tilted view is no similarity, but
  neither is one with a part hidden or bent), all of it (getMinInlierShareNotRigid()) within half that, since the
  perspective part would otherwise bend an occluder's edge or a bent limb onto the target.
  <b>Dead zone.</b> Only the part of the tilt beyond the dead zone is commanded: along each principal axis of the
  tilt's covariance (vpMorphHomography::covariance(): noise, blur, a thin object whose tilt about its long axis barely
  changes its outline), getSigmas() standard deviations, and at least getOutlineDeadZone() (getDeadZone() on polygons
  without measured outlines, which see a tilt to a few degrees). On the final approach the estimates of the recent
  periods are fused (information-weighted, their covariance scaled by their reduced chi-square), and only what both
  the fused and this period's estimate show is commanded.
  <b>Verification.</b> isVerified(): the last estimate plus k deviations (getDeviation()) within getFinalThreshold():
  a tilt within its dead zone is not commanded, but it is not known to be small either.

  \code
  vpMorphTiltEstimator tilt;
  vpHomogeneousMatrix cMct; double Zp;
  if (tilt.estimate(currentN, targetN, Zd, currentToTarget, rigid, true, gain, cMct, Zp)) { // add gain * cMct's twist
  }
  \endcode
  \sa vpServoMorph, vpMorphHomography, \ref page_design_servo
*/
class vpMorphTiltEstimator
{
public:
  //! One reading of the tilt for vpMorphHandEyeExploration: the plane normal's image-plane part and its covariance.
  struct Reading
  {
    double nx = 0;  //!< n's x in the current camera frame
    double ny = 0;  //!< n's y in the current camera frame
    double c00 = 0; //!< covariance of nx
    double c01 = 0; //!< covariance of nx and ny
    double c11 = 0; //!< covariance of ny
  };

  //! Default dead zones and thresholds for the default camera.
  vpMorphTiltEstimator() = default;

  //! The size of a pixel in normalised units (1 / px of the intrinsics; default 1/800), for the residuals' limits.
  void setPixelSize(double unitsPerPixel);
  //! The size of a pixel in normalized units.
  double getPixelSize() const { return m_pixel; }

  //! Dead zone on polygons without edge outlines (rad, >= 0, default 0.07: a polygon's homography sees a few deg).
  void setDeadZone(double rad);
  //! Dead zone on polygons (rad).
  double getDeadZone() const { return m_deadZone; }
  //! Dead zone floor on measured outlines (rad, >= 0, default 0.0026: 0.15 deg).
  void setOutlineDeadZone(double rad);
  //! Dead zone floor on edge outlines (rad).
  double getOutlineDeadZone() const { return m_outlineDeadZone; }
  //! Tilt that the final goal tolerates, bound included (rad, > 0, default 0.002).
  void setFinalThreshold(double rad);
  //! Tilt that the final goal tolerates, bound included (rad).
  double getFinalThreshold() const { return m_final; }
  //! Standard deviations of the tilt's estimate within which it is not commanded (2).
  static double getSigmas() { return 2.0; }
  //! Least inlier share of a usable homography on a rigid view (0.9).
  static double getMinInlierShare() { return 0.9; }
  //! Least inlier share on a view that is not rigid (0.99: the whole outline; at half the residual).
  static double getMinInlierShareNotRigid() { return 0.99; }
  //! Largest RMS residual of a usable homography (0.5 px: the outline's noise limit,
  //! vpMorphViewAligner::outlineSigmaLimitPx()).
  static double getMaxResidualPx() { return 0.5; }
  //! Periods of the final approach fused at most (16).
  static unsigned int getWindow() { return 16; }

  //! A new sequence: the warm start, the fused estimates and the latch forgotten.
  void reset();
  /*!
    The levelling displacement \e cMct and the depth \e Zp of the plane point at the current centroid, from the
    current outline \e currentN to the target's \e targetN (normalised) at depth \e Zd. \e currentToTarget: the
    similarity the aligner measured (the start of the homography without a warm one); \e rigid: the aligner found the
    view rigid; \e final: the final approach (fusion, latch); \e gain: the share of the command executed per period.
    False (cMct the identity) when no usable homography, or (polygons) the tilt within the dead zone on the final
    approach, after which the planar law finishes alone.
  */
  bool estimate(const vpMorphContour &currentN, const vpMorphContour &targetN, double Zd,
                const vpMorphRigidTransform &currentToTarget, bool rigid, bool final, double gain,
                vpHomogeneousMatrix &cMct, double &Zp);
  /*!
    Reads the tilt of a view turned by \e turn (rad) about the optical axis since the last reading (the exploration
    turn's readings, each started from the last turned by \e turn, else from \e currentToTarget). The whole outline
    must be explained (a bent or hidden view's tilt is not read). False when it cannot be read.
  */
  bool read(const vpMorphContour &currentN, const vpMorphContour &targetN, double Zd, double turn,
            const vpMorphRigidTransform &currentToTarget, Reading &r);
  //! Forgets the readings' warm start.
  void resetReadings() { m_readWarm = false; }

  //! Angle between the optical axis and the plane normal at the last estimate (rad; 0 when not estimated).
  double getResidual() const { return m_residual; }
  //! cMcd from the last homography (identity when not estimated).
  const vpHomogeneousMatrix &getHomographyPose() const { return m_cMcd; }
  //! The last period estimated the homography.
  bool isEstimated() const { return m_estimated; }
  //! The dead zone of the last estimate (rad).
  double getDeadZoneUsed() const { return m_deadZoneUsed; }
  //! One standard deviation of the last estimate about its worse-seen axis (rad; the polygons' dead zone / getSigmas()
  //! without measured outlines; infinite when not estimated, and on outlines before three periods of the final
  //! approach show their scatter).
  double getDeviation() const { return m_deviation; }
  //! The last period estimated the tilt, and its estimate plus \e sigmas deviations is within getFinalThreshold(): the
  //! view is untilted (false without an estimate: the tilt is then unknown).
  bool isVerified(double sigmas) const;
  //! Whether a tilt command of the last estimate exceeded its dead zone (the hand-eye estimator must not pair it).
  bool commanded() const { return m_estimated && m_residual > m_deadZoneUsed; }
  //! Whether the tilt is still being levelled or measured: a command beyond the dead zone while the tilt is not yet
  //! verified (isVerified() with \e sigmas), or too few periods of the final approach yet to know its deviation
  //! (getDeviation() infinite).
  bool isLevelling(double sigmas) const
  {
    return (commanded() && !isVerified(sigmas)) || (m_estimated && !std::isfinite(m_deviation));
  }

private:
  bool homography(const vpMorphContour &currentN, const vpMorphContour &targetN, const vpMorphHomography &start,
                  double minInliers, double maxResidualPx, vpMorphHomography &G) const;
  void fuse(const vpMatrix &C, double &angle, double &ax, double &ay, double &sa);

  double m_pixel = 1.0 / vpMorphViewAligner::getDefaultCameraParameters().get_px();
  double m_deadZone = 0.07, m_outlineDeadZone = 0.0026, m_final = 0.002;
  // State of a sequence.
  vpMorphHomography m_warm;
  bool m_haveWarm = false, m_latched = false, m_estimated = false;
  double m_residual = 0.0, m_deadZoneUsed = m_deadZone;
  double m_deviation = std::numeric_limits<double>::infinity();
  vpHomogeneousMatrix m_cMcd;
  // Tilt executed since the final approach began (rad): the fused estimates of earlier periods are compensated by it.
  double m_sumX = 0.0, m_sumY = 0.0;
  struct Sample
  {
    double ex = 0, ey = 0;            // rotation vector that levels the camera (rad)
    double c00 = 0, c01 = 0, c11 = 0; // its covariance
    double sx = 0, sy = 0;            // the tilt executed then
    double deadZone = 0;              // this period's own dead zone
  };
  std::vector<Sample> m_window;
  double m_kappa = 1.0;        // reduced chi-square of the last window of three or more
  bool m_scatterKnown = false; // the last window had three or more periods
  // The readings' warm start.
  vpMorphHomography m_readG;
  bool m_readWarm = false;
};

#endif
