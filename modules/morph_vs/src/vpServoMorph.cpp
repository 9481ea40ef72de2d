#include <visp3/morph_vs/vpServoMorph.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>

#include <Eigen/Dense>

#include <visp3/core/vpExponentialMap.h>
#include <visp3/core/vpRotationMatrix.h>
#include <visp3/core/vpThetaUVector.h>
#include <visp3/core/vpVelocityTwistMatrix.h>
#include <visp3/morph/vpMorph.h>
#include <visp3/morph/vpMorphException.h>

#include "vpMorphRegionCheck.h"

namespace
{
// Multiples of the tilt's standard deviation (from the outlines' homography) within which it is not commanded.
const double kTiltSigmas = 2.0;
// Periods of the final approach fused into one tilt estimate at most (see fuseTilt()).
const std::size_t kTiltWindow = 16;
// The largest standard deviation of a 2x2 covariance [c00 c01; c01 c11] (its largest eigenvalue's square root).
double largestDeviation(double c00, double c01, double c11)
{
  return std::sqrt(std::max(0.0, 0.5 * (c00 + c11) + std::sqrt(0.25 * (c00 - c11) * (c00 - c11) + c01 * c01)));
}
// The tilt (angle, axis (ax, ay) of norm sa = sin(angle)) as a rotation vector (ex, ey); zero when untilted.
void tiltVector(double angle, double ax, double ay, double sa, double &ex, double &ey)
{
  ex = sa > 1e-12 ? angle * ax / sa : 0.0;
  ey = sa > 1e-12 ? angle * ay / sa : 0.0;
}
/*
  The tilt to command from the estimate e, given a second estimate f and the covariance S = [s00 s01; s01 s11] of one
  period's estimate: along each principal axis of S, what both e and f show on the same side beyond k standard
  deviations (and at least floor), the smaller of the two; nothing on an axis where they disagree. Per axis, because a
  thin object's tilt about its long axis is seen ten times worse than about its short one (the pliers: 0.33 and
  0.04 deg): one dead zone for both either left the short axis's tilt uncorrected or followed the long axis's noise.
*/
void tiltBeyondDeadZone(double ex, double ey, double fx, double fy, double s00, double s01, double s11, double floor,
                        double k, double &cx, double &cy)
{
  const double mean = 0.5 * (s00 + s11), half = std::sqrt(0.25 * (s00 - s11) * (s00 - s11) + s01 * s01);
  const double th = 0.5 * std::atan2(2.0 * s01, s00 - s11); // the axis of the larger variance
  const double variance[2] = {mean + half, std::max(0.0, mean - half)};
  const double axis[2][2] = {{std::cos(th), std::sin(th)}, {-std::sin(th), std::cos(th)}};
  cx = cy = 0.0;
  for (int i = 0; i < 2; ++i) {
    const double a = ex * axis[i][0] + ey * axis[i][1], b = fx * axis[i][0] + fy * axis[i][1];
    const double beyond = std::min(std::fabs(a), std::fabs(b)) - std::max(floor, k * std::sqrt(variance[i]));
    if (a * b > 0.0 && beyond > 0.0) {
      cx += std::copysign(beyond, a) * axis[i][0];
      cy += std::copysign(beyond, a) * axis[i][1];
    }
  }
}
// Acceptance of the homography refined on edge outlines: inlier share and RMS residual (pixels).
const double kOutlineMinInliers = 0.9, kOutlineMaxResidualPx = 0.5;
// Inlier share and RMS residual (pixels) the homography on edge outlines needs when the regions are not alike (see
// estimateTilt()): it must show the whole outline seen in perspective. Tilted whole views (6dof set) fit to 0.004-0.107
// px and noisy ones (noise set) to 0.14 px at most; a thin pliers bitten by a card was fitted to 0.49-0.50 px, 99 % of
// it, by a 38-41 deg tilt that bent the card's edge onto its outline (Viper850, occlusion seed 3 start 18).
const double kNotAlikeMinInliers = 0.99, kNotAlikeMaxResidualPx = 0.25;
// The hand-eye tilt exploration's turn rate (rad/s) and the largest deviation of its estimate that corrects eMc (rad).
const double kExploreSpeed = 1.0, kExploreMaxDeviation = 0.006;
const double kExploreBorderPx = 40.0; // the view's distance to the image border at which the turn comes back
// Turn (rad) after which a view with fewer readings than periods / 2 ends the exploration; the correction (rad) beyond
// which a second turn reads what is left, and the turns at most.
const double kExploreProbe = 0.35, kExploreRepeat = 0.01;
// The smallest correction applied (rad), and how many deviations it must be.
const double kExploreMinTilt = 0.01, kExploreSigmas = 5.0;
// A view off the turn's way with its area within kExploreAreaChange for kExploreJumps periods was displaced.
const double kExploreAreaChange = 0.1;
// The view's drift per period along the turn, at most (px): 5 px measured with the mount 10 deg off.
const double kExploreDriftPx = 6.0;
const unsigned int kExploreJumps = 3;
const unsigned int kExplorePasses = 2;
// Deformed view, overlap and undeformed part: the constants shared with vpFeatureMorph (see vpMorphRegionCheck).
constexpr double kDeformedOutside = vpMorphRegionCheck::kDeformedOutside;
constexpr std::size_t kOverlapPoints = vpMorphRegionCheck::kOverlapPoints;
constexpr double kRigidPartTolerancePx = vpMorphRegionCheck::kRigidPartTolerancePx;
constexpr double kRigidPartMinShare = vpMorphRegionCheck::kRigidPartMinShare;
constexpr unsigned int kRigidPartPeriod = vpMorphRegionCheck::kRigidPartPeriod;
// Share of a deformed view left outside the target at its largest overlap above which no rigid placement explains
// it: a tool bent by 10-15 deg leaves its limb out (at most 11.4 % over every period of the held-out deformable,
// occlusion, noise, planar-hard, 6dof and calib runs on the free camera), pliers opened by 32 deg leave an arm out
// (27.5-28.2 %, at the outlines' length scale; more at their own), and so would another object.
const double kUnexplainedOutside = 0.2;
// Least share of the outline that the largest part lying on the target's must cover for its fit to replace the
// edge fit on a view whose region is not the target's (a wedge with a sagging top: 0.69).
const double kEdgePartMinShare = 0.5;
// Searches in a row for that part before waiting kRigidPartPeriod periods again (a view that has none: an occluded
// one showing less than that share of its outline on the target's, or one still far from it).
const unsigned int kEdgePartRetries = 3;
// Periods in a row without a usable homography, none fitted yet in the sequence (see estimateTilt()), after which the
// tilt is only tried every kTiltRetryPeriod periods: a bent or partly hidden outline, which no homography explains,
// failed every period of the deformable and occlusion sets' final approaches (a fifth of their control time). A view
// fitted once is tried every period: a key's fits failed 23 periods in a row (its regions judged not alike, its fits
// held to 99 % of the outline), then came back (calib seed 2 start 14: 1.4 deg off when tried every 8th period).
const unsigned int kTiltRetryPeriod = 8;
// Largest change of the outline's length that a bend explains (relative): the drawn bends change it by under 0.5 %.
const double kBendLengthChange = 0.01;
// Turn of the outline (or area) fit from one period to the next beyond which the overlap's warm start is checked
// against the last placement (a period's step at the final approach is a tenth of a residual of a few degrees).
const double kOverlapStartJump = vpMath::rad(1.0);
// The plan of a view whose regions are not alike: the outline fit's robust scale floor (pixels), and how much less of
// the view's area it must leave outside the target than the least squares to replace them (see start()).
const double kPlanOutlineSigmaPx = 0.1, kPlanInsideGain = 0.01;
// Largest change of the fitted scale (log) from the last period's fit to a sub-goal's first fit: the sub-goals are a
// step apart (the sub-goal thresholds: 5 px on a 100 px object), a tenth is a jump to another basin.
const double kSwitchScaleJump = 0.1;
// A view does not halve or double in one period: a fit whose scale changes by more (log) ran away (to a point, or to
// the view's double).
const double kScaleRunaway = std::log(2.0);

// The largest part of the outline \e dense lying within \e tolerance of \e target: searched over the whole outline, or
// followed from its last \e offset to \e base (a few rounds).
vpMorphRigidTransform rigidPart(const vpMorphContour &dense, const vpMorphContour &target,
                                const vpMorphRigidTransform &base, bool search, const vpMorphRigidTransform &offset,
                                double tolerance, double &share)
{
  return search ? vpMorphRigidTransform::fitRigidPart(dense, target, base, tolerance, &share)
                : vpMorphRigidTransform::refineRigidPart(dense, target, offset * base, tolerance, &share);
}

void checkPositive(double v, const char *what)
{
  if (!std::isfinite(v) || v <= 0.0) {
    std::ostringstream os;
    os << "vpServoMorph: " << what << " must be finite and > 0, got " << v;
    throw vpMorphException(vpMorphException::badParameterError, os.str());
  }
}

void checkNonNegative(double v, const char *what)
{
  if (!std::isfinite(v) || v < 0.0) {
    std::ostringstream os;
    os << "vpServoMorph: " << what << " must be finite and >= 0, got " << v;
    throw vpMorphException(vpMorphException::badParameterError, os.str());
  }
}

bool allFinite(const vpColVector &v)
{
  for (unsigned int i = 0; i < v.size(); ++i)
    if (!std::isfinite(v[i]))
      return false;
  return true;
}

// Area ratio goal / current and the two centroids, from the regions measured on the images when both contours
// carry one (sub-pixel, steady from one image to the next), else from the polygons (which can only be compared
// with polygons: a region's area is not a polygon's).
double areaRatio(const vpMorphContour &goal, const vpMorphContour &current)
{
  if (goal.hasRegion() && current.hasRegion())
    return goal.regionArea() / current.regionArea();
  return goal.area() / current.area();
}

void centroids(const vpMorphContour &goal, const vpMorphContour &current, double &gx, double &gy, double &cx,
               double &cy)
{
  if (goal.hasRegion() && current.hasRegion()) {
    goal.regionCentroid(gx, gy);
    current.regionCentroid(cx, cy);
  } else {
    goal.centroid(gx, gy);
    current.centroid(cx, cy);
  }
}

// Orientation (mod pi) of a measured region's principal axis and its anisotropy (l1 - l2) / (l1 + l2) in [0, 1].
void principalAxis(const vpMorphContour &c, double &phi, double &anisotropy)
{
  double mu20, mu11, mu02;
  c.regionMoments(mu20, mu11, mu02);
  phi = 0.5 * std::atan2(2.0 * mu11, mu20 - mu02);
  const double tr = mu20 + mu02;
  anisotropy = tr > 0.0 ? std::hypot(mu20 - mu02, 2.0 * mu11) / tr : 0.0;
}

/*
  The rotation current -> goal refined by the measured regions' principal axes: a fit over corresponded vertices
  is biased by a few tenths of a degree when the two polygons place their vertices differently, the grey-level
  moments are not. Only a refinement: used when both regions are clearly elongated (anisotropy >= 0.1) and alike
  (anisotropies within 0.02: the same shape, not a deformed or occluded one), on the branch (mod pi) nearest to
  the fit, and only within 0.1 rad of it; otherwise the fit stands.
*/
double refinedRotation(const vpMorphContour &goal, const vpMorphContour &current, double thetaFit)
{
  if (!goal.hasRegion() || !current.hasRegion())
    return thetaFit;
  double pg, ag, pc, ac;
  principalAxis(goal, pg, ag);
  principalAxis(current, pc, ac);
  if (ag < 0.1 || ac < 0.1 || std::fabs(ag - ac) > 0.02)
    return thetaFit;
  double d = pg - pc;
  d += M_PI * std::round((thetaFit - d) / M_PI);
  return std::fabs(d - thetaFit) <= 0.1 ? d : thetaFit;
}

// Share of the view's area that lies outside the goal's region once F lays it on the goal.
const auto outsideShare = &vpMorphRegionCheck::outsideShare;

// The largest distance between the points of \e c moved by \e A and by \e B.
double largestShift(const vpMorphRigidTransform &A, const vpMorphRigidTransform &B, const vpMorphContour &c)
{
  double moved = 0.0;
  for (std::size_t i = 0; i < c.size(); ++i) {
    double x0, y0, x1, y1;
    A.apply(c.x(i), c.y(i), x0, y0);
    B.apply(c.x(i), c.y(i), x1, y1);
    moved = std::max(moved, std::hypot(x1 - x0, y1 - y0));
  }
  return moved;
}

// T with the scale of the edge fit Te, when Te moves the outline \e o by at most \e maxShift from where T puts it (the
// same basin); T as it is otherwise.
vpMorphRigidTransform withEdgeScale(const vpMorphRigidTransform &T, const vpMorphRigidTransform &Te,
                                    const vpMorphContour &o, double maxShift)
{
  if (largestShift(T, Te, o) > maxShift)
    return T;
  return vpMorphRigidTransform(T.theta(), T.tx(), T.ty(), Te.scale(), T.cx(), T.cy());
}

double rmsRadius(const vpMorphContour &c)
{
  double cx, cy, s = 0;
  c.centroid(cx, cy);
  for (std::size_t k = 0; k < c.size(); ++k)
    s += (c.x(k) - cx) * (c.x(k) - cx) + (c.y(k) - cy) * (c.y(k) - cy);
  return std::sqrt(s / c.size());
}
} // namespace

