/*!
  \file vpMorphCorrespondence.h
  \brief A cyclic, order-preserving vertex correspondence between two polygons and its work.
*/
#ifndef VP_MORPH_CORRESPONDENCE_H
#define VP_MORPH_CORRESPONDENCE_H

#include <cstddef>
#include <utility>
#include <vector>

/*!
  \class vpMorphCorrespondence
  \ingroup group_morph
  \brief Result of vpMorphMatcher: which input vertex goes with which target vertex, and at what work.

  pairs()[k] = (i_k, j_k) are indices into the input (m vertices) and the target (n vertices).
  Consecutive pairs advance the input, the target, or both by one vertex (cyclically, in the direction of
  positive signed area: backwards through the vertex list of a negatively oriented polygon); every vertex of
  each polygon appears at least once; the list starts with the starting pair and closes back onto it.
  max(m, n) <= pairs().size() <= m + n.

  \code
  vpMorphCorrespondence c = vpMorphMatcher().match(input, target);
  for (const auto &p : c.pairs())  // p.first: input vertex, p.second: target vertex
    std::cout << p.first << " -> " << p.second << std::endl;
  double D = c.work();             // D_morph (Eq. 4)
  \endcode
  \sa vpMorphMatcher, vpMorph, \ref page_method
*/
class vpMorphCorrespondence
{
public:
  //! An empty correspondence (no pairs, zero work).
  vpMorphCorrespondence() = default;
  //! From its pairs and the two parts of their work; the pairs are taken as given (not checked here).
  vpMorphCorrespondence(std::size_t m, std::size_t n, std::vector<std::pair<std::size_t, std::size_t>> pairs,
                        double stretching, double bending)
    : m_m(m), m_n(n), m_pairs(std::move(pairs)), m_stretching(stretching), m_bending(bending)
  {
  }

  //! m, the number of vertices of the input.
  std::size_t inputSize() const { return m_m; }
  //! n, the number of vertices of the target.
  std::size_t targetSize() const { return m_n; }
  //! The pairs (input index, target index), from the starting pair on.
  const std::vector<std::pair<std::size_t, std::size_t>> &pairs() const { return m_pairs; }
  //! Number of pairs.
  std::size_t size() const { return m_pairs.size(); }
  //! True when there is no pair.
  bool empty() const { return m_pairs.empty(); }
  //! Starting pair (input index, target index): the first pair of the list.
  std::pair<std::size_t, std::size_t> start() const
  {
    return m_pairs.empty() ? std::make_pair(std::size_t(0), std::size_t(0)) : m_pairs.front();
  }
  //! Total work E = stretching + bending (Eq. 4 when minimised over all starting pairs).
  double work() const { return m_stretching + m_bending; }
  //! The stretching part of the work (Eq. 2 summed over the segments).
  double stretchingWork() const { return m_stretching; }
  //! The bending part of the work (Eq. 3 summed over the vertices).
  double bendingWork() const { return m_bending; }

private:
  std::size_t m_m = 0, m_n = 0;
  std::vector<std::pair<std::size_t, std::size_t>> m_pairs;
  double m_stretching = 0.0, m_bending = 0.0;
};

#endif
