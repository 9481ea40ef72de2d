/*!
  \file vpServoMorph.h
  \brief The morph-goal servo task: servo through the virtual contours of a morph, with online hand-eye estimation.
*/
#ifndef VP_SERVO_MORPH_H
#define VP_SERVO_MORPH_H

#include <algorithm>
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpColVector.h>
#include <visp3/core/vpColor.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpImage.h>
#include <visp3/core/vpMatrix.h>
#include <visp3/core/vpRGBa.h>
#include <visp3/core/vpThetaUVector.h>
#include <visp3/core/vpVelocityTwistMatrix.h>
#include <visp3/morph/vpMorphContour.h>
#include <visp3/morph/vpMorphDatabase.h>
#include <visp3/morph/vpMorphHomography.h>
#include <visp3/morph/vpMorphRigidTransform.h>
#include <visp3/morph/vpMorphTemplate.h>
#include <visp3/morph_vs/vpFeatureMorph.h>
#include <visp3/morph_vs/vpMorphCorrespondenceTracker.h>
#include <visp3/morph_vs/vpMorphHandEyeEstimator.h>
#include <visp3/vs/vpServo.h>

/*!
  \class vpServoMorph
  \ingroup group_morph_vs
  \brief The paper's controller (section 3): the contours of the morph from the current view to the target are
  the successive goals (sub-goals) of an eye-in-hand robot, and the hand-eye transform is estimated on line.

  <b>Sequence.</b> At the first call of computeControlLaw() (and after restart()), vpMorph builds the morph from
  the current contour to the target (rigid rectification, then deformation) and takes its sequence(n) as the
  sub-goals, n = subGoalCount() (0: the target only). When the current region is not the target's seen again (below),
  the rigid part of the plan is the outline fit (vpMorphRigidTransform::refineOnOutline, from the least squares) if
  it lays the view inside the target better, by 1 % of its area: with part of the object hidden, the least squares
  carry the hidden part into their scale, and the rigid frames moved the camera towards the object for the
  deformation frames to take it back (paths of 3-7 times the straight line on the occlusion set). Such a view then
  lies on the target where it shows it, and its deformation frames would only grow the occluder's bite into the
  hidden stretch, which no camera motion shows: they are left out, and the sequence goes from the last rigid frame
  to the target (fewer sub-goals than subGoalCount()). A bent view keeps the least squares, which the bend drags
  less, and all its frames. A sub-goal is reached when the residual similarity from
  the current contour to it is below subGoalThresholds() (the paper's 0.10 rad and 5 px); the last one (the
  target) needs the finer finalThresholds(), then the status is CONVERGED and the velocity zero.

  <b>Control law (Eq. 5-11, HOMOGENEOUS_TRANSFORMS).</b> The correspondence current -> sub-goal (tracked from
  the previous iteration, vpMorphCorrespondenceTracker) gives the image-plane similarity (angle theta about the
  current centroid c, translation t, scale s, in normalised coordinates with the estimated intrinsics): theta by
  robust least squares over the corresponded vertices, c the current area centroid, t the displacement of the area
  centroid and s the square root of the area ratio (a vertex fit biases t and s by millimetres when the two
  polygons place their vertices differently, as a real contour and a stored one do), unless the current region is
  not the target's seen again (its similarity invariants, spread over area and eccentricity of the second moments,
  more than 2 % from the target's when the sequence starts: part of the object hidden, or deformed): then the whole
  similarity comes from the outline, the robust vertex fit refined by a trimmed outline fit
  (vpMorphRigidTransform::refineOnOutline), for the whole sequence (Iteration::areaBased).
  On the target, when both carry their measured region and edges, the area ratio is the regions', the target's less
  the band along its edges that the current edges lie off it by (one common offset fitted with a similarity, every
  8th period): a background clipped by the lighting shrinks the measured region by such a band, which the ratio
  would take for depth (1.5 mm on a thin pliers).
  At the first fit to the target, the current region laid on it is checked: an occluder only hides, so a region
  that sticks out of the target's by more than 2 % of its area (on the edge outlines when both contours carry
  them; not a silhouette joined across a cut, which has no measured region) is deformed, for the rest of the
  sequence. Its rotation and translation then come from the placement of largest overlap
  (vpMorphRigidTransform::fitOnOverlap, starts over +-10 deg the first time, then refined from the last period's
  offset to the outline fit; Iteration::overlapBased): the pose at which a bent tool lies on its template as well
  as a rigid placement can, whatever part of it is longest. Its scale (the depth) is the scale of its largest
  undeformed part (vpMorphRigidTransform::fitRigidPart: a stretch of edges within 0.25 px of the target's over a
  tenth of the outline or more, the one whose scale is best determined; searched every 8 periods and followed by
  vpMorphRigidTransform::refineRigidPart at the periods between). When no such part is found, the outlines' length
  ratio, which a bend nearly keeps, times the last part's ratio to it (the lengths alone: a drawn bend changes them
  by 0.2-0.5 %; its area and an outline fit change by percents).
  Through the image projection of a
  plane parallel to the image at the current depth Z (estimated from the area: \f$Z = Z^* \sqrt{a^{*} / a}\f$), the
  camera displacement that produces it is \f[ {}^cM_{c'} = \left[R_z(-\theta),\ \left(k Z (c - R(-\theta)(c + t)/s),\ Z
  (1 - 1/s)\right)\right] \f] (the image of a static object moves opposite to the camera; k is the estimated projection
  scale, see vpMorphHandEyeEstimator); Eq. 11 conjugates it through the hand-eye transform: \f${}^eM_{e'} = {}^eM_c\,
  {}^cM_{c'}\, {}^eM_c^{-1}\f$. The output is the velocity of a fraction gain() of that step over the sampling time:
  \f$v_e = \mathrm{gain} \cdot \log({}^eM_{e'}) / \Delta t\f$ (vpExponentialMap), in the end-effector frame;
  cameraVelocity() gives it in the (estimated) camera frame.

  <b>Stock law (STOCK_VPSERVO).</b> Alternatively the same sub-goals are servoed by a stock vpServo
  (EYEINHAND_CAMERA, current L, tilt velocities masked: the task is planar) over vpFeatureMorph, with
  lambda = gain / dt, and the camera velocity is mapped to the end effector with the estimated eMc.

  <b>Online calibration.</b> Call computeControlLaw() once per sampling period, after the robot executed the
  previous velocity for dt. The image motion observed since an anchor iteration is \f$T_{now}^{-1} T_{anchor}\f$
  (both fits are to the same sub-goal, so no extra correspondence is needed); it gives the observed camera move,
  and with the product of the end-effector moves commanded since the anchor it updates vpMorphHandEyeEstimator
  (see there: planar hand-eye part and projection scale, least squares with forgetting). An observation is made
  once the image has moved by 8 px or 0.05 rad, then the anchor moves to the current fit: the per-period motion
  of a velocity loop is a pixel or less, comparable to the jitter of a contour extracted from a real image, and
  a least-squares fit on such noisy regressors shrinks the projection scale towards 0 (regression dilution).

  <b>Out-of-plane correction (setTiltCorrection(), beyond the paper; off by default).</b> The similarity law above is
  planar: it never commands a tilt, so a camera that is tilted with respect to the object plane (a tilted start, or a
  rotation about the optical axis executed through a hand-eye estimate whose rotation is off) stays tilted, and
  converges in the image to a view that is not the goal. The desired view is fronto-parallel to the plane at depth
  Zd: the tilt goal is zero. When the correction is on, vpMorphHomography::fit() estimates the plane homography from
  the current contour to the target (normalised coordinates with the estimated intrinsics; a second correspondence
  tracker; robust scale floored at half a pixel) and vpMorphHomography::inputMtarget(Zd) decomposes it into cMcd,
  which gives the plane normal n in the current camera frame and the depth of the plane point P seen at the current
  centroid. The tilt displacement turns the optical axis onto n about P, \f${}^cM_{c'} = [R_t,\ P - R_t P]\f$ (an
  orbit that keeps the object where it is in the image, so it does not fight the planar law, whose sub-goals and
  paths are unchanged); only the part of the tilt beyond the dead zone is commanded (and none once it has been
  within it on the final approach), its twist scaled by gain() and added to the planar one, and the depth of P
  replaces the area depth in the planar displacement (the area shrinks by cos(tilt)). The final goal also needs the
  tilt below max(finalTiltThreshold(), dead zone). No hand-eye observation spans a tilt command (an orbit executed
  through a wrong eMc moves the image in ways the planar model would misread). TILT_FINAL_APPROACH corrects on the
  last sub-goal only, TILT_ALWAYS from the first iteration.

  How well the tilt is seen decides everything: 0.5 deg of tilt moves the outline of a 15 cm object at 0.5 m by at
  most 0.16 px. Polygons see it to 1-6 deg (two polygonisations of one silhouette differ by tenths of a pixel), hence
  their dead zone tiltDeadZone() (4 deg). When both contours carry the edge outline measured by
  vpMorphContourExtractor (vpMorphContour::outline(): a point per boundary pixel, to a few hundredths of a pixel),
  the polygons' homography is refined on the outlines (vpMorphHomography::refine(), robust scale floored at a tenth
  of a pixel), which see the tilt of a compact object to about a tenth of a degree; the dead zone is then
  outlineTiltDeadZone() (0.15 deg), widened about each principal axis of the tilt's covariance
  (vpMorphHomography::covariance(): noise, blur, or a thin object whose tilt about its long axis barely changes its
  outline) to twice its standard deviation there. On the final approach the outlines' estimates of the last periods
  (up to 16, each with the tilt commands executed since taken off, while those stay within its dead zone) are also
  averaged, weighted by their covariances, and the covariance is scaled by the reduced chi-square of their scatter
  (a thin object's estimate jumps by twice its reported deviation from one view to the next). The dead zones are
  one period's deviations, not the average's: near the goal the views barely change and their errors do not average
  out. About each axis, only what both this period's estimate and the average show beyond its dead zone is commanded
  (measured on held-out planar pliers starts: 0.52-0.54 deg -> 0.13-0.19 deg off). The planar law
  runs alone for an iteration when the homography is not trusted: a triangle, a poor
  polygon fit (under 60 % inliers or 2 px RMS), a poor outline fit (under 90 % inliers or 0.5 px RMS), regions that
  are not alike (see above: a tilted view, or a part hidden or bent) unless the homography explains the whole
  outline (99 % inliers: an occluder's edge fitted away by the robust weights still pulls the perspective part), or
  a current contour without a measured region towards a target with one (an outline joined across a cut: part of it
  was bridged, not seen). Such a homography shows the view was only tilted: once the regions compare alike again,
  the sequence's "not alike" and "deformed" verdicts are withdrawn (once per sequence), so that a tilted start ends
  as a rigid view does (measured: a key tilted by 22 deg, whose 99 % fits failed near the goal, ending 2.0 deg off). On
  the final approach, an estimate that its own commands do not bring down (still at least the first commanded one along
  the executed way, three periods in a row, once half a dead zone has been executed) is not the view's tilt: the
  correction stops until restart().

  Why off by default: it is not the paper's law, and on polygons alone (contours built by hand, or stored without
  their outlines) it removes large tilts but stops within its 4 deg dead zone. With extracted contours on the
  benchmark's free camera ("morph", final approach), the calib set goes from 2/10 to 9/10 and the other sets are
  unchanged (README).

  <b>Safety.</b> The velocity is zero, never NaN, and status() says why when the target is lost (empty
  contour), the contour degenerates (area below minArea(), non-finite values, a failed morph), or the
  correspondence is unreliable: a distance jump (work above jumpFactor() * previous work + workFloor() to the
  same sub-goal) together with a jump of the fitted rotation (more than gain() x the previous rotation residual +
  0.1 rad: a contour extracted from an image gains and loses vertices, which changes the work but not the fit),
  or a low margin after a full search (below minMargin(): a symmetric shape, ambiguous rotation) with the same
  rotation jump, or before any fit to the current sub-goal to compare with.

  <b>Faults</b> (what a real loop meets; each is tested, see the README's "Fault injection and soak"):
  - <em>No image or no object</em> (a dropped frame, the object absent): call computeControlLaw() with an empty
    contour. The status is TARGET_LOST and the velocity zero (hold: the robot stays where it is); the sequence,
    the last fit and the hand-eye estimate are kept, so when the object reappears in a view consistent with the
    last fit the servo resumes on the same sub-goal (no new morph). A dropped frame must never be replaced by the
    previous image: the calibration would pair an old image with a new move. After more than
    maxLostIterations() successive empty calls the status is LOST_TOO_LONG: a stop, zero velocity until restart().
  - <em>Jump of the view</em> (the robot or the object was bumped): the fit to the same sub-goal moves by more
    than one commanded step explains, in rotation (gain() x previous rotation residual + 0.1 rad) or in
    translation (2 gain() x previous translation residual + jumpPixels()), while the work stays (D_morph does not
    change under a rigid motion: same shape, new place). The morph is re-planned from the new view (a new
    sequence, status REPLANNED, zero velocity for this period, no calibration observation across the jump), at
    most maxReplans() times per task; one more jump stops with TOO_MANY_REPLANS. When the work jumps as well, it
    may be another shape (an occluder, another object) as much as the same one re-digitised at a new place
    (measured on rendered images after a 20 mm / 10 deg jump): with a target check (below) the D_morph distance
    between the last contour and this one tells them apart (the same shape: at most a quarter of the target's
    acceptance threshold; re-plan), otherwise, and without a target check, the status is
    UNRELIABLE_CORRESPONDENCE (zero velocity; a re-plan from an occluded view turned the wedge the wrong way
    at 0.26 m/s in the bench, twelve times the clean run's speed). A view whose regions are not alike (occluded,
    cut) is fitted on its outline from the correspondence's fit; when that jumps, the outline fit is also run from
    the last fit, and kept if it does not jump and lays less of the view outside the goal: on a wrench cut in two
    by a card, the correspondence's fit fell into another basin at each arrival at the target (three re-plans).
  - <em>Wrong target</em> (recognition chose another object's template): with setTargetCheck() (the template
    database and the target's name), the current contour is recognised again at each new sequence and when the
    final goal would be reached. It is not the target when its distance to the target exceeds the target's
    acceptance threshold times the slack and it shows less than the database's minimum support of the target
    template's outline (the rule of vpMorphDatabase::accepts(), with the distance to the target contour: an
    occluded view of the target is the target), or when the database's best template is another one, accepted,
    that costs at least mismatchRatio() (1.2) times less work: the thresholds alone do not separate near
    neighbours (calibrated on 20 % occlusions, they can exceed the distance between two objects: 1.73 for a tee
    against 1.44 between the tee and the bracket of the tests), unless the view shows more of the target's outline
    than of that template's (vpMorphDatabase::support(): a bent view may be nearer another template by the
    distance). Then the status is TARGET_MISMATCH (a stop: the
    servo would otherwise align the best-fitting similarity of two different shapes and report CONVERGED, or, for
    one that lies far off the target, move until its first fit to the target and stop there, see below); the
    caller recognises anew or gives up.
  - <em>Deformed beyond one rigid placement</em>: a view found deformed at its first fit to the target (see the
    law above) that, laid on the target by its largest overlap at the scale taken for its depth, still leaves over
    a fifth of its area outside is not the target bent: a bent tool leaves its limb out (3-11 % measured), pliers
    opened by 32 deg leave a whole arm out (28 % and more). No single pose lays both arms, and nothing gives their
    depth: the outline grows with the opening, and given the pliers' template the servo converged 286 mm off.
    Then the status is DEFORMATION_UNRESOLVED, a stop.
  LOST_TOO_LONG, TOO_MANY_REPLANS, TARGET_MISMATCH and DEFORMATION_UNRESOLVED are stops: every later call returns
  zero velocity with the same status until restart() or setTarget().

  Not copyable (it owns a vpServo that points to its own features).
*/
class vpServoMorph
{
public:
  //! Outcome of the last computeControlLaw().
  enum Status {
    NOT_STARTED,               //!< No iteration yet.
    MOVING,                    //!< Moving towards the current sub-goal.
    SUBGOAL_REACHED,           //!< A sub-goal was reached at this iteration; moving towards the next one.
    CONVERGED,                 //!< The final goal is reached within finalThresholds(); zero velocity.
    TARGET_LOST,               //!< Empty contour given; zero velocity.
    DEGENERATE_CONTOUR,        //!< Contour too small, non-finite, or unusable by the morph; zero velocity.
    UNRELIABLE_CORRESPONDENCE, //!< Distance jump or low margin; zero velocity.
    REPLANNED,                 //!< The view jumped (same shape, new place): new sequence from it; zero velocity.
    LOST_TOO_LONG,             //!< Stop: no contour for more than maxLostIterations() successive calls; zero velocity.
    TOO_MANY_REPLANS,          //!< Stop: one view jump more than maxReplans(); zero velocity.
    TARGET_MISMATCH,           //!< Stop: the contour is not the target's shape (setTargetCheck()); zero velocity.
    //! Stop: a deformed view that no rigid placement lays on the target (an opened pliers); zero velocity.
    DEFORMATION_UNRESOLVED
  };
  //! How the sub-goal error becomes a velocity.
  enum ControlLaw {
    HOMOGENEOUS_TRANSFORMS, //!< The paper's Eq. 5-11 (default).
    STOCK_VPSERVO           //!< A stock vpServo over vpFeatureMorph.
  };
  //! Out-of-plane (tilt) correction from the contour's homography to the target (see the class description).
  enum TiltCorrection {
    TILT_OFF,            //!< The paper's planar law: no tilt command (default).
    TILT_FINAL_APPROACH, //!< Tilt commanded on the last sub-goal (the target) only.
    TILT_ALWAYS          //!< Tilt commanded from the first iteration.
  };
  /*!
    The camera path through the rigid sub-goals (the first vpMorph::rigidFrameCount() of the sequence).
  */
  enum RigidPath {
    /*!
      The images seen from evenly spaced poses on the straight line from the current camera pose to the rigidly
      rectified one (rotation about the optical axis shared evenly): the shortest camera path. The object's image
      turns about the principal point and its centroid stays within the larger of its start and goal distances
      to it (default).
    */
    CAMERA_STRAIGHT_LINE,
    /*!
      The paper's image-space interpolation of the rigid transform, turning about the contour's centroid: the
      object turns in place in the image, the camera travels on an arc about the object (path ratio up to pi/2
      and more at 180 deg).
    */
    ABOUT_OBJECT_CENTROID
  };

