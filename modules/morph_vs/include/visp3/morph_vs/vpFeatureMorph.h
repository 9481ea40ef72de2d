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
#include <visp3/morph_vs/vpMorphViewAligner.h>
#include <visp3/visual_features/vpBasicFeature.h>

/*!
  \class vpFeatureMorph
  \ingroup group_morph_vs
  \brief Visual feature \f${\bf s} = (x_g, y_g, \theta, \sigma)\f$ of a planar object's contour, a vpBasicFeature.

  <b>s.</b> In normalised coordinates (x = X/Z, y = Y/Z):
  - \f$x_g, y_g\f$: the centroid of the object's region (measured on the image when the contour carries its region,
    vpMorphContour::hasRegion(); else the polygon's);
  - \f$\theta\f$: the in-plane rotation that lays the view on the desired one; it has no absolute value
    (\f$\theta^* = 0\f$): error() measures it;
  - \f$\sigma = \ln \sqrt{a}\f$, \e a the region's area: \f$\sigma - \sigma^* = \ln(Z^{*} / Z)\f$ for a plane parallel
  to the image, so it drives depth.

  <b>Error.</b> error() measures the similarity T (rotation \f$\theta_T\f$, scale \f$s_T\f$) that lays this view on the
  desired one with vpMorphViewAligner, vpServoMorph's measurement (a robust outline fit: hidden and bent parts left
  out), and gives \f${\bf e} = (x_g - x_g^*,\ y_g - y_g^*,\ -\theta_T,\ -\ln s_T)\f$ with \f$(x_g^*, y_g^*) = T(x_g,
  y_g)\f$: the desired values of this view's own region (for a view with a part hidden, the visible part's centroid and
  size at the goal). A view the aligner cannot explain gives a zero error (a stock vpServo then holds) and
  getAlignment() says why.

  <b>Interaction matrix</b> (6 columns, camera velocity \f$(v, \omega)\f$), for the plane \f$1/Z = A x + B y + C\f$
  (Chaumette, T-RO 2004), \f$n_{ij}\f$ the region's normalised centred moments, \f$1/Z_g = A x_g + B y_g + C\f$:
  \f[ L_{x_g} = [-1/Z_g,\ 0,\ x_g/Z_g + 4(A n_{20} + B n_{11}),\ x_g y_g + 4 n_{11},\ -(1 + x_g^2 + 4 n_{20}),\ y_g] \f]
  \f[ L_{y_g} = [0,\ -1/Z_g,\ y_g/Z_g + 4(A n_{11} + B n_{02}),\ 1 + y_g^2 + 4 n_{02},\ -x_g y_g - 4 n_{11},\ -x_g] \f]
  \f[ L_{\sigma} = [-A/2,\ -B/2,\ (3/Z_g - C)/2,\ \tfrac{3}{2} y_g,\ -\tfrac{3}{2} x_g,\ 0] \f]
  and \f$L_\theta\f$ the mean angular velocity of the vertices about their mean (last entry -1 for a parallel plane).

  <b>Depth.</b> The matrix needs the plane: buildFrom(contour, cam, Z) for a plane parallel to the image at depth Z,
  buildFrom(contour, cam, A, B, C) for a known tilted one. Seen from a camera whose desired view is at depth \f$Z^*\f$,
  \f$Z = Z^* s_T\f$ (getAlignment().transform.scale() after error()), as vpServoMorph takes it.

  <b>With vpServo.</b> task.addFeature(s, s_star) with a built desired feature (vpServo keeps raw pointers: both
  objects must outlive the task). CURRENT, DESIRED or MEAN interaction matrices, EYEINHAND_CAMERA or
  EYEINHAND_L_cVe_eJe. Selection: selectXg() | selectYg() | selectTheta() | selectScale().

  \code
  vpFeatureMorph s, sd;
  sd.buildFrom(target, cam, Zd);                 // the desired view, pixels
  s.buildFrom(current, cam, Zd);                 // a first depth; then Zd * s.getAlignment().transform.scale()
  vpServo task;
  task.setServo(vpServo::EYEINHAND_CAMERA);
  task.addFeature(s, sd);
  vpColVector v = task.computeControlLaw();
  \endcode
  \sa vpMorphViewAligner, vpServoMorph
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

  //! Resets to an unbuilt 4-component feature (vpBasicFeature's contract).
  void init() override;
  //! The selected rows of the interaction matrix (see the class description). \throw vpMorphException when not built.
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
  //! Same on a colour image's display.
  void display(const vpCameraParameters &cam, const vpImage<vpRGBa> &I, const vpColor &color = vpColor::green,
               unsigned int thickness = 1) const override;
  //! What display() draws, burnt into the pixels of \e I (vpImageDraw): for pictures and videos without a window.
  void draw(const vpCameraParameters &cam, vpImage<vpRGBa> &I, const vpColor &color = vpColor::green,
            unsigned int thickness = 1) const;
  //! A fresh heap copy (vpServo owns it when it made it, and calls init() on it).
  vpFeatureMorph *duplicate() const override;
  //! Writes the selected components to std::cout (ViSP's contract for print(); only on the caller's request).
  void print(unsigned int select = FEATURE_ALL) const override;
  //! Writes the selected components to \e os.
  void print(std::ostream &os, unsigned int select = FEATURE_ALL) const;

  //! Selects \f$x_g\f$.
  static unsigned int selectXg() { return FEATURE_LINE[0]; }
  //! Selects \f$y_g\f$.
  static unsigned int selectYg() { return FEATURE_LINE[1]; }
  //! Selects \f$\theta\f$.
  static unsigned int selectTheta() { return FEATURE_LINE[2]; }
  //! Selects \f$\sigma\f$.
  static unsigned int selectScale() { return FEATURE_LINE[3]; }

  //! True once buildFrom() has been called.
  bool isBuilt() const { return !m_contour.empty(); }
  //! \f$x_g\f$ (normalized).
  double get_xg() const { return s[0]; }
  //! \f$y_g\f$ (normalized).
  double get_yg() const { return s[1]; }
  //! \f$\theta\f$ (0: it has no absolute value).
  double get_theta() const { return s[2]; }
  //! \f$\sigma = \ln \sqrt{a}\f$.
  double get_sigma() const { return s[3]; }
  //! Depth of the plane at the centroid, 1 / (A xg + B yg + C).
  double get_Z() const { return m_Z; }
  //! Plane coefficient A of 1/Z = A x + B y + C.
  double get_A() const { return m_A; }
  //! Plane coefficient B.
  double get_B() const { return m_B; }
  //! Plane coefficient C.
  double get_C() const { return m_C; }
  //! The contour in normalised coordinates.
  const vpMorphContour &contour() const { return m_contour; }
  //! The measurement (its goal is the desired feature's contour).
  const vpMorphViewAligner &getAligner() const { return m_aligner; }
  //! The measurement, to configure it.
  vpMorphViewAligner &getAligner() { return m_aligner; }
  //! The alignment measured by the last error() call (normalised coordinates, current -> desired).
  const vpMorphViewAlignment &getAlignment() const { return m_aligner.getLastAlignment(); }

private:
  void checkBuilt(const char *caller) const;
  void setContour(const vpMorphContour &normalized, double A, double B, double C);

  vpMorphContour m_contour; // normalised
  vpCameraParameters m_cam;
  double m_Z = 1.0, m_A = 0.0, m_B = 0.0, m_C = 1.0;
  double m_n20 = 0.0, m_n02 = 0.0, m_n11 = 0.0;
  vpMorphViewAligner m_aligner;
};

#endif
