/*!
  \file vpMorphRigidCheck.h
  \brief Whether a view is a rigid part's template: the two outlines laid on each other by a plane homography.
*/
#ifndef VP_MORPH_RIGID_CHECK_H
#define VP_MORPH_RIGID_CHECK_H

#include <visp3/morph/vpMorphContour.h>
#include <visp3/morph/vpMorphHomography.h>
#include <visp3/morph/vpMorphRigidShape.h>
#include <visp3/morph/vpMorphRigidTransform.h>

/*!
  \class vpMorphRigidCheck
  \ingroup group_morph
  \brief The exact, rigid-aware comparison of a view with a template: the view's outline is laid on the template's
  by the plane homography that a camera's view of a flat part is, and what coincides within the measurement's
  tolerance is counted both ways.

  Why: look-alike parts differ by details that a deformation-tolerant distance absorbs (D_morph lets the
  correspondence slide and bend), while a rigid part's view is its template seen through a homography, to the
  outline's measurement noise. Laid on each other, the right template's outline coincides with the view's
  everywhere the view shows it, and a look-alike's leaves its differences uncovered.

  Outlines measured at different blurs differ along the details finer than the blur (a sharp corner, a tooth): the
  sharper of the two is first laid at the other's blur (vpMorphRigidShape::atBlur(), the start's scale converting
  between their pixels), so that the two are compared as one image would show them.

  check(input, target, start): a start that scales the input's size (square root of its area) to less than half or
  more than twice the target's is no view of it (as vpMorphRigidShape's hypotheses) and is not fitted. From the
  similarity \e start (input to target, vpMorphRigidShape::alignOn()), the
  homography is fitted by Gauss-Newton on point-to-edge distances both ways (64 points of each outline onto the
  other's edges, Tukey weights whose cut-off shrinks from a twentieth of the target's size to twice tolerance(): the
  parts one outline lacks, hidden or an occluder's edge, drop out). When the input's outline tells its own edges
  (vpMorphContour::ownEdge(), the extractor's marks), only they are fitted, both ways: an occluder's edge or a bridge
  is no part of any template, and left in, it pulls the fit where it runs near the target's outline. A fit that no
  camera gives (a view tilted more than 45 deg, mirrored, or a perspective that changes the area scale by more than a
  factor 2 across the outline: a free homography can squash one outline onto a few edges of another) is not fitted. Then
  256 points spread evenly along each outline are mapped onto the other and their distance d to it measured. Each side
  gives the share of its points with d <= tolerance() (the target's: how much of the template the view shows; the
  input's: how much of the view the template explains, less than 1 where an occluder's edge runs) and the mean of min(d,
  tolerance)^2 / tolerance^2; the cost is the mean of the two sides', 0 for outlines that coincide, 1 for nothing in
  common. The input's own edge that the target leaves unexplained is counted apart (Result::unexplainedShare): an
  occluder only hides, so a view of the target shows none. Conversely, a view whose outline is its own edge all round
  hides nothing, and the target's outline outside its region is counted (Result::absentShare). The curves are the
  measured (dense, sub-pixel) outlines when the contours have them (vpMorphContour::outline()), else the polygons.

  \code
  const vpMorphRigidShape t(tmpl), q(view);
  const vpMorphRigidCheck::Result r = vpMorphRigidCheck::check(q, t, q.alignOn(t).transform);
  // r.targetShare: share of the template's outline the view shows; r.cost: ranks templates
  \endcode
  \sa vpMorphRigidShape, vpMorphDatabase, \ref page_design_recognition
*/
class vpMorphRigidCheck
{
public:
  //! The comparison of a view with a template.
  struct Result
  {
    double cost = 1.0;        //!< two-way truncated quadratic mean, in [0, 1]
    double targetShare = 0.0; //!< share of the target's outline within tolerance of the mapped input
    double inputShare = 0.0;  //!< share of the input's outline within tolerance of the target
    //! share of the input's outline outside the target's region by more than twice the tolerance: an occluder only
    //! takes away, so a view of the target never sticks out of it (0 for an input without a measured region: a
    //! silhouette joined across its occluder, vpMorphContourExtractor::extractJoined(), has bridges that may)
    double outsideShare = 0.0;
    //! share of the target's outline outside the view's region by more than twice the tolerance, for a view whose
    //! outline is its own edge all round (vpMorphContour::ownEdge(): nothing cuts it, so it hides nothing): what it
    //! would show of the target and shows as background (0 for any other view, which does not tell hidden from absent)
    double absentShare = 0.0;
    //! share of the input's outline on its own edge (vpMorphContour::ownEdge()) and not within tolerance of the
    //! target: the view's own boundary where the target has none (0 without marks)
    double unexplainedShare = 0.0;
    vpMorphHomography homography; //!< input to target, pixels (identity when the fit failed)
    vpMorphRigidTransform start;  //!< the similarity the fit started from (of the hypotheses tried, the best's)
    bool fitted = false;          //!< the fit converged to a possible view (else the shares are 0 and the cost 1)
  };