  //! One iteration, for plots (Fig. 2 of the paper: residual per move).
  struct Iteration
  {
    unsigned int iteration = 0;
    std::size_t subGoal = 0;
    Status status = NOT_STARTED;
    double rotationResidual = 0;    //!< |theta| to the sub-goal (rad)
    double translationResidual = 0; //!< |t| to the sub-goal (px)
    double scaleResidual = 0;       //!< |s - 1| times the contour's RMS radius (px)
    double work = 0;                //!< work of the correspondence to the sub-goal
    bool fullMatch = false;         //!< the correspondence came from a full search
    bool areaBased = false; //!< translation and scale from the area centroids and ratio (regions if both have one),
                            //!< not from the outline fit (see fitToSubGoal in the source: occluded or deformed views)
    bool overlapBased = false;      //!< rotation and translation from the largest overlap (a deformed view)
    vpHomogeneousMatrix eMc;        //!< hand-eye estimate after this iteration
    double translationScale = 1;    //!< projection scale estimate after this iteration
    vpColVector ve;                 //!< commanded end-effector velocity
    double tiltResidual = 0;        //!< angle between the optical axis and the plane normal (rad), 0 if not estimated
  };

  vpServoMorph();
  vpServoMorph(const vpServoMorph &) = delete;
  vpServoMorph &operator=(const vpServoMorph &) = delete;

