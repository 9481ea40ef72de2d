/*!
  \file vpMorphContour.h
  \brief A closed polygon, the shape the morph works on.
*/
#ifndef VP_MORPH_CONTOUR_H
#define VP_MORPH_CONTOUR_H

#include <cstddef>
#include <memory>
#include <vector>

#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpImagePoint.h>

/*!
  \class vpMorphContour
  \ingroup group_morph
  \brief Closed polygon (value type) in pixel or normalised image coordinates.

  Vertices are stored as (x, y) pairs: in pixels x = u (column) and y = v (row); in normalised coordinates
  x = X/Z and y = Y/Z. The edge from the last vertex back to the first is implicit.

  A valid contour has at least 3 finite vertices, no two consecutive vertices equal, and a non-zero area;
  its coordinates must be within maxCoordinate() in magnitude and its edge lengths representable in double
  precision (no edge whose length underflows to 0: vertices about 1e-160 apart are refused);
  the constructors check this and throw vpMorphException otherwise, so every algorithm downstream can rely
  on it. Self-intersection is not rejected at construction (linear morphs may legitimately produce it):
  test it with isSimple().

  A contour extracted from an image (vpMorphContourExtractor) also carries the region it approximates (grey-level
  area, centroid and second moments, hasRegion()) and the object's dense edge outline (hasOutline()); geometric
  operations carry both along.

  \code
  vpMorphContour c({0, 100, 100, 0}, {0, 0, 50, 50});        // a 100 x 50 px rectangle, counter-clockwise
  double a = c.area();                                        // 5000 px^2
  vpMorphContour m = c.transformed(M_PI / 2, 10, 0);          // turned about its centroid, moved 10 px in x
  vpMorphContour n = c.toNormalized(cam);                     // x = (u - u0) / px, y = (v - v0) / py
  \endcode
  \throw vpMorphException::badContourError on an invalid polygon (constructors).
  \sa vpMorphContourExtractor, \ref page_design_morph
*/
class vpMorphContour
{
public:
  //! Coordinate system of the vertices.
  enum Units {
    PIXEL,     //!< x = u (column), y = v (row), in pixels.
    NORMALIZED //!< x = X/Z, y = Y/Z (metric image plane at unit depth).
  };

  //! Empty contour (size() == 0); the only invalid state, produced only by default construction.
  vpMorphContour() = default;
  //! From the vertices' coordinates (same length). \throw vpMorphException::badContourError on an invalid polygon.
  vpMorphContour(const std::vector<double> &x, const std::vector<double> &y, Units units = PIXEL);
  //! From ViSP image points: x = get_u(), y = get_v().
  explicit vpMorphContour(const std::vector<vpImagePoint> &points, Units units = PIXEL);

  //! Largest coordinate magnitude accepted (1e75): the moments of the region (fourth powers) must stay finite.
  static double maxCoordinate() { return 1e75; }

  //! Number of vertices.
  std::size_t size() const { return m_x.size(); }
  //! True only for a default-constructed contour.
  bool empty() const { return m_x.empty(); }
  //! Coordinate system of the vertices.
  Units units() const { return m_units; }
  //! x of vertex k (k < size(), unchecked).
  double x(std::size_t k) const { return m_x[k]; }
  //! y of vertex k (k < size(), unchecked).
  double y(std::size_t k) const { return m_y[k]; }
  //! All x coordinates.
  const std::vector<double> &xs() const { return m_x; }
  //! All y coordinates.
  const std::vector<double> &ys() const { return m_y; }
  //! Vertex k as a ViSP image point (u = x, v = y).
  vpImagePoint point(std::size_t k) const { return vpImagePoint(m_y[k], m_x[k]); }
  //! All vertices as ViSP image points (u = x, v = y).
  std::vector<vpImagePoint> points() const;

  //! Signed area (shoelace); positive when the vertices turn counter-clockwise in the (x, y) axes.
  double signedArea() const;
  //! Area of the polygon (absolute value of signedArea()).
  double area() const;
  //! True when the vertices turn counter-clockwise in the (x, y) axes.
  bool isCounterClockwise() const { return signedArea() > 0.0; }
  //! Sum of the edge lengths, the closing edge included.
  double perimeter() const;
  /*!
    Area of the intersection of this polygon's region with \e other's (both simple; either orientation), exact
    (Green's theorem over the pieces of each boundary inside the other region). With area(), it measures how well
    two shapes overlay: intersection over union = overlap / (area() + other.area() - overlap).
    \throw vpMorphException on an empty contour or different units.
  */
  double overlapArea(const vpMorphContour &other) const;
  //! Area centroid (x, y) of the polygon.
  void centroid(double &cx, double &cy) const;