  /*!
    Compares \e input with \e target from the similarity \e start (input pixels to target pixels).
    \throw vpMorphException::badParameterError on an empty shape or units that differ.
  */
  static Result check(const vpMorphRigidShape &input, const vpMorphRigidShape &target,
                      const vpMorphRigidTransform &start);
  //! The best (least cost) of check() from the alignment's transform, its alternative when it has one, and its
  //! symmetric hypotheses.
  static Result check(const vpMorphRigidShape &input, const vpMorphRigidShape &target,
                      const vpMorphRigidShape::Alignment &alignment);
  /*!
    As check(input, target, alignment), but once the cost is sure to exceed \e abandonAbove the measurement stops and
    the result is only a cost > abandonAbove (fitted false); exact otherwise. A search that needs the two least costs
    measures no further a template that can be neither.
  */
  static Result check(const vpMorphRigidShape &input, const vpMorphRigidShape &target,
                      const vpMorphRigidShape::Alignment &alignment, double abandonAbove);
  /*!
    The objective that check()'s fit from \e start first descends: the mean Tukey loss, in [0, 1], of the fit's point
    to edge distances both ways at its first cut-off (a twentieth of the target's size). Unlike the coarse stage's
    cost, it is measured on the outlines: of a part's alike turns (its teeth, say) the right one costs least. 1 for a
    start that is no view of the target. The distances of one of the fit's steps, nothing solved.
    \throw vpMorphException::badParameterError on an empty shape or units that differ.
  */
  static double startCost(const vpMorphRigidShape &input, const vpMorphRigidShape &target,
                          const vpMorphRigidTransform &start);
  //! check() of two contours, prepared here.
  static Result check(const vpMorphContour &input, const vpMorphContour &target, const vpMorphRigidTransform &start);

  /*!
    How surely the view \e input is target \e a rather than target \e b, from their comparisons \e ra and \e rb
    (fitted): b's cost less a's, each with what of the target the view hides counted as neutral. A target's sample
    that the view does not show counts 0 when its nearest sample of the view's outline is an occluder's edge (no own
    edge of the view, vpMorphContour::ownEdge(); without marks, a sample neither target explains), 1 otherwise: an
    occluder hides only behind its edge, and a part that the other target's outline closes off is absent, not hidden.
    When the view shows an occluder's edge, the three samples' worth by which its stretches' six ends (two on each
    outline) can tip either way are taken off. About 0 when the view cannot tell the two apart, at most 1. \throw
    vpMorphException::badParameterError when either comparison was not fitted.
  */
  static double evidence(const vpMorphRigidShape &input, const vpMorphRigidShape &a, const Result &ra,
                         const vpMorphRigidShape &b, const Result &rb);
  /*!
    Distance within which two points of the outlines coincide, in the target's units: half a pixel between measured
    outlines (the edge outline's error under the documented noise and blur is a tenth of a pixel, and a homography
    maps a flat part's views onto each other exactly), 1.5 px when either is a polygon (each vertex is a boundary
    pixel's centre, up to half a pixel's diagonal off the edge, on either contour). For NORMALIZED contours the same
    as for a target whose size (square root of its area) is 128 px.
  */
  static double tolerance(const vpMorphContour &input, const vpMorphContour &target);

  /*!
    How far two contours are from being one shape at two sizes: \e input laid on \e target by the similarity that
    fits their outlines best (started from vpMorphRigidShape::alignOn() both ways, refined point to edge), the
    \e quantile of the distances of 256 points of each outline to the other, in pixels of the coarser of the two (an
    input twice smaller than the target has pixels two target pixels wide). Two digitisations of one outline lie within
    half a pixel's diagonal of it each, so one shape seen at two sizes is within sqrt(2) at every point.
    \throw vpMorphException::badContourError on an empty or degenerate contour, badParameterError on units that
    differ or a quantile outside [0, 1].
  */
  static double similarityDeviation(const vpMorphContour &input, const vpMorphContour &target, double quantile = 0.99);
  //! similarityDeviation() of shapes already prepared (many pairs of few shapes).
  static double similarityDeviation(const vpMorphRigidShape &input, const vpMorphRigidShape &target,
                                    double quantile = 0.99);

private:
  //! The input and the target as a fit from \e start lays them (the sharper at the other's blur); false for a start
  //! off the sizes a view of the target can have.
  static bool laid(const vpMorphRigidShape &input, const vpMorphRigidShape &target, const vpMorphRigidTransform &start,
                   const vpMorphRigidShapeData *&in, const vpMorphRigidShapeData *&tg);
  //! check() from \e start, abandoned above \e abandonAbove when it is >= 0.
  static Result checkFrom(const vpMorphRigidShape &input, const vpMorphRigidShape &target,
                          const vpMorphRigidTransform &start, double abandonAbove);
};

#endif