  //! Intrinsics (an estimate: they may be off, see the class description).
  void setCameraParameters(const vpCameraParameters &cam) { m_cam = cam; }
  const vpCameraParameters &getCameraParameters() const { return m_cam; }
  //! Initial hand-eye estimate; restarts the estimator.
  void set_eMc(const vpHomogeneousMatrix &eMc) { m_estimator.reset(eMc); }
  //! Current hand-eye estimate.
  vpHomogeneousMatrix get_eMc() const { return m_estimator.get_eMc(); }
  const vpMorphHandEyeEstimator &handEyeEstimator() const { return m_estimator; }
  vpMorphHandEyeEstimator &handEyeEstimator() { return m_estimator; }
  void setOnlineCalibration(bool on) { m_online = on; }
  bool onlineCalibration() const { return m_online; }

  /*!
    The goal: the target contour in pixels, seen from the desired pose at depth Zd (object plane parallel to the
    image). Restarts the sequence.
    \throw vpMorphException::badParameterError on an empty or normalised contour, or Zd not finite and > 0.
  */
  void setTarget(const vpMorphContour &target, double Zd);
  /*!
    The goal from a template (its contour, and the depth of its cdMo). An articulated template
    (vpMorphTemplate::articulation()) is posed, at the start of each sequence, at the opening its current view shows
    (vpMorphArticulation::estimate()), with the part that needs the smaller turn where the taught view has it: the
    view is then a rigid placement of the target, and its depth follows from it: from the edges on the final
    approach, as the posed target's region is drawn from its parts' outlines, not seen.
  */
  void setTarget(const vpMorphTemplate &t);
  //! The opening the articulated target was posed at (radians; 0 for a rigid target or before the first period).
  double targetOpening() const { return m_opening; }
  //! The part of the articulated target that stays where the taught view has it (0 or 1).
  unsigned int targetFixedPart() const { return m_fixedPart; }
  //! Number of sub-goals (0: the target only). Restarts the sequence.
  void setSubGoalCount(std::size_t n);
  //! The parameter of setSubGoalCount() (subGoals().size() is max(1, it) once started).
  std::size_t subGoalCount() const { return m_nSub; }
  //! The camera path through the rigid sub-goals. Restarts the sequence.
  void setRigidPath(RigidPath p);
  RigidPath rigidPath() const { return m_rigidPath; }
  //! Residual below which a sub-goal is reached (default: the paper's 0.10 rad and 5 px; translation and scale).
  void setSubGoalThresholds(double rotationRad, double translationPx);
  //! Residual below which the final goal is reached (default 0.001 rad and 0.1 px: noise-free images; with
  //! image noise, set them above the noise level or CONVERGED is never reported).
  void setFinalThresholds(double rotationRad, double translationPx);
  //! Relative scale error |s - 1| below which the final goal is reached, on top of setFinalThresholds() (default 0:
  //! none). Why: the translation threshold counts a scale error in pixels at the object's RMS radius, and on a small
  //! object 0.2 px there is 0.25 % of the depth (1.2 mm at 0.5 m), while the edge outlines measure the scale ten
  //! times better than that.
  void setFinalScaleThreshold(double relativeScale);
  double finalScaleThreshold() const { return m_scaleFine; }
  //! Fraction of the step commanded per sampling period, in (0, 1] (default 0.5).
  void setGain(double gain);
  double gain() const { return m_gain; }
  //! Sampling period in seconds (> 0, default 0.1).
  void setSamplingTime(double dt);
  double samplingTime() const { return m_dt; }
  void setControlLaw(ControlLaw law);
  ControlLaw controlLaw() const { return m_law; }
  void setJumpFactor(double f);
  double jumpFactor() const { return m_jumpFactor; }
  void setWorkFloor(double w);
  double workFloor() const { return m_workFloor; }
  void setMinMargin(double m);
  double minMargin() const { return m_minMargin; }
  void setMinArea(double px2);
  double minArea() const { return m_minArea; }
  //! Out-of-plane correction (default TILT_OFF: the paper's planar law; see the class description). Restarts the
  //! sequence.
  void setTiltCorrection(TiltCorrection mode);
  TiltCorrection tiltCorrection() const { return m_tiltMode; }
  //! Tilt below which the final goal can be reached, in rad (> 0, default 0.002: 0.11 deg).
  void setFinalTiltThreshold(double rad);
  double finalTiltThreshold() const { return m_tiltFine; }
  /*!
    Estimated tilts below this angle (rad, >= 0) are not commanded, and only the excess is above it; the final goal
    accepts a tilt below max(finalTiltThreshold(), dead zone). Default 0.07 rad (4 deg): from polygonised contours
    extracted from images the homography sees the tilt only to a few degrees (0.5 deg of tilt moves the outline of
    a 15 cm object at 0.5 m by 0.16 px, less than the polygonisation changes between two views). Once the estimated
    tilt is within the dead zone on the final approach, the correction stops until restart(): below it the estimate
    follows the polygonisation, and a camera that followed it would random-walk. 0 for exact or densely sampled
    contours (no latch).
  */
  void setTiltDeadZone(double rad);
  double tiltDeadZone() const { return m_tiltDeadZone; }
  /*!
    The dead zone (rad, >= 0) that replaces tiltDeadZone() when both the current contour and the target carry a
    measured edge outline (vpMorphContour::outline(), from vpMorphContourExtractor): the homography found on the
    polygons is then refined on the outlines (vpMorphHomography::refine()), which give the tilt of a compact
    object to a tenth of a degree. Widened, about each principal axis of the tilt's covariance, to twice its
    standard deviation there when the fit is less sure (a thin object's tilt about its long axis; see the class
    description). Default 0.0026 rad (0.15 deg).
  */
  void setOutlineTiltDeadZone(double rad);
  double outlineTiltDeadZone() const { return m_outlineTiltDeadZone; }
  /*!
    Before the first sequence (and after each restart()), turn the camera about its optical axis by \e rad and back,
    reading the view's tilt (its outline's homography to the target) at each period, and correct eMc by the tilt of
    the camera on the hand they show (its error about the axes of the image plane). Why: a turn about an optical axis
    that eMc gets wrong by e tilts the camera by 2 sin(turn / 2) e, and a thin object's outline barely shows a tilt
    about its long axis, so the final approach cannot take that back; along a turn, the object's long axis turns in
    the image and the readings see every axis of e.
    - The turn runs at 1 rad/s: set setSamplingTime() to the loop's period, which the turn's angle is counted in.
    - It does not start when the joints (setJointState()) would pass a limit along it.
    - It comes back early when the view comes within 40 px of the border of the \e imageWidth x \e imageHeight image,
      and does not start there; it comes back when the view's tilt cannot be read (a bent or hidden object: the
      outline's homography explains less than 99 % of it): after its first two views unread, or with fewer than half
      of its views read by 0.35 rad.
    - A view off the turn's way (more than jumpPixels(), plus 6 px a period since the last view read) or whose area
      changed by 10 % is not read: another region joined to the object, an occluder. Off the way with its area kept
      three periods in a row, the robot or the object was displaced: the turn ends there, uncorrected, and the view
      is planned again (REPLANNED, counted in maxReplans()).
    - The correction is applied when it is at least 0.01 rad and 5 deviations of its estimate: below that, the
      readings' correlated errors on a thin object (a few times the deviation they show) would tilt a camera mounted
      right. Once applied, a second turn reads what the intrinsics' error left of it (the readings are scaled by it).
    - Cost: 2 \e rad / (1 rad/s) per turn, with the camera's centre still if eMc is right.
    Needs measured outlines (vpMorphContourExtractor). \e rad in [0, pi] (0, the default: no turn), the image's size
    > 0 when \e rad > 0; restarts the task. \throw vpMorphException otherwise.
  */
  void setHandEyeTiltExploration(double rad, unsigned int imageWidth, unsigned int imageHeight);
  double handEyeTiltExploration() const { return m_exploreAngle; }
  //! True while the exploration turn runs (its commands are the turn's).
  bool exploring() const { return m_explorePhase == EXPLORE_OUT || m_explorePhase == EXPLORE_BACK; }
  //! The rotation the exploration applied to eMc, about axes of the image plane (zero when none was applied).
  const vpThetaUVector &exploredHandEyeTilt() const { return m_exploredTilt; }
  //! Successive calls without a contour (TARGET_LOST, holding) before LOST_TOO_LONG (default 25).
  void setMaxLostIterations(unsigned int n) { m_maxLost = n; }
  unsigned int maxLostIterations() const { return m_maxLost; }
  //! Re-plans allowed after view jumps per task (default 3); 0: the first jump stops (TOO_MANY_REPLANS).
  void setMaxReplans(unsigned int n) { m_maxReplans = n; }
  unsigned int maxReplans() const { return m_maxReplans; }
  //! Translation of the fit, beyond what the commanded step explains, that is a view jump (px, default 20).
  void setJumpPixels(double px);
  double jumpPixels() const { return m_jumpPx; }
  /*!
    The robot's joints: \e eJe at the joint positions \e q, and their limits (infinite: none). Read when a sequence
    is planned (the first call, a re-plan): the turn about the optical axis can be planned either way round, and
    the short way is taken unless the joints' end, predicted to first order (q + eJe^+ eVc times the planned camera
    displacement), comes within jointMargin() of a limit where the long way's does not. Why: near half a turn the two
    ways differ by less than the rotation's estimate, and an arm's wrist may allow only one of them (a Viper850
    started at -179.1 deg was turned +180.9 deg, its wrist ending on its limit). Call it each period before
    computeControlLaw() (it does not restart the sequence); never called, the short way is taken.
    \throw vpMorphException::badParameterError if eJe is not 6 x n for n positions and limits, or a position is
    NaN or outside its limits.
  */
  void setJointState(const vpMatrix &eJe, const vpColVector &q, const vpColVector &qMin, const vpColVector &qMax);
  //! Share of a joint's range kept clear of its limits at a plan's predicted end (3 %: 21.6 deg of a +-360 deg wrist).
  static double jointMargin() { return 0.03; }
  //! True when the current sequence turns the long way round (see setJointState()).
  bool turnsLongWay() const { return m_longWay; }
  //! The joints' end predicted for the current sequence (empty without setJointState()).
  const vpColVector &plannedJointEnd() const { return m_qEnd; }
  /*!
    Checks that the current contour is the target's shape (see the class description) against the template
    database \e db (copied) in which the target is template \e name; \e slack multiplies its acceptance
    threshold (a view met during the servo is not the view recognised). Call after setTarget().
    \throw vpMorphException::notFoundError if \e name is not in \e db; badParameterError if \e slack is not
    finite and >= 1.
  */
  void setTargetCheck(const vpMorphDatabase &db, const std::string &name, double slack = 1.25);
  //! No target check (default).
  void clearTargetCheck() { m_checkDb = vpMorphDatabase(); }
  bool hasTargetCheck() const { return !m_checkDb.empty(); }
  //! See the class description.
  static double mismatchRatio() { return 1.2; }
  //! Distance from the contour to the target at the last check (NaN before any check).
  double targetDistance() const { return m_targetDistance; }
  //! Re-plans done since the last restart().
  unsigned int replanCount() const { return m_replans; }
  //! True after a stop status (LOST_TOO_LONG, TOO_MANY_REPLANS, TARGET_MISMATCH, DEFORMATION_UNRESOLVED) until
  //! restart().
  bool halted() const { return m_halted; }
  //! Forgets the sequence and the history: the next call morphs the then current contour anew.
  void restart();

