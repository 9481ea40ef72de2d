/*!
  \file vpMorphBenchJoint.h
  \brief Internal: an object's joint as vispmorph-make-data describes it (DATA/joints/NAME.json).
*/
#ifndef VP_MORPH_BENCH_JOINT_H
#define VP_MORPH_BENCH_JOINT_H

#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include <visp3/morph/vpMorphException.h>

/*!
  The two parts of an articulated object, drawn alone in the object image's frame, the pin and the opening's range
  in that frame (texels, degrees; part 1's turn relative to part 0), and the turn of each part, about the pin, in the
  object's deformed variant.
*/
struct vpMorphBenchJoint
{
  std::string parts[2]; //!< the parts' images (paths)
  double pivotU = 0.0, pivotV = 0.0;
  double minDeg = 0.0, maxDeg = 0.0;
  double deformedTurnDeg[2] = {0.0, 0.0};

  //! The joint file of \e name under \e dataDir, or an empty string when it has none.
  static std::string file(const std::string &dataDir, const std::string &name)
  {
    const std::string f = dataDir + "/joints/" + name + ".json";
    return std::ifstream(f).good() ? f : std::string();
  }

  //! Reads \e file. \throw vpMorphException::ioError on an unreadable or malformed file.
  static vpMorphBenchJoint read(const std::string &file)
  {
    std::ifstream f(file);
    if (!f)
      throw vpMorphException(vpMorphException::ioError, "vpMorphBench: cannot read joint file '" + file + "'");
    vpMorphBenchJoint j;
    try {
      nlohmann::json o;
      f >> o;
      const std::vector<std::string> parts = o.at("parts").get<std::vector<std::string>>();
      const std::vector<double> pivot = o.at("pivot").get<std::vector<double>>();
      const std::vector<double> range = o.at("range_deg").get<std::vector<double>>();
      const std::vector<double> turns = o.at("deformed_turns_deg").get<std::vector<double>>();
      if (parts.size() != 2 || pivot.size() != 2 || range.size() != 2 || turns.size() != 2)
        throw vpMorphException(vpMorphException::ioError, "2 parts, a pivot (u, v), a range and 2 turns needed");
      const std::string dir = file.substr(0, file.find_last_of('/') + 1);
      for (unsigned int k = 0; k < 2; ++k) {
        j.parts[k] = dir + parts[k];
        j.deformedTurnDeg[k] = turns[k];
      }
      j.pivotU = pivot[0];
      j.pivotV = pivot[1];
      j.minDeg = range[0];
      j.maxDeg = range[1];
    } catch (const nlohmann::json::exception &e) {
      throw vpMorphException(vpMorphException::ioError,
                             "vpMorphBench: malformed joint file '" + file + "': " + e.what());
    } catch (const vpMorphException &e) {
      throw vpMorphException(vpMorphException::ioError,
                             "vpMorphBench: malformed joint file '" + file + "': " + e.getStringMessage());
    }
    return j;
  }
};

#endif
