/*!
  \file vpMorphBenchObservability.h
  \brief What a taught view lets a servo know of its pose at pixel noise: its symmetry, and the bounds on its pose.
*/
#ifndef VP_MORPH_BENCH_OBSERVABILITY_H
#define VP_MORPH_BENCH_OBSERVABILITY_H

#include <string>
#include <vector>

#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/morph/vpMorphContour.h>

/*!
  \class vpMorphBenchObservability
  \ingroup group_morph_bench
  \brief Decides from a template alone, before any run, how a view of it is scored: modulo its rotational symmetry,
  or apart when its pose cannot be bounded within the success tolerance at pixel noise.

  <b>Noise model.</b> A point of the measured edge outline (vpMorphContour::outline(), a point per boundary pixel)
  lies off the true edge along its normal by (1) an independent error of sigma = kPointNoisePx = 0.1 px: 6 grey
  levels of sensor noise (the bench's noisiest rendering) over a 170-level edge, summed over the 7 pixels across it,
  6 sqrt(7) / 170 = 0.093 px; and (2) a slowly varying offset shared by neighbouring points, up to kOutlineBiasPx =
  0.25 px: the edge level moved by blur, clipping and an illumination gradient across the object. The first averages out
  over the outline, the second does not.

  <b>Symmetry</b> (symmetryOrder()). The outline turned about its centroid by 2 pi / k (k = 2..12) and refined
  (rotation and translation, point-to-edge least squares) lies on itself within 2 sigma RMS: a turn no single point
  can tell from the noise. The order is the largest such k; a disc, which also turns onto itself by 13, 43 and 101 deg,
  has a continuous symmetry (order 0). Runs are scored modulo the symmetry (symmetricPlacements()).

  <b>Nearly symmetric</b> (nearlySymmetric()). The best turn outside the symmetry (a 2 deg scan, the best refined)
  lies on the outline within 2 x kOutlineBiasPx = 0.5 px RMS: the slowly varying offsets of two views can make it
  explain a view as well as the right one. Such a view cannot be bounded: its runs are tallied apart.

  <b>Bounds</b> (the Cramer-Rao bound of the pose from the outline). Each outline point at pixel u with normal n,
  on the plane of the taught view, moves by n^T diag(px, py) L(u) v for a camera twist v (L the point's interaction
  matrix); with independent noise sigma the Fisher information is sum g g^T / sigma^2. Its inverse, mapped to the
  error of the object's pose (translation at the object, rotation), gives 3-sigma bounds on the in-plane
  translation, the depth, the rotation about the optical axis and, when the task needs it (a start or a mount that
  tilts the camera), the tilt. A planar task estimates 4 degrees of freedom, a tilted one 6; the rotation of a
  continuous symmetry is left out. A bound beyond the tolerance (1 mm, 0.5 deg) makes the view unobservable ("too
  thin for the tilt", "too small for the depth").

  \code
  const vpMorphBenchObservability o(templateContour, cam, cdMo);
  if (!o.observable(true)) std::cout << o.reason(true) << std::endl;  // e.g. "tilt"
  \endcode
  \sa \ref page_servo_measurement, \ref page_benchmarks
*/
class vpMorphBenchObservability
{
public:
  static constexpr double kPointNoisePx = 0.1;   //!< sigma of one outline point, px (see the noise model)
  static constexpr double kOutlineBiasPx = 0.25; //!< slowly varying outline offset of one view, px

  /*!
    \param contour : the taught view's contour in pixels, with its measured outline (else its polygon is sampled
    every pixel).
    \param cam, cdMo : the camera and the desired pose (the plane parallel to the image).
    \param translationTolerance, rotationTolerance : the success tolerance (m, rad).
    \throw vpMorphException::badContourError for a contour under 8 points; badParameterError for a bad tolerance.
  */
  vpMorphBenchObservability(const vpMorphContour &contour, const vpCameraParameters &cam,
                            const vpHomogeneousMatrix &cdMo, double translationTolerance = 0.001,
                            double rotationTolerance = 0.5 * M_PI / 180.0);

  //! Order of the rotational symmetry: 1 none, k a k-fold one, 0 a continuous one (a disc).
  unsigned int symmetryOrder() const { return m_order; }
  //! True when a turn outside the symmetry explains the outline within 2 x kOutlineBiasPx.
  bool nearlySymmetric() const { return m_nearResidual <= 2.0 * kOutlineBiasPx; }
  //! That turn (rad): the best turn outside the symmetry.
  double nearTurn() const { return m_nearTurn; }
  //! Its RMS residual (px).
  double nearResidualPx() const { return m_nearResidual; }
  //! 3-sigma bounds: in-plane translation and depth of the object (m), rotation about the optical axis and tilt (rad)
  //! (\e tilt: with the tilt estimated; without, the tilt bound is 0).
  double translationBound(bool tilt) const { return tilt ? m_bound6[0] : m_bound4[0]; }
  //! 3-sigma bound of the depth (m).
  double depthBound(bool tilt) const { return tilt ? m_bound6[1] : m_bound4[1]; }
  //! 3-sigma bound of the rotation about the optical axis (rad).
  double rotationBound(bool tilt) const { return tilt ? m_bound6[2] : m_bound4[2]; }
  //! 3-sigma bound of the tilt (rad; 0 without \e tilt).
  double tiltBound(bool tilt) const { return tilt ? m_bound6[3] : 0.0; }
  //! True when the pose is bounded within the tolerance and not nearly symmetric (\e tilt: the task needs the tilt).
  bool observable(bool tilt) const { return reason(tilt).empty(); }
  //! Why not: "nearly-symmetric", "translation", "depth", "rotation", "tilt"; empty when observable.
  std::string reason(bool tilt) const;
  /*!
    The in-plane motions W of the object frame that map the object onto itself (k-fold symmetry: k - 1 of them):
    for a desired pose cdMo, cdMo * W is an equally good one.
  */
  const std::vector<vpHomogeneousMatrix> &symmetricPlacements() const { return m_placements; }
  /*!
    For a continuous symmetry: the desired pose, turned about the object's centre of symmetry, nearest to \e cMo
    (the turn about the plane's normal taken out of the error); cdMo otherwise.
  */
  vpHomogeneousMatrix nearestDesiredPose(const vpHomogeneousMatrix &cMo) const;

private:
  unsigned int m_order = 1;
  double m_nearTurn = 0, m_nearResidual = 0;
  double m_bound4[4] = {0, 0, 0, 0}, m_bound6[4] = {0, 0, 0, 0};
  double m_tolT, m_tolR;
  vpHomogeneousMatrix m_cdMo;
  double m_centreX = 0, m_centreY = 0; // the centre of symmetry in the object frame, m
  std::vector<vpHomogeneousMatrix> m_placements;
};

#endif