  /*!
    One iteration: returns the end-effector velocity (6, ViSP order v, w) to apply during samplingTime(), zero
    on failure (see status()). An empty contour means the target is lost.
    \throw vpMorphException::badParameterError if no target was set or the contour is not in pixels.
  */
  vpColVector computeControlLaw(const vpMorphContour &current);

  Status status() const { return m_status; }
  static const char *statusName(Status s);
  bool converged() const { return m_status == CONVERGED; }
  std::size_t subGoalIndex() const { return m_k; }
  const std::vector<vpMorphContour> &subGoals() const { return m_subGoals; }
  double rotationResidual() const { return m_rotRes; }
  double translationResidual() const { return m_transRes; }
  double scaleResidual() const { return m_scaleRes; }
  //! Angle between the optical axis and the plane normal at the last iteration (rad; 0 when not estimated).
  double tiltResidual() const { return m_tiltRes; }
  //! cMcd from the last homography to the target (identity when not estimated), see tiltEstimated().
  const vpHomogeneousMatrix &homographyPose() const { return m_cMcdH; }
  //! True when the last iteration estimated the homography to the target.
  bool tiltEstimated() const { return m_tiltOk; }
  //! Last commanded velocity in the end-effector frame.
  const vpColVector &endEffectorVelocity() const { return m_ve; }
  //! Last commanded velocity in the estimated camera frame.
  const vpColVector &cameraVelocity() const { return m_vc; }
  const std::vector<Iteration> &history() const { return m_history; }
  //! The correspondence tracker of the control law in use (with STOCK_VPSERVO, the one of vpFeatureMorph).
  const vpMorphCorrespondenceTracker &tracker() const { return m_law == STOCK_VPSERVO ? m_s.tracker() : m_tracker; }