vpServoMorph::vpServoMorph() : m_cam(800, 800, 320, 240), m_ve(6, 0.0), m_vc(6, 0.0)
{
  m_task.setServo(vpServo::EYEINHAND_CAMERA);
  m_task.setInteractionMatrixType(vpServo::CURRENT);
  m_task.addFeature(m_s, m_sd);
  vpColVector dof(6, 1.0);
  dof[3] = dof[4] = 0.0; // planar task: no tilt
  m_task.setCameraDoF(dof);
}

const char *vpServoMorph::statusName(Status s)
{
  switch (s) {
  case NOT_STARTED:
    return "not started";
  case MOVING:
    return "moving";
  case SUBGOAL_REACHED:
    return "sub-goal reached";
  case CONVERGED:
    return "converged";
  case TARGET_LOST:
    return "target lost";
  case DEGENERATE_CONTOUR:
    return "degenerate contour";
  case UNRELIABLE_CORRESPONDENCE:
    return "unreliable correspondence";
  case REPLANNED:
    return "replanned";
  case LOST_TOO_LONG:
    return "lost too long";
  case TOO_MANY_REPLANS:
    return "too many replans";
  case TARGET_MISMATCH:
    return "target mismatch";
  case DEFORMATION_UNRESOLVED:
    return "deformation unresolved";
  }
  return "?";
}

void vpServoMorph::setTarget(const vpMorphContour &target, double Zd)
{
  if (target.empty() || target.units() != vpMorphContour::PIXEL)
    throw vpMorphException(vpMorphException::badParameterError,
                           "vpServoMorph::setTarget: the target must be a non-empty contour in pixels");
  checkPositive(Zd, "the desired depth Zd");
  m_target = target;
  m_Zd = Zd;
  m_template = vpMorphTemplate();
  m_opening = 0.0;
  m_fixedPart = 0;
  restart();
}

void vpServoMorph::setTarget(const vpMorphTemplate &t)
{
  const double Zd = t.cdMo()[2][3];
  if (!(Zd > 0.0))
    throw vpMorphException(vpMorphException::badParameterError,
                           "vpServoMorph::setTarget: the template has no desired pose (cdMo depth <= 0); set it "
                           "with vpMorphTemplate::setPlanarPose() or use setTarget(contour, Zd)");
  setTarget(t.contour(), Zd);
  if (t.isArticulated())
    m_template = t;
}

void vpServoMorph::poseArticulatedTarget(const vpMorphContour &current)
{
  m_target = m_template.viewFor(current, &m_opening, &m_fixedPart);
}

void vpServoMorph::setSubGoalCount(std::size_t n)
{
  m_nSub = n;
  restart();
}

void vpServoMorph::setSubGoalThresholds(double rotationRad, double translationPx)
{
  checkPositive(rotationRad, "the sub-goal rotation threshold");
  checkPositive(translationPx, "the sub-goal translation threshold");
  m_rotThr = rotationRad;
  m_pxThr = translationPx;
}

void vpServoMorph::setFinalThresholds(double rotationRad, double translationPx)
{
  checkPositive(rotationRad, "the final rotation threshold");
  checkPositive(translationPx, "the final translation threshold");
  m_rotFine = rotationRad;
  m_pxFine = translationPx;
}

void vpServoMorph::setFinalScaleThreshold(double relativeScale)
{
  if (!(relativeScale >= 0.0 && relativeScale < 1.0))
    throw vpMorphException(vpMorphException::badParameterError,
                           "vpServoMorph::setFinalScaleThreshold: the relative scale error must be in [0, 1)");
  m_scaleFine = relativeScale;
}

void vpServoMorph::setGain(double gain)
{
  checkPositive(gain, "the gain");
  if (gain > 1.0)
    throw vpMorphException(vpMorphException::badParameterError, "vpServoMorph::setGain: the gain must be <= 1");
  m_gain = gain;
}

void vpServoMorph::setSamplingTime(double dt)
{
  checkPositive(dt, "the sampling time");
  m_dt = dt;
}

void vpServoMorph::setControlLaw(ControlLaw law)
{
  m_law = law;
  restart();
}

void vpServoMorph::setJumpFactor(double f)
{
  checkPositive(f, "the jump factor");
  m_jumpFactor = f;
}

void vpServoMorph::setWorkFloor(double w)
{
  checkNonNegative(w, "the work floor");
  m_workFloor = w;
}

void vpServoMorph::setMinMargin(double m)
{
  if (!std::isfinite(m) || m < 0 || m > 1)
    throw vpMorphException(vpMorphException::badParameterError, "vpServoMorph::setMinMargin: must be in [0, 1]");
  m_minMargin = m;
}

void vpServoMorph::setMinArea(double px2)
{
  checkPositive(px2, "the minimum area");
  m_minArea = px2;
}

void vpServoMorph::setJumpPixels(double px)
{
  checkPositive(px, "the jump threshold in pixels");
  m_jumpPx = px;
}

void vpServoMorph::setJointState(const vpMatrix &eJe, const vpColVector &q, const vpColVector &qMin,
                                 const vpColVector &qMax)
{
  const unsigned int n = q.size();
  if (n == 0 || eJe.getRows() != 6 || eJe.getCols() != n || qMin.size() != n || qMax.size() != n)
    throw vpMorphException(vpMorphException::badParameterError,
                           "vpServoMorph::setJointState: eJe must be 6 x n for n joint positions and limits");
  for (unsigned int i = 0; i < n; ++i)
    if (!(q[i] >= qMin[i] && q[i] <= qMax[i]))
      throw vpMorphException(vpMorphException::badParameterError,
                             "vpServoMorph::setJointState: a joint position is NaN or outside its limits");
  m_eJe = eJe;
  m_q = q;
  m_qMin = qMin;
  m_qMax = qMax;
}

void vpServoMorph::setTargetCheck(const vpMorphDatabase &db, const std::string &name, double slack)
{
  if (!std::isfinite(slack) || slack < 1.0)
    throw vpMorphException(vpMorphException::badParameterError,
                           "vpServoMorph::setTargetCheck: the slack must be finite and >= 1");
  const std::size_t k = db.find(name);
  if (k == vpMorphRecognition::npos)
    throw vpMorphException(vpMorphException::notFoundError,
                           "vpServoMorph::setTargetCheck: no template '" + name + "' in the database");
  m_checkDb = db;
  m_checkIndex = k;
  m_checkSlack = slack;
}

bool vpServoMorph::targetMismatch(const vpMorphContour &current)
{
  if (m_checkDb.empty())
    return false;
  const vpMorphRecognition r = m_checkDb.recognize(current);
  if (m_template.isArticulated()) {
    // Its distance to the target posed at one opening varies by half its threshold from one view to the next: the
    // database's, over its poses.
    if (!m_checkDb.accepts(current, m_checkIndex, m_checkSlack, &m_targetDistance))
      return true;
  } else {
    m_targetDistance = m_checkDb.distance().distance(current, m_target);
    if (!(m_targetDistance <= m_checkSlack * m_checkDb.threshold(m_checkIndex)) &&
        !(m_checkDb.support(current, m_checkIndex, r.index == m_checkIndex && r.mirrored) >=
          m_checkDb.minimumSupport()))
      return true; // NaN too; an occluded view of the target (it shows enough of its outline) is not a mismatch
  }
  if (!(r.index != vpMorphRecognition::npos && r.index != m_checkIndex && r.accepted &&
        m_targetDistance >= mismatchRatio() * r.distance))
    return false;
  // Nearer by the distance, another template still does not replace the target when it explains less of the view:
  // a bent view is far from its template by the distance, and may be nearer another (measured: a bent screwdriver at
  // its goal, 0.89 from its template and 0.70 from the pliers, showing 0.65 of its own outline and 0.40 of theirs,
  // was re-recognised as the pliers and servoed 17 cm away).
  return !(std::isfinite(r.support) &&
           m_checkDb.support(current, m_checkIndex, m_checkDb.distance().mirrors()) > r.support);
}

void vpServoMorph::restart()
{
  m_started = false;
  m_lost = 0;
  m_replans = 0;
  m_halted = false;
  m_targetDistance = std::numeric_limits<double>::quiet_NaN();
  m_current = vpMorphContour();
  m_subGoals.clear();
  m_k = 0;
  m_status = NOT_STARTED;
  m_iter = 0;
  m_haveMove = m_haveWork = false;
  m_tracker.reset();
  m_tiltOk = false;
  forgetTilt();
  forgetDeformation();
  m_explorePhase = m_exploreAngle > 0.0 ? EXPLORE_OUT : EXPLORE_NONE;
  m_exploreTheta = 0.0;
  m_exploreReadings.clear();
  m_readWarm = false;
  m_exploreCount = 0;
  m_explorePass = 0;
  m_exploreJumps = 0;
  m_exploreSince = 0;
  m_exploreTurned = 0.0;
  m_exploredTilt = vpThetaUVector(0, 0, 0);
  m_overlapBased = false;
  m_tiltRes = 0;
  m_cMcdH.eye();
  m_history.clear();
  m_ve = vpColVector(6, 0.0);
  m_vc = vpColVector(6, 0.0);
}

