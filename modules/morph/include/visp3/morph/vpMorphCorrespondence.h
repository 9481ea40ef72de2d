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
*/
class vpMorphCorrespondence
{
public:
  vpMorphCorrespondence() = default;
  vpMorphCorrespondence(std::size_t m, std::size_t n, std::vector<std::pair<std::size_t, std::size_t>> pairs,
                        double stretching, double bending)
    : m_m(m), m_n(n), m_pairs(std::move(pairs)), m_stretching(stretching), m_bending(bending)
  {
  }

  std::size_t inputSize() const { return m_m; }
  std::size_t targetSize() const { return m_n; }
  const std::vector<std::pair<std::size_t, std::size_t>> &pairs() const { return m_pairs; }
  std::size_t size() const { return m_pairs.size(); }
  bool empty() const { return m_pairs.empty(); }
  //! Starting pair (input index, target index): the first pair of the list.
  std::pair<std::size_t, std::size_t> start() const
  {
    return m_pairs.empty() ? std::make_pair(std::size_t(0), std::size_t(0)) : m_pairs.front();
  }
  //! Total work E = stretching + bending (Eq. 4 when minimised over all starting pairs).
  double work() const { return m_stretching + m_bending; }
  double stretchingWork() const { return m_stretching; }
  double bendingWork() const { return m_bending; }

private:
  std::size_t m_m = 0, m_n = 0;
  std::vector<std::pair<std::size_t, std::size_t>> m_pairs;
  double m_stretching = 0.0, m_bending = 0.0;
};

#endif