  //! The last contour given to computeControlLaw() (pixels; empty after an empty one, or on a stop).
  const vpMorphContour &getCurrentContour() const { return m_current; }
  //! The target in pixels (an articulated target as posed for the current sequence).
  const vpMorphContour &getTargetContour() const { return m_target; }
  /*!
    Draws in one call what the servo sees and chases, on the display attached to \e I (vpDisplay: no-op without one):
    - the target (\e targetColor, \e thickness + 2 pixels wide, underneath the rest, so that it stays visible where
      the current contour reaches it);
    - the current sub-goal while it is not the target (\e subGoalColor);
    - the correspondence from the current contour to that sub-goal, a line per corresponded pair of vertices (cyan),
      while the servo moves or has converged;
    - the last contour given to computeControlLaw() (\e currentColor);
    - the status in yellow on a black band in the top-left corner: statusName(), the sub-goal chased (k / n), the
      residuals to it (rad, px; none during the exploration turn) and the tilt when it is estimated.
    \code
    vpImage<unsigned char> I;                // the camera image
    vpDisplayX d(I, 0, 0, "camera");         // or vpDisplayOpenCV
    for (;;) {
      acquire(I);                            // the user's grabber
      const vpColVector ve = servo.computeControlLaw(vpMorphContourExtractor().extract(I));
      vpDisplay::display(I);
      servo.display(I);
      vpDisplay::flush(I);
      if (!servo.converged()) robot.setVelocity(vpRobot::END_EFFECTOR_FRAME, ve); else break;
    }
    \endcode
  */
  void display(const vpImage<unsigned char> &I, const vpColor &currentColor = vpColor::red,
               const vpColor &subGoalColor = vpColor::orange, const vpColor &targetColor = vpColor::green,
               unsigned int thickness = 1) const;
  void display(const vpImage<vpRGBa> &I, const vpColor &currentColor = vpColor::red,
               const vpColor &subGoalColor = vpColor::orange, const vpColor &targetColor = vpColor::green,
               unsigned int thickness = 1) const;
  //! What display() draws, burnt into the pixels of \e I (vpImageDraw, vpFont): video frames without a window.
  void draw(vpImage<vpRGBa> &I, const vpColor &currentColor = vpColor::red,
            const vpColor &subGoalColor = vpColor::orange, const vpColor &targetColor = vpColor::green,
            unsigned int thickness = 1) const;
  //! The status lines display() writes.
  std::vector<std::string> statusText() const;

private:
  void start(const vpMorphContour &current);
  //! An articulated target posed at the opening \e current shows (setTarget(const vpMorphTemplate &)).
  void poseArticulatedTarget(const vpMorphContour &current);
  vpColVector stop(Status s);
  // \e switching: the sub-goal was just reached (no fit to it yet; the last period's fit was to the one before).
  vpMorphRigidTransform fitToSubGoal(const vpMorphContour &currentN, const vpMorphContour &currentPx, double Z,
                                     bool switching = false);
  vpHomogeneousMatrix cameraDisplacement(const vpMorphRigidTransform &T, double Z, double k) const;
  // The joints' end predicted (first order) for the plan cMcp turned by \e turn (image, rad), from setJointState()'s.
  vpColVector jointEnd(const vpMatrix &eJeInv, const vpVelocityTwistMatrix &eVc, const vpHomogeneousMatrix &cMcp,
                       double turn) const;
  // Whether the joint positions \e q come within jointMargin() of a limit of setJointState()'s.
  bool nearJointLimit(const vpColVector &q) const;
  void residuals(const vpMorphRigidTransform &T, const vpMorphContour &currentPx);
  // Against the last fit to the same sub-goal (m_prevT): the rotation moved by no more than one step and noise;
  // the view jumped when it did not, or when the translation moved beyond what one step explains plus jumpPixels().
  bool rotationConsistent(const vpMorphRigidTransform &T) const;
  bool viewJumped(const vpMorphRigidTransform &T) const;
  // |ln(scale / the last period's)|: how far the fit's scale moved since the last period's fit.
  double scaleChange(const vpMorphRigidTransform &T) const;
  // n pixels in normalised image units (along the finer axis).
  double normalisedPixels(double n) const { return n / std::max(m_cam.get_px(), m_cam.get_py()); }
  vpMorphRigidTransform overlapFit(const vpMorphContour &currentN, const vpMorphContour &goalN,
                                   const vpMorphRigidTransform &T);
  // A new sequence: the tilt's correspondence, warm start, latch and guard start again.
  void forgetTilt();
  // A new sequence: whether the view is deformed, and its offsets, are decided again; the edges' band measured again.
  void forgetDeformation();
  // Target's over current region's area (both measured with their edges, views alike, the target the sub-goal), the
  // target's less the band along its edges that the current edges lie off it by (see the source), fitted from T.
  double bandCorrectedAreaRatio(const vpMorphContour &currentN, const vpMorphRigidTransform &T);
  //! The current edge outline laid on the target's (both normalised; the caller has the target's normalised once) by
  //! their similarity, from T (robust scale floored at a fifth of a half pixel): the depth at the goal when the
  //! regions cannot give it.
  vpMorphRigidTransform targetEdgeFit(const vpMorphContour &currentOutline, const vpMorphContour &targetOutline,
                                      const vpMorphRigidTransform &T) const;
  bool tiltActive() const;
  bool estimateTilt(const vpMorphContour &currentN, vpHomogeneousMatrix &cMct, double &Zp);
  // estimateTilt()'s fit, each time it is tried.
  bool fitTilt(const vpMorphContour &currentN, vpHomogeneousMatrix &cMct, double &Zp);
  /*
    The homography current -> target that fitTilt() and readTilt() read the tilt from: refined on the measured edge
    outlines (when both have them) from \e warm (6 iterations) or, without it or when that fails, from the polygons'
    correspondence (m_tiltTracker) fit then refined (8). False when it does not explain the view: the polygons' fit
    under max(m_tiltMinInliers, polygonMinInliers) of inliers or over m_tiltMaxResidualPx, the refined one under
    minInliers or over maxResidualPx (pixels).
  */
  bool outlineHomography(const vpMorphContour &currentN, const vpMorphContour &targetN, const vpMorphHomography *warm,
                         double polygonMinInliers, double minInliers, double maxResidualPx, vpMorphHomography &G);
  void fuseTilt(const vpMatrix &C, double &angle, double &ax, double &ay, double &sa);
  void record();
  bool targetMismatch(const vpMorphContour &current);

