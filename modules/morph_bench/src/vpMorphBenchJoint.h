/*!
  \file vpMorphBenchJoint.h
  \brief Internal: an object's joint as vispmorph-make-data describes it (DATA/joints/NAME.json).
*/
#ifndef VP_MORPH_BENCH_JOINT_H
#define VP_MORPH_BENCH_JOINT_H

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include <visp3/morph/vpMorphException.h>
#include <visp3/morph/vpMorphJointFile.h>

/*!
  The joint file of an articulated object (vpMorphJointFile: the parts drawn alone in the object image's frame, the
  pin and the range, in texels of that image) and the turn of each part about the pin in the object's deformed
  drawing (degrees, key "deformed_turns_deg"), which the scenes undo to lay that drawing on the template.
*/
struct vpMorphBenchJoint
{
  vpMorphJointFile joint;
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
    std::stringstream text;
    text << f.rdbuf();
    const std::string what = "joint file '" + file + "'";
    vpMorphBenchJoint j;
    j.joint = vpMorphJointFile::fromJson(text.str(), file.substr(0, file.find_last_of('/')), what);
    try {
      const std::vector<double> turns =
          nlohmann::json::parse(text.str()).at("deformed_turns_deg").get<std::vector<double>>();
      if (turns.size() != 2)
        throw vpMorphException(vpMorphException::ioError,
                               "vpMorphBench: malformed " + what + ": 2 turns are needed (deformed_turns_deg)");
      j.deformedTurnDeg[0] = turns[0];
      j.deformedTurnDeg[1] = turns[1];
    } catch (const nlohmann::json::exception &e) {
      throw vpMorphException(vpMorphException::ioError, "vpMorphBench: malformed " + what + ": " + e.what());
    }
    return j;
  }
};

#endif
