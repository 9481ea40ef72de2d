/*!
  \file vpMorphRigidTransform.h
  \brief The rigid part of a morph: a 2-D similarity about an explicit centre, and its estimators.
*/
#ifndef VP_MORPH_RIGID_TRANSFORM_H
#define VP_MORPH_RIGID_TRANSFORM_H

#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpMatrix.h>
#include <visp3/morph/vpMorphContour.h>
#include <visp3/morph/vpMorphCorrespondence.h>

/*!
  \class vpMorphRigidTransform
  \ingroup group_morph
  \brief 2-D similarity \f$ x' = s R(\theta) (x - c) + c + t \f$ with an explicit centre \f$c\f$ (value type).

  The centre is part of the parametrisation, not of the transform: the same map can be written about any
  centre. It matters for interpolated(): with \f$c\f$ at the shape's centroid, the intermediate transforms
  rotate the shape about itself while its centroid moves on a straight line, instead of swinging it around
  the image origin. The estimators always return the transform written about the input polygon's area
  centroid for that reason.

  Angles are in radians, counter-clockwise in the (x, y) axes (clockwise on screen for pixel contours,
  whose y axis points down), normalised to (-pi, pi] so that interpolation takes the short way round.

  <b>Scale.</b> The paper's rigid part is rotation + translation. A scale is estimated too by default,
  because for an eye-in-hand camera a depth change between the current and the desired view is a uniform
  scale of the image, not a deformation: leaving it to Eq. 1 would make the intermediate contours shrink
  or grow non-uniformly. Pass withScale = false for the paper's rotation + translation (scale fixed to 1).

  <b>Estimators.</b>
  - fitElongation(): the paper's method, from the principal axes ("elongation vectors") of the two
    shapes, the correspondence telling which way each axis points.
  - fitLeastSquares(): weighted 2-D Procrustes (Umeyama, closed form in 2-D) over the corresponded vertex
    pairs, each weighted by the contour length it stands for (half of the adjacent corresponded segments, on
    the input and on the target, each normalised by its perimeter), so that a densely sampled part of a
    polygon does not outweigh a sparsely sampled one; made robust by iteratively reweighted least squares.
    Well posed for shapes with isotropic moments (a square, a disc), where the elongation axis does not exist.

  \code
  vpMorphCorrespondence c = vpMorphMatcher().match(input, target);
  vpMorphRigidTransform T = vpMorphRigidTransform::fitLeastSquares(input, target, c, true,
                                                                   vpMorphRigidTransform::TUKEY, 30, 0.5);
  vpMorphContour rectified = T.apply(input);          // laid on the target, about the input's centroid
  vpMorphRigidTransform half = T.interpolated(0.5);   // half the turn, half the shift, sqrt of the scale
  \endcode
  \sa vpMorph, vpMorphOutlineFit, \ref page_design_morph
*/
class vpMorphRigidTransform
{
public:
  //! Robust loss used by fitLeastSquares().
  enum RobustLoss {
    NO_ROBUST, //!< Plain weighted least squares (outliers drag the fit).
    HUBER,     //!< Huber IRLS: bounded influence, convex, always converges.
    TUKEY      //!< Huber warm start, then Tukey biweight IRLS: outliers get weight 0 (default).
  };

  //! Identity about the origin.
  vpMorphRigidTransform() = default;
  /*!
    \param theta Rotation (radians), normalised to (-pi, pi].
    \param tx, ty Translation, in the units of the contours.
    \param scale Uniform scale, finite and > 0.
    \param cx, cy Centre of the rotation and scale.
    \throw vpMorphException::badParameterError on a non-finite value or scale <= 0.
  */
  vpMorphRigidTransform(double theta, double tx, double ty, double scale = 1.0, double cx = 0.0, double cy = 0.0);

  //! Rotation (radians, in (-pi, pi]).
  double theta() const { return m_theta; }
  //! Translation along x (the contours' units).
  double tx() const { return m_tx; }
  //! Translation along y.
  double ty() const { return m_ty; }
  //! Uniform scale (> 0).
  double scale() const { return m_scale; }
  //! Centre's x.
  double cx() const { return m_cx; }
  //! Centre's y.
  double cy() const { return m_cy; }
  //! The centre (cx, cy).
  void centre(double &cx, double &cy) const
  {
    cx = m_cx;
    cy = m_cy;
  }

  //! Transformed point (x, y) -> (xo, yo).
  void apply(double x, double y, double &xo, double &yo) const;
  //! Transformed image point; u is x and v is y, as in vpMorphContour.
  vpImagePoint apply(const vpImagePoint &p) const;
  //! Transformed contour (same vertex order and units).
  vpMorphContour apply(const vpMorphContour &c) const;