void vpServoMorph::setRigidPath(RigidPath p)
{
  m_rigidPath = p;
  restart();
}

void vpServoMorph::start(const vpMorphContour &current)
{
  m_regionsAlike = UNDECIDED;
  m_regionsRejudged = false;
  m_longWay = false;
  m_qEnd = vpColVector();
  if (m_nSub == 0) {
    m_subGoals = {m_target};
  } else {
    // The plan follows the correspondence the tracker would choose (checked on the regions, see
    // vpMorphCorrespondenceTracker): otherwise a deformed view is planned half a turn round and then fitted the
    // other way at the last sub-goal, a jump that re-plans the same way again.
    vpMorphMatcher &matcher = m_tracker.matcher();
    const vpMorphCorrespondence corr =
        m_tracker.regionCheck() ? matcher.matchOnRegions(current, m_target) : matcher.match(current, m_target);
    vpMorph morph(current, m_target, corr);
    // Whether the two regions are one shape seen twice is a property of the current object against the target
    // (the sub-goals before the deformation frames are views of the current contour itself): see fitToSubGoal().
    m_regionsAlike = vpMorphRegionCheck::alike(m_target, current, morph.rigidTransform().scale(), m_regionMismatch)
                         ? ALIKE
                         : NOT_ALIKE;
    bool occludedPlan = false;
    if (m_regionsAlike == NOT_ALIKE) {
      // Part of the object hidden: the least-squares fit crowds the pairs of the hidden stretch onto the occluder's
      // edge and its scale carries the missing part (a card over a pliers' jaws: 20 % large), so the rigid frames
      // drove the camera 9 cm towards the object and the deformation frames back (path 5 times the straight line).
      // The visible outline laid on the target's does not: that fit is the plan's rigid part when it lays the view
      // inside the target clearly better (1 % of its area) than the least squares. Not for a bent view, which both
      // lay out of the target alike and whose bend drags the outline fit (a bent hammer's scale 1.9 % off where the
      // least squares were 0.1 %); it keeps the least squares.
      try {
        const vpMorphRigidTransform Tls = morph.rigidTransform();
        const vpMorphRigidTransform Te =
            vpMorphRigidTransform::refineOnOutline(current, m_target, Tls, true, kPlanOutlineSigmaPx);
        if (outsideShare(Te, current, m_target) + kPlanInsideGain < outsideShare(Tls, current, m_target)) {
          morph = vpMorph(current, m_target, corr, Te);
          occludedPlan = true;
        }
      } catch (const vpException &) {
        // the outline fit degenerated: the least squares stand
      }
    }
    // The rigid transform (pixels) as a camera displacement cMc' = [Rz(-theta), d] at the current depth.
    const vpMorphRigidTransform &Tp = morph.rigidTransform();
    const double px = m_cam.get_px(), py = m_cam.get_py();
    const vpMorphRigidTransform Tn(Tp.theta(), Tp.tx() / px, Tp.ty() / py, Tp.scale(), (Tp.cx() - m_cam.get_u0()) / px,
                                   (Tp.cy() - m_cam.get_v0()) / py);
    const double Z = m_Zd * std::sqrt(areaRatio(m_target, current));
    const vpHomogeneousMatrix cMcp = cameraDisplacement(Tn, Z, 1.0);
    // The short way round unless the joints would end near a limit and the long way keeps them clear.
    const double theta = Tp.theta(), longTurn = theta - std::copysign(2.0 * M_PI, theta);
    if (m_q.size() > 0) {
      const vpMatrix eJeInv = m_eJe.pseudoInverse();
      const vpVelocityTwistMatrix eVc(m_estimator.get_eMc());
      m_qEnd = jointEnd(eJeInv, eVc, cMcp, theta);
      const vpColVector qLong = jointEnd(eJeInv, eVc, cMcp, longTurn);
      m_longWay = nearJointLimit(m_qEnd) && !nearJointLimit(qLong);
      if (m_longWay)
        m_qEnd = qLong;
    }
    const double turn = m_longWay ? longTurn : theta; // the image's rotation along the rigid frames
    m_subGoals = morph.sequence(m_nSub, m_longWay);
    const std::size_t nr = morph.rigidFrameCount(m_nSub);
    if (m_rigidPath == CAMERA_STRAIGHT_LINE && nr > 1) {
      // The pose alpha of the way along the straight line is [Rz(-alpha theta), alpha d] (theta: the turn chosen
      // above), and a plane parallel to the image at depth Z is seen from it through x' = s R(alpha theta) x -
      // s R(alpha theta) alpha d_xy / Z, s = Z / (Z - alpha d_z) (normalised coordinates, about the principal point).
      const vpMorphContour currentN = current.toNormalized(m_cam);
      for (std::size_t k = 1; k < nr; ++k) { // the last rigid frame stays the rectified contour itself
        const double a = double(k) / double(nr), th = a * turn;
        const double dx = a * cMcp[0][3], dy = a * cMcp[1][3], dz = a * cMcp[2][3];
        if (!(Z - dz > 0.0) || !std::isfinite(Z))
          break; // not a camera pose in front of the plane: keep the image-space frames
        const double sc = Z / (Z - dz), ct = std::cos(th), st = std::sin(th);
        const vpMorphRigidTransform Ta(th, -sc * (ct * dx - st * dy) / Z, -sc * (st * dx + ct * dy) / Z, sc, 0.0, 0.0);
        m_subGoals[k - 1] = Ta.apply(currentN).toPixels(m_cam);
      }
    }
    // An occluded view planned on its outline is rectified onto the target where it shows it: its deformation frames
    // only grow the occluder's bite into the hidden stretch, which no camera motion shows, and the view fitted to
    // them was 17 % small, then 10 % large (a wedge whose camera went 10 cm off the way and back: path 19 times its
    // 12 mm straight line). Its sequence goes from the last rigid frame to the target.
    if (occludedPlan && m_subGoals.size() > nr + 1)
      m_subGoals.erase(m_subGoals.begin() + static_cast<std::ptrdiff_t>(nr), m_subGoals.end() - 1);
  }
  m_k = 0;
  m_tracker.reset();
  forgetTilt();
  forgetDeformation();
  m_haveWork = false;
  m_fittedInSequence = false;
  m_started = true;
}

bool vpServoMorph::planAgain(const vpMorphContour &current, bool replan, vpColVector &v)
{
  if (replan) {
    if (m_replans >= m_maxReplans) {
      m_halted = true;
      v = stop(TOO_MANY_REPLANS);
      return false;
    }
    ++m_replans;
  }
  start(current);
  if (targetMismatch(current)) {
    m_halted = true;
    v = stop(TARGET_MISMATCH);
    return false;
  }
  if (replan) {
    v = stop(REPLANNED);
    return false;
  }
  return true;
}

vpColVector vpServoMorph::stop(Status s)
{
  m_status = s;
  m_ve = vpColVector(6, 0.0);
  m_vc = vpColVector(6, 0.0);
  m_haveMove = false; // the robot does not move: nothing to observe next time
  record();
  return m_ve;
}

