/*!
  \file vpFeatureMorph.h
  \brief The morph visual feature: a contour's position, in-plane rotation and scale, for any stock vpServo.
*/
#ifndef VP_FEATURE_MORPH_H
#define VP_FEATURE_MORPH_H

#include <ostream>

#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/morph/vpMorphContour.h>
#include <visp3/morph/vpMorphRigidTransform.h>
#include <visp3/morph_vs/vpMorphCorrespondenceTracker.h>
#include <visp3/visual_features/vpBasicFeature.h>

/*!
  \class vpFeatureMorph
  \ingroup group_morph_vs
  \brief Visual feature \f${\bf s} = (x_g, y_g, \theta, \sigma)\f$ of a planar object's contour, a vpBasicFeature.

  All components are computed on the contour in normalised coordinates (x = X/Z, y = Y/Z):
  - \f$x_g, y_g\f$: area centroid of the polygon region (image-plane translation of the object);
  - \f$\theta\f$: in-plane orientation of the contour relative to the desired one. It has no absolute value:
    error() finds the minimal-work correspondence between the current and the desired contours
    (vpMorphCorrespondenceTracker: tracked from the previous iteration, full search on the first frame or
    when unreliable) and fits the similarity that maps the current contour onto the desired one over the
    corresponded pairs (vpMorphRigidTransform::fitLeastSquares, plain weighted least squares so that the
    interaction matrix below is its exact derivative); \f$\theta - \theta^* = -\f$ its angle. So the error
    comes from the correspondence, not from vertex indices, and works from any rotation up to 180 deg.
    get_s() shows the value of the last error() call (0 before), \f$\theta^* = 0\f$.
  - \f$\sigma = \ln \sqrt{a}\f$ with \e a the region area: \f$\sigma - \sigma^* = \ln(Z^{*} / Z)\f$ for a plane
    parallel to the image, so it drives depth.

  <b>Measured contours.</b> A contour from vpMorphContourExtractor carries the region and the edge outline measured
  on the image (vpMorphContour::hasRegion(), hasOutline()). When the current and the desired contours both carry a
  region, \f$x_g, y_g, \sigma\f$ and the moments below are the regions' (else both polygons'); when both carry an
  outline, the fit that gives \f$\theta\f$ is refined on the two outlines (vpMorphRigidTransform::refineOnOutline(),
  robust scale floored at a tenth of a pixel). Why: a polygon's area, centroid and corresponded vertices move from
  one image to the next as its vertices do, and a stock vpServo then wanders a millimetre about its goal without
  settling (rendered planar starts: 0.3-2.2 mm off at the budget, 0.006-0.046 mm with the measurements).

  <b>A part hidden.</b> When the desired contour carries its measured region and the current one is not that region
  seen again (their similarity invariants more than 2 % apart, or no region: an outline joined across an occluder's
  cut), the fit is robust (Tukey, then refined on the outlines), and once it turns the view within 5 deg of the goal
  the view laid by it is checked against the desired region: an occluder only hides, a bend sticks out (by more than
  2 % of the view). A view with a part hidden (so taken until checked, and for good once checked or joined) has the
  desired values the fit gives its own region: \f$x_g^*, y_g^*\f$ where the fit lays its centroid, \f$\sigma^* =
  \sigma + \ln s\f$ with \e s the fit's scale. The visible part is a fixed part of the object (the occluder lies on the
  plane), so these are its values at the goal; the desired region's own centroid and area (the whole object against a
  part of it) put the loop 13-49 mm off. Its fit is also refined from the last error()'s, and the one whose scale moved
  less is kept: the fit of an outline joined across a card, whose bridge changes from one image to the next, has two
  basins (a key's 4 % apart in scale), between which the loop chattered or jumped. Regions alike are checked once too,
  near the goal: a small occluder or bend barely changes their invariants. A view that the regions lay out of the
  desired region (by 2 %) is hidden from then on if the robust fit lays it inside, bent if that one does not either.

  <b>A bent view</b> (with both outlines; else the regions) is laid as vpServoMorph lays it: rotation and translation
  of the largest overlap with the desired region (vpMorphRigidTransform::fitOnOverlap at the decision, then refined
  from the last period's), at the scale of its largest undeformed part (vpMorphRigidTransform::fitRigidPart, searched
  every 8 periods and followed in between; the outlines' length ratio times the last part's ratio to it when none is
  found). The desired values then come from that fit, as for a part hidden. On the regions' centroid and area (which a
  bend moves) the loop converged 2-25 mm off (bench deformable set, free camera: 2/10 -> 8/10). The decisions are reset
  by init().

  <b>Interaction matrices</b> (6 columns, camera velocity \f$(v, \omega)\f$), for a planar object whose plane is
  \f$1/Z = A x + B y + C\f$ in the camera frame (buildFrom() with a depth Z assumes the plane parallel to the
  image, A = B = 0, C = 1/Z: the paper's task; pass A, B, C when the tilt is known). With \f$n_{ij} = \mu_{ij}/a\f$
  the normalised centred region moments and \f$1/Z_g = A x_g + B y_g + C\f$ (Chaumette, "Image moments: a general
  and useful set of features for visual servoing", T-RO 2004):
  \f[ L_{x_g} = [-1/Z_g,\ 0,\ x_g/Z_g + 4(A n_{20} + B n_{11}),\ x_g y_g + 4 n_{11},\ -(1 + x_g^2 + 4 n_{20}),\ y_g] \f]
  \f[ L_{y_g} = [0,\ -1/Z_g,\ y_g/Z_g + 4(A n_{11} + B n_{02}),\ 1 + y_g^2 + 4 n_{02},\ -x_g y_g - 4 n_{11},\ -x_g] \f]
  \f[ L_{\sigma} = [-A/2,\ -B/2,\ (3/Z_g - C)/2,\ \tfrac{3}{2} y_g,\ -\tfrac{3}{2} x_g,\ 0] \f]
  \f$L_\theta\f$ is the derivative of the least-squares angle: the weighted mean angular velocity of the
  vertices about their weighted mean \f$c\f$, \f$L_\theta = \sum_i w_i (a_{x,i} L_{y,i} - a_{y,i} L_{x,i}) /
  \sum_i w_i |a_i|^2\f$ with \f$a_i = p_i - c\f$, \f$L_{x,i}, L_{y,i}\f$ the point interaction matrices of vertex
  \e i at its depth on the plane and \f$w_i\f$ half its two adjacent edge lengths (the fit's length weights);
  for a parallel plane its last entry is -1 and its three first are 0. It is exact while the current contour is
  a similarity of the desired one, as near convergence.

  <b>With vpServo.</b> Always add it as task.addFeature(s, s_star) with a built desired feature: vpServo keeps
  raw pointers, so both objects must outlive the task, and vpServo::addFeature(s) alone would use a duplicate()
  reset by init(), which has no contour. The desired feature supports interaction(), so the interaction
  matrix may be CURRENT, DESIRED or MEAN, with EYEINHAND_CAMERA or EYEINHAND_L_cVe_eJe.
  Selection is a bitmask of selectXg() | selectYg() | selectTheta() | selectScale().
*/
class vpFeatureMorph : public vpBasicFeature
{
public:
  vpFeatureMorph();

