/*!
  \file vpMorphMatcher.h
  \brief Minimal-work cyclic correspondence between two polygons and the morph distance D_morph.
*/
#ifndef VP_MORPH_MATCHER_H
#define VP_MORPH_MATCHER_H

#include <cstddef>
#include <vector>

#include <visp3/morph/vpMorphContour.h>
#include <visp3/morph/vpMorphCorrespondence.h>
#include <visp3/morph/vpMorphWorkModel.h>

/*!
  \class vpMorphMatcher
  \ingroup group_morph
  \brief Finds the vertex correspondence that morphs an input polygon A (m vertices) into a target B
  (n vertices) with the least stretching + bending work, and D_morph (Eq. 4), its minimum over all starting pairs.

  <b>The exact model.</b> A correspondence is a closed monotone path on the m x n torus of vertex pairs:
  from pair (i, j) it steps to (i+1, j+1) (both advance), (i+1, j) (only A advances: B's vertex j is matched
  again) or (i, j+1) (only B advances). Each step is charged when it enters its cell (i, j), and the charge
  depends only on that cell and that step, which is what makes the fast search below exact:
  - stretching, Eq. 2: the step creates one segment of the morph polygon; its input length is
    \f$l^A_i = |A_i - A_{i-1}|\f$ if A advances, else 0, and its target length \f$l^B_j\f$ likewise;
    the charge is vpMorphWorkModel::stretching(l^A, l^B) (a zero length is a collapsed segment, \f$k_s L / c_s\f$);
  - bending, Eq. 3: the morph polygon turns at the new vertex by \f$\phi^A_i\f$ (A's signed turning angle at
    vertex i) on the input side if A advances, else by 0 (a repeated vertex does not turn again), and by
    \f$\phi^B_j\f$ or 0 on the target side; the charge is vpMorphWorkModel::bending(phi^A, phi^B).
    So a vertex of A matched to several vertices of B bends once, on the first of its pairs, and the
    vertices of B it is also matched to are straightened from their turning angle to 0.
  The total work of a correspondence is the sum over its steps; it is the same whichever pair is taken as
  the start.

  <b>Invariance.</b> Lengths and turning angles do not change under translation or rotation. With
  scale normalisation (the default, needed for recognition) both polygons are scaled to unit perimeter
  first, so the work is scale invariant too. Both polygons are traversed with positive signed area
  (reversed internally if needed; indices are reported in the caller's numbering), so the work does not
  depend on the direction in which vertices were listed. The model is symmetric in A and B, so distance(A, B) ==
  distance(B, A).

  <b>Search.</b> Every closed path matches A's vertex 0, so the minimum over all m n starting pairs equals
  the minimum over the n paths that start at (0, b), b = 0..n-1, and end at (m, b + n) on the grid where B is
  doubled. matchFromStart() runs the O(mn) dynamic programme for one start; matchBruteForce() runs it for
  every b (O(m n^2)); match() is exact and fast: optimal paths of different starts never need to cross, so Maes'
  divide and conquer solves the middle start, then recurses on each half inside the band left between the
  bounding paths (O(mn log n)), skipping a small range of starts whose lower bound (one programme from all its
  starts at once) is no better than the best found. matchWindow() does the same for the starts near a given one,
  for tracking from frame to frame.

  Not thread safe (it reuses its buffers); copy one per thread.

  \code
  vpMorphMatcher matcher;                              // vpMorphWorkModel defaults, scale normalized
  vpMorphCorrespondence c = matcher.match(A, B);       // exact minimum over all starting pairs
  double D = c.work();                                 // D_morph(A, B) == D_morph(B, A)
  \endcode
  \sa vpMorphWorkModel, vpMorph, \ref page_method, \ref page_design_morph
*/
class vpMorphMatcher
{
public:
  //! A matcher with the work model \e model, scaling both polygons to unit perimeter when \e normalizeScale.
  explicit vpMorphMatcher(const vpMorphWorkModel &model = vpMorphWorkModel(), bool normalizeScale = true);

  //! The work model (Eq. 2-3).
  const vpMorphWorkModel &model() const { return m_model; }
  //! Sets the work model.
  void setModel(const vpMorphWorkModel &model) { m_model = model; }
  //! Whether both polygons are scaled to unit perimeter before matching (default true).
  bool scaleNormalization() const { return m_normalizeScale; }
  //! Turns the scale normalization on or off.
  void setScaleNormalization(bool on) { m_normalizeScale = on; }