  /*!
    The fraction \e alpha in [0, 1] of this transform, about the same centre: angle alpha*theta, translation
    alpha*t, scale s^alpha (geometric, so that halving twice equals quartering). alpha = 0 is the identity,
    alpha = 1 this transform.
    With \e longWay, the angle turns the other way round, alpha*(theta - 2 pi sign(theta)) (theta = 0: a whole turn):
    the same end, for a robot whose joints cannot go the short way.
    \throw vpMorphException::badParameterError if alpha is not finite or outside [0, 1].
  */
  vpMorphRigidTransform interpolated(double alpha, bool longWay = false) const;
  //! Inverse map, written about the image c + t of this centre (so its translation is -t).
  vpMorphRigidTransform inverse() const;
  //! Composition: (a * b).apply(x) == a.apply(b.apply(x)); written about b's centre.
  vpMorphRigidTransform operator*(const vpMorphRigidTransform &b) const;
  //! Same map, written about another centre (interpolation then rotates about that centre).
  vpMorphRigidTransform recentred(double cx, double cy) const;
  //! 3x3 homogeneous matrix of the map, [sR, b; 0 0 1] with b = c + t - sRc.
  vpMatrix toMatrix() const;

  /*!
    The paper's estimator (section 2): the elongation vector of each shape is the principal (major) axis
    of its corresponded points, through their centre. Every vertex of both polygons is corresponded
    (vpMorphCorrespondence), so each shape's corresponded points are its whole contour, and the axis and
    centre are those of the region the contour encloses: its second-order moments and centroid (the
    measured region's when the contour carries one, vpMorphContour::hasRegion(), else the polygon's).
    Translation = difference of the centres; rotation = angle between the two axes, with the 180 deg
    ambiguity of an axis resolved by the correspondence (the sign that makes the corresponded points
    agree best); scale (if \e withScale) = ratio of the RMS spreads.

    Why the region's moments rather than the vertices': two polygonal approximations of one outline put
    their vertices at different places along its edges, and the vertices' moments (each weighted by the
    length it stands for) move with them by up to a few percent of the spread on a long thin part, an
    error that the region's moments, exact for the enclosed area, do not have.

    Ill-posed when either region has (nearly) isotropic second moments (a square, a disc, a regular
    polygon): the axis is then arbitrary. \e anisotropy (if not null) receives
    \f$\min_{A,B} (\lambda_1 - \lambda_2) / (\lambda_1 + \lambda_2)\f$ in [0, 1]: below about 0.05 the
    rotation is unreliable; use fitLeastSquares() instead.
    \throw vpMorphException on empty contours, different units, or a correspondence that does not fit them.
  */
  static vpMorphRigidTransform fitElongation(const vpMorphContour &input, const vpMorphContour &target,
                                             const vpMorphCorrespondence &correspondence, bool withScale = true,
                                             double *anisotropy = nullptr);

  /*!
    Robust weighted least-squares similarity over all corresponded pairs: minimises
    \f$\sum_k w_k \rho_k \| s R (A_{i_k} - c) + c + t - B_{j_k} \|^2\f$ (closed-form weighted 2-D Procrustes),
    with \f$w_k\f$ the length weights and \f$\rho_k\f$ IRLS weights from the residual norms in units of a
    robust scale \f$\sigma = 1.4826\,\mathrm{MAD}\f$ of the pooled residual components. Huber threshold
    2 sigma, Tukey 5 sigma (the 1-D constants 1.345 and 4.685 widened for 2-D residual norms). TUKEY starts
    from a converged Huber fit, because the biweight needs a good start. Occluded or deformed parts of a
    contour then stop dragging the rigid part, and stay for Eq. 1 to morph.
    \param maxIterations IRLS iterations per stage (Huber, then Tukey), >= 1.
    \param minSigma floor of the robust scale sigma, in the contours' units (>= 0; 0: only a rounding floor).
    Give the resolution of the coordinates, e.g. 0.5 px for contours extracted from images: their vertices lie
    on the pixel grid, so near a goal most of them can coincide exactly with their partners; the MAD is then 0,
    the IRLS weights keep only those vertices and the fit is exactly the identity even when the contours differ
    by a pixel or two elsewhere (a false "goal reached").
    \throw vpMorphException on empty contours, different units, a correspondence that does not fit them, or a
    negative or non-finite minSigma.
  */
  static vpMorphRigidTransform fitLeastSquares(const vpMorphContour &input, const vpMorphContour &target,
                                               const vpMorphCorrespondence &correspondence, bool withScale = true,
                                               RobustLoss loss = TUKEY, unsigned int maxIterations = 30,
                                               double minSigma = 0.0);

