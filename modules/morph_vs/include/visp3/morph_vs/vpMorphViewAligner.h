/*!
  \file vpMorphViewAligner.h
  \brief The one measurement of the morph servo: the similarity from the current view to a goal view.
*/
#ifndef VP_MORPH_VIEW_ALIGNER_H
#define VP_MORPH_VIEW_ALIGNER_H

#include <algorithm>
#include <map>

#include <visp3/core/vpCameraParameters.h>
#include <visp3/morph/vpMorphContour.h>
#include <visp3/morph/vpMorphHomography.h>
#include <visp3/morph/vpMorphOutlineFit.h>
#include <visp3/morph/vpMorphRigidTransform.h>
#include <visp3/morph_vs/vpMorphCorrespondenceTracker.h>
#include <visp3/morph_vs/vpMorphViewAlignment.h>

/*!
  \class vpMorphViewAligner
  \ingroup group_morph_vs
  \brief Measures the similarity (rotation about the optical axis, translation, scale) that lays the current view of
  a planar object on a goal view: a sub-goal of the morph or the target. vpServoMorph and vpFeatureMorph both
  measure through it.

  <b>Method (OUTLINE, default).</b> The view's outline is laid on the goal's by vpMorphOutlineFit: a robust
  point-to-edge fit of the similarity, and of one common edge offset where a clipped level may have grown or shrunk
  a measured outline all round (edgesMayBeOffset(): that is not a depth). The fit starts from the last alignment to the
  same goal (the camera moved by a fraction of it since), or from setStart(); without one, when its fit has lost the
  view (fewer than half of its samples on the goal), or when the last alignment alone (no setStart() or turnStart():
  the motion since unknown) gives a fit that leaves part of the view off the goal (a robust fit drops what it does not
  reach, so a start a turn off can settle on the wrong part), also from the minimal-work correspondence
  (vpMorphCorrespondenceTracker) and its robust vertex fit, which finds the rotation at any angle; when both ran, the
  lower robust cost at one scale wins. Hidden, bent and articulated parts are the robust fit's outliers: the part of the
  view that lies on the goal fixes the pose (up to half of the view may be anything else), and
  vpMorphViewAlignment::model says which model explains the residuals. A view that a similarity explains only with a
  part hidden or bent, but a homography explains whole, is the goal seen tilted: RIGID, its similarity the homography's
  own over the view (vpMorphViewAlignment::perspective). A view that no similarity explains at all is read under the
  homography with the same model test (a tilted view whose narrow gap the foreshortening closed: a part bent). The
  homography starts from the last period's when the view was seen tilted; where that start leaves part of the view off
  the goal, the start from the similarity competes, the lower robust cost at one scale winning, as for the
  similarity's own warm fit. Measured outlines (vpMorphContourExtractor) are compared at one blur: the sharper of the
  two, view or goal, is laid at the other's blur (vpMorphOutlineBlur; their blurs from vpMorphContour::outlineBlur(),
  the view's seen at the goal's scale) where the difference can move the finest edge the pixel grid draws by more than
  the outlines' floor, as a blur rounds every detail of an edge finer than itself; polygons without them are fitted
  edge to edge, their robust scale floored at half a pixel (vertices on the pixel grid).

  <b>Method (PAPER).</b> The paper's rectification: the rotation and translation between the elongation vectors of the
  two shapes, their directions told by the correspondence of every period (vpMorphRigidTransform::fitElongation), and
  the scale of their spreads. The model is then RIGID with an unknown covariance (infinite).

  Units: contours in pixels (converted with setCameraParameters()) or already normalised; transforms in normalised
  coordinates. The limits in pixels use the camera's px (800 by default).

  \code
  vpMorphViewAligner aligner;
  aligner.setCameraParameters(cam);
  aligner.setGoal(target);                              // pixels, e.g. a template's contour
  vpMorphViewAlignment a = aligner.align(current);      // current view, pixels
  if (a.explained()) { double depthRatio = a.transform.scale(); }   // Z / Zd for the target
  \endcode
  \sa vpMorphOutlineFit, vpMorphViewAlignment, \ref page_servo_measurement
*/
class vpMorphViewAligner
{
public:
  //! How the view is aligned.
  enum Method {
    OUTLINE, //!< robust outline fit (default)
    PAPER    //!< the paper's elongation vectors over the correspondence
  };

