/*
  \file vpMorphGreyClasses.h
  \brief Internal to the morph module (not installed): the two grey-level classes of an image, object and background,
  under a light that varies across it (vpMorphContourExtractor's segmentation).
*/
#ifndef VP_MORPH_GREY_CLASSES_H
#define VP_MORPH_GREY_CLASSES_H

#include <array>
#include <cstddef>

#include <opencv2/core.hpp>

/*
  Two classes of grey levels under one light: a plane and an object lit by a light that falls off across the view share
  its shading S(x, y) = 1 + a x + b y (a gain on both, to first order), each class's level its mean times S. Otsu's
  criterion generalised: the within-class squared deviation from each class's level, a sample at the sensor's limits
  (0, 255) deviating only by how far its level lies beyond the limit on its side (it bounds its value). Otsu's split
  minimises the criterion with constant levels: when neither of its classes shows a slope, it stands. Else the
  criterion is lowered by alternating (Lloyd): the levels fitted by least squares (the shading on both classes' own
  surfaces: not at the limits, nor next to the other class, which the edge mixes; worth its two parameters by
  vpMorphAffineLevel::slope()'s tests), each sample given to the class it deviates less from. The criterion is not
  convex (two classes meeting across the plane's ramp are a local minimum), so it is descended from two starts: Otsu's
  split, and Otsu's split of the samples with the dominant surface's level removed. The lower split is kept whose levels
  stay apart across the whole image and which lowers the criterion of Otsu's split with constant levels by more than
  the Bayesian information criterion charges for the shading's two parameters (a step in the plane's own level is no
  shading); else Otsu's split stands. The levels are fitted on a lattice of 2^12 to 2^14 pixels: a level fitted from
  them has at most 1/64 of the noise's deviation, under a grey level for any noise in which an 8-bit image can show an
  object at all.
*/
class vpMorphGreyClasses
{
public:
  using Histogram = std::array<long, 256>;

  //! Grey-level histogram of the \e n pixels at \e p.
  static Histogram histogram(const unsigned char *p, std::size_t n);
  //! Otsu's threshold of a histogram of \e total pixels (a level above it is on the bright side).
  static int otsu(const Histogram &h, long total);

  //! Fits the classes of \e grey (8 bits, one channel, not empty) from Otsu's threshold \e t of its histogram.
  vpMorphGreyClasses(const cv::Mat &grey, int t);

  //! The level halfway between the two classes' at pixel (u, v) (column, row).
  double threshold(double u, double v) const { return m_t0 + m_tu * u + m_tv * v; }
  //! Writes 255 where \e grey is above threshold(), 0 elsewhere, into \e dst (allocated by the caller, same size);
  //! under a shading a pixel at a sensor's limit goes to the class on its side (at 255 always, at 0 never). \e grey
  //! may be a part of the image whose first pixel is \e origin: each pixel is classified as in the whole image.
  void bright(const cv::Mat &grey, cv::Mat &dst, const cv::Point &origin = cv::Point()) const;

private:
  double m_t0, m_tu, m_tv; // threshold(u, v) = t0 + tu u + tv v
};

#endif
