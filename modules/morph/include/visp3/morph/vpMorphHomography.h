/*!
  \file vpMorphHomography.h
  \brief The plane homography between two views of a planar contour, and its decomposition into a camera pose.
*/
#ifndef VP_MORPH_HOMOGRAPHY_H
#define VP_MORPH_HOMOGRAPHY_H

#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpMatrix.h>
#include <visp3/morph/vpMorphContour.h>
#include <visp3/morph/vpMorphCorrespondence.h>

/*!
  \class vpMorphHomography
  \ingroup group_morph
  \brief Plane homography \f$ x_t \sim G\, x_i \f$ from an input contour to a target contour (value type), its
  robust estimation from the two outlines, and its decomposition into the camera displacement when the plane is
  known in the target view.

  Why: a similarity (vpMorphRigidTransform) describes two views of a plane only when both cameras look straight at
  it; a tilt distorts the outline projectively, and only a homography captures that distortion. With normalised
  coordinates and the plane fronto-parallel at depth d in the target view, it gives the full camera displacement.

  <b>Estimation</b> (fit()). The minimal-work correspondence only starts it (two polygonisations of one outline do not
  place their vertices at the same points): a normalised DLT (Hartley), robust by iteratively reweighted least
  squares, on samples taken along the corresponded segments; then Gauss-Newton on point-to-segment distances both
  ways (input samples mapped by G onto the target polygon, target samples by G^-1 onto the input), nearest points
  recomputed at each iteration as in ICP, Huber weights until an update moves no sample by the robust scale (1.4826
  MAD floored at \e minSigma, half a pixel in these units for contours from images), Tukey's after: an occluded or
  deformed part stops pulling.
  Exact projections of one polygon give the true homography to numerical precision.

  <b>Edge offset</b> (refine() on measured edges). An outline measured at a biased edge level (a clipping light, a
  blur) is the object's outline grown or shrunk all round, which eight parameters would bend into a tilt and a depth.
  refine() can fit one common offset of the target's edges (its distance level set, corners rounded as a blurred edge
  makes them), held at 0 until an update of G moves no sample by the edges' robust scale. Not for polygons: their
  edges are chords, whose misfit is no offset.

  <b>Degenerate input</b> throws vpMorphException: empty contours, different units, a correspondence that does not
  fit them, fewer than 4 vertices on either contour (a triangle does not fix a homography), normal equations too
  ill-conditioned to solve (a sliver), or a singular result.

  <b>Decomposition</b> (inputMtarget()). With the plane \f$ n^T X = d \f$, n = (0, 0, 1), in the target camera frame,
  \f$ H = G^{-1} \sim {}^iR_t + {}^it_t\, n^T / d \f$: its first two columns, scaled to unit norm and made
  orthonormal (wrong intrinsics make them not exactly so), are those of \f${}^iR_t\f$, their cross product the third,
  and the third column minus it is \f${}^it_t / d\f$, signed to put the plane in front of the input camera.

  \code
  vpMorphContour cn = current.toNormalized(cam), tn = target.toNormalized(cam);
  vpMorphHomography G = vpMorphHomography::fit(cn, tn, vpMorphMatcher().match(cn, tn), 0.5 / cam.get_px());
  vpHomogeneousMatrix cMcd = G.inputMtarget(0.5); // the target view fronto-parallel at 0.5 m
  \endcode
  \sa vpMorphRigidTransform, \ref page_design_servo
*/
class vpMorphHomography
{
public:
  //! Samples per contour of fit() and refine() by default.
  static const unsigned int kDefaultSamples = 200;
  //! Gauss-Newton iterations of fit() and refine() at most, by default.
  static const unsigned int kDefaultIterations = 20;

  //! Identity.
  vpMorphHomography();
  /*!
    From a 3x3 matrix G (input to target), stored scaled to unit Frobenius norm.
    \throw vpMorphException::badParameterError if G is not 3x3, not finite, or singular.
  */
  explicit vpMorphHomography(const vpMatrix &G);

