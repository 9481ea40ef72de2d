/*!
  \file vpMorphContourExtractor.h
  \brief Automatic object segmentation and outer-contour extraction, with nothing to tune.
*/
#ifndef VP_MORPH_CONTOUR_EXTRACTOR_H
#define VP_MORPH_CONTOUR_EXTRACTOR_H

#include <cstddef>
#include <vector>

#include <visp3/core/vpImage.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpRGBa.h>
#include <visp3/morph/vpMorphContour.h>

/*!
  \class vpMorphContourExtractor
  \ingroup group_morph
  \brief Finds the objects of an image and returns their outer boundaries as polygons (PIXEL units).

  The paper extracts contours automatically; so does this class, without any parameter:
  - <b>Classes:</b> two classes of grey levels, Otsu's split generalised to a light that falls off across the image
    (it shades the plane and the object alike: one affine shading times each class's level): when a class of Otsu's
    split shows a slope, the shading and the levels are fitted by least squares on the classes' own surfaces and each
    pixel given to the nearer level until none moves, from Otsu's split and from Otsu's split of the image with the
    plane's trend removed, the split with the lower within-class deviation kept (pixels at 0 or 255 bound their level);
    an evenly lit view keeps Otsu's threshold.
  - <b>Polarity:</b> the object is the class that does NOT dominate the image border, because a camera frames
    an object inside its background: the border pixels are mostly background whether the object is dark on
    light (Kimia-99, the project's own silhouettes) or light on dark (MPEG-7). If both classes cover exactly
    half of the border, the class with fewer pixels in the whole image is the object.
  - <b>Regions:</b> outer boundaries of the 8-connected object regions (holes are ignored), as 8-connected
    chains of pixel centres (x = u, y = v). The binary image is padded with one pixel of background first, so
    an object that touches or crosses the image border is closed along the border.
  - <b>Validity floor:</b> a region must enclose an area of at least minRegionArea() square pixels (a 3x3
    pixel block) to be an object. Smaller specks cannot form a polygon of non-zero area; this is a safety floor
    of the pixel grid, not a tuning knob.
  - <b>Which region:</b> extract() takes the largest. Where a larger region may be in view (a distractor, the floor
    beyond the plane's edge), extractCandidates() lists the outlines the object may have for a template database to
    choose on a first image, and extractJoined(I, previous) follows the chosen one in the next images.
  - <b>Own edges:</b> each point of the edge outline is marked (vpMorphContour::ownEdge()) as the object's own edge
    when beyond it, past the edge's blur, lies the background (a grey level within 4 sigma of the background's, fitted
    along the outline) or the object itself (a groove), and no bridge of a joined silhouette runs to the next point:
    an occluder's edge and a bridge are not, so that a comparison with a template does not take them for the part's.
  - <b>Polygon:</b> vpMorphPolygonApproximation (parameterless, L1 vertex placement, counter-clockwise in
    the (x, y) axes).

  Regions are ordered by decreasing enclosed area (ties by top-most, then left-most boundary pixel), so the
  result does not depend on the scan order. Bad input (empty, smaller than 3x3, uniform, no object) throws
  vpMorphException::badImageError with a message saying which.

  \code
  vpImage<unsigned char> I;
  vpImageIo::read(I, "view.png");
  vpMorphContour c = vpMorphContourExtractor().extract(I); // largest object, polygonised, region and outline

  // In a servo loop, among other regions: recognised once, then followed.
  std::size_t chosen = 0;
  const std::vector<vpMorphContour> candidates = vpMorphContourExtractor().extractCandidates(I);
  vpMorphRecognition r = db.recognize(candidates, chosen);
  vpMorphContour last = candidates[chosen];
  // ... next image: last = vpMorphContourExtractor().extractJoined(I, last);
  \endcode
  \sa vpMorphPolygonApproximation, \ref page_design_morph
*/
class vpMorphContourExtractor
{
public:
  vpMorphContourExtractor() = default;

  //! Outer boundary of the largest object, polygonised.
  vpMorphContour extract(const vpImage<unsigned char> &I) const;
  //! Same on a colour image (converted to grey levels with vpImageConvert).
  vpMorphContour extract(const vpImage<vpRGBa> &I) const;

