/*!
  \file vpMorphOutlineFit.h
  \brief Robust point-to-edge fit of a similarity (and a common edge offset) between two outlines, with its
  uncertainty.
*/
#ifndef VP_MORPH_OUTLINE_FIT_H
#define VP_MORPH_OUTLINE_FIT_H

#include <limits>
#include <memory>
#include <vector>

#include <visp3/core/vpMatrix.h>
#include <visp3/morph/vpMorphContour.h>
#include <visp3/morph/vpMorphRigidTransform.h>

class vpMorphNearestEdge;

/*!
  \class vpMorphOutlineFit
  \ingroup group_morph
  \brief Lays an input outline on a goal outline: the similarity \f$x' = s R(\theta)(x - c) + c + t\f$ (\f$c\f$ the
  input's centroid) that minimises the robust sum of the input samples' distances to the goal's edges, optionally
  with one common offset \f$\delta\f$ of the goal's edges along their normals.

  <b>Model.</b> The input is sampled every perimeter / getSampleCount() along its outline (vpMorphContour::outline(),
  the measured edges when it has them). Each sample's signed distance to the goal's edges (moved by \f$\delta\f$) is
  its residual. Samples of the object seen twice have residuals of one noise scale \f$\sigma\f$; samples that the
  goal lacks (an occluder's edge, a bent limb) lie far off. The fit is iteratively reweighted least squares with
  Tukey's biweight at \f$4.685\sigma\f$ (95 % efficiency under Gaussian noise), \f$\sigma = 1.4826\,\mathrm{MAD}\f$
  of the residuals floored at getMinimumSigma(): the weights of samples beyond the cut are 0, so up to half of the
  input may belong to anything else (the MAD's breakdown point). The offset absorbs an outline measured grown or
  shrunk all round (a lighting that clips, a blur) that would otherwise be taken for a scale.

  <b>Results</b> of the last fit(): the transform, \f$\sigma\f$, \f$\delta\f$, the share of the input's samples that
  are inliers, outside the goal's region or inside it (beyond the cut), the residuals, and the covariance of
  \f$(\theta, t_x, t_y, \ln s)\f$, \f$\sigma^2 (J^T W J)^{-1}\f$ with the offset marginalised.

  \code
  vpMorphOutlineFit fit(target);                       // the goal's edge grid is built once
  vpMorphRigidTransform T = fit.fit(current, Tstart);  // Tstart in the right basin (e.g. from a correspondence)
  if (fit.getInlierShare() > 0.5) { double sd_theta = std::sqrt(fit.getCovariance()[0][0]); }
  \endcode
  \sa vpMorphRigidTransform, \ref page_servo_measurement
*/
class vpMorphOutlineFit
{
public:
  /*!
    \param goal : the goal; its outline() is used (its measured edges when it carries them).
    \throw vpMorphException::badContourError on an empty goal.
  */
  explicit vpMorphOutlineFit(const vpMorphContour &goal);

  //! Fit the common edge offset too (default true).
  void setEdgeOffset(bool on) { m_withOffset = on; }
  //! Whether the common edge offset is fitted.
  bool getEdgeOffset() const { return m_withOffset; }
  /*!
    Also lay the goal's samples on the input's edges (default true): a fit of the input alone onto the goal can
    shrink it onto one of the goal's edges, where every sample lies on it; the goal's samples rule that out.
  */
  void setSymmetric(bool on) { m_symmetric = on; }
  //! Whether the goal's samples are laid on the input's edges too.
  bool getSymmetric() const { return m_symmetric; }
  //! Fit the scale (default true; false: rotation and translation only).
  void setWithScale(bool on) { m_withScale = on; }
  //! Whether the scale is fitted.
  bool getWithScale() const { return m_withScale; }
  /*!
    Floor of the robust scale, in the contours' units (>= 0, default 0: a rounding floor only). Outlines measured
    on images never coincide exactly; polygons with vertices on the pixel grid do: give them half a pixel.
    \throw vpMorphException::badParameterError on a negative or non-finite value.
  */
  void setMinimumSigma(double sigma);
  //! Floor of the robust scale (the contours' units).
  double getMinimumSigma() const { return m_minSigma; }
  /*!
    Largest robust scale of the noise, in the contours' units (> 0, default infinite). A fit whose scale settles above
    it is continued with the scale halved, and refined at each, down to it (graduated non-convexity): it then lies on
    the largest part of the input that meets the goal within that noise (a limb bent about a pivot leaves residuals
    that grow steadily from it, which a scale taken from them alone would absorb). getSigma() stays the inliers' own.
    \throw vpMorphException::badParameterError on a value that is not > 0.
  */
  void setMaximumSigma(double sigma);
  //! Largest robust scale of the noise (the contours' units; infinite: none).
  double getMaximumSigma() const { return m_maxSigma; }
  /*!
    The width under which a neck of the input may be seen joined or parted from one image to the next (the contours'
    units, >= 0, default 0: none): the part it holds (a filament, a knob, the gap behind a slit) keeps or loses its
    pixels as the pixel grid moves under it, and the outline goes round the part or not. A run of outliers on such a
    part is not counted in getOutsideShare() and getInsideShare(); fineWidth() gives the width for an outline measured
    on an image. \throw vpMorphException::badParameterError on a negative or non-finite value.
  */
  void setFineWidth(double width);
  /*!
    The fine width of an outline measured on an image whose pixel is \e pixel wide and whose edges are blurred by
    \e blur (Gaussian sigma), both in the contours' units: a bar 2 sqrt(2) erf^-1(1/2) blur = 1.349 blur wide keeps
    half its contrast at its middle, where the object mask is cut; one pixel more for the grid's phase.
  */
  static double fineWidth(double pixel, double blur) { return pixel + 1.3489795003921634 * blur; }
  //! The width under which a neck may be seen joined or parted (the contours' units; 0: none).
  double getFineWidth() const { return m_fineWidth; }
  //! Reweighting rounds at most (>= 1, default 20). \throw vpMorphException::badParameterError on 0.
  void setMaxIterations(unsigned int n);
  //! Reweighting rounds at most.
  unsigned int getMaxIterations() const { return m_maxIterations; }
  //! Samples taken along the input, and along the goal (>= 8, default 256). \throw vpMorphException::badParameterError
  //! below 8.
  void setSampleCount(unsigned int n);
  //! Samples taken along the input, and along the goal.
  unsigned int getSampleCount() const { return m_samples; }