vpMorphRigidTransform vpServoMorph::fitToSubGoal(const vpMorphContour &currentN, const vpMorphContour &currentPx,
                                                 double Z, bool switching)
{
  const vpMorphContour goalN = m_subGoals[m_k].toNormalized(m_cam);
  vpMorphRigidTransform T;
  const vpMorphCorrespondenceTracker *tr = &m_tracker;
  if (m_law == HOMOGENEOUS_TRANSFORMS) {
    const vpMorphCorrespondence &corr = m_tracker.update(currentN, goalN);
    // Contours come from images: their vertices are on the pixel grid, so the robust scale is floored at half a
    // pixel (in normalised units); otherwise, near a goal, the exactly coinciding vertices win and the fit is the
    // identity a pixel or two away from the goal (CONVERGED reported 0.6 deg / 7 mm off on rendered images).
    const double halfPixel = normalisedPixels(0.5);
    const vpMorphRigidTransform Tfit = vpMorphRigidTransform::fitLeastSquares(
        currentN, goalN, corr, true, vpMorphRigidTransform::TUKEY, 30, halfPixel);
    // The rotation comes from the correspondence (nothing else can tell it beyond 90 deg), but the translation and
    // scale of a fit over corresponded vertices are biased when the two polygons place their vertices differently
    // (a real contour and a stored or morphed one: millimetres on a thin-handled object). The region's area
    // centroid and area are not: use them.
    // When both contours carry the region measured on their image, its sub-pixel area and centroid are used.
    double cx, cy, gx, gy;
    centroids(goalN, currentN, gx, gy, cx, cy);
    const double s = std::sqrt(areaRatio(goalN, currentN));
    // The regions are not one shape seen twice when part of the object is hidden or it is deformed: their areas
    // and centroids would carry the missing part into the pose, the robust fit over corresponded vertices
    // (outliers down-weighted) does not. Decided once per sequence, against the target (at start(), or at the
    // first fit when the target is the only sub-goal): an occluder or a bend belongs to the scene, not to one
    // frame, and switching between the two estimates (millimetres apart on a thin object, whose fitted scale is
    // noisy) from one frame to the next made the loop chatter (measured: a Viper850 run oscillating by 1-6 mm and
    // stopping 1.02 mm off).
    if (m_regionsAlike == UNDECIDED)
      m_regionsAlike = vpMorphRegionCheck::alike(goalN, currentN, Tfit.scale(), m_regionMismatch) ? ALIKE : NOT_ALIKE;
    // An occluder that comes during the sequence hides part of a region that was alike: from then on, to the end of
    // the sequence, it is not (one way only: no chatter). Checked against the target, whose region the current one
    // is a view of whatever the sub-goal (measured: a key that a card covered at iteration 30 converged 18 mm off,
    // its lost area taken for depth).
    else if (m_regionsAlike == ALIKE && m_target.hasRegion() &&
             !vpMorphRegionCheck::alike(m_target, currentPx, 1.0, m_regionMismatch))
      m_regionsAlike = NOT_ALIKE;
    m_areaBased = m_regionsAlike == ALIKE;
    if (!m_areaBased) {
      // Part of the outline is not the target's (hidden by an occluder, cut, bent): the corresponded vertices
      // then crowd the missing part onto the cut and drag the fit along a straight handle by centimetres; the
      // visible outline laid on the goal's does not slide.
      // Its robust scale is floored at a tenth of a pixel, not half: distances to the goal's edges are continuous
      // (not vertices on the pixel grid), and a cut at 5 x half a pixel kept the occluder's edge where it meets
      // the outline (the fit's scale 0.1 % off at the goal, half a millimetre of depth).
      T = vpMorphRigidTransform::refineOnOutline(currentN, goalN, Tfit, true, 0.2 * halfPixel);
      // The fit over a tracked correspondence can start it in another basin when the joined outline changes its
      // vertices (a wrench cut in two by a card: 21 % off in scale and 20 px away for one period, taken for a jump,
      // re-planned, three times over). Then it is refined from the last fit to the same sub-goal too, and that one
      // is kept if it is no jump and leaves less of the view outside the goal. A fit whose scale ran away (a
      // drifting correspondence fitted at a fifth of the view's size, then refined to a point, inside the goal) is no
      // view either: the second opinion is kept whenever its own scale is steady. At a sub-goal switch there is no
      // fit to this sub-goal yet, but the sub-goals are a step apart: a first fit more than kSwitchScaleJump in scale
      // from the last period's (a wrench cut in two, first fitted on its target at 0.78 of its size, then re-planned)
      // is refined from that one too, which is kept if it stays within it.
      const bool switchJump = switching && m_fittedInSequence && scaleChange(T) > kSwitchScaleJump;
      if ((m_haveWork && (viewJumped(T) || scaleChange(T) > kScaleRunaway)) || switchJump) {
        try {
          const vpMorphRigidTransform Tw =
              vpMorphRigidTransform::refineOnOutline(currentN, goalN, m_prevT, true, 0.2 * halfPixel);
          if (switchJump ? scaleChange(Tw) <= kSwitchScaleJump
                         : !viewJumped(Tw) && scaleChange(Tw) <= kScaleRunaway &&
                               (scaleChange(T) > kScaleRunaway ||
                                outsideShare(Tw, currentN, goalN) < outsideShare(T, currentN, goalN)))
            T = Tw;
        } catch (const vpException &) {
          // no second opinion (a view the outline fit or the overlap cannot take): the jump stands
        }
      }
      // On the target, with the edges measured on both images: the scale (the depth at the goal) from the same fit
      // on them, which does not depend on where the two polygonisations put their vertices (tenths of a pixel on a
      // 100 px object: a millimetre at 0.5 m; measured: an occluded wrench ending 1.19 mm deep, 0.11 mm with it).
      // Only the scale: along a straight cut the edges, like the polygons, leave the fit free to slide, and the
      // edges' fit slides further (an occluded key drifting 15 cm instead of 13 mm). Nor when it moves the outline
      // by more than two pixels, which the polygons place to a pixel.
      // Not for a deformed view (see overlapFit(): its scale comes from its undeformed part).
      if (m_k + 1 == m_subGoals.size() && currentN.hasOutline() && m_target.hasOutline() && m_deformed != DEFORMED) {
        const vpMorphContour &o = currentN.outline();
        const vpMorphContour targetOutline = m_target.toNormalized(m_cam).outline();
        const vpMorphRigidTransform Te = targetEdgeFit(o, targetOutline, T);
        // A bend that only takes area away (a wedge whose top sags) is not found deformed by overlapFit() (nothing
        // of the view lies outside the target), and the edge fit, pulled by the bent stretch, ended 1.6 % off in
        // scale (8 mm deep). So the pose is the fit of the largest part of the outline lying on the target's, when
        // it is at least kEdgePartMinShare of it (an occluded view: the part it shows, about the edge fit itself).
        // Searched every kRigidPartPeriod periods (milliseconds), and once found followed from its last offset to the
        // edge fit in between. When lost, searched again at the next periods (kEdgePartRetries times): falling back
        // to the edge fit for a period or two is enough to make the loop chatter, the two fits being millimetres
        // apart on a bent view (a wedge wandering 5-7 mm off until the budget ran out).
        const bool search =
            m_edgePartCount++ % kRigidPartPeriod == 0 || (!m_edgePartKnown && m_edgePartMisses < kEdgePartRetries);
        if (search || m_edgePartKnown) {
          const vpMorphContour dense = o.resampled(2 * kOverlapPoints);
          const double tolerance = normalisedPixels(kRigidPartTolerancePx);
          double share = 0.0;
          vpMorphRigidTransform R = rigidPart(dense, targetOutline, Te, search, m_edgePartOffset, tolerance, share);
          m_edgePartKnown = share >= kEdgePartMinShare && R.scale() > 0.0;
          // The edge fit itself has two basins on a sagging wedge (scales 1.6 % apart, the polygon's correspondence
          // picking one or the other from one period to the next), so the part followed from its offset to the edge
          // fit was lost whenever the edge fit changed basin, and the fallback's scale kicked the depth every few
          // periods (a wedge wandering 0.5-2 mm off until the budget ran out, deformable seed 3 start 19). Then it is
          // followed from where it was found at the last period, which does not depend on the edge fit's basin.
          if (!m_edgePartKnown && !search) {
            R = vpMorphRigidTransform::refineRigidPart(dense, targetOutline, m_edgePartLast, tolerance, &share);
            m_edgePartKnown = share >= kEdgePartMinShare && R.scale() > 0.0;
          }
          if (m_edgePartKnown) {
            m_edgePartOffset = R * Te.inverse();
            m_edgePartLast = R;
          }
          m_edgePartMisses = m_edgePartKnown ? 0 : m_edgePartMisses + 1;
        }
        if (m_edgePartKnown)
          T = m_edgePartOffset * Te;
        else
          T = withEdgeScale(T, Te, o, 4.0 * halfPixel);
      }
    } else {
      T = vpMorphRigidTransform(refinedRotation(goalN, currentN, Tfit.theta()), gx - cx, gy - cy, s, cx, cy);
      // On the target, when both carry their measured regions and edges: the target's region (not the morph's last
      // frame, a polygon), less the band along its edges that a lighting can shift the current edges by.
      if (m_k + 1 == m_subGoals.size() && currentN.hasRegion() && currentN.hasOutline() && m_target.hasRegion() &&
          m_target.hasOutline()) {
        T = vpMorphRigidTransform(T.theta(), T.tx(), T.ty(), std::sqrt(bandCorrectedAreaRatio(currentN, T)), T.cx(),
                                  T.cy());
        // A target posed at another opening (vpMorphArticulation::pose()) carries the region of its parts' outlines
        // drawn, not a camera's view of the object: its area is off a view's by the band along the edges (0.1 % of
        // scale on the bench's opened pliers, half a millimetre of depth at 0.5 m), while its edges are the taught
        // ones turned, on which the view's lie within 0.03 %. Its depth comes from the edges, as when the regions are
        // not alike.
        if (m_opening != 0.0) {
          const vpMorphRigidTransform Te = targetEdgeFit(currentN.outline(), m_target.toNormalized(m_cam).outline(), T);
          T = withEdgeScale(T, Te, currentN.outline(), 4.0 * normalisedPixels(0.5));
        }
      }
    }
  } else {
    m_sd.buildFrom(goalN, m_Zd * std::sqrt(areaRatio(m_target, m_subGoals[m_k])));
    m_s.buildFrom(currentN, Z);
    // vpServo calls m_s.error(m_sd) once: that is this iteration's correspondence and fit, no second search.
    m_task.setLambda(m_gain / m_dt);
    m_stockVc = m_task.computeControlLaw();
    T = m_s.lastFit();
    tr = &m_s.tracker();
  }
  m_overlapBased = false;
  if (m_law == HOMOGENEOUS_TRANSFORMS && m_k + 1 == m_subGoals.size())
    T = overlapFit(currentN, goalN, T);
  m_work = tr->work();
  m_fullMatch = tr->lastSource() == vpMorphCorrespondenceTracker::FULL;
  m_margin = tr->margin();
  residuals(T, currentPx);
  return T;
}

bool vpServoMorph::rotationConsistent(const vpMorphRigidTransform &T) const
{
  const double dth = std::fabs(std::remainder(T.theta() - m_prevT.theta(), 2 * M_PI));
  return dth <= m_gain * std::fabs(m_prevT.theta()) + m_jumpRotation;
}

double vpServoMorph::scaleChange(const vpMorphRigidTransform &T) const
{
  // The fits' scales are finite and > 0 (vpMorphRigidTransform's invariant): the log is defined.
  return std::fabs(std::log(T.scale() / m_prevT.scale()));
}

bool vpServoMorph::viewJumped(const vpMorphRigidTransform &T) const
{
  if (!rotationConsistent(T))
    return true;
  // The fit's translation moves by about gain x its previous value per period (twice that for calibration errors);
  // beyond, plus jumpPixels(), the view jumped.
  const double px = m_cam.get_px(), py = m_cam.get_py();
  const double dt = std::hypot((T.tx() - m_prevT.tx()) * px, (T.ty() - m_prevT.ty()) * py);
  return dt > 2.0 * m_gain * std::hypot(m_prevT.tx() * px, m_prevT.ty() * py) + m_jumpPx;
}

void vpServoMorph::forgetTilt()
{
  m_tiltTracker.reset();
  m_tiltWarm = false;
  m_tiltLatched = false;
  m_tiltSumX = m_tiltSumY = m_tiltRefX = m_tiltRefY = 0.0;
  m_tiltNoProgress = 0;
  m_tiltMisses = 0;
  m_tiltFitted = false;
  m_tiltWindow.clear();
  m_tiltKappa = 1.0;
}

void vpServoMorph::forgetDeformation()
{
  m_overlapWarm = false;
  m_deformed = SHAPE_UNDECIDED;
  m_scaleBias = 1.0;
  m_rigidPartCount = 0;
  m_partKnown = false;
  m_edgePartCount = 0;
  m_edgePartKnown = false;
  m_edgePartMisses = 0;
  m_bandCount = 0;
  m_band = 0.0;
}