  //! Minimal-work correspondence with input vertex \e a matched first to target vertex \e b.
  vpMorphCorrespondence matchFromStart(const vpMorphContour &A, const vpMorphContour &B, std::size_t a, std::size_t b);
  //! Exact D_morph correspondence by running matchFromStart() from every target vertex (reference).
  vpMorphCorrespondence matchBruteForce(const vpMorphContour &A, const vpMorphContour &B);
  //! Exact D_morph correspondence, fast (divide and conquer over starts, with band pruning).
  vpMorphCorrespondence match(const vpMorphContour &A, const vpMorphContour &B);
  /*!
    Best correspondence among the starts (a, b) with b within \e halfWidth of \e bCenter (cyclically):
    exact within that window. Used to track a correspondence from one frame to the next.
  */
  vpMorphCorrespondence matchWindow(const vpMorphContour &A, const vpMorphContour &B, std::size_t a,
                                    std::size_t bCenter, std::size_t halfWidth);
  //! D_morph(A, B) = match(A, B).work().
  double distance(const vpMorphContour &A, const vpMorphContour &B);
  /*!
    match(), checked against the two regions: the minimal-work correspondence, unless the similarity fitted to it
    lays A's region on B's clearly worse than another rotation does. Then the least work among the starts whose
    own fitted rotation agrees with that placement (within the 30 deg sampling's half step).
    Why: the work compares shapes, not placements. Two views of one object that differ by a deformation (a
    wedge whose top sags) can cost less work matched half a turn round, a correspondence under which no rigid
    move lays one view on the other (\ref page_design_morph). The placements are compared by intersection over union,
    both at the area-ratio scale and refined on the overlap (vpMorphRigidTransform::refineOnOverlap()); the others are
    sampled every 30 deg about the centroids, and only the best of them is refined. Views that the minimal-work
    placement already covers to within \e minGain are not searched (the usual case: a rigid view covers itself to 1).
    Where the regions cannot be compared (self-intersecting contours, a placement degenerate in floating point), the
    minimal work decides.
    A view whose regions leave the choice to the work is then checked on the outlines, half a turn round: an
    occluded view's region is not its target's, so no placement wins on the regions, and the work can match a
    nearly symmetric outline end for end. The share of
    B's outline that A shows, laid from the work's robust fit and from that fit turned half a turn about B's centroid
    (each refined point to edge both ways, as vpMorphDatabase::support() measures it), picks the placement when it
    wins by \e minGain and shows at least 3/4 of B's outline (what an occluder hiding a fifth of it leaves).
    \param minGain the intersection over union, or the share of B's outline, the other placement must win by, in
    (0, 1].
    \param gain if not null, receives that win when the correspondence was replaced, else 0.
    \param leastWork if not null, match(A, B) already computed by the caller, which is then not solved again.
    \throw vpMorphException as match(), and on a bad \e minGain.
  */
  vpMorphCorrespondence matchOnRegions(const vpMorphContour &A, const vpMorphContour &B, double minGain = 0.1,
                                       double *gain = nullptr, const vpMorphCorrespondence *leastWork = nullptr);

private:
  //! The columns a path of the grid spans in each row (leftmost, rightmost): the bounds of Maes' bands.
  struct Path
  {
    std::vector<int> left, right;
  };
  //! Best start found so far, with the band it was solved in.
  struct Best
  {
    double work = 0.0;
    int b = 0;
    bool hasLo = false, hasHi = false; // bounded on that side
    Path lo, hi;
  };
  static void checkStart(const vpMorphContour &A, const vpMorphContour &B, std::size_t a, std::size_t b);
  void prepare(const vpMorphContour &A, const vpMorphContour &B, std::size_t a, std::size_t b);
  double solveStart(int b, const Path *lo, const Path *hi, Path *extent, std::vector<std::pair<int, int>> *cells,
                    int bLast = -1);
  void solveBetween(int bLo, int bHi, const Path *lo, const Path *hi, std::size_t depth, Best &best);
  vpMorphCorrespondence solveRange(int count);
  vpMorphCorrespondence toCorrespondence(const std::vector<std::pair<int, int>> &cells, double tableWork);
  //! The least work among the starts whose fitted rotation is within \e tolerance of \e theta; false if none.
  bool matchTurned(const vpMorphContour &A, const vpMorphContour &B, double theta, double tolerance,
                   vpMorphCorrespondence &placed);

  vpMorphWorkModel m_model;
  bool m_normalizeScale;

  // The prepared problem: A rotated so that grid row 0 is its vertex m_a0; B rotated so that grid column 0
  // is its vertex m_b0, traversed backwards when the orientations differ, and doubled (columns 0 .. 2n-1).
  std::size_t m_m = 0, m_n = 0, m_a0 = 0, m_b0 = 0;
  bool m_reversedA = false, m_reversedB = false;
  std::vector<double> m_lenA, m_phiA, m_lenB, m_phiB;
  // Step costs: A-only steps per row, B-only steps per column, diagonal steps per cell (m x 2n, row-major).
  std::vector<double> m_costA, m_costB, m_costDiag;
  std::vector<double> m_prefB; // prefix sums of m_costB

  // Work buffers of the dynamic programme, reused from call to call.
  std::vector<double> m_table;       // D over the band, row by row
  std::vector<std::size_t> m_rowOff; // where each row starts in m_table
  std::vector<int> m_L, m_R;         // column range of each row of the band
  std::vector<Path> m_pool;          // bounding paths, one per recursion level
};

#endif
