/*!
  \file vpMorphRigidShape.h
  \brief A contour prepared for fast similarity alignment on another: the first stage of rigid recognition.
*/
#ifndef VP_MORPH_RIGID_SHAPE_H
#define VP_MORPH_RIGID_SHAPE_H

#include <memory>
#include <vector>

#include <visp3/morph/vpMorphContour.h>
#include <visp3/morph/vpMorphRigidTransform.h>

struct vpMorphRigidShapeData; // the prepared data (internal)

/*!
  \class vpMorphRigidShape
  \ingroup group_morph
  \brief A contour with what aligns it on another by a similarity in some tens of microseconds, whatever the turn,
  shift and scale between them and with part of either outline hidden (value type, cheap to copy).

  Why: naming the exact part among look-alikes needs their outlines laid on each other (vpMorphRigidCheck), and
  that needs a start in the right basin for every template of a database. The minimal-work correspondence gives one
  but costs tens of microseconds per pair and is misled by an occluder (the notch is matched somewhere), and the
  region's centroid and area move with the part an occluder hides.

  <b>Frame.</b> Coordinates are taken about the region's centroid in units of the square root of its area (the
  size), so a similarity between two shapes is near a pure turn in these units.

  <b>Alignment of an input on a target</b> (alignOn()), on the outlines smoothed along their length by a Gaussian of
  1 % of the perimeter (the details of a few pixels that blur and a change of depth alter differ from view to view;
  the smoothed outlines do not). When the input's outline tells its own edges (vpMorphContour::ownEdge()), its
  histogram, votes, refinement and input-side cost use those only (as long as at least 4 samples, a similarity's
  parameters, remain): an occluder's edge belongs to no template, and left in, its long straight run is the
  histogram's highest peak and pulls the votes and the fit to the template's straight edges.
  -# Turns: the circular correlation of the two orientation histograms (the outline's length per tangent direction,
     72 bins: a turn moves it round, a shift and a scale do not); its four highest peaks are the candidate turns.
  -# Shifts: per candidate turn, each input sample (every other one) votes, with every target sample whose tangent
     direction agrees within 12.5 deg, for the shift that lays the one on the other (a generalised Hough transform); the
     part an occluder hides casts no vote and an occluder's edge left unmarked votes at random. A hidden part also
     shrinks the input's area, so the input's size overstates the scale, and the area of a thin part varies with its
     edges' blur: the votes are cast at scales 1.05, 0.92 and 0.8 (the true ratio of the two sizes, in [0.75, 1.1] for
     up to 40 % of the area hidden or a thin outline's width off by a tenth, is within 0.07 of one of them), and each
     turn keeps its best-voted scale.
  -# Per candidate turn, a second start: the whole view's, no shift and the sizes' ratio as the scale (a similarity
     lays a whole view's centroid and area on the template's exactly). A scale 0.07 off moves a long or thin
     outline's far end (a snake, a fork) by more than the refinement can pull back, and a view that hides nothing
     needs no vote.
  -# Each is refined by Gauss-Newton on the target's signed distance grid (bilinear, 64 x 64 cells over 1.25 times
     its largest radius), the input's samples with a distance beyond tau() left out: two steps each, after which each
     turn keeps the start that costs less, then up to four more for the two best turns. The one that costs least
     (below) wins; the best that turns elsewhere is kept as the alternative (a nearly symmetric outline). A
     hypothesis whose scale leaves [0.5, 2] sizes is discarded (a fit that shrinks the input to a point lays all its
     samples on one edge).
  -# The winner turned by each of the target's symmetries (symmetries(), found once when it is prepared) that its
     cost cannot rule out (Alignment::symmetric): four candidate turns cannot cover a star's ten alike lobes, and the
     smoothed outlines rank them by chance, so the outlines decide (vpMorphRigidCheck tries each).
  -# The winner turned by every eighteenth of a turn about the target's centre, each refined on this input, and kept
     (Alignment::symmetric) when its cost is at most twice the winner's: a near-isotropic outline (an apple, a watch)
     has no orientation peak to turn on, and an occluder can rank a wrong turn of it first, which no symmetry of the
     target's whole outline describes. 18 turns: the refinement pulls the samples within tau() of the target's edges,
     and a turn of 10 deg moves the outline of a disc of unit area by 0.56 x 0.17 = 0.098 sizes, so every turn lies
     within reach of one of them.
  The cost of the result is the mean distance, truncated at tau() and divided by it, of the input's samples to the
  target plus that of the target's samples to the input (each on the other's grid): 0 for outlines that coincide, 2
  for none in common. It ranks templates; it does not decide (vpMorphRigidCheck does, on the outlines).

  \code
  const vpMorphRigidShape t(templateContour), q(viewContour);
  const vpMorphRigidShape::Alignment a = q.alignOn(t); // a.transform: view pixels -> template pixels
  \endcode
  \sa vpMorphRigidCheck, \ref page_design_recognition
*/
class vpMorphRigidShape
{
public:
  //! A similarity from the input's coordinates to the target's and its cost, as alignOn() measures it.
  struct Hypothesis
  {
    vpMorphRigidTransform transform; //!< input pixels to target pixels
    double cost = 2.0;               //!< its cost, in [0, 2] (see the class description)
  };
  //! A similarity from the input's coordinates to the target's, and the alignment's cost (see the description).
  struct Alignment
  {
    vpMorphRigidTransform transform; //!< input pixels to target pixels
    double cost = 2.0;               //!< the alignment's cost, in [0, 2] (see the class description)
    //! The other refined hypothesis when it turns more than 10 deg away (a nearly symmetric outline), else none.
    vpMorphRigidTransform alternative;
    bool hasAlternative = false; //!< whether \e alternative is set
    /*!
      \e transform followed by each of the target's turns onto itself (symmetries()) that the cost cannot rule out, and
      other than \e alternative: a turn whose own cost is at most twice this alignment's (were the turned hypothesis
      the true one at no more than that cost, the triangle inequality on the truncated distances would bound the
      turn's cost by the sum of the two). Each with its cost, unrefined. Then the turns of the sweep (see the class
      description) that cost at most twice this alignment's, refined, each more than 10 deg from every hypothesis
      before it.
    */
    std::vector<Hypothesis> symmetric;
    //! How many of \e symmetric, first, are the target's turns onto itself (the rest are the sweep's).
    std::size_t selfTurns = 0;
  };
  //! A turn of a shape onto itself, in its normalised frame (X = a x - b y + tx, Y = b x + a y + ty), and its cost.
  struct Symmetry
  {
    double a = 1.0;    //!< scale times the cosine of the turn
    double b = 0.0;    //!< scale times the sine of the turn
    double tx = 0.0;   //!< shift along x (sizes)
    double ty = 0.0;   //!< shift along y (sizes)
    double cost = 2.0; //!< the cost of the shape on itself through it (as an alignment's)
  };