vpMorphRigidTransform vpServoMorph::overlapFit(const vpMorphContour &currentN, const vpMorphContour &goalN,
                                               const vpMorphRigidTransform &T)
{
  // A silhouette joined across an occluder's cut (no measured region, see vpMorphContourExtractor::extractJoined)
  // sticks out of the target along its bridge: that is occlusion, not a bend.
  if (goalN.hasRegion() && !currentN.hasRegion())
    return T;
  // On the edge outlines when both have them (the polygons alone differ by half a pixel all along a thin tool:
  // several percent of its area), resampled a few pixels apart.
  const bool dense = currentN.hasOutline() && goalN.hasOutline();
  const vpMorphContour cur = dense ? currentN.outline().resampled(kOverlapPoints) : currentN;
  const vpMorphContour goal = dense ? goalN.outline().resampled(kOverlapPoints) : goalN;
  // Decided once, at the first fit to the target: a bend belongs to the scene, not to one frame, and an outline
  // fit that is off for one period (a region 3 % out on an occluded key) must not switch the pose estimate.
  if (m_deformed == SHAPE_UNDECIDED) {
    auto outside = [&](const vpMorphRigidTransform &F) { return outsideShare(F, cur, goal); };
    m_deformed = outside(T) > kDeformedOutside ? DEFORMED : UNDEFORMED;
    // Regions found alike lay the view by their areas and centroids, which carry a part that a small occluder hides
    // (its moments barely change) into the pose: laid off by that much, an occluded view sticks out of its target.
    // If its outline, fitted robustly (the occluder's edge weighed out), lays it inside the target, it is occluded,
    // not bent: from then on its regions are not alike (measured: a wrench whose jaw a card bit, taken for a bent one
    // and scaled by its outline's length, which the cut had changed, ending 14.6 mm deep).
    if (m_deformed == DEFORMED && m_regionsAlike == ALIKE && dense) {
      const double halfPixel = normalisedPixels(0.5);
      const vpMorphRigidTransform To =
          vpMorphRigidTransform::refineOnOutline(currentN.outline(), goalN.outline(), T, true, 0.2 * halfPixel);
      if (outside(To) <= kDeformedOutside) {
        m_regionsAlike = NOT_ALIKE;
        m_deformed = UNDEFORMED;
        return To;
      }
    }
  }
  if (m_deformed != DEFORMED)
    return T;
  // The scale (the depth) from the outlines' lengths: a bend keeps them (to a few tenths of a percent where a
  // drawn bend stretches an edge), while it changes the area and drags an outline fit (measured on rendered
  // views of the deformed objects at their goal: length ratio 0.2-0.5 % off, area 0.7-5 %, fit 0.5-2.3 %).
  // Resampled every 3 pixels or so for the lengths: the pixel staircase does not count, small teeth do.
  // Replaced by the scale of the largest undeformed part (its edges lie on the template's: a bent key's bow) when one
  // is found, below.
  const double lengthScale = goalN.outline().resampled(2 * kOverlapPoints).perimeter() /
                             currentN.outline().resampled(2 * kOverlapPoints).perimeter();
  const double s = m_scaleBias * lengthScale;
  const vpMorphRigidTransform Ts(T.theta(), T.tx(), T.ty(), s, T.cx(), T.cy());
  // The offset between the largest overlap and the outline (or area) fit is a property of the two shapes: it
  // barely changes from one period to the next, so it warm-starts the search; the first time, starts over
  // +-10 deg on the polygons find the right basin.
  vpMorphRigidTransform start =
      m_overlapWarm ? m_overlapOffset * Ts
                    : vpMorphRigidTransform::fitOnOverlap(currentN, goalN, Ts, vpMath::rad(10.0), 5, 25);
  // The offset carries the error of the fit it was learnt from: when that fit turned by more than a period's step
  // since, one of the two was off, and the last placement, a period's motion away, is the better start if it leaves
  // less of the view outside (measured: a bent hammer's fit at its switch to the target 10 deg off, whose offset
  // put the next period's start 10 deg away, in another basin: a jump, re-planned, then stopped as unreliable).
  if (m_overlapWarm && std::fabs(std::remainder(Ts.theta() - m_overlapFitTheta, 2.0 * M_PI)) > kOverlapStartJump) {
    const vpMorphRigidTransform last(m_overlapLast.theta(), m_overlapLast.tx(), m_overlapLast.ty(), s,
                                     m_overlapLast.cx(), m_overlapLast.cy());
    if (outsideShare(last, cur, goal) < outsideShare(start, cur, goal))
      start = last;
  }
  // Then on the outlines, from within a fraction of a pixel: a short first step and a few rounds, the search
  // going on from there at the next period (a whole search from each start costs tens of milliseconds).
  const vpMorphRigidTransform Tovl =
      vpMorphRigidTransform::refineOnOverlap(cur, goal, start, m_overlapWarm ? 6 : 20, 0.002);
  m_overlapOffset = Tovl * Ts.inverse(); // scale 1: Tovl keeps Ts's
  m_overlapFitTheta = Ts.theta();
  m_overlapLast = Tovl;
  m_overlapWarm = true;
  m_overlapBased = true;
  // The scale of the largest undeformed part, when one is found: searched every kRigidPartPeriod periods (the whole
  // outline, milliseconds) and followed from one period to the next in between (from its last offset to the overlap
  // fit). It is measured each period because the lengths' scale is not steady enough to carry it: resampled at other
  // places on the pixel staircase, a key's outline changes its length by 0.5 % from one period to the next, which
  // moved a ratio measured once by as much (a key ending 2.2 mm deep).
  double scale = m_scaleBias * lengthScale;
  if (dense) {
    const bool search = m_rigidPartCount++ % kRigidPartPeriod == 0;
    if (search || m_partKnown) {
      const vpMorphContour curDense = currentN.outline().resampled(2 * kOverlapPoints);
      const double tolerance = normalisedPixels(kRigidPartTolerancePx);
      double share = 0.0;
      const vpMorphRigidTransform R =
          rigidPart(curDense, goalN.outline(), Tovl, search, m_partOffset, tolerance, share);
      m_partKnown = share >= kRigidPartMinShare && std::fabs(R.scale() / lengthScale - 1.0) < kBendLengthChange;
      if (m_partKnown) {
        m_partOffset = R * Tovl.inverse();
        m_scaleBias = R.scale() / lengthScale; // for the periods where the part is lost
        scale = R.scale();
      }
    }
  }
  const vpMorphRigidTransform Tres(Tovl.theta(), Tovl.tx(), Tovl.ty(), scale, Tovl.cx(), Tovl.cy());
  if (outsideShare(Tres, cur, goal) > kUnexplainedOutside)
    m_deformed = UNEXPLAINED;
  return Tres;
}

double vpServoMorph::bandCorrectedAreaRatio(const vpMorphContour &currentN, const vpMorphRigidTransform &T)
{
  const vpMorphContour targetN = m_target.toNormalized(m_cam);
  // A background clipped at the sensor's limit makes the edge pixels read too bright, so the region is measured short
  // of a band all round, which the area ratio takes for depth all the more as the object is thin (a pliers under gain
  // 1.28 measured 0.58 % small in area: 1.5 mm deep, noise seed 3). The band is the offset of the target's edges that
  // the current ones, fitted on them with a similarity from T, lie on (a twentieth of a pixel there), times the
  // target's perimeter. Why not the scale of that fit: it rests on the outline's ends, which a blur rounds off
  // (0.07 % under a 1.4 px blur), where an area keeps what a blur spreads. The band belongs to the scene (its
  // lighting, the edges' blur): fitted every kRigidPartPeriod periods (a fifth of a millisecond) and carried in
  // between. Not when the fit moves the outline by more than two pixels from T's (another basin): no band then.
  if (m_bandCount++ % kRigidPartPeriod == 0) {
    const double halfPixel = normalisedPixels(0.5);
    const vpMorphContour o = currentN.outline().resampled(2 * kOverlapPoints);
    const vpMorphContour &to = targetN.outline();
    double offset = 0.0;
    const vpMorphRigidTransform Te =
        vpMorphRigidTransform::refineOnOutline(o, to, T, true, 0.2 * halfPixel, 5, &offset);
    // The target's edges moved by offset along their left normals: inwards on a counter-clockwise outline.
    m_band = largestShift(T, Te, o) <= 4.0 * halfPixel
                 ? (to.isCounterClockwise() ? 1.0 : -1.0) * to.resampled(2 * kOverlapPoints).perimeter() * offset
                 : 0.0;
  }
  const double goalArea = targetN.regionArea() - m_band;
  return (goalArea > 0.0 ? goalArea : targetN.regionArea()) / currentN.regionArea();
}

vpMorphRigidTransform vpServoMorph::targetEdgeFit(const vpMorphContour &currentOutline,
                                                  const vpMorphContour &targetOutline,
                                                  const vpMorphRigidTransform &T) const
{
  // Five rounds from T: the fit has settled by then (ten gave the held-out runs the same outcomes, final errors
  // within 0.002 mm and iterations within 2, at twice the cost).
  return vpMorphRigidTransform::refineOnOutline(currentOutline, targetOutline, T, true, 0.2 * normalisedPixels(0.5), 5);
}

void vpServoMorph::residuals(const vpMorphRigidTransform &T, const vpMorphContour &currentPx)
{
  m_rotRes = std::fabs(T.theta());
  m_transRes = std::hypot(T.tx() * m_cam.get_px(), T.ty() * m_cam.get_py());
  m_scaleRel = std::fabs(T.scale() - 1.0);
  m_scaleRes = m_scaleRel * rmsRadius(currentPx);
}

vpHomogeneousMatrix vpServoMorph::cameraDisplacement(const vpMorphRigidTransform &T, double Z, double k) const
{
  // Image similarity x' = s R(theta) (x - c) + c + t of a plane parallel to the image at depth Z
  // <=> camera move cMc' = [Rz(-theta), (k Z (c - R(-theta)(c + t) / s), Z (1 - 1/s))].
  const double th = T.theta(), s = T.scale(), ct = std::cos(th), st = std::sin(th);
  const double qx = T.cx() + T.tx(), qy = T.cy() + T.ty();
  const double rx = ct * qx + st * qy, ry = -st * qx + ct * qy;
  const double tx = k * Z * (T.cx() - rx / s), ty = k * Z * (T.cy() - ry / s), tz = Z * (1.0 - 1.0 / s);
  return vpHomogeneousMatrix(tx, ty, tz, 0, 0, -th);
}

vpColVector vpServoMorph::jointEnd(const vpMatrix &eJeInv, const vpVelocityTwistMatrix &eVc,
                                   const vpHomogeneousMatrix &cMcp, double turn) const
{
  vpColVector xi(6, 0.0); // the plan's camera displacement as a twist: translation d, turn -turn about z
  for (unsigned int i = 0; i < 3; ++i)
    xi[i] = cMcp[i][3];
  xi[5] = -turn;
  return m_q + eJeInv * (eVc * xi);
}

bool vpServoMorph::nearJointLimit(const vpColVector &q) const
{
  for (unsigned int i = 0; i < q.size(); ++i) {
    const double margin = jointMargin() * (m_qMax[i] - m_qMin[i]);
    if (std::isfinite(margin) && (q[i] < m_qMin[i] + margin || q[i] > m_qMax[i] - margin))
      return true;
  }
  return false;
}

void vpServoMorph::record()
{
  Iteration it;
  it.iteration = m_iter;
  it.subGoal = m_k;
  it.status = m_status;
  it.rotationResidual = m_rotRes;
  it.translationResidual = m_transRes;
  it.scaleResidual = m_scaleRes;
  it.work = m_work;
  it.fullMatch = m_fullMatch;
  it.areaBased = m_areaBased;
  it.overlapBased = m_overlapBased;
  it.eMc = m_estimator.get_eMc();
  it.translationScale = m_estimator.translationScale();
  it.ve = m_ve;
  it.tiltResidual = m_tiltRes;
  m_history.push_back(it);
}