  /*!
    The similarity from \e input to the goal, refined from \e initial (which must lie in the right basin). The input
    and the goal must have the same units. \e initialSigma: the residuals' scale at the start (the last fit's
    getSigma() for a view that moved a little since; 0: the MAD of all the residuals). From then on the scale is the
    MAD of the residuals within the last round's cut, so the fit stays on the part it started on. On a fit that
    degenerates (no inlier, a scale run to 0) \e initial is returned and getInlierShare() is 0. \throw
    vpMorphException::badContourError on an empty input, badParameterError on units that differ from the goal's.
  */
  vpMorphRigidTransform fit(const vpMorphContour &input, const vpMorphRigidTransform &initial,
                            double initialSigma = 0.0);
  /*!
    fit() from the best of several hypotheses, for a start that may lie in another basin (the first fit of a view):
    \e initial and its turns by twelfths about the input's centroid (a nearly symmetric part's correspondence may
    start a lobe off) fitted on the whole input, and each of 12 windows
    (a sixth of the input, half overlapping) fitted alone, all at \e initial's scale; each refined with its scale
    free, and kept is the one of least cost() both ways at the edges' noise (the windows' residuals' own spread from
    sample to sample) among those that lay the input's area within a factor 2 of the goal's (the largest rigid part
    of the view: what an occluder leaves, the part a bend did not move), refined by fit() at its own residual scale.
    \throw vpMorphException as fit().
  */
  vpMorphRigidTransform search(const vpMorphContour &input, const vpMorphRigidTransform &initial);

  //! The goal's outline (the contour the distances are measured to).
  const vpMorphContour &getGoal() const { return m_goal; }
  //! Robust scale of the last fit's residuals (the contours' units).
  double getSigma() const { return m_sigma; }
  //! The goal's edges moved along their outward normals by this (the contours' units; 0 without the offset).
  double getOffset() const { return m_offset; }
  //! Share of the input's samples with a non-zero weight, in [0, 1].
  double getInlierShare() const { return m_inlierShare; }
  /*!
    Share of the input's samples in runs of outliers that lie outside the goal's region (a part that sticks out: a
    bend). Runs no longer than the noise's isolated outliers make by chance do not count: at the rate p of the
    isolated ones, a run of m comes by chance about n p^m times, so only runs beyond the m that makes it 1e-3 do. Nor
    does a run on a part held by a neck narrower than getFineWidth().
  */
  double getOutsideShare() const { return m_outsideShare; }
  //! The same for runs inside the goal's region (an occluder's edge, a cut).
  double getInsideShare() const { return m_insideShare; }
  //! Share of the goal's samples that lie on the input's edges (symmetric fits; NaN otherwise): a hidden part lowers
  //! it.
  double getGoalCoverage() const { return m_goalCoverage; }
  //! Signed residual of each sample (positive outside the goal's region), in the contours' units.
  const std::vector<double> &getResiduals() const { return m_residuals; }
  /*!
    Covariance of \f$(\theta, t_x, t_y, \ln s)\f$ of the last fit (4 x 4; the offset marginalised; without scale,
    its row and column are 0). Infinite diagonal when the inliers do not determine the similarity.
  */
  const vpMatrix &getCovariance() const { return m_covariance; }
  /*!
    Mean Tukey loss of the last fit's residuals at the scale \e sigma, in [0, 1] (0: every sample on the goal's edges,
    1: none within the cut): the criterion that compares fits from different starts at one scale.
  */
  double cost(double sigma) const { return cost(m_residuals, sigma); }
  //! The same criterion for given residuals (1 when there are none or sigma is not > 0).
  static double cost(const std::vector<double> &residuals, double sigma);

  //! Tukey's cut in units of the robust scale.
  static double tukeyConstant() { return 4.685; }

private:
  struct Goal;   // the goal's edge grid, samples and normals: built once, shared by copies
  struct Solver; // the fits' machinery (vpMorphOutlineFit.cpp)
  // edges: the input outline's, when the fit has them (else built if needed).
  void structuredOutliers(const std::vector<double> &weights, const vpMorphContour &outline,
                          const vpMorphNearestEdge *edges);

  std::shared_ptr<const Goal> m_goalData;
  vpMorphContour m_goal;
  bool m_goalCcw = true;
  bool m_withOffset = true, m_withScale = true;
  double m_minSigma = 0.0, m_maxSigma = std::numeric_limits<double>::infinity(), m_fineWidth = 0.0;
  unsigned int m_maxIterations = 20, m_samples = 256;

  double m_sigma = 0.0, m_offset = 0.0, m_inlierShare = 0.0, m_outsideShare = 0.0, m_insideShare = 0.0;
  double m_goalCoverage = 0.0;
  bool m_symmetric = true;
  std::vector<double> m_residuals;
  vpMatrix m_covariance;
};

#endif