  /*!
    From a contour in pixels (or already normalised) and the depth of the object's plane.
    \throw vpMorphException::badParameterError if Z is not finite and > 0;
    badContourError if the contour is empty, or smaller than 1e-50 normalised units (square root of its area) or
    with non-finite moments: too small for the interaction matrix in double precision.
  */
  void buildFrom(const vpMorphContour &contour, const vpCameraParameters &cam, double Z);
  //! From a contour in normalised coordinates (the camera parameters are then only used by display()).
  void buildFrom(const vpMorphContour &normalizedContour, double Z);
  /*!
    With the object's plane 1/Z = A x + B y + C in the camera frame (normalised coordinates), for a tilted
    object: the interaction matrices are then exact for it.
    \throw vpMorphException::badParameterError if the plane is not in front of the camera at every vertex.
  */
  void buildFrom(const vpMorphContour &contour, const vpCameraParameters &cam, double A, double B, double C);
  //! Plane coefficients (A, B, C) of the object plane in the camera frame, from its pose cMo and its normal
  //! in the object frame (z axis by default); a helper for simulations and pose-based set-ups.
  static void planeFromPose(const vpHomogeneousMatrix &cMo, double &A, double &B, double &C);

  void init() override;
  vpMatrix interaction(unsigned int select = FEATURE_ALL) override;
  /*!
    Error \f$(x_g - x_g^*, y_g - y_g^*, -\theta_{fit}, \ln\sqrt{a/a^*})\f$ against a built vpFeatureMorph, with
    one correspondence per call (see the class description).
    \throw vpMorphException::badParameterError if s_star is not a vpFeatureMorph or either is not built.
  */
  vpColVector error(const vpBasicFeature &s_star, unsigned int select = FEATURE_ALL) override;
  /*!
    Draws the feature as ViSP's features draw theirs: its contour and a cross at its centroid \f$(x_g, y_g)\f$, in
    pixels through \e cam, on the display attached to \e I (no-op without one, or when not built). The desired
    feature drawn wider and first stays visible where the current one reaches it (vpServoDisplay::display(task, cam,
    I, currentColor, desiredColor) draws both, the same width):
    \code
    vpDisplayX d(I);
    vpDisplay::display(I);
    s_star.display(cam, I, vpColor::green, 3);
    s.display(cam, I, vpColor::red);
    vpDisplay::flush(I);
    \endcode
  */
  void display(const vpCameraParameters &cam, const vpImage<unsigned char> &I, const vpColor &color = vpColor::green,
               unsigned int thickness = 1) const override;
  void display(const vpCameraParameters &cam, const vpImage<vpRGBa> &I, const vpColor &color = vpColor::green,
               unsigned int thickness = 1) const override;
  //! What display() draws, burnt into the pixels of \e I (vpImageDraw): for pictures and videos without a window.
  void draw(const vpCameraParameters &cam, vpImage<vpRGBa> &I, const vpColor &color = vpColor::green,
            unsigned int thickness = 1) const;
  //! A fresh heap copy (vpServo owns it when it made it, and calls init() on it).
  vpFeatureMorph *duplicate() const override;
  //! Writes the selected components to std::cout (ViSP's contract for print(); only on the caller's request).
  void print(unsigned int select = FEATURE_ALL) const override;
  void print(std::ostream &os, unsigned int select = FEATURE_ALL) const;