vpColVector vpServoMorph::computeControlLaw(const vpMorphContour &current)
{
  if (m_target.empty())
    throw vpMorphException(vpMorphException::badParameterError,
                           "vpServoMorph::computeControlLaw: no target; call setTarget() first");
  ++m_iter;
  m_current = vpMorphContour();
  if (m_halted) // a stop status stays until restart()
    return stop(m_status);
  if (current.empty()) {
    // Hold: nothing seen this period (dropped frame, object absent). The sequence and the last fit are kept.
    if (++m_lost > m_maxLost) {
      m_halted = true;
      return stop(LOST_TOO_LONG);
    }
    return stop(TARGET_LOST);
  }
  m_lost = 0;
  if (current.units() != vpMorphContour::PIXEL)
    throw vpMorphException(vpMorphException::badParameterError,
                           "vpServoMorph::computeControlLaw: the current contour must be in pixels");
  m_current = current;
  const double a = current.area();
  if (!std::isfinite(a) || a < m_minArea)
    return stop(DEGENERATE_CONTOUR);
  try {
    if (!m_started) {
      if (m_template.isArticulated())
        poseArticulatedTarget(current);
      vpColVector v;
      if (!planAgain(current, false, v))
        return v;
    }
    const vpMorphContour currentN = current.toNormalized(m_cam);
    if (m_explorePhase == EXPLORE_OUT || m_explorePhase == EXPLORE_BACK) {
      vpColVector ve;
      if (exploreStep(current, currentN, ve)) {
        m_status = MOVING;
        m_ve = ve;
        m_vc = vpVelocityTwistMatrix(m_estimator.get_eMc().inverse()) * ve;
        return m_ve;
      }
      // Back where it started (with eMc corrected), or where a jump left it: plan again; a jump is a re-plan.
      const bool jumped = m_explorePhase == EXPLORE_JUMPED;
      m_explorePhase = EXPLORE_DONE;
      vpColVector v;
      if (!planAgain(current, jumped, v))
        return v;
    }
    const double Z = m_Zd * std::sqrt(areaRatio(m_target, current));
    vpMorphRigidTransform T = fitToSubGoal(currentN, current, Z);
    // A distance jump or a low margin alone is not a wrong correspondence: a real contour gains or loses a vertex
    // from one image to the next, which changes the work and the margin while the fit does not. Unreliable is
    // either of them together with a jump of the fitted rotation beyond what one step (gain x previous residual)
    // and noise explain; with no previous fit to the same sub-goal, a low margin alone.
    const bool consistent = m_haveWork && rotationConsistent(T);
    if (m_fullMatch && m_margin < m_minMargin && !consistent) {
      return stop(UNRELIABLE_CORRESPONDENCE);
    }
    const bool workJump = m_haveWork && m_work > m_jumpFactor * m_prevWork + m_workFloor;
    if (workJump && !consistent) {
      // Both jumped: another shape (an occluder, another object), or the same one re-digitised at a new place.
      // With a database, the distance from the last contour tells them apart (D_morph ignores the place);
      // without one, stop.
      const bool sameShape =
          !m_checkDb.empty() && !m_prevContour.empty() &&
          m_checkDb.distance().distance(current, m_prevContour) <= m_shapeChange * m_checkDb.threshold(m_checkIndex);
      if (!sameShape)
        return stop(UNRELIABLE_CORRESPONDENCE);
    }
    if (m_haveWork && viewJumped(T)) {
      // The view jumped (the robot or the object was displaced, with the target check: whatever the work did).
      // Re-plan from this view (the sub-goals of the old plan lead from where the camera no longer is), bounded;
      // the target check at the new start stops on another shape; no calibration observation across the jump.
      vpColVector v;
      planAgain(current, true, v);
      return v;
    }

    // Online calibration: the image motion since the anchor (a fit to the same sub-goal) against the moves
    // commanded since then, once it is large enough for the contour noise not to bias the estimate.
    if (m_online && m_haveMove) {
      m_accCmd = m_accCmd * m_prevCmd;
      const vpMorphRigidTransform Tobs = T.inverse() * m_anchorT; // anchor contour -> current contour
      const double px = std::hypot(Tobs.tx() * m_cam.get_px(), Tobs.ty() * m_cam.get_py());
      if (std::fabs(Tobs.theta()) >= m_calibRotation || px >= m_calibPx) {
        m_estimator.addMove(m_accCmd, cameraDisplacement(Tobs, m_anchorZ, 1.0));
        m_haveMove = false; // re-anchored below
      }
    }

    m_status = MOVING;
    const std::size_t last = m_subGoals.size() - 1;
    while (m_k < last && m_rotRes < m_rotThr && m_transRes < m_pxThr && m_scaleRes < m_pxThr) {
      ++m_k;
      m_haveWork = false;
      m_haveMove = false; // fits to another sub-goal: re-anchor the calibration
      m_status = SUBGOAL_REACHED;
      T = fitToSubGoal(currentN, current, Z, true);
    }
    if (m_deformed == UNEXPLAINED) { // see overlapFit(): no pose to servo to, and no depth
      m_halted = true;
      return stop(DEFORMATION_UNRESOLVED);
    }
    // Out-of-plane part from the homography to the target (zero displacement when off or not estimated).
    vpHomogeneousMatrix cMct;
    double Zp = Z;
    const bool tilt = estimateTilt(currentN, cMct, Zp);
    if (m_k == last && m_rotRes < m_rotFine && m_transRes < m_pxFine && m_scaleRes < m_pxFine &&
        (m_scaleFine == 0.0 || m_scaleRel < m_scaleFine) &&
        (!tilt || m_tiltRes <= std::max(m_tiltFine, m_tiltDeadZoneUsed))) {
      m_prevWork = m_work;
      m_haveWork = true;
      if (targetMismatch(current)) { // aligned, but not the target's shape: never report CONVERGED on it
        m_halted = true;
        return stop(TARGET_MISMATCH);
      }
      return stop(CONVERGED);
    }

    const vpHomogeneousMatrix eMc = m_estimator.get_eMc();
    const double k = m_estimator.translationScale();
    vpColVector ve;
    if (m_law == HOMOGENEOUS_TRANSFORMS) {
      const vpHomogeneousMatrix eMe = eMc * cameraDisplacement(T, tilt ? Zp : Z, k) * eMc.inverse(); // Eq. 11
      ve = m_gain * vpExponentialMap::inverse(eMe, m_dt);
    } else {
      vpColVector vc = m_stockVc; // computed with the fit to the current sub-goal
      vc[0] *= k;
      vc[1] *= k;
      ve = vpVelocityTwistMatrix(eMc) * vc;
    }
    // The hand-eye estimator sees the planar part only: the tilt orbit leaves the image similarity unchanged.
    const vpColVector vePlanar = ve;
    if (tilt)
      ve += m_gain * (vpVelocityTwistMatrix(eMc) * vpExponentialMap::inverse(cMct, m_dt));
    if (!allFinite(ve))
      return stop(DEGENERATE_CONTOUR);
    m_ve = ve;
    m_vc = vpVelocityTwistMatrix(eMc.inverse()) * ve;
    m_prevCmd = vpExponentialMap::direct(vePlanar, m_dt);
    if (!m_haveMove) { // new anchor for the calibration
      m_anchorT = T;
      m_anchorZ = Z;
      m_accCmd.eye();
    }
    m_prevT = T;
    m_fittedInSequence = true;
    m_prevContour = current;
    m_prevWork = m_work;
    m_haveWork = true;
    // A tilt orbit executed through a wrong eMc moves the image in ways the planar calibration model cannot tell
    // from a planar error: no calibration observation spans a tilt command (re-anchored at the next iteration).
    m_haveMove = !(tilt && m_tiltRes > m_tiltDeadZoneUsed);
    record();
    return m_ve;
  } catch (const vpException &) {
    // A contour the morph cannot use (e.g. it collapsed): stop rather than throw from inside a control loop.
    return stop(DEGENERATE_CONTOUR);
  }
}

// ---------------------------------------------------------------------------------------------------------------
// Out-of-plane (tilt) correction: the homography from the current contour to the target.

void vpServoMorph::setTiltCorrection(TiltCorrection mode)
{
  m_tiltMode = mode;
  restart();
}

void vpServoMorph::setFinalTiltThreshold(double rad)
{
  checkPositive(rad, "the final tilt threshold");
  m_tiltFine = rad;
}

void vpServoMorph::setTiltDeadZone(double rad)
{
  checkNonNegative(rad, "the tilt dead zone");
  m_tiltDeadZone = rad;
}

void vpServoMorph::setOutlineTiltDeadZone(double rad)
{
  checkNonNegative(rad, "the outline tilt dead zone");
  m_outlineTiltDeadZone = rad;
}

bool vpServoMorph::tiltActive() const
{
  return m_tiltMode == TILT_ALWAYS || (m_tiltMode == TILT_FINAL_APPROACH && m_k + 1 == m_subGoals.size());
}

/*
  The final approach's tilt from this period's outline estimate (angle, axis (ax, ay) of norm sa = sin(angle), the
  homography's covariance C) and the recent periods': replaces them by the fused ones, and measures how much the
  periods scatter beyond their covariances (m_tiltKappa). Why: a thin object's tilt about its long axis jumps by twice
  its reported deviation from one view to the next (measured: pliers at rest, estimates of -1.2..+1.4 deg, deviation
  0.33 deg), and each jump beyond the dead zone was commanded: planar starts ended 0.3-0.46 deg off. The mean only
  smooths the estimate; it does not narrow the dead zone (see estimateTilt()).
*/
void vpServoMorph::fuseTilt(const vpMatrix &C, double &angle, double &ax, double &ay, double &sa)
{
  // This period's tilt as a rotation vector e (angle along the axis) and its covariance. The perspective part
  // (d6, d7) of the homography is the plane normal's (n0, n1) near the goal, and e = (-n1, n0).
  TiltSample cur;
  tiltVector(angle, ax, ay, sa, cur.ex, cur.ey);
  cur.c00 = C[7][7];
  cur.c01 = -C[6][7];
  cur.c11 = C[6][6];
  cur.sx = m_tiltSumX;
  cur.sy = m_tiltSumY;
  cur.deadZone = m_tiltDeadZoneUsed;
  // An earlier period stands for the tilt now once the commands executed since are taken off, while they are smaller
  // than its dead zone (an execution off by a few percent then moves it by a few percent of its noise).
  m_tiltWindow.erase(
      std::remove_if(m_tiltWindow.begin(), m_tiltWindow.end(),
                     [&](const TiltSample &s) { return !(std::hypot(cur.sx - s.sx, cur.sy - s.sy) <= s.deadZone); }),
      m_tiltWindow.end());
  m_tiltWindow.push_back(cur);
  if (m_tiltWindow.size() > kTiltWindow)
    m_tiltWindow.erase(m_tiltWindow.begin(), m_tiltWindow.end() - static_cast<std::ptrdiff_t>(kTiltWindow));

  // Information-weighted mean.
  double i00 = 0, i01 = 0, i11 = 0, b0 = 0, b1 = 0;
  std::vector<std::array<double, 5>> info; // e (compensated), information matrix
  for (const TiltSample &s : m_tiltWindow) {
    const double det = s.c00 * s.c11 - s.c01 * s.c01;
    if (!(det > 0.0))
      continue;
    const double j00 = s.c11 / det, j01 = -s.c01 / det, j11 = s.c00 / det;
    const double ex = s.ex - (cur.sx - s.sx), ey = s.ey - (cur.sy - s.sy);
    info.push_back({ex, ey, j00, j01, j11});
    i00 += j00;
    i01 += j01;
    i11 += j11;
    b0 += j00 * ex + j01 * ey;
    b1 += j01 * ex + j11 * ey;
  }
  const double det = i00 * i11 - i01 * i01;
  if (info.empty() || !(det > 0.0))
    return; // no covariance: this period's estimate and dead zone as they are
  const double mx = (i11 * b0 - i01 * b1) / det, my = (-i01 * b0 + i00 * b1) / det;
  // The outlines' covariance counts only the noise that a fit's residuals show; what changes from one view to the
  // next (the pixel grid's phase under the edges) is not in it. The scatter of the periods about their mean measures
  // it: the covariance is scaled by their reduced chi-square (kept from the last window of three or more).
  if (info.size() >= 3) {
    double chi2 = 0.0;
    for (const auto &q : info) {
      const double dx = q[0] - mx, dy = q[1] - my;
      chi2 += q[2] * dx * dx + 2.0 * q[3] * dx * dy + q[4] * dy * dy;
    }
    m_tiltKappa = std::max(1.0, chi2 / (2.0 * double(info.size() - 1)));
  }
  const double fused = std::hypot(mx, my);
  angle = fused;
  sa = std::sin(angle);
  ax = angle > 0.0 ? sa * mx / angle : 0.0;
  ay = angle > 0.0 ? sa * my / angle : 0.0;
}