  //! An empty shape (empty() is true).
  vpMorphRigidShape() = default;
  /*!
    Prepares \e c (its measured region and outline when it has them, else its polygon): a few tenths of a millisecond.
    \throw vpMorphException::badContourError on an empty or degenerate contour (fewer than 3 vertices, no area).
  */
  explicit vpMorphRigidShape(const vpMorphContour &c);

  //! Whether the shape was prepared (a default-constructed one is empty).
  bool empty() const { return !m_data; }
  //! The contour it was prepared from.
  const vpMorphContour &contour() const;

  /*!
    This shape aligned on \e target (see the class description).
    \throw vpMorphException::badParameterError when either is empty.
  */
  Alignment alignOn(const vpMorphRigidShape &target) const;
  //! alignOn(), with Alignment::symmetric left empty unless \e symmetric: for a caller that needs only the cost or
  //! the transform.
  Alignment alignOn(const vpMorphRigidShape &target, bool symmetric) const;
  /*!
    The cost of \e transform (this shape's pixels to the target's) as alignOn() measures it, without search.
    \throw as alignOn().
  */
  double cost(const vpMorphRigidShape &target, const vpMorphRigidTransform &transform) const;

  /*!
    The shape's near-symmetries: every peak of its orientation histogram's correlation with itself, more than 10 deg
    from no turn, refined on its own distance grid as an alignment's turns are, with its cost (least first). A star of
    five alike lobes has four cheap ones: the smoothed outlines the coarse stage compares cannot tell its lobes apart,
    and only the outlines can (vpMorphRigidCheck, from each hypothesis in Alignment::symmetric).
  */
  const std::vector<Symmetry> &symmetries() const;

  /*!
    This shape as an image of the part blurred to an outline blur of \e blur (pixels, as vpMorphContour::outlineBlur()
    measures it) would show it: the nearest to \e blur of this shape and the rungs of its blur ladder, blurs
    blurRung() apart, each laid by vpMorphOutlineBlur and prepared on first use (a few milliseconds), then kept and
    shared by the shape's copies (thread-safe; the reference lives as long as any copy). A blur rounds the details
    finer than itself, so outlines measured at different blurs differ there by more than their noise: the exact
    comparison (vpMorphRigidCheck) lays the sharper at the other's blur. This shape itself for a blur not above its
    own, a contour without a measured outline or in NORMALIZED units, and a part that the blur would erase.
    \throw vpMorphException::badParameterError when the shape is empty.
  */
  const vpMorphRigidShape &atBlur(double blur) const;
  /*!
    Spacing of the blur ladder (pixels): half a pixel, vpMorphRigidCheck's tolerance between measured outlines. A blur
    off by half a rung moves a straight edge not at all and a right-angled corner's tip by 0.77 times that, a fifth of a
    pixel.
  */
  static double blurRung() { return 0.5; }

  //! Distance (in sizes) beyond which a sample is an outlier: a tenth of the size, a few percent of a part's length.
  static double tau() { return 0.1; }

private:
  //! Appends to \e a.symmetric the hypotheses that alignOn() describes there (\e a from alignOn(target, false)).
  void addSymmetric(const vpMorphRigidShape &target, Alignment &a) const;

  friend class vpMorphRigidCheck;  // the fine stage reads the prepared outline
  friend class vpMorphRigidSearch; // the search asks the cache for the next template's data and adds the symmetric
                                   // hypotheses to its shortlist's alignments only
  std::shared_ptr<const vpMorphRigidShapeData> m_data;
};

#endif