  //! The 3x3 matrix G (input to target), of unit Frobenius norm.
  const vpMatrix &matrix() const { return m_G; }
  //! Maps (x, y) of the input to the target; false (outputs unchanged) when the point maps to infinity.
  bool apply(double x, double y, double &xo, double &yo) const;
  /*!
    Mapped contour (vertices only: a measured region does not follow a projective map and is dropped).
    \throw vpMorphException::badContourError if a vertex maps to infinity or the result is not a valid contour.
  */
  vpMorphContour apply(const vpMorphContour &c) const;
  //! The target to input homography.
  vpMorphHomography inverse() const;

  //! RMS of the point-to-segment distances of the inlier samples after fit() (units of the contours).
  double residual() const { return m_residual; }
  /*!
    The common offset of the target's edges along their outward normals that the fit found (units of the contours;
    positive when the mapped input is measured larger than the target all round), after refine() with the offset; 0
    otherwise.
  */
  double edgeOffset() const { return m_edgeOffset; }
  //! Share of the samples whose final robust weight is not zero, after fit() (1 for a constructed homography).
  double inlierShare() const { return m_inlierShare; }
  //! Gauss-Newton iterations run by fit().
  unsigned int iterations() const { return m_iterations; }
  /*!
    Covariance (8x8) of the parameters d of a perturbation G (I + D), D = [d0 d1 d2; d3 d4 d5; d6 d7 0], after fit()
    or refine(): sigma^2 (J^T W J)^-1 at the last iteration, sigma^2 the weighted squared residuals over the degrees
    of freedom left. Why: how well the outlines fix each part of G, the perspective part (d6, d7: about the tilt in
    radians when G is near the identity in normalised coordinates) above all, which a thin object barely fixes.
    The samples along an outline are not independent (neighbouring edge points share pixels), so it is optimistic
    by the number of samples per independent one. The edge offset is marginalised. Zero for a constructed or
    inverted homography.
  */
  const vpMatrix &covariance() const { return m_covariance; }

  /*!
    Robust homography from \e input to \e target (same units; normalised coordinates for inputMtarget()),
    started from \e correspondence (see the class description).
    \param samples samples per contour for the refinement (>= 16).
    \param maxIterations Gauss-Newton iterations at most (>= 1).
    \param minSigma floor of the robust scale, in the contours' units (>= 0).
    \throw vpMorphException on degenerate input (see the class description) or bad parameters.
  */
  static vpMorphHomography fit(const vpMorphContour &input, const vpMorphContour &target,
                               const vpMorphCorrespondence &correspondence, double minSigma = 0.0,
                               unsigned int samples = kDefaultSamples, unsigned int maxIterations = kDefaultIterations);

  /*!
    Robust refinement of \e initial (step 2 of fit() alone: two-way point-to-segment Gauss-Newton, Huber then
    Tukey weights). Why: a homography known closely, from fit() on the polygons or from the previous image of a
    sequence, refined on dense outlines (vpMorphContour::outline(): a point per boundary pixel), is fixed to a few
    hundredths of a pixel, where polygons leave tenths. Nearest edges are found through a grid, so the cost grows
    with the samples, not with the outlines' sizes.
    \param edgeOffset fit the common edge offset too (see the class description): for outlines measured on the
    grey levels (vpMorphContour::hasOutline()), not for polygons. It starts from \e initial's edgeOffset() (a
    homography refined on the last image of a sequence carries it).
    \throw vpMorphException as fit() (no correspondence is involved).
  */
  static vpMorphHomography refine(const vpMorphContour &input, const vpMorphContour &target,
                                  const vpMorphHomography &initial, double minSigma = 0.0,
                                  unsigned int samples = kDefaultSamples,
                                  unsigned int maxIterations = kDefaultIterations, bool edgeOffset = false);

  /*!
    The pose of the target camera in the input camera frame, iMt (with the current view as input and the desired
    one as target: cMcd, the displacement that reaches the goal), for a homography between
    normalised coordinates and the plane z = d of the target camera frame (fronto-parallel at depth d).
    \throw vpMorphException::badParameterError if d is not finite and > 0; badContourError if the homography has
    no such decomposition (rank-deficient columns).
  */
  vpHomogeneousMatrix inputMtarget(double d) const;

private:
  vpMatrix m_G;
  vpMatrix m_covariance = vpMatrix(8, 8, 0.0);
  double m_residual = 0.0, m_inlierShare = 1.0, m_edgeOffset = 0.0;
  unsigned int m_iterations = 0;
};

#endif