/*
  cMct: the camera displacement that turns the optical axis onto the plane normal about the plane point P seen at the
  current centroid (so that the object stays where it is in the image), and Zp the depth of P, from the homography
  current -> target decomposed with the target's plane (fronto-parallel at Zd). False (identity, Zp unchanged) when
  the correction is off on this sub-goal or the homography is not usable: the planar law then runs alone.
*/
bool vpServoMorph::estimateTilt(const vpMorphContour &currentN, vpHomogeneousMatrix &cMct, double &Zp)
{
  m_tiltOk = false;
  m_tiltRes = 0;
  m_cMcdH.eye();
  cMct.eye();
  // A target measured on its image, a current contour not (vpMorphContourExtractor::extractJoined() bridged pieces
  // an occluder cut: part of that outline was never seen): no perspective to read in it.
  if (!tiltActive() || m_tiltLatched || (m_target.hasRegion() && !currentN.hasRegion()))
    return false;
  // After kTiltRetryPeriod misses in a row and no fit yet, one try every kTiltRetryPeriod periods: the planar law
  // runs alone in between, as it does after a miss.
  if (!m_tiltFitted && m_tiltMisses >= kTiltRetryPeriod && m_tiltMisses++ % kTiltRetryPeriod != 0)
    return false;
  const bool ok = fitTilt(currentN, cMct, Zp);
  m_tiltFitted = m_tiltFitted || ok;
  if (!ok && m_tiltMisses < kTiltRetryPeriod)
    ++m_tiltMisses;
  return ok;
}

bool vpServoMorph::fitTilt(const vpMorphContour &currentN, vpHomogeneousMatrix &cMct, double &Zp)
{
  try {
    const vpMorphContour targetN = m_target.toNormalized(m_cam);
    const bool dense = currentN.hasOutline() && targetN.hasOutline();
    // Regions not alike (see start()): a tilted view, or a part hidden or bent. Only a homography that explains the
    // whole outline tells the first: an occluder's edge or a bent limb fitted away by the robust weights still
    // pulls the perspective part (measured: an occluded hammer ending 7.9 deg off).
    const bool notAlike = m_regionsAlike == NOT_ALIKE;
    const double minInliers = notAlike ? kNotAlikeMinInliers : 0.0;
    const double maxResidualPx = notAlike ? kNotAlikeMaxResidualPx : kOutlineMaxResidualPx;
    // Outlines: from the previous period's homography (the camera moved by a fraction of its error since), which
    // follows the view smoothly and saves the polygons' correspondence and fit; from the polygons otherwise.
    const bool warm = m_tiltWarm; // outlineHomography() starts from it on outlines only
    m_tiltWarm = false;
    vpMorphHomography G;
    if (!outlineHomography(currentN, targetN, warm ? &m_tiltG : nullptr, minInliers,
                           std::max(kOutlineMinInliers, minInliers), maxResidualPx, G))
      return false;
    m_tiltDeadZoneUsed = m_tiltDeadZone;
    // A homography that explains the whole outline (a fit held to kNotAlikeMinInliers) shows a rigid, unhidden object
    // seen in perspective: the regions were not alike because of the tilt. Once it is corrected enough for the
    // measured regions to compare alike again, the verdicts made on the tilted view are withdrawn (once per sequence:
    // no chatter): areas and centroids stand for the pose again, and the view is not taken for a bent one.
    if (m_regionsAlike == NOT_ALIKE && !m_regionsRejudged && targetN.hasRegion() && currentN.hasRegion() &&
        vpMorphRegionCheck::alike(targetN, currentN, 1.0, m_regionMismatch)) {
      m_regionsRejudged = true;
      m_regionsAlike = ALIKE;
      forgetDeformation();
    }
    if (dense) {
      m_tiltG = G;
      m_tiltWarm = true;
      // The tilt's uncertainty: the largest standard deviation of the perspective part (d6, d7 of the covariance,
      // radians of tilt near the goal). Noise, blur, or a thin object (whose tilt about its long axis barely
      // changes its outline) widen it. Kept with this period's estimate in fuseTilt(); what is commanded is decided
      // per axis below.
      const vpMatrix &C = G.covariance();
      const double sd = largestDeviation(C[6][6], C[6][7], C[7][7]);
      m_tiltDeadZoneUsed = std::max(m_outlineTiltDeadZone, kTiltSigmas * sd);
    }
    const vpHomogeneousMatrix cMcd = G.inputMtarget(m_Zd);
    const vpColVector n = cMcd.getRotationMatrix().getCol(2); // plane normal in the current camera frame
    const vpTranslationVector t = cMcd.getTranslationVector();
    const double dc = m_Zd + n[0] * t[0] + n[1] * t[1] + n[2] * t[2]; // distance of the camera to the plane
    double cx, cy;
    currentN.regionCentroid(cx, cy);
    const double nr = n[0] * cx + n[1] * cy + n[2];
    if (!(dc > 0.0) || !(nr > 1e-3))
      return false;
    const double lambda = dc / nr; // depth of P
    const vpColVector P = vpColVector({lambda * cx, lambda * cy, lambda});
    double angle = std::acos(std::max(-1.0, std::min(1.0, n[2])));
    double ax = -n[1], ay = n[0], sa = std::hypot(ax, ay); // the tilt's axis (in the image plane), |.| = sin(angle)
    const bool final = m_k + 1 == m_subGoals.size();
    double tx = 0.0, ty = 0.0; // the tilt commanded, as a rotation vector (its gain() share is executed)
    if (dense) {
      const vpMatrix &C = G.covariance();
      double ex, ey, mx, my; // this period's estimate, and the one commanded from (the average on the final approach)
      tiltVector(angle, ax, ay, sa, ex, ey);
      if (final)
        fuseTilt(C, angle, ax, ay, sa);
      // The dead zone is one period's deviation (scaled by the periods' scatter), not the mean's: near the goal the
      // camera barely moves, consecutive views share their pixel phase, and their errors do not average out (the
      // pliers' mean stayed 0.5-0.8 deg off along their long axis over 40 periods, at a deviation of 0.33 deg).
      const double kappa = final ? m_tiltKappa : 1.0;
      tiltVector(angle, ax, ay, sa, mx, my);
      tiltBeyondDeadZone(mx, my, ex, ey, kappa * C[7][7], -kappa * C[6][7], kappa * C[6][6], m_outlineTiltDeadZone,
                         kTiltSigmas, tx, ty);
      // As one number along the estimate (the convergence test and the calibration's compare the tilt left to it).
      const double c = std::hypot(tx, ty);
      m_tiltDeadZoneUsed = c > 0.0 ? std::max(0.0, angle - c) : std::max(angle, m_tiltDeadZoneUsed);
    }
    if (!dense && m_tiltDeadZoneUsed > 0.0 && angle <= m_tiltDeadZoneUsed && final) {
      // Within the dead zone on the final approach: what polygons show below it is the polygonisation, and
      // following it would random-walk the camera; the planar law finishes alone (latched until restart()).
      // Outlines are not latched: their estimate, still read, commands nothing within the dead zone, but a tilt
      // the planar moves bring back (through a wrong eMc) or a dead zone that narrows as the view settles is
      // corrected again.
      m_tiltLatched = true;
      m_tiltRes = angle;
      return false;
    }
    // Only the part beyond the dead zone is commanded: below it the estimate is not trusted (see setTiltDeadZone()).
    if (!dense && sa > 1e-12) {
      const double cmd = std::max(0.0, angle - m_tiltDeadZoneUsed);
      tx = cmd * ax / sa;
      ty = cmd * ay / sa;
    }
    const double cmd = std::hypot(tx, ty);
    // An estimate that its own commands do not bring down is not the view's tilt: once half a dead zone has been
    // executed towards it, an estimate along that way still at least the first commanded one, three periods in a
    // row, latches the correction off (measured: a thin pliers whose tilt about its long axis the outlines barely
    // show, the estimate 0.7-1.5 deg while the camera, turned by it, went from 0.1 to 0.54 deg off).
    if (sa > 1e-12 && final) {
      double ex, ey;
      tiltVector(angle, ax, ay, sa, ex, ey);
      const double done = std::hypot(m_tiltSumX, m_tiltSumY);
      if (done == 0.0) {
        m_tiltRefX = ex;
        m_tiltRefY = ey;
      } else if (done >= 0.5 * m_tiltDeadZoneUsed) {
        const double ux = m_tiltSumX / done, uy = m_tiltSumY / done;
        m_tiltNoProgress = ex * ux + ey * uy >= m_tiltRefX * ux + m_tiltRefY * uy ? m_tiltNoProgress + 1 : 0;
        if (m_tiltNoProgress >= 3) {
          m_tiltLatched = true;
          m_tiltRes = angle;
          return false;
        }
      }
      if (cmd > 0.0) { // executed as a gain() share of it per period
        m_tiltSumX += m_gain * tx;
        m_tiltSumY += m_gain * ty;
      }
    }
    vpRotationMatrix Rt; // identity when already aligned
    if (cmd > 0.0)
      Rt = vpRotationMatrix(vpThetaUVector(tx, ty, 0.0));
    const vpColVector RP = vpMatrix(Rt) * P;
    const vpTranslationVector tt(P[0] - RP[0], P[1] - RP[1], P[2] - RP[2]);
    cMct = vpHomogeneousMatrix(tt, Rt);
    if (!std::isfinite(lambda) || !std::isfinite(angle) || !std::isfinite(tt[0]) || !std::isfinite(tt[1]) ||
        !std::isfinite(tt[2])) {
      cMct.eye();
      return false;
    }
    m_cMcdH = cMcd;
    m_tiltRes = angle;
    m_tiltOk = true;
    Zp = lambda;
    return true;
  } catch (const vpException &) {
    cMct.eye();
    return false;
  }
}

bool vpServoMorph::outlineHomography(const vpMorphContour &currentN, const vpMorphContour &targetN,
                                     const vpMorphHomography *warm, double polygonMinInliers, double minInliers,
                                     double maxResidualPx, vpMorphHomography &G)
{
  const double pixel = normalisedPixels(1.0);
  const bool dense = currentN.hasOutline() && targetN.hasOutline();
  // Measured edges of one plane's outline meet within hundredths of a pixel (tenths under noise): a fit on them
  // that leaves a tenth out, or half a pixel RMS, is of an outline that changed (bent, partly hidden).
  auto denseFit = [&](const vpMorphHomography &start, unsigned int iterations) {
    G = vpMorphHomography::refine(currentN.outline(), targetN.outline(), start, 0.1 * pixel, 400, iterations);
    return G.inlierShare() >= minInliers && G.residual() <= maxResidualPx * pixel;
  };
  if (dense && warm) {
    try {
      if (denseFit(*warm, 6))
        return true;
    } catch (const vpException &) {
      // from the polygons, below
    }
  }
  const vpMorphCorrespondence &corr = m_tiltTracker.update(currentN, targetN);
  G = vpMorphHomography::fit(currentN, targetN, corr, 0.5 * pixel, 120, 12);
  // A wrong correspondence ends in a local minimum that leaves much of the outline unexplained: ignore it.
  if (G.inlierShare() < std::max(m_tiltMinInliers, polygonMinInliers) || G.residual() > m_tiltMaxResidualPx * pixel)
    return false;
  // Refined on the measured edges: tenths of a pixel -> hundredths.
  return !dense || denseFit(vpMorphHomography(G), 8);
}