  //! OUTLINE, the default camera (getDefaultCameraParameters()), no goal.
  vpMorphViewAligner();

  //! The intrinsics that convert pixels to normalized coordinates.
  void setCameraParameters(const vpCameraParameters &cam);
  //! The intrinsics in use.
  const vpCameraParameters &getCameraParameters() const { return m_cam; }
  /*!
    The goal view (pixels or normalised). Forgets the last alignment (the next align() starts from the correspondence
    or from setStart()).
    \throw vpMorphException::badParameterError on an empty contour.
  */
  void setGoal(const vpMorphContour &goal);
  //! The goal in pixels.
  const vpMorphContour &getGoal() const { return m_goalPx; }
  //! The goal in normalised coordinates.
  const vpMorphContour &getGoalNormalized() const { return m_goalN; }
  //! True once a goal is set.
  bool hasGoal() const { return !m_goalPx.empty(); }
  /*!
    The start of the next align() (normalised coordinates, current -> goal), in place of the last alignment, with the
    residuals' scale there (pixels; 0: unknown). E.g. the last alignment moved by the share of it a command executed.
    A start told the motion is trusted: the correspondence's fit runs beside it only when its fit loses the view.
    \throw vpMorphException::badParameterError on a negative or non-finite sigma.
  */
  void setStart(const vpMorphRigidTransform &currentToGoal, double sigmaPx = 0.0);
  /*!
    The camera turned by \e rad about its optical axis since the last view (a commanded turn): the next align()
    starts from the last alignment composed with that turn, the view having turned about the principal point, trusted
    as a setStart() is. Nothing to turn without a last alignment.
  */
  void turnStart(double rad);
  //! Forgets the last alignment and the correspondence (after a jump of the view).
  void reset();
  //! The method (default OUTLINE); forgets the last alignment.
  void setMethod(Method m);
  //! The method in use.
  Method getMethod() const { return m_method; }

  /*!
    Aligns \e current (pixels or normalised) on the goal. Never throws for a view it cannot align (empty, degenerate,
    another shape): the result is then UNEXPLAINED.
    \throw vpMorphException::badParameterError without a goal.
  */
  vpMorphViewAlignment align(const vpMorphContour &current);
  //! The last alignment (UNEXPLAINED before any).
  const vpMorphViewAlignment &getLastAlignment() const { return m_last; }
  //! The correspondence tracker of the cold starts (and of every period with PAPER).
  const vpMorphCorrespondenceTracker &getTracker() const { return m_tracker; }