  vpCameraParameters m_cam;
  vpMorphContour m_target;
  vpMorphTemplate m_template; // the target's articulated template (none for a rigid target)
  double m_opening = 0.0;     // the opening m_target was posed at
  unsigned int m_fixedPart = 0;
  vpMorphContour m_current; // last contour given (pixels), for display()
  double m_Zd = 0.5;
  std::size_t m_nSub = 10;
  RigidPath m_rigidPath = CAMERA_STRAIGHT_LINE;
  double m_rotThr = 0.10, m_pxThr = 5.0, m_rotFine = 0.001, m_pxFine = 0.1, m_scaleFine = 0.0;
  double m_gain = 0.5, m_dt = 0.1;
  ControlLaw m_law = HOMOGENEOUS_TRANSFORMS;
  double m_jumpFactor = 2.0, m_workFloor = 0.05, m_minMargin = 0.02, m_minArea = 25.0;
  double m_jumpRotation = 0.1;                    // rad: fit rotation jump beyond one step that is not noise
  double m_regionMismatch = 0.02; // change of the regions' similarity invariants above which they are not alike
  enum { UNDECIDED, ALIKE, NOT_ALIKE } m_regionsAlike = UNDECIDED; // decided at the first fit of a sequence
  bool m_regionsRejudged = false;                 // NOT_ALIKE withdrawn once in this sequence (estimateTilt())
  double m_calibRotation = 0.05, m_calibPx = 8.0; // image motion that makes one calibration observation
  bool m_online = true;
  TiltCorrection m_tiltMode = TILT_OFF;
  double m_tiltFine = 0.002;
  double m_tiltDeadZone = 0.07;
  double m_outlineTiltDeadZone = 0.0026;
  double m_tiltDeadZoneUsed = 0.07; // the dead zone of the last estimate (outlines or polygons)
  double m_tiltMinInliers = 0.6, m_tiltMaxResidualPx = 2.0; // a homography fit worse than this is not used
  unsigned int m_maxLost = 25, m_maxReplans = 3;
  double m_jumpPx = 20.0;
  vpMatrix m_eJe; // setJointState(): empty until given
  vpColVector m_q, m_qMin, m_qMax, m_qEnd;
  bool m_longWay = false; // the current sequence turns the long way round
  vpMorphDatabase m_checkDb;
  std::size_t m_checkIndex = 0;
  double m_checkSlack = 1.25;
  double m_shapeChange = 0.25; // x the target's threshold: distance between two views that is another shape
  vpMorphContour m_prevContour; // contour of the last commanded iteration