  /*!
    The largest object and the pieces an occluder cut from it, as one outline: every region of at least
    joinedMinShare() of the largest one's area, whose boundary comes within joinedMaxGap() times the largest
    one's bounding-box diagonal of the group (nearest first), is joined to it across the gap by the convex hull
    of both boundaries' cut edges: their pixels within 1.5 gaps of the closest pair and within the gap (plus a
    quarter, at least 2 px) of the other side. A limb cut straight across is closed with its own width, and the
    rest of a bow or a head near a long cut stays out of the hull. Why: a card lying across a thin tool leaves two
    pieces, and the largest piece alone is another shape. Without such pieces it is extract(); a joined outline
    carries no region (part of its area is bridged, not seen), but its edge outline, from the largest piece's grey
    levels (where it crosses the bridge there is no edge). \throw vpMorphException::badImageError as extract().
  */
  vpMorphContour extractJoined(const vpImage<unsigned char> &I) const;
  //! Same on a colour image.
  vpMorphContour extractJoined(const vpImage<vpRGBa> &I) const;
  /*!
    The object that continues \e previous (its outline in the last image, PIXEL units), among regions that may be
    larger (a distractor, the floor beyond the plane's edge): extractJoined() restricted to the regions that overlap
    \e previous (the largest of them joined with the others near it). Why: between two images the object moves less
    than the gap that separates it from other regions, so where it was tells it from them without a rule on size,
    and an occluder's cut pieces, which lie where the object was, are joined back. A fast motion moves a small piece
    farther than its own size: a caller that knows the camera's motion since passes \e previous moved by it. The grey
    classes are fitted on the whole image, but the pixels are classified and traced in a window about \e previous
    (its box grown by a quarter of its diagonal) when the regions that overlap \e previous lie inside it, in the whole
    image otherwise: the answer of the whole image at the window's cost (but for an object seen inside a hole of
    another region, which the whole image's outer boundaries miss). An empty \e previous gives extractJoined(I).
    \throw vpMorphException::badImageError as extract(), and when no region overlaps \e previous (the object left the
    view or is lost); badParameterError when \e previous is not in PIXEL units.
  */
  vpMorphContour extractJoined(const vpImage<unsigned char> &I, const vpMorphContour &previous) const;
  //! Same on a colour image.
  vpMorphContour extractJoined(const vpImage<vpRGBa> &I, const vpMorphContour &previous) const;
  /*!
    The outlines the object may have, for a first image where nothing says which region it is: for each region of at
    least joinedMinShare() of the largest one's area (largest first), and for the largest region seen whole (one the
    image's border does not cut: the largest may be the floor beyond the plane's edge, whose area says nothing of the
    object's), the region joined with the smaller pieces near it (extractJoined()'s rule around it), then, when a
    piece was joined, the region alone. The first is
    extractJoined(I). A template database tells which one shows a known part (vpMorphDatabase::recognize() on a
    list); extractJoined(I, previous) follows it afterwards. \throw vpMorphException::badImageError as extract().
  */
  std::vector<vpMorphContour> extractCandidates(const vpImage<unsigned char> &I) const;
  //! Same on a colour image.
  std::vector<vpMorphContour> extractCandidates(const vpImage<vpRGBa> &I) const;
  //! Smallest area of a piece joined by extractJoined(), as a share of the largest region's (smaller: specks).
  static double joinedMinShare() { return 0.1; }
  //! Largest gap bridged by extractJoined(), as a share of the largest region's bounding-box diagonal.
  static double joinedMaxGap() { return 0.5; }

  //! Outer boundaries of every object region, polygonised, largest first.
  std::vector<vpMorphContour> extractAll(const vpImage<unsigned char> &I) const;
  //! Same on a colour image.
  std::vector<vpMorphContour> extractAll(const vpImage<vpRGBa> &I) const;

  //! Raw outer boundary of the largest object: closed 8-connected chain of pixel centres (u, v).
  std::vector<vpImagePoint> boundary(const vpImage<unsigned char> &I) const;
  //! Same on a colour image.
  std::vector<vpImagePoint> boundary(const vpImage<vpRGBa> &I) const;

  //! Raw outer boundaries of every object region, largest first.
  std::vector<std::vector<vpImagePoint>> boundaries(const vpImage<unsigned char> &I) const;
  //! Same on a colour image.
  std::vector<std::vector<vpImagePoint>> boundaries(const vpImage<vpRGBa> &I) const;

  /*!
    Binary object mask (255 = object, 0 = background) after the automatic classes and polarity choice:
    what the boundaries are traced on, for display and debugging.
  */
  vpImage<unsigned char> objectMask(const vpImage<unsigned char> &I) const;
  /*!
    Otsu's threshold of \e I, from which the classes of objectMask() start (a pixel above it is on the bright side):
    cv::threshold()'s THRESH_OTSU arithmetic, on a histogram counted in one pass in which runs of 8 equal pixels (a
    rendered background) count at once, and which also gives the image's range (no second pass for the uniform check).
    \throw vpMorphException::badImageError on an empty image.
  */
  static int otsuThreshold(const vpImage<unsigned char> &I);

  //! Smallest area (square pixels, enclosed by the boundary chain) of a region counted as an object.
  static double minRegionArea() { return 4.0; }
  //! Smallest image side accepted.
  static unsigned int minImageSize() { return 3; }
};

#endif
