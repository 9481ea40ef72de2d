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
  Two classes of grey levels whose levels are affine functions of the image position: a plane and an object lit by
  one light that falls off across the view (a shading gain on both, to first order) are two such classes. Otsu's
  criterion generalised: the within-class squared deviation from each class's level. Otsu's split minimises it with
  constant levels; when a class of that split shows a slope, the criterion is lowered from there by alternating
  (Lloyd): each class's level fitted by least squares, each pixel given to the class whose level is nearer, until no
  pixel changes class. A class's slope is fitted on its own surface: not on pixels at the sensor's limits (0, 255),
  which only bound it, nor on those next to the other class, which the edge mixes; a slope counts when it is seen and
  worth its parameters (vpMorphAffineLevel::slope()), else the class's level is the mean of its pixels. Levels that
  cross within the image (no longer two surfaces under one light) leave Otsu's split. The levels are fitted on a lattice
  of 2^12 to 2^14 pixels: a level fitted from them has at most 1/64 of the noise's deviation, under a grey level for any
  noise in which an 8-bit image can show an object at all.
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
  //! Writes 255 where \e grey is above threshold(), 0 elsewhere, into \e dst (allocated by the caller, same size).
  void bright(const cv::Mat &grey, cv::Mat &dst) const;

private:
  double m_t0, m_tu, m_tv; // threshold(u, v) = t0 + tu u + tv v
};

#endif