// ---------------------------------------------------------------------------------------------------------------
// Hand-eye tilt exploration.

void vpServoMorph::setHandEyeTiltExploration(double rad, unsigned int imageWidth, unsigned int imageHeight)
{
  if (!std::isfinite(rad) || rad < 0.0 || rad > M_PI) {
    std::ostringstream os;
    os << "vpServoMorph::setHandEyeTiltExploration: the turn must be in [0, pi] rad, got " << rad;
    throw vpMorphException(vpMorphException::badParameterError, os.str());
  }
  if (rad > 0.0 && (imageWidth == 0 || imageHeight == 0))
    throw vpMorphException(vpMorphException::badParameterError,
                           "vpServoMorph::setHandEyeTiltExploration: the image's size is needed (0 given)");
  m_imageWidth = imageWidth;
  m_imageHeight = imageHeight;
  m_exploreAngle = rad;
  restart();
}

bool vpServoMorph::readTilt(const vpMorphContour &currentN, TiltReading &r)
{
  try {
    const vpMorphContour targetN = m_target.toNormalized(m_cam);
    if (!currentN.hasOutline() || !targetN.hasOutline() || !currentN.hasRegion())
      return false;
    // From the last reading's homography turned by the turn commanded since (a turn about the optical axis maps the
    // normalised image by that rotation): the readings follow the view as fitTilt()'s do, at a fraction of the cost.
    const bool warm = m_readWarm;
    m_readWarm = false;
    if (warm)
      m_readG = vpMorphHomography(m_readG.matrix() *
                                  vpMorphRigidTransform(m_exploreTheta - m_readTheta, 0, 0, 1, 0, 0).toMatrix());
    vpMorphHomography G;
    if (!outlineHomography(currentN, targetN, warm ? &m_readG : nullptr, 0.0, kNotAlikeMinInliers,
                           kOutlineMaxResidualPx, G))
      return false;
    m_readG = G;
    m_readTheta = m_exploreTheta;
    m_readWarm = true;
    const vpColVector n = G.inputMtarget(m_Zd).getRotationMatrix().getCol(2);
    const vpMatrix &C = G.covariance();
    r.nx = n[0];
    r.ny = n[1];
    r.c00 = C[6][6];
    r.c01 = C[6][7];
    r.c11 = C[7][7];
    r.theta = m_exploreTheta;
    return std::isfinite(r.nx) && std::isfinite(r.ny) && r.c00 > 0.0 && r.c00 * r.c11 - r.c01 * r.c01 > 0.0;
  } catch (const vpException &) {
    return false;
  }
}

bool vpServoMorph::exploreStep(const vpMorphContour &current, const vpMorphContour &currentN, vpColVector &ve)
{
  // The view turns by the commanded angle about the principal point and drifts by up to kExploreDriftPx a period (the
  // tilt the turn makes, the centre's offset), its area kept. A view that is not so is not read, nor is its border
  // looked at: another region taken for the object (the tag half out of the image, unmasked, joined to it), an
  // occluder come. Off that way with its area kept for kExploreJumps periods, the robot or the object was displaced:
  // the turn ends there, uncorrected (its readings would be another view's, and the way back would not lead back).
  double cx, cy;
  current.centroid(cx, cy);
  const double area = current.area();
  // Near the border it does not start, and turns back (whatever the view: a region joined to the object is no reason
  // to turn it out of the image); on the way back, the way out's border is not reached again unless the view moved
  // otherwise: it stops there.
  double border = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < current.size(); ++k)
    border = std::min(
        {border, current.x(k), current.y(k), m_imageWidth - 1.0 - current.x(k), m_imageHeight - 1.0 - current.y(k)});
  // A turn that the joints cannot make (their limits, with the Jacobian of the start) is not started: the Afma6's
  // wrist has about 100 deg either way, which the turn to the goal may need.
  if (m_exploreCount == 0 && m_explorePass == 0 && m_q.size() > 0) {
    vpColVector xi(6, 0.0);
    xi[5] = m_exploreAngle;
    const vpColVector qEnd = m_q + m_eJe.pseudoInverse() * (vpVelocityTwistMatrix(m_estimator.get_eMc()) * xi);
    for (unsigned int i = 0; i < qEnd.size() && i < m_qMin.size(); ++i)
      if (!(qEnd[i] >= m_qMin[i] && qEnd[i] <= m_qMax[i])) {
        m_explorePhase = EXPLORE_DONE;
        return false;
      }
  }
  const bool comingBack = m_explorePhase == EXPLORE_BACK;
  if (border < kExploreBorderPx && m_explorePhase == EXPLORE_OUT && m_exploreTheta > 0.0)
    m_explorePhase = EXPLORE_BACK;
  if (m_exploreCount > 0) {
    const double u0 = m_cam.get_u0(), v0 = m_cam.get_v0(), c = std::cos(m_exploreTurned), s = std::sin(m_exploreTurned);
    const double px = u0 + c * (m_exploreCx - u0) + s * (m_exploreCy - v0);
    const double py = v0 - s * (m_exploreCx - u0) + c * (m_exploreCy - v0);
    const bool areaKept = std::fabs(area / m_exploreArea - 1.0) < kExploreAreaChange;
    const bool onTheWay =
        std::hypot(cx - px, cy - py) <= m_jumpPx + kExploreDriftPx * std::max(0.0, m_exploreSince - 1.0);
    if (!areaKept || !onTheWay) {
      m_exploreJumps = areaKept ? m_exploreJumps + 1 : 0;
      if (m_exploreJumps >= kExploreJumps) {
        m_explorePhase = EXPLORE_JUMPED;
        return false;
      }
      return exploreCommand(ve);
    }
  }
  m_exploreJumps = 0;
  m_exploreSince = 0;
  m_exploreCx = cx;
  m_exploreCy = cy;
  m_exploreArea = area;
  m_exploreTurned = 0.0;
  if (border < kExploreBorderPx && (m_exploreTheta == 0.0 || comingBack)) {
    m_explorePhase = EXPLORE_DONE;
    return false;
  }
  TiltReading r;
  if (readTilt(currentN, r))
    m_exploreReadings.push_back(r);
  // A view whose tilt cannot be read (bent, partly hidden): back at once, nothing to learn. Such a view is unread from
  // its start (seed 2's 114 camera turns of six sets: none whose first two views were unread read enough later): its
  // first two views unread, or fewer than half read by kExploreProbe.
  const bool unread = m_exploreReadings.empty() && m_exploreCount >= 1;
  if (m_explorePhase == EXPLORE_OUT &&
      (unread || (std::fabs(m_exploreTheta) >= kExploreProbe && 2 * m_exploreReadings.size() < m_exploreCount))) {
    m_exploreReadings.clear();
    m_explorePhase = EXPLORE_BACK;
  }
  return exploreCommand(ve);
}

bool vpServoMorph::exploreCommand(vpColVector &ve)
{
  ++m_exploreCount;
  const double step = kExploreSpeed * m_dt;
  double w = 0.0;
  if (m_explorePhase == EXPLORE_OUT) {
    w = std::min(step, m_exploreAngle - m_exploreTheta);
    if (m_exploreTheta + w >= m_exploreAngle - 1e-12)
      m_explorePhase = EXPLORE_BACK;
  } else if (m_exploreTheta > 1e-12) {
    w = -std::min(step, m_exploreTheta);
  } else {
    // Back where it started. The correction is the tilt seen through the intrinsics, off by their error (a fifth,
    // on the bench): a second turn through the corrected eMc reads what is left.
    const double corrected = finishExploration();
    if (!(corrected > kExploreRepeat) || ++m_explorePass >= kExplorePasses)
      return false;
    m_explorePhase = EXPLORE_OUT;
    m_exploreReadings.clear();
    m_exploreCount = 0;
    w = step;
  }
  m_exploreTheta += w;
  m_exploreTurned += w;
  ++m_exploreSince;
  vpColVector vc(6, 0.0);
  vc[5] = w / m_dt;
  ve = vpVelocityTwistMatrix(m_estimator.get_eMc()) * vc;
  return true;
}

double vpServoMorph::finishExploration()
{
  m_explorePhase = EXPLORE_DONE;
  // The plane normal seen after a turn theta about the true axis z + a (a small, in the image plane) from a start
  // where it was z + n0: z + a + Rot(-theta) (n0 - a), to first order. Its image-plane part is read at each period
  // with the homography's covariance; a and g = n0 - a are its weighted least squares, the chi-square scaling the
  // covariance for the scatter the homographies do not show.
  Eigen::Matrix4d A = Eigen::Matrix4d::Zero();
  Eigen::Vector4d b = Eigen::Vector4d::Zero();
  std::vector<std::pair<Eigen::Matrix<double, 2, 4>, Eigen::Matrix2d>> rows;
  for (const TiltReading &r : m_exploreReadings) {
    Eigen::Matrix2d C;
    C << r.c00, r.c01, r.c01, r.c11;
    const Eigen::Matrix2d J = C.inverse();
    const double c = std::cos(r.theta), s = std::sin(r.theta);
    Eigen::Matrix<double, 2, 4> M;
    M << 1, 0, c, s, 0, 1, -s, c;
    A += M.transpose() * J * M;
    b += M.transpose() * J * Eigen::Vector2d(r.nx, r.ny);
    rows.emplace_back(M, J);
  }
  if (m_exploreReadings.size() < 8)
    return 0.0;
  Eigen::LDLT<Eigen::Matrix4d> ldlt(A);
  const Eigen::Vector4d x = ldlt.solve(b);
  double chi2 = 0.0;
  for (std::size_t k = 0; k < m_exploreReadings.size(); ++k) {
    const Eigen::Vector2d e = rows[k].first * x - Eigen::Vector2d(m_exploreReadings[k].nx, m_exploreReadings[k].ny);
    chi2 += e.transpose() * rows[k].second * e;
  }
  const double kappa = std::max(1.0, chi2 / (2.0 * m_exploreReadings.size() - 4.0));
  const Eigen::Matrix4d cov = kappa * A.inverse();
  const double sdA = std::sqrt(std::max(cov(0, 0), cov(1, 1)));
  // Applied when it stands out of the readings' scatter and, at the first turn, is a tilt the final approach could
  // not be sure to take back on a thin object: below kExploreMinTilt, an estimate off by its deviation (which the
  // readings' correlated errors make a few times what they show) would tilt a camera that is mounted right. The
  // second turn, after a correction, reads what the intrinsics' error left of it.
  const double tilt = std::hypot(x[0], x[1]);
  if (!x.allFinite() || !(sdA < kExploreMaxDeviation) || (m_explorePass == 0 && tilt < kExploreMinTilt) ||
      tilt < kExploreSigmas * sdA)
    return 0.0;
  // The commanded turn's axis, seen in the true camera, is z + a: turning eMc by the rotation that takes z to z - a
  // makes it the optical axis.
  const vpHomogeneousMatrix Q(0, 0, 0, x[1], -x[0], 0);
  m_estimator.reset(m_estimator.get_eMc() * Q);
  m_exploredTilt = vpThetaUVector(vpRotationMatrix(m_exploredTilt) * Q.getRotationMatrix());
  return tilt;
}
