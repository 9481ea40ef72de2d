#include <visp3/morph/vpMorphJointFile.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <vector>

#include <nlohmann/json.hpp>

#include <visp3/core/vpImage.h>
#include <visp3/core/vpMath.h>
#include <visp3/io/vpImageIo.h>
#include <visp3/morph/vpMorphException.h>

vpMorphJointFile vpMorphJointFile::read(const std::string &file)
{
  std::ifstream f(file);
  if (!f)
    throw vpMorphException(vpMorphException::ioError, "vpMorphJointFile: cannot read joint file '" + file + "'");
  std::stringstream text;
  text << f.rdbuf();
  const std::size_t slash = file.find_last_of('/');
  return fromJson(text.str(), slash == std::string::npos ? std::string() : file.substr(0, slash),
                  "joint file '" + file + "'");
}

vpMorphJointFile vpMorphJointFile::fromJson(const std::string &text, const std::string &baseDir,
                                            const std::string &what)
{
  auto malformed = [&](const std::string &why) {
    return vpMorphException(vpMorphException::ioError, "vpMorphJointFile: malformed " + what + ": " + why);
  };
  vpMorphJointFile j;
  try {
    const nlohmann::json o = nlohmann::json::parse(text);
    const std::vector<std::string> parts = o.at("parts").get<std::vector<std::string>>();
    const std::vector<double> pivot = o.at("pivot").get<std::vector<double>>();
    const std::vector<double> range = o.at("range_deg").get<std::vector<double>>();
    if (parts.size() != 2 || pivot.size() != 2 || range.size() != 2)
      throw malformed("2 parts, a pivot (u, v) and a range (min, max) are needed");
    for (unsigned int k = 0; k < 2; ++k) {
      if (parts[k].empty())
        throw malformed("part " + std::to_string(k) + " has no image");
      j.m_parts[k] = baseDir.empty() || parts[k].front() == '/' ? parts[k] : baseDir + "/" + parts[k];
    }
    if (!std::isfinite(pivot[0]) || !std::isfinite(pivot[1]))
      throw malformed("the pivot is not finite");
    // JSON has no NaN, but a number too large for a double reads as infinity.
    if (!(range[0] <= 0.0 && 0.0 <= range[1] && range[0] > -180.0 && range[1] < 180.0))
      throw malformed("the range must hold 0 and stay within a half turn either way (degrees)");
    j.m_pivot.set_uv(pivot[0], pivot[1]);
    j.m_min = vpMath::rad(range[0]);
    j.m_max = vpMath::rad(range[1]);
  } catch (const nlohmann::json::exception &e) {
    throw malformed(e.what());
  }
  return j;
}

const std::string &vpMorphJointFile::part(unsigned int k) const
{
  if (k > 1)
    throw vpMorphException(vpMorphException::badParameterError, "vpMorphJointFile::part: the parts are 0 and 1");
  return m_parts[k];
}

vpMorphArticulation vpMorphJointFile::articulation(const vpMorphContourExtractor &extractor) const
{
  vpMorphContour c[2];
  for (unsigned int k = 0; k < 2; ++k) {
    vpImage<unsigned char> I;
    try {
      vpImageIo::read(I, m_parts[k]);
    } catch (const vpException &e) {
      throw vpMorphException(vpMorphException::ioError,
                             "vpMorphJointFile: cannot read part image '" + m_parts[k] + "': " + e.getStringMessage());
    }
    try {
      c[k] = extractor.extract(I);
    } catch (const vpException &e) {
      throw vpMorphException(vpMorphException::badImageError,
                             "vpMorphJointFile: part image '" + m_parts[k] + "': " + e.getStringMessage());
    }
  }
  return vpMorphArticulation(c[0], c[1], m_pivot, m_min, m_max);
}
