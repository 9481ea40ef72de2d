/*!
  \file vpMorphHeightFunction.h
  \brief The height-function descriptor of an outline and the cyclic dynamic-programming distance between two.
*/
#ifndef VP_MORPH_HEIGHT_FUNCTION_H
#define VP_MORPH_HEIGHT_FUNCTION_H

#include <cstddef>
#include <vector>

#include <visp3/morph/vpMorphContour.h>

/*!
  \class vpMorphHeightFunction
  \ingroup group_morph
  \brief Shape retrieval's height functions (Wang, Bai, You, Liu and Latecki, Pattern Recognition Letters 2012):
  each point of an outline described by the heights of all the others above its tangent, and two outlines compared
  by the cheapest cyclic correspondence of their points.

  Why: D_morph compares local lengths and turns, so a long, thin limb and a short stub that turn alike cost little;
  a height function sees from every point where the whole rest of the outline lies, which tells such classes apart
  while staying local where it matters (near points weigh most).

  <b>Descriptor</b> (describe()): the outline resampled counter-clockwise to points() points equally spaced by arc
  length; at point i the tangent runs from point i-1 to point i+1; the height of point i+j (j = 0 .. N-1) is its
  signed distance to that tangent line, positive inside. The heights are averaged over segments() runs of N / segments
  consecutive points (the descriptor's entries), and each entry is divided by its largest magnitude over the outline
  (so the descriptor is in [-1, 1] and invariant to scale).

  <b>Distance</b> (distance()): the cost of matching point p of one outline with point q of the other is the weighted
  L1 difference of their descriptors, the weight of entry m falling as 1 / (1 + its segment's distance from the point
  in segments; nearer parts of the outline matter more: they move less under articulation and occlusion); a point
  left unmatched costs getSkipCost(). The distance is the least cost of an order-preserving correspondence (dynamic
  programming) over the starting points of the second outline, divided by the number of points; with mirrors, the
  smaller of the direct and mirrored comparisons. Invariant to a similarity and to the start of the outlines;
  symmetric up to where the cyclic correspondence is cut (at the first outline's first point). Starting points: the
  cost matrix's diagonal sums rank every start in O(N^2), and the dynamic programming runs from the
  getCandidateStarts() cheapest of their local minima (a correspondence that skips points reaches the starts next to
  a candidate, so candidates are distinct basins).

  \code
  const vpMorphHeightFunction h;
  const double d = h.distance(h.describe(contourA), h.describe(contourB));
  \endcode
  \sa vpMorphShapeDistance, \ref page_design_recognition
*/
class vpMorphHeightFunction
{
public:
  //! An outline's descriptor: points() columns of segments() entries, column-major; its mirror image's if used.
  struct Descriptor
  {
    std::vector<float> direct;   //!< entry m of point i at i * segments() + m
    std::vector<float> mirrored; //!< the same for the mirror image (empty without mirrors)
  };

  /*!
    Default settings: 100 points (the published method's count); 20 segments (an entry averages 5 % of the outline,
    the smallest detail the descriptor keeps); skip cost 0.3 (a point of each outline skipped, 0.6, is preferred to a
    match whose descriptors differ by more than 30 % of the largest difference, 2); mirrors; 4 candidate starts (a
    square's four quarter turns each stay a candidate).
  */
  vpMorphHeightFunction();

  //! Points per outline.
  std::size_t getPoints() const { return m_points; }
  //! Segments per descriptor.
  std::size_t getSegments() const { return m_segments; }
  /*!
    \throw vpMorphException::badParameterError unless points >= 8, segments >= 2 and segments divides points.
  */
  void setPoints(std::size_t points, std::size_t segments);
  //! Cost of a point left unmatched.
  double getSkipCost() const { return m_skip; }
  //! \throw vpMorphException::badParameterError unless finite and positive.
  void setSkipCost(double c);
  //! Whether mirror images are compared too.
  bool getMirrors() const { return m_mirrors; }
  //! Compares mirror images too (or not).
  void setMirrors(bool on) { m_mirrors = on; }
  //! Starting points the dynamic programming is run from (0: every start, exact).
  std::size_t getCandidateStarts() const { return m_starts; }
  //! Sets the number of candidate starts (0: every start).
  void setCandidateStarts(std::size_t n) { m_starts = n; }

  /*!
    The descriptor of \e c (see the class description).
    \throw vpMorphException::badContourError on a contour of fewer than 3 vertices or of zero area.
  */
  Descriptor describe(const vpMorphContour &c) const;
  /*!
    Distance between two descriptors (see the class description); \e mirrored (if not null) tells whether b's mirror
    image gave it.
    \throw vpMorphException::badParameterError if either was made with other settings.
  */
  double distance(const Descriptor &a, const Descriptor &b, bool *mirrored = nullptr) const;

private:
  std::vector<float> heights(const vpMorphContour &c) const;
  double oriented(const std::vector<float> &a, const std::vector<float> &b) const;

  std::size_t m_points;
  std::size_t m_segments;
  double m_skip;
  bool m_mirrors;
  std::size_t m_starts;
  std::vector<float> m_weights;
};

#endif