  /*!
    Refines \e initial by aligning the input's outline to the target's (trimmed ICP): 256 points spread evenly
    along the input's edges are paired with their closest points on the target's edges, and a similarity is
    fitted to the pairs point to edge (one linear solve a round, so it slides along the edges at once), each pair
    Tukey-weighted by its distance (5 sigma, sigma = 1.4826 MAD, floored at \e minSigma), until it stops moving.
    Unlike a fit over corresponded vertices, this needs no vertex-to-vertex pairing and lets the parts of the
    input that the target does not have (an occluder's edge, a cut across a hidden part) drop out as outliers;
    the rest of the outline then fixes the pose. The result is only as good as \e initial's basin: give it a fit
    from a correspondence.
    \param maxIterations pairing rounds, >= 1.
    \param edgeOffset when given, the target's edges are also moved along their normals (the left of each edge,
    as the target runs) by one common offset, fitted with the similarity and returned there (target units; 0 if the
    fit failed). Why: an edge level biased by the image (a background clipped at the sensor's limit) measures an
    outline grown or shrunk all round. That changes the area and a plain fit's scale with the outline's width,
    whereas an offset does not stretch the outline along its length: fitted apart, it leaves the scale to the
    outline's extent.
    \throw vpMorphException on empty contours, different units, a bad \e minSigma or \e maxIterations.
  */
  static vpMorphRigidTransform refineOnOutline(const vpMorphContour &input, const vpMorphContour &target,
                                               const vpMorphRigidTransform &initial, bool withScale = true,
                                               double minSigma = 0.0, unsigned int maxIterations = 10,
                                               double *edgeOffset = nullptr);

  /*!
    Refines \e initial so that the input's region, moved by it, covers as much of the target's region as it can
    (the area of their intersection is maximised over rotation and translation; the scale stays \e initial's).
    Why: a deformed object (a bent handle, opened jaws) has no pose at which its outline lies on the template's;
    its best rigid placement is the one of largest overlap, which needs no choice of which part is "the object"
    (an outline fit follows whichever part is longest). The overlap is exact (Green's theorem over the boundary
    pieces inside the other region), and so is its gradient; it is climbed by a pattern search along the gradient
    and the axes with an adaptive step (its maxima often sit on kinks, where gradient methods stall), from
    \e initial, to a local maximum: give it a start in the right basin, or several starts.
    Pass dense outlines for sub-pixel accuracy; polygons are faster.
    \param maxIterations search rounds (each at most 7 overlap evaluations), >= 1.
    \param initialStep first step, as a share of the input's radius of gyration, in (0, 1]; it stops at 1e-5
    of it (a thousandth of a pixel on a 100-pixel object). Give a small one from a start already close.
    \throw vpMorphException on empty contours, different units, a bad \e maxIterations or \e initialStep.
  */
  static vpMorphRigidTransform refineOnOverlap(const vpMorphContour &input, const vpMorphContour &target,
                                               const vpMorphRigidTransform &initial, unsigned int maxIterations = 200,
                                               double initialStep = 0.01);

  /*!
    The best of refineOnOverlap() started from \e initial and from \e initial turned about the moved input's
    centroid by every multiple of angleRange / ((starts - 1) / 2) up to +-angleRange: the overlap of a deformed
    object has a local maximum wherever one of its parts lies on the template's (its edges coincide there), and
    the largest overlap is often elsewhere.
    \param angleRange radians, finite and >= 0; \param starts odd, >= 1.
    \throw vpMorphException as refineOnOverlap(), and on a bad angleRange or starts.
  */
  static vpMorphRigidTransform fitOnOverlap(const vpMorphContour &input, const vpMorphContour &target,
                                            const vpMorphRigidTransform &initial, double angleRange,
                                            unsigned int starts, unsigned int maxIterations = 200);

  /*!
    Checks that \e correspondence fits the two contours (non-empty contours, same units, sizes equal to the
    contours', indices in range, every vertex of each contour used at least once).
    \throw vpMorphException::badContourError on an empty contour, badParameterError otherwise.
  */
  static void checkCorrespondence(const vpMorphContour &input, const vpMorphContour &target,
                                  const vpMorphCorrespondence &correspondence, const char *caller);

private:
  double m_theta = 0.0, m_tx = 0.0, m_ty = 0.0, m_scale = 1.0, m_cx = 0.0, m_cy = 0.0;
};

#endif