  /*!
    Area, centroid and second-order central moments of the image region this polygon approximates, when they were
    measured on the image (by vpMorphContourExtractor, to a fraction of a pixel). Why: the polygon's own area and
    centroid move when a vertex appears or shifts from one image to the next; the region's grey-level moments do not.
    Geometric operations carry the region along (similarities, unit changes, mirroring, re-ordering, resampling);
    constructors leave it unset.
  */
  bool hasRegion() const { return m_regionArea > 0.0; }
  /*!
    Sets the measured region: area > 0, finite centroid and finite central moments mu20, mu11, mu02 divided by
    the area (a positive semi-definite matrix), in this contour's units; throws vpMorphException otherwise.
  */
  void setRegion(double area, double cx, double cy, double mu20, double mu11, double mu02);
  //! The measured region's area, or the polygon's area() when none was measured.
  double regionArea() const { return hasRegion() ? m_regionArea : area(); }
  //! The measured region's centroid, or the polygon's centroid() when none was measured.
  void regionCentroid(double &cx, double &cy) const;
  //! The measured region's central moments mu20, mu11, mu02 divided by its area, or the polygon's when none was
  //! measured.
  void regionMoments(double &mu20, double &mu11, double &mu02) const;
  /*!
    The object's edge as measured on the image, densely (about a point per boundary pixel, each from the grey
    levels across the edge, to a few hundredths of a pixel on a clean image), when vpMorphContourExtractor
    measured it. Why: an out-of-plane tilt shows only in the perspective distortion of the outline, a fraction of a
    pixel, below what a polygon keeps. Geometric operations carry it along as they carry the region; constructors
    leave it unset.
  */
  bool hasOutline() const { return static_cast<bool>(m_outline); }
  //! The measured edge outline, or this polygon when none was measured.
  const vpMorphContour &outline() const { return m_outline ? *m_outline : *this; }
  /*!
    Sets the measured edge outline: a valid contour (at least 4 vertices) in this contour's units; its own outline
    and region, if any, are dropped, its ownEdge() marks kept. \e blur: the edge's blur where it was measured, in the
    same units (the std of the Gaussian that spreads a sharp step as the image did, the pixel's area included; 0:
    unknown). Throws vpMorphException otherwise (and on a negative or non-finite blur).
  */
  void setOutline(const vpMorphContour &outline, double blur = 0.0);
  /*!
    The measured outline's blur (this contour's units; 0: unknown or no outline). Why: a blurred image rounds every
    detail of an edge finer than its blur, so two outlines of one object compare only at one blur
    (vpMorphOutlineBlur).
  */
  double outlineBlur() const { return m_outlineBlur; }
  /*!
    Whether the edge from vertex k to the next is the object's own edge, as the extractor measured it on the image
    (vpMorphContourExtractor marks its edge outline's vertices): beyond it lies the background or the object itself,
    not an occluder, and it is no bridge across a gap. Why: an occluder only hides, so a view of a part shows nothing
    of its own edge that the part's template lacks, while an occluder's edge belongs to no template. false where not
    measured; geometric operations carry the marks along.
  */
  bool ownEdge(std::size_t k) const { return k < m_ownEdges.size() && m_ownEdges[k] != 0; }
  //! Whether ownEdge() was measured.
  bool hasOwnEdges() const { return !m_ownEdges.empty(); }
  //! Sets ownEdge() per vertex (size() marks; an empty vector clears them). Throws vpMorphException otherwise.
  void setOwnEdges(const std::vector<bool> &marks);
  /*!
    Moves the measured region and edge outline (if any) by the affine map x' = A x + b, A = [a11 a12; a21 a22] (the
    outline's blur scaled by sqrt |det A|):
    for geometric operations on the vertices defined outside this class (vpMorphRigidTransform::apply), so that
    they follow their polygon.
  */
  void mapRegion(double a11, double a12, double a21, double a22, double b1, double b2);
  /*!
    Orientation of the principal (elongation) axis of the polygon region, in radians in (-pi/2, pi/2],
    from its second-order central moments; meaningless for a shape with isotropic moments (a disc, a square).
  */
  double orientation() const;
  //! Length of edge k, from vertex k-1 to vertex k (cyclically), so edge 0 closes the polygon.
  double edgeLength(std::size_t k) const;
  //! Signed turning angle at vertex k in (-pi, pi]: positive for a left turn.
  double turningAngle(std::size_t k) const;
  //! True when no two non-adjacent edges intersect and adjacent edges do not fold back onto each other.
  bool isSimple() const;

  //! Same polygon with vertex k first.
  vpMorphContour rotatedStart(std::size_t k) const;
  //! Same polygon traversed the other way round (vertex 0 stays first).
  vpMorphContour reversed() const;
  //! Mirror image about the vertical axis through the centroid (x -> 2 cx - x); keeps the orientation sign.
  vpMorphContour mirrored() const;
  //! Counter-clockwise version (reversed if needed).
  vpMorphContour counterClockwise() const;
  /*!
    Similarity transform about the centroid: scale by \e s, rotate by \e theta (radians, counter-clockwise
    in the (x, y) axes), then translate by (tx, ty).
  */
  vpMorphContour transformed(double theta, double tx, double ty, double s = 1.0) const;
  //! Translated and scaled so that its centroid is at the origin and its perimeter is 1.
  vpMorphContour normalized() const;
  //! \e n vertices equally spaced along the perimeter, starting at vertex 0.
  vpMorphContour resampled(std::size_t n) const;
  //! Pixel to normalised coordinates with the camera intrinsics (no distortion).
  vpMorphContour toNormalized(const vpCameraParameters &cam) const;
  //! Normalised to pixel coordinates with the camera intrinsics (no distortion).
  vpMorphContour toPixels(const vpCameraParameters &cam) const;

private:
  void validate() const;
  // The polygon region's central moments divided by its area (Green's theorem).
  void polygonMoments(double &mu20, double &mu11, double &mu02) const;

  std::vector<double> m_x, m_y;
  Units m_units = PIXEL;
  double m_regionArea = 0.0, m_regionCx = 0.0, m_regionCy = 0.0; // area 0: not measured
  double m_regionMu20 = 0.0, m_regionMu11 = 0.0, m_regionMu02 = 0.0;
  std::shared_ptr<const vpMorphContour> m_outline; // shared: contours are copied often, the outline is not changed
  double m_outlineBlur = 0.0;
  std::vector<char> m_ownEdges; // ownEdge() per vertex; empty: not measured
};

#endif
