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
  first, so the work is scale invariant too. The two polygons are brought to the same orientation
  (B's traversal is reversed internally when the signs of their areas differ; indices are reported in
  the original numbering). The model is symmetric in A and B, so distance(A, B) == distance(B, A).

  <b>Search.</b> Every closed path matches A's vertex 0, so the minimum over all m n starting pairs equals
  the minimum over the n paths that start at (0, b), b = 0..n-1, and end at (m, b + n) on the grid where B is
  doubled. matchFromStart() runs the O(mn) dynamic programme for one start; matchBruteForce() runs it for
  every b (O(m n^2)); match() is exact and fast: optimal paths of different starts never need to cross
  (uncrossing two crossing paths at their shared cell keeps both costs, since costs depend only on the cell
  and the step into it), so Maes' divide and conquer solves the middle start, then recurses on each half
  inside the band left between the bounding paths (O(mn log n)). Bands whose lower bound (the minimum of the
  two bounding paths' costs can't be used, so: the cheapest possible cost of any path in the band, from a
  per-row minimum) already exceeds the best work found are skipped.
  matchWindow() does the same for the starts near a given one, for tracking from frame to frame.

  Not thread safe (it reuses its buffers); copy one per thread.
*/
class vpMorphMatcher
{
public:
  explicit vpMorphMatcher(const vpMorphWorkModel &model = vpMorphWorkModel(), bool normalizeScale = true);

  const vpMorphWorkModel &model() const { return m_model; }
  void setModel(const vpMorphWorkModel &model) { m_model = model; }
  bool scaleNormalization() const { return m_normalizeScale; }
  void setScaleNormalization(bool on) { m_normalizeScale = on; }

  //! Minimal-work correspondence with input vertex \e a matched first to target vertex \e b.
  vpMorphCorrespondence matchFromStart(const vpMorphContour &A, const vpMorphContour &B, std::size_t a,
                                       std::size_t b);
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

private:
  struct Problem;
  void prepare(const vpMorphContour &A, const vpMorphContour &B, std::size_t a, std::size_t b);
  double solveStart(std::size_t b, const std::vector<int> *lo, const std::vector<int> *hi, std::vector<int> *pathLo,
                    std::vector<int> *pathHi);
  vpMorphCorrespondence solveRange(std::size_t bFirst, std::size_t count);
  vpMorphCorrespondence tracePath(std::size_t b);

  vpMorphWorkModel m_model;
  bool m_normalizeScale;

  // Prepared problem: per-vertex edge lengths and turning angles of A (rotated so that row 0 is the
  // start vertex) and of B (rotated, reversed if needed, and doubled).
  std::size_t m_m = 0, m_n = 0, m_a0 = 0, m_b0 = 0;
  bool m_reversedB = false;
  std::vector<double> m_lenA, m_phiA, m_lenB, m_phiB;
  // Per-cell step costs for the current problem (row-major over the (m+1) x (2n+1) grid), built once.
  std::vector<double> m_costDiag, m_costA, m_costB;
  std::vector<double> m_dp;
  std::vector<unsigned char> m_step;
};

#endif
