/*!
  \file vpMorphWorkModel.h
  \brief The physics-based work of stretching and bending one polygon into another (Eq. 2 and 3).
*/
#ifndef VP_MORPH_WORK_MODEL_H
#define VP_MORPH_WORK_MODEL_H

/*!
  \class vpMorphWorkModel
  \ingroup group_morph
  \brief Stretching (Eq. 2) and bending (Eq. 3) work of the paper, with its stiffness parameters.

  For a one-step morph from input to target, the paper's original and "before" states coincide
  (L_O = L_I, phi_O = phi_I), so Eq. 2 and Eq. 3 reduce to
  \f[ E_s = k_s \frac{(L_T - L_I)^2}{(1 - c_s) L_{min} + c_s L_{max}}, \qquad
      E_b = k_b (\phi_T - \phi_I)^2 \f]
  with \f$L_{min}, L_{max}\f$ the smaller and larger of the two lengths. An edge that collapses to a point
  (length 0 on one side) costs \f$k_s L / c_s\f$: \f$c_s\f$ is the penalty for collapsing segments.

  Defaults: \f$k_s = 1\f$, \f$c_s = 0.5\f$, \f$k_b = 0.02\f$. Lengths are measured on contours normalised to unit
  perimeter (see vpMorphMatcher), so an edge of a 30-vertex polygon is about 0.03 long; \f$k_b = 0.02\f$
  makes a 0.3 rad turning mismatch cost about as much as stretching such an edge by 40 %, so neither term
  dominates.

  \code
  vpMorphMatcher matcher(vpMorphWorkModel(1.0, 0.1, 0.5));  // the paper's model with a stiffer bending
  double D = matcher.distance(A, B);
  \endcode
  \sa vpMorphMatcher, \ref page_method
*/
class vpMorphWorkModel
{
public:
  /*!
    \param ks Stretching stiffness, finite and > 0.
    \param kb Bending stiffness, finite and > 0 (without bending the work ignores the shape of corners).
    \param cs Collapse penalty, finite, in (0, 1].
    \throw vpMorphException::badParameterError otherwise.
  */
  explicit vpMorphWorkModel(double ks = 1.0, double kb = 0.02, double cs = 0.5);

  //! Stretching stiffness \f$k_s\f$.
  double ks() const { return m_ks; }
  //! Bending stiffness \f$k_b\f$.
  double kb() const { return m_kb; }
  //! Collapse penalty \f$c_s\f$.
  double cs() const { return m_cs; }

  //! Eq. 2: work to stretch a segment of length \e lI into one of length \e lT (either may be 0, not both).
  double stretching(double lI, double lT) const
  {
    const double lmin = lI < lT ? lI : lT;
    const double lmax = lI < lT ? lT : lI;
    const double d = lT - lI;
    return m_ks * d * d / ((1.0 - m_cs) * lmin + m_cs * lmax);
  }
  //! Eq. 3: work to bend a turning angle \e phiI into \e phiT (radians).
  double bending(double phiI, double phiT) const
  {
    const double d = phiT - phiI;
    return m_kb * d * d;
  }

  //! True when the three parameters are equal.
  bool operator==(const vpMorphWorkModel &o) const { return m_ks == o.m_ks && m_kb == o.m_kb && m_cs == o.m_cs; }

private:
  double m_ks, m_kb, m_cs;
};

#endif
