/*!
  \file vpMorph.h
  \brief A morph from an input contour to a target contour: correspondence, rigid rectification, Eq. 1.
*/
#ifndef VP_MORPH_H
#define VP_MORPH_H

#include <cstddef>
#include <vector>

#include <visp3/morph/vpMorphContour.h>
#include <visp3/morph/vpMorphCorrespondence.h>
#include <visp3/morph/vpMorphMatcher.h>
#include <visp3/morph/vpMorphRigidTransform.h>

/*!
  \class vpMorph
  \ingroup group_morph
  \brief The paper's modified metamorphosis (section 2): rectify the rigid part first, then the deformation.

  Plain linear interpolation of corresponded vertices (Eq. 1) between two views of the same object that
  differ by a large rotation makes the intermediate contours cross over or collapse (at 180 deg they all pass
  through a point). So the morph first estimates the similarity between the input and the target from the
  correspondence (vpMorphRigidTransform), moves the input by it ("rectified" input), and only then applies
  Eq. 1 between the rectified input and the target, over the same correspondence:
  \f[ S(t)_k = (1 - t)\, \mathrm{rectified}(S^I)_{i_k} + t\, S^T_{j_k}, \qquad k \text{ over the pairs.} \f]

  The correspondence is computed once (by vpMorphMatcher, or reused from a recognition) and is not changed
  by the rectification, as in the paper. All results are value types computed at construction or on demand;
  a vpMorph is immutable and safe to share between threads.

  \code
  vpMorphContour c = vpMorphContourExtractor().extract(I);     // the view, in pixels
  vpMorphContour t = vpMorphContourExtractor().extract(Iref);  // the stored view
  vpMorph morph(c, t);                                         // minimal-work correspondence, rigid fit
  double d = morph.distance();                                 // D_morph (Eq. 4)
  std::vector<vpMorphContour> subgoals = morph.sequence(10);   // rigid frames, then Eq. 1; the last is t
  \endcode
  \sa \ref page_method, \ref page_design_morph
*/
class vpMorph
{
public:
  //! How the rigid part is estimated (see vpMorphRigidTransform).
  enum Estimator {
    ELONGATION,    //!< The paper's elongation vectors (principal axes); ill-posed for isotropic shapes.
    LEAST_SQUARES, //!< Robust weighted least squares over all pairs (default: more accurate, always posed).
    NONE,          //!< No rigid rectification: plain Eq. 1 on the raw input (the paper's failure case, for comparison).
    GIVEN //!< Given by the caller (the constructor that takes it): e.g. fitted on the edges of an occluded view.
  };

  /*!
    Morph with the default matcher (vpMorphWorkModel defaults, scale normalisation on).
    \throw vpMorphException on empty contours or different units (badParameterError); badContourError when the
    rectified input degenerates (rounding merges two of its vertices: scales differing by many orders of magnitude).
  */
  vpMorph(const vpMorphContour &input, const vpMorphContour &target, Estimator estimator = LEAST_SQUARES,
          bool withScale = true);
  //! Morph with a given matcher (its work model and scale normalisation); the matcher is copied, not modified.
  vpMorph(const vpMorphContour &input, const vpMorphContour &target, const vpMorphMatcher &matcher,
          Estimator estimator = LEAST_SQUARES, bool withScale = true);
  /*!
    Morph over a given correspondence, e.g. the one a recognition already computed (no matching is run).
    \throw vpMorphException if the correspondence does not fit the contours.
  */
  vpMorph(const vpMorphContour &input, const vpMorphContour &target, const vpMorphCorrespondence &correspondence,
          Estimator estimator = LEAST_SQUARES, bool withScale = true);

  /*!
    Morph over a given correspondence and a rigid part estimated by the caller (estimator() is GIVEN), for an input
    whose corresponded vertices do not tell its pose: with part of the object hidden, the least-squares fit crowds the
    pairs of the hidden stretch onto the occluder's edge, and its scale carries the missing part into the rigid frames
    (a fit of the view's edges does not).
    \throw vpMorphException as the constructor above.
  */
  vpMorph(const vpMorphContour &input, const vpMorphContour &target, const vpMorphCorrespondence &correspondence,
          const vpMorphRigidTransform &rigid);

  //! The input contour, as given.
  const vpMorphContour &input() const { return m_input; }
  //! The target contour, as given.
  const vpMorphContour &target() const { return m_target; }
  //! How the rigid part was estimated.
  Estimator estimator() const { return m_estimator; }
  //! Whether the rigid part includes a scale (a similarity) or not (rotation and translation only).
  bool withScale() const { return m_withScale; }
  //! The vertex correspondence from the input to the target.
  const vpMorphCorrespondence &correspondence() const { return m_corr; }
  //! Work of the correspondence (D_morph when it came from vpMorphMatcher::match()).
  double distance() const { return m_corr.work(); }
  //! Rigid part, written about the input's centroid (identity for NONE).
  const vpMorphRigidTransform &rigidTransform() const { return m_rigid; }
  //! The input after rigid rectification (the input itself for NONE).
  const vpMorphContour &rectified() const { return m_rectified; }

  /*!
    Deformation at \e t in [0, 1] by Eq. 1 over the pairs. at(0) is rectified(); at(1) is the target itself
    (Eq. 1 would repeat the target vertices that are matched several times). For 0 < t < 1 the contour has one
    vertex per pair, starting at the starting pair, except that exactly coincident consecutive vertices are
    merged.
    \throw vpMorphException::badParameterError if t is not finite or outside [0, 1];
    badContourError if the interpolated polygon degenerates: without rectification (two views far apart in
    rotation), or between very different or very differently scaled shapes, where a vertex can run onto its
    neighbour or all vertices become collinear.
  */
  vpMorphContour at(double t) const;

  /*!
    \e n intermediate contours (virtual images, sub-goals), NOT including the input: nr rigid frames first
    (the input moved by rigidTransform().interpolated(k / nr), k = 1..nr, the last one being rectified()),
    then nd deformation frames at(k / nd), k = 1..nd. nd = max(1, n / 2) and nr = n - nd: half of the frames
    for each stage, with at least the final one, so that n = 1 gives just the target. For NONE, nr = 0.
    The last contour is exactly the target. n = 0 gives an empty vector. With \e longWay the rigid frames turn the
    other way round (vpMorphRigidTransform::interpolated()) to the same rectified contour.
    \throw vpMorphException::badContourError when a frame degenerates (see at(); a rigid frame can too, when the
    input is scaled by orders of magnitude and rounding makes two of its vertices coincide).
  */
  std::vector<vpMorphContour> sequence(std::size_t n, bool longWay = false) const;
  //! input() followed by sequence(n): n + 1 contours, as drawn in the paper's figures.
  std::vector<vpMorphContour> sequenceWithInput(std::size_t n) const;
  //! nr, the number of rigid frames at the start of sequence(n).
  std::size_t rigidFrameCount(std::size_t n) const;

private:
  void build();

  vpMorphContour m_input, m_target;
  Estimator m_estimator;
  bool m_withScale;
  vpMorphCorrespondence m_corr;
  vpMorphRigidTransform m_rigid;
  vpMorphContour m_rectified;
};

#endif