  vpMorphHandEyeEstimator m_estimator;
  vpMorphCorrespondenceTracker m_tracker;
  vpMorphCorrespondenceTracker m_tiltTracker; // current -> target, for the homography
  vpMorphHomography m_tiltG;                  // the last homography refined on outlines (warm start)
  bool m_tiltWarm = false;
  vpFeatureMorph m_s, m_sd;
  vpServo m_task;

  bool m_started = false;
  std::vector<vpMorphContour> m_subGoals;
  std::size_t m_k = 0;
  Status m_status = NOT_STARTED;
  unsigned int m_iter = 0;
  double m_rotRes = 0, m_transRes = 0, m_scaleRes = 0, m_scaleRel = 0, m_work = 0;
  bool m_fullMatch = false, m_areaBased = false, m_overlapBased = false;
  bool m_overlapWarm = false; // m_overlapOffset holds the last deformed view's offset
  // Decided at the first fit to the target; UNEXPLAINED (a stop) at any fit that leaves too much of it outside.
  enum { SHAPE_UNDECIDED, DEFORMED, UNDEFORMED, UNEXPLAINED } m_deformed = SHAPE_UNDECIDED;
  vpMorphRigidTransform m_overlapOffset; // largest-overlap fit o (outline or area fit)^-1, to warm-start the next
  vpMorphRigidTransform m_overlapLast;   // the last period's placement of largest overlap
  double m_overlapFitTheta = 0.0;        // and the rotation of the outline (or area) fit it was found from
  double m_scaleBias = 1.0; // scale of the largest undeformed part over the outlines' length ratio (a deformed view)
  unsigned int m_rigidPartCount = 0;  // periods since the deformed view was found, for the part's search
  bool m_partKnown = false;           // the undeformed part was found at the last period
  vpMorphRigidTransform m_partOffset; // its fit o the overlap fit^-1, to follow it to the next period
  unsigned int m_edgePartCount = 0;   // periods of the final approach of a view not alike its target
  bool m_edgePartKnown = false;       // its largest part lying on the target's covers kEdgePartMinShare of it
  vpMorphRigidTransform m_edgePartOffset; // that part's fit o the edge fit^-1, carried between its searches
  vpMorphRigidTransform m_edgePartLast;   // that part's fit itself, at the last period it was found
  unsigned int m_edgePartMisses = 0;      // searches in a row that did not find it
  unsigned int m_bandCount = 0;           // periods of the final approach of a view alike its target
  double m_band = 0.0; // area of the band along the target's edges that the current edges lie off (normalised units)
  double m_tiltRes = 0;
  bool m_tiltOk = false, m_tiltLatched = false;
  // Tilt executed since the first tilt command of the final approach (camera frame, rad), the estimate at that
  // command, and the periods in a row the estimate has not come down along it (see estimateTilt()).
  double m_tiltSumX = 0.0, m_tiltSumY = 0.0, m_tiltRefX = 0.0, m_tiltRefY = 0.0;
  unsigned int m_tiltNoProgress = 0;
  // Tries in a row without a usable homography, then counting the periods between tries, until one is fitted in the
  // sequence (see estimateTilt()).
  unsigned int m_tiltMisses = 0;
  bool m_tiltFitted = false;
  // The outlines' tilt estimates of the final approach, fused by fuseTilt().
  struct TiltSample
  {
    double ex = 0, ey = 0;            // rotation vector that levels the camera (rad)
    double c00 = 0, c01 = 0, c11 = 0; // its covariance, from the homography's
    double sx = 0, sy = 0;            // m_tiltSumX, m_tiltSumY then
    double deadZone = 0;              // this period's own dead zone
  };
  std::vector<TiltSample> m_tiltWindow;
  double m_tiltKappa = 1.0; // reduced chi-square of the last window of three or more
  vpHomogeneousMatrix m_cMcdH;
  // Hand-eye tilt exploration (setHandEyeTiltExploration()): the turn asked and commanded so far (rad), the image's
  // size, and the readings of the view's tilt along the turn.
  double m_exploreAngle = 0.0, m_exploreTheta = 0.0;
  // The last view read (centroid, area), the turn commanded since, the views in a row displaced from it.
  double m_exploreCx = 0.0, m_exploreCy = 0.0, m_exploreArea = 0.0, m_exploreTurned = 0.0;
  unsigned int m_exploreJumps = 0, m_exploreSince = 0; // and the periods since it was read
  unsigned int m_imageWidth = 0, m_imageHeight = 0;
  unsigned int m_exploreCount = 0, m_explorePass = 0; // periods of this turn, turns done
  vpThetaUVector m_exploredTilt{0, 0, 0};             // the correction applied to eMc
  enum { EXPLORE_NONE, EXPLORE_OUT, EXPLORE_BACK, EXPLORE_JUMPED, EXPLORE_DONE } m_explorePhase = EXPLORE_NONE;
  struct TiltReading
  {
    double theta = 0, nx = 0, ny = 0; // the turn then, and the plane normal's image-plane part in the camera
    double c00 = 0, c01 = 0, c11 = 0; // its covariance
  };
  std::vector<TiltReading> m_exploreReadings;
  vpMorphHomography m_readG; // the last reading's homography, and the turn then: the next reading's warm start
  double m_readTheta = 0.0;
  bool m_readWarm = false;
  bool exploreStep(const vpMorphContour &current, const vpMorphContour &currentN, vpColVector &ve);
  bool exploreCommand(vpColVector &ve);
  // A sequence planned from \e current anew, with the target check of a new start; with \e replan, after a view
  // jump (counted, at most maxReplans()). False with the zero velocity \e v of the stop or of REPLANNED.
  bool planAgain(const vpMorphContour &current, bool replan, vpColVector &v);
  bool readTilt(const vpMorphContour &currentN, TiltReading &r);
  double finishExploration();
  // For the distance-jump test and the calibration: the previous iteration to the same sub-goal.
  bool m_haveWork = false, m_haveMove = false;
  bool m_fittedInSequence = false; // m_prevT is a fit of this sequence (to this sub-goal or the one before)
  double m_prevWork = 0, m_margin = 1;
  vpMorphRigidTransform m_prevT;
  vpHomogeneousMatrix m_prevCmd; // eMe' commanded at the previous iteration
  // Calibration baseline: the fit at the anchor and the moves commanded since then.
  vpMorphRigidTransform m_anchorT;
  double m_anchorZ = 0;
  vpHomogeneousMatrix m_accCmd;
  vpColVector m_ve, m_vc;
  vpColVector m_stockVc; // STOCK_VPSERVO: camera velocity of vpServo, computed with the fit
  std::vector<Iteration> m_history;
  // Faults: successive calls without a contour, re-plans, stop latch, last target check.
  unsigned int m_lost = 0, m_replans = 0;
  bool m_halted = false;
  double m_targetDistance = std::numeric_limits<double>::quiet_NaN();
};

#endif
