/*!
  \file vpMorphJointFile.h
  \brief An articulated template's joint as a file describes it: the parts' images, the pin and the opening's range.
*/
#ifndef VP_MORPH_JOINT_FILE_H
#define VP_MORPH_JOINT_FILE_H

#include <string>

#include <visp3/core/vpImagePoint.h>
#include <visp3/morph/vpMorphArticulation.h>
#include <visp3/morph/vpMorphContourExtractor.h>

/*!
  \class vpMorphJointFile
  \ingroup group_morph
  \brief The joint of an articulated template, read from a JSON file (value type).

  Why a file: the parts and the pin are known where the template's image is made, and whatever builds a database
  from that image (a folder of images, a scene) takes them from there.

  \code{.json}
  {"parts": ["pliers-part0.png", "pliers-part1.png"], "pivot": [320, 240], "range_deg": [-8, 60]}
  \endcode
  - "parts": two images, each showing one part alone, drawn in the template image's frame (paths relative to the
    file);
  - "pivot": the pin (u, v) in that frame, pixels;
  - "range_deg": the range of the opening, part 1's turn against part 0 from the template image, degrees
    (min <= 0 <= max, under a half turn either way).

  Other keys are left to the caller.

  \code
  vpMorphJointFile j = vpMorphJointFile::read("data/joints/pliers.json");
  vpMorphTemplate t("pliers", vpMorphContourExtractor().extract(I));  // I: the template image, same frame
  t.setArticulation(j.articulation());
  \endcode
  \sa vpMorphArticulation, \ref page_design_recognition
*/
class vpMorphJointFile
{
public:
  /*!
    Reads \e file. \throw vpMorphException::ioError on an unreadable file, or a malformed one (not JSON, a key
    missing or of the wrong type or size, an empty part name, a range that is not min <= 0 <= max within a half turn).
  */
  static vpMorphJointFile read(const std::string &file);
  /*!
    Parses the text of a joint file; part paths are resolved against \e baseDir (none: as they are). \e what names
    the source in error messages. \throw vpMorphException::ioError as read().
  */
  static vpMorphJointFile fromJson(const std::string &text, const std::string &baseDir = "",
                                   const std::string &what = "joint file");

  //! Part \e k's image (0 or 1), resolved. \throw vpMorphException::badParameterError for k > 1.
  const std::string &part(unsigned int k) const;
  //! The pin in the template image's frame (pixels).
  const vpImagePoint &pivot() const { return m_pivot; }
  //! The least opening (radians, <= 0).
  double minAngle() const { return m_min; }
  //! The largest opening (radians, >= 0).
  double maxAngle() const { return m_max; }

  /*!
    The articulation of a template made from an image in the same frame: each part the largest object of its image
    (\e extractor), with its measured region and edge outline.
    \throw vpMorphException::ioError on an unreadable part image (named); badImageError on one without an object.
  */
  vpMorphArticulation articulation(const vpMorphContourExtractor &extractor = vpMorphContourExtractor()) const;

private:
  std::string m_parts[2];
  vpImagePoint m_pivot;
  double m_min = 0.0, m_max = 0.0;
};

#endif