  /*!
    Floor of the outline fit's robust scale on measured outlines (pixels, 0.1): two views of one edge place it within
    about a tenth of a pixel of each other (each view's outline lies a few hundredths of a pixel from the true edge,
    more at corners and where the pixel phase differs). Below it the fit would keep only the straightest stretches.
  */
  static double outlineSigmaFloorPx() { return 0.1; }
  //! Floor on polygons without measured outlines (pixels, 0.5: their vertices lie on the pixel grid).
  static double polygonSigmaFloorPx() { return 0.5; }
  /*!
    Robust scale beyond which measured outlines are not the same edges seen twice (pixels, 0.5: two measurements of
    one edge each lie within a few tenths of a pixel, under the quantisation of a boundary at whole pixels).
  */
  static double outlineSigmaLimitPx() { return 0.5; }
  //! The same for polygons (pixels, 1.5: two polygonisations place their vertices up to a pixel apart, on the grid).
  static double polygonSigmaLimitPx() { return 1.5; }
  /*!
    Whether two measured outlines of one object may lie offset all round: one of them was measured on a level the
    sensor clipped (its blur unknown, vpMorphContour::outlineBlur() 0), where vpMorphContourExtractor's edge model
    leaves up to a tenth of a pixel; elsewhere its outlines lie on their edges to a few hundredths. The fits then add
    one common offset of the goal's edges (vpMorphOutlineFit::setEdgeOffset()), and not otherwise: on a view explained
    in part, a free offset trades for the scale wherever the inliers' edges lie about equally far from their centroid,
    and a bend's edges near its pivot pull along that trade.
  */
  static bool edgesMayBeOffset(const vpMorphContour &view, const vpMorphContour &goal)
  {
    return view.hasOutline() && goal.hasOutline() && !(view.outlineBlur() > 0.0 && goal.outlineBlur() > 0.0);
  }
  //! The camera until setCameraParameters(): 800 px focal length, a 640 x 480 image (a 44 deg field of view).
  static vpCameraParameters getDefaultCameraParameters() { return vpCameraParameters(800, 800, 320, 240); }
  /*!
    Step of the blurs the goal is laid at (pixels, 0.1): half a step of blur moves an edge of curvature up to 1/px by
    at most 0.1 px (the outlines' floor) up to a blur of 2 px (a curvature flow: sigma dsigma kappa).
  */
  static double blurStepPx() { return 0.1; }

private:
  //! The goal laid at one blur: its contour (normalised) and the outline fit on it.
  struct BlurredGoal
  {
    explicit BlurredGoal(const vpMorphContour &n) : goalN(n), fit(n) {}
    vpMorphContour goalN;
    vpMorphOutlineFit fit;
  };
  //! The goal at \e currentN's blur; \e currentN laid at the goal's when it is the sharper.
  BlurredGoal &atOneBlur(vpMorphContour &currentN);
  double normalisedPixels(double px) const { return px / std::max(m_cam.get_px(), m_cam.get_py()); }
  //! The width of the view's necks the grid may join or part (vpMorphOutlineFit::fineWidth()); 0 on polygons.
  double fineWidth(const vpMorphContour &currentN, bool measured) const
  {
    return measured ? vpMorphOutlineFit::fineWidth(normalisedPixels(1.0), currentN.outlineBlur()) : 0.0;
  }
  vpMorphViewAlignment fromFit(const vpMorphRigidTransform &T, const vpMorphOutlineFit &fit,
                               const vpMorphContour &currentN, bool cold, bool measured) const;
  //! A view no similarity explains, tried as \e goalN (the goal at the view's blur) seen tilted (a homography): true,
  //! \e a updated, when it is; \e warmOnly: from the last period's homography alone.
  bool perspective(const vpMorphContour &currentN, const vpMorphContour &goalN, vpMorphViewAlignment &a,
                   bool warmOnly = false);
  //! Share of the view's region (normalised) that lies in the goal's once laid by T.
  double overlapShare(const vpMorphRigidTransform &T, const vpMorphContour &currentN) const;
  vpMorphRigidTransform correspondenceStart(const vpMorphContour &currentN, vpMorphViewAlignment &a);

  vpCameraParameters m_cam;
  Method m_method = OUTLINE;
  vpMorphContour m_goalPx, m_goalN, m_goalRegion;
  std::map<long, BlurredGoal> m_goals; // by the blur added to the goal, in blurStepPx(); 0: the goal as given
  vpMorphCorrespondenceTracker m_tracker;
  bool m_haveStart = false;
  vpMorphRigidTransform m_start;
  double m_startSigma = 0.0;     // the residuals' scale at the start (normalised; 0: unknown)
  bool m_startPredicted = false; // the start moved by the motion since the last view (setStart(), turnStart())
  vpMorphViewAlignment m_last;
  vpMorphHomography m_homography; // the last period's, when the view was seen tilted
  bool m_haveHomography = false;
};

#endif
