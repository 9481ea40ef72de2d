/*!
  \file vpMorphException.h
  \brief Errors raised by the VISPMorph modules.
*/
#ifndef VP_MORPH_EXCEPTION_H
#define VP_MORPH_EXCEPTION_H

#include <string>

#include <visp3/core/vpException.h>

/*!
  \class vpMorphException
  \ingroup group_morph
  \brief Error raised by VISPMorph for bad input or a failed operation.

  Derives from vpException so that a ViSP control loop that already catches vpException handles it.
  The message always says what was wrong and with which value, so a user can act on it.

  \code
  try {
    vpMorphDatabase db = vpMorphDatabase::load("objects.json");
  } catch (const vpMorphException &e) {
    if (e.getCode() == vpMorphException::ioError)
      std::cerr << e.getStringMessage() << std::endl; // what was wrong, with the file and the value
  }
  \endcode
*/
class vpMorphException : public vpException
{
public:
  //! What went wrong (getCode()).
  enum errorCodeEnum {
    badContourError = 100, //!< Fewer than 3 vertices, NaN, repeated vertices, zero area, self-intersection.
    badImageError,         //!< Empty, uniform, too small image, or no object found.
    badParameterError,     //!< NaN, non-positive or out-of-range parameter.
    ioError,               //!< Unreadable, malformed or wrong-version file.
    notFoundError          //!< Unknown object, name or index.
  };

  //! An error of kind \e code (errorCodeEnum) with its message.
  vpMorphException(int code, const std::string &msg) : vpException(code, msg) {}
};

#endif
