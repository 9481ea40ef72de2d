/*!
  \file vpMorphPolygonApproximation.h
  \brief Parameterless polygonal approximation of a closed digital boundary.
*/
#ifndef VP_MORPH_POLYGON_APPROXIMATION_H
#define VP_MORPH_POLYGON_APPROXIMATION_H

#include <vector>

#include <visp3/core/vpImagePoint.h>
#include <visp3/morph/vpMorphContour.h>

/*!
  \class vpMorphPolygonApproximation
  \ingroup group_morph
  \brief Turns a closed 8-connected pixel chain into a polygon, with no parameter to tune.

  The paper segments contours with a parameterless, linear-time method that places the vertices by minimising
  the sum of absolute (L1) errors of the piecewise-linear approximation. This class implements a documented
  equivalent in three stages; every threshold comes from the pixel grid itself, never from the user.

  <b>Digitisation bound.</b> For an edge (chord) of direction phi, a boundary pixel of a digital straight
  segment lies within half the unit pixel projected on the edge normal, 0.5 (|cos phi| + |sin phi|), of the
  true straight edge, and so does each digitised chord end; the worst-case distance of a pixel of a straight
  edge from its digitised chord is therefore t(phi) = |cos phi| + |sin phi| (1 to sqrt(2) px), the first-order
  tolerance of Prasad et al.'s parameter-free Ramer-Douglas-Peucker (Image Vis. Comput. 2012). Any deviation
  within t(phi) cannot be told from sampling, any larger one is shape.

  -# <b>Split.</b> Start from the two mutually farthest boundary pixels (diameter of the convex hull, ties
     broken by coordinates), so the result does not depend on where the chain starts. Each of the two arcs is
     split recursively at its pixel farthest from the chord while that distance exceeds t(phi).
  -# <b>L1 refinement.</b> Each vertex slides along the chain, strictly between its two neighbours, to the
     pixel that minimises \f$ \sum_i |d_i| \f$, the sum of the distances of the chain pixels of its two
     adjacent edges to those edges (the paper's L1 criterion). Vertices are visited in turn until no vertex
     moves (each move lowers the total L1 error, so this terminates).
  -# <b>Merge.</b> A vertex is removed (smallest error first) while the merged edge's mean absolute
     deviation \f$ \frac{1}{n}\sum_i |d_i| \f$ stays within 3 t(phi)/4 and its maximal deviation within
     2 t(phi). 3 t(phi)/4 is the largest mean that digitisation alone can produce: a pixel's own error is
     uniform within +-t(phi)/2 (mean t(phi)/4), and the digitised chord ends shift the chord by at most
     t(phi)/2. The L1 average absorbs zero-mean boundary jitter; the max bound (one pixel step beyond twice the
     sampling error) keeps narrow features such as a key tooth. Merging and L1 refinement alternate until no
     vertex is removed.

  The result keeps chain pixel centres as vertices, so it stays within about t(phi) of the boundary.
  It is returned counter-clockwise in the (x = u, y = v) axes (positive vpMorphContour::signedArea(); in the
  image, with v pointing down, this appears clockwise) and simple (vpMorphContour::isSimple()): if a stage
  produces self-intersections (hair-thin parts where the chain runs back over itself), the previous stage's
  polygon is used, then vertices that create crossings are dropped.

  Complexity for a chain of N pixels and V vertices: split and merge O(N V) in the worst case; one refinement
  sweep O(N^2 / V) for evenly spread vertices. It is not linear like the cited method: an exact L1 placement
  needs no search window, which would be a parameter.

  \code
  std::vector<vpImagePoint> chain = vpMorphContourExtractor().boundary(I); // 8-connected pixel centres
  vpMorphContour polygon = vpMorphPolygonApproximation::approximate(chain);
  \endcode
  \sa vpMorphContourExtractor, \ref page_design_morph
*/
class vpMorphPolygonApproximation
{
public:
  /*!
    Polygon (PIXEL units, x = u, y = v) approximating a closed 8-connected chain of pixel centres, as given by
    cv::findContours with CHAIN_APPROX_NONE (the last pixel is adjacent to the first, not repeated).
    Throws vpMorphException::badContourError when the chain has fewer than 3 distinct pixels or encloses no
    area (a one-pixel-wide line), or when no simple polygon can be formed.
  */
  static vpMorphContour approximate(const std::vector<vpImagePoint> &chain);

  //! Digitisation tolerance t(phi) = |cos phi| + |sin phi| of a chord from (x0, y0) to (x1, y1), in pixels.
  static double tolerance(double x0, double y0, double x1, double y1);

  /*!
    Chain indices (into \e chain) of the polygon vertices, before orientation; the same vertices as
    approximate(), exposed so that callers can relate each vertex to its boundary arc.
  */
  static std::vector<std::size_t> vertexIndices(const std::vector<vpImagePoint> &chain);
};

#endif