  static unsigned int selectXg() { return FEATURE_LINE[0]; }
  static unsigned int selectYg() { return FEATURE_LINE[1]; }
  static unsigned int selectTheta() { return FEATURE_LINE[2]; }
  static unsigned int selectScale() { return FEATURE_LINE[3]; }

  bool isBuilt() const { return !m_contour.empty(); }
  double get_xg() const { return s[0]; }
  double get_yg() const { return s[1]; }
  double get_theta() const { return s[2]; }
  double get_sigma() const { return s[3]; }
  //! Depth of the plane at the centroid, 1 / (A xg + B yg + C).
  double get_Z() const { return m_Z; }
  double get_A() const { return m_A; }
  double get_B() const { return m_B; }
  double get_C() const { return m_C; }
  //! The contour in normalised coordinates.
  const vpMorphContour &contour() const { return m_contour; }
  //! The correspondence tracker (statistics: full and tracked searches, margin).
  const vpMorphCorrespondenceTracker &tracker() const { return m_tracker; }
  vpMorphCorrespondenceTracker &tracker() { return m_tracker; }
  //! Similarity current -> desired fitted by the last error() call (normalised coordinates).
  const vpMorphRigidTransform &lastFit() const { return m_fit; }

private:
  void checkBuilt(const char *caller) const;
  //! The similarity from this contour to sd's over \e corr, and whether a part of it is hidden (see the class).
  vpMorphRigidTransform fitToDesired(const vpFeatureMorph &sd, const vpMorphCorrespondence &corr);
  //! A bent view's fit to sd's (both with outlines): its largest undeformed part's scale, the largest overlap's pose.
  vpMorphRigidTransform bentFit(const vpFeatureMorph &sd, const vpMorphRigidTransform &base, bool warm);
  void setContour(const vpMorphContour &normalized, double A, double B, double C);

  vpMorphContour m_contour; // normalised
  vpCameraParameters m_cam;
  double m_Z = 1.0, m_A = 0.0, m_B = 0.0, m_C = 1.0;
  double m_n20 = 0.0, m_n02 = 0.0, m_n11 = 0.0;
  double m_polyS[3] = {0.0, 0.0, 0.0}; // the polygon's own xg, yg and sigma (s holds the region's when measured)
  vpMorphCorrespondenceTracker m_tracker;
  vpMorphRigidTransform m_fit;
  // Whether the current region is the desired one seen again, or not (then, near the goal, found a part of it hidden
  // or bent: see the class); reset by init().
  enum {
    REGIONS_UNDECIDED,
    REGIONS_ALIKE,
    REGIONS_NOT_ALIKE,
    REGIONS_HIDDEN,
    REGIONS_BENT
  } m_regions = REGIONS_UNDECIDED;
  bool m_regionsChecked = false; // regions alike, checked once near the goal against the robust fit
  unsigned int m_bentCount = 0;  // periods since the view was found bent (the part's search every few)
  bool m_partKnown = false;      // its largest undeformed part was found at the last period
  vpMorphRigidTransform m_partOffset; // that part's fit o the base fit^-1, to follow it
  double m_scaleBias = 1.0;           // the part's scale over the outlines' length ratio, when it is lost
};

#endif
