#include <visp3/morph_bench/vpMorphBenchObjectSet.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>

#include <unistd.h>

#include <nlohmann/json.hpp>

#include <visp3/io/vpImageIo.h>
#include <visp3/morph/vpMorphException.h>
#include <visp3/morph_sim/vpMorphBendGenerator.h>
#include <visp3/morph_sim/vpMorphSilhouetteLayout.h>

#include "vpMorphBenchHash.h"
#include "vpMorphBenchJoint.h"

namespace fs = std::filesystem;

namespace
{
const char *const kTools[] = {"pliers", "wedge", "key", "hammer", "screwdriver", "wrench"};
const char *const kImageExtensions[] = {".png", ".pgm", ".ppm", ".jpg", ".jpeg", ".bmp"};

bool isImage(const fs::path &p)
{
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return std::find(std::begin(kImageExtensions), std::end(kImageExtensions), ext) != std::end(kImageExtensions);
}

bool endsWith(const std::string &s, const std::string &tail)
{
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

//! A variant beside \e path: the same folder and extension, the stem followed by \e suffix; empty when there is none.
std::string beside(const std::string &path, const std::string &suffix)
{
  const fs::path p(path);
  const fs::path v = p.parent_path() / (p.stem().string() + suffix + p.extension().string());
  std::error_code ec;
  return fs::is_regular_file(v, ec) ? v.string() : std::string();
}

void makeDirectory(const std::string &dir)
{
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (!fs::is_directory(dir, ec))
    throw vpMorphException(vpMorphException::ioError, "vpMorphBenchObjectSet: cannot create folder '" + dir + "'");
}

//! Writes \e I to \e path through a file of its own renamed in place: runs that share a folder never read half a file.
void write(const vpImage<unsigned char> &I, const std::string &path)
{
  const std::string tmp = path + ".tmp-" + std::to_string(::getpid()) + ".png";
  try {
    vpImageIo::write(I, tmp);
  } catch (const vpException &e) {
    throw vpMorphException(vpMorphException::ioError,
                           "vpMorphBenchObjectSet: cannot write '" + path + "': " + e.getStringMessage());
  }
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec)
    throw vpMorphException(vpMorphException::ioError, "vpMorphBenchObjectSet: cannot write '" + path + "'");
}

//! The rough variant of \e image written as WORK/objects/NAME-rough.png.
std::string writeRough(const vpImage<unsigned char> &image, const std::string &objects, const std::string &name)
{
  const std::string path = objects + "/" + name + "-rough.png";
  write(vpMorphSilhouetteLayout::roughened(image, vpMorphBenchObjectSet::kRoughPixels), path);
  return path;
}
} // namespace

vpMorphBenchObjectSet vpMorphBenchObjectSet::tools(const std::string &dataDir, const std::string &workDir)
{
  const std::string objects = workDir + "/objects";
  makeDirectory(objects);
  vpMorphBenchObjectSet set;
  for (const char *name : kTools) {
    Object o;
    o.name = name;
    o.image = dataDir + "/objects/" + o.name + ".png";
    o.deformedImage = dataDir + "/objects/" + o.name + "-deformed.png";
    for (const std::string &f : {o.image, o.deformedImage})
      if (!fs::is_regular_file(f))
        throw vpMorphException(vpMorphException::notFoundError, "vpMorphBenchObjectSet: missing image '" + f + "'");
    o.jointFile = vpMorphBenchJoint::file(dataDir, o.name);
    if (!o.jointFile.empty())
      vpMorphBenchJoint::read(o.jointFile); // a malformed joint file is an error now, not a template missing later
    o.truth = o.jointFile.empty() ? TRUTH_OVERLAP : TRUTH_ARTICULATED;
    o.roughImage = writeRough(vpMorphSilhouetteLayout::read(o.image), objects, o.name);
    set.m_objects.push_back(o);
  }
  return set;
}

vpMorphBenchObjectSet vpMorphBenchObjectSet::images(const std::vector<Source> &sources, const std::string &workDir,
                                                    unsigned int seed)
{
  const std::string objects = workDir + "/objects";
  makeDirectory(objects);
  vpMorphBenchObjectSet set;
  std::set<std::string> names;
  for (const Source &src : sources) {
    if (src.name.empty() || src.name.find_first_of("/,\" \t\n") != std::string::npos) {
      set.m_skipped.push_back({src.path, "the name '" + src.name + "' is empty or holds a separator"});
      continue;
    }
    if (!names.insert(src.name).second) {
      set.m_skipped.push_back({src.path, "another object is already named '" + src.name + "'"});
      continue;
    }
    try {
      const vpMorphSilhouetteLayout layout(vpMorphSilhouetteLayout::read(src.path));
      Object o;
      o.name = src.name;
      o.image = objects + "/" + o.name + ".png";
      write(layout.image(), o.image);
      o.deformedImage = objects + "/" + o.name + "-deformed.png";
      o.deformedMask = objects + "/" + o.name + "-deformed-mask.png";
      const std::string deformed = beside(src.path, "-deformed"), mask = beside(src.path, "-deformed-mask");
      if (!deformed.empty()) {
        write(layout.apply(vpMorphSilhouetteLayout::read(deformed)), o.deformedImage);
        if (!mask.empty())
          write(layout.apply(vpMorphSilhouetteLayout::read(mask)), o.deformedMask);
        else
          o.deformedMask.clear();
        o.truth = mask.empty() ? TRUTH_OVERLAP : TRUTH_PART;
      } else {
        const std::string key = std::to_string(seed) + ":" + o.name;
        const vpMorphBendGenerator::Bend b =
            vpMorphBendGenerator::generate(layout.image(), vpMorphBenchHash::low(key) ^ vpMorphBenchHash::high(key));
        write(b.image, o.deformedImage);
        write(b.undeformedMask, o.deformedMask);
        o.truth = TRUTH_PART;
        o.undeformedShare = b.undeformedShare;
      }
      o.roughImage = writeRough(layout.image(), objects, o.name);
      set.m_objects.push_back(o);
    } catch (const vpMorphException &e) {
      if (e.getCode() == vpMorphException::ioError && e.getStringMessage().find("cannot write") != std::string::npos)
        throw;
      set.m_skipped.push_back({src.path, e.getStringMessage()});
    }
  }
  return set;
}

std::vector<vpMorphBenchObjectSet::Source> vpMorphBenchObjectSet::listImages(const std::string &dirOrList)
{
  std::error_code ec;
  std::vector<std::string> paths;
  if (fs::is_directory(dirOrList, ec)) {
    for (const fs::directory_entry &e : fs::directory_iterator(dirOrList, ec))
      if (e.is_regular_file(ec) && isImage(e.path())) {
        const std::string stem = e.path().stem().string();
        if (!endsWith(stem, "-deformed") && !endsWith(stem, "-deformed-mask") && !endsWith(stem, "-rough"))
          paths.push_back(e.path().string());
      }
    if (ec)
      throw vpMorphException(vpMorphException::ioError,
                             "vpMorphBenchObjectSet: cannot read folder '" + dirOrList + "'");
    std::sort(paths.begin(), paths.end());
  } else if (fs::is_regular_file(dirOrList, ec)) {
    std::ifstream f(dirOrList);
    if (!f)
      throw vpMorphException(vpMorphException::ioError, "vpMorphBenchObjectSet: cannot read list '" + dirOrList + "'");
    const fs::path base = fs::path(dirOrList).parent_path();
    std::string line;
    while (std::getline(f, line)) {
      line.erase(0, line.find_first_not_of(" \t\r"));
      line.erase(line.find_last_not_of(" \t\r") + 1);
      if (line.empty() || line[0] == '#')
        continue;
      const fs::path p(line);
      paths.push_back(p.is_absolute() ? p.string() : (base / p).string());
    }
  } else {
    throw vpMorphException(vpMorphException::notFoundError,
                           "vpMorphBenchObjectSet: no folder or list file '" + dirOrList + "'");
  }
  std::vector<Source> out;
  for (const std::string &p : paths)
    out.push_back({p, fs::path(p).stem().string()});
  return out;
}

std::vector<vpMorphBenchObjectSet::Source> vpMorphBenchObjectSet::poolImages(const std::string &splitFile,
                                                                             const std::string &datasetsDir,
                                                                             const std::string &pool,
                                                                             unsigned int perClass)
{
  if (pool != "development" && pool != "evaluation")
    throw vpMorphException(vpMorphException::badParameterError,
                           "vpMorphBenchObjectSet: unknown pool '" + pool + "' (development, evaluation)");
  if (perClass == 0)
    throw vpMorphException(vpMorphException::badParameterError, "vpMorphBenchObjectSet: perClass must be > 0");
  std::error_code ec;
  if (!fs::is_regular_file(splitFile, ec))
    throw vpMorphException(vpMorphException::notFoundError, "no split file '" + splitFile + "'");
  if (!fs::is_directory(datasetsDir, ec))
    throw vpMorphException(vpMorphException::notFoundError, "no datasets folder '" + datasetsDir + "'");
  nlohmann::json split;
  try {
    std::ifstream f(splitFile);
    split = nlohmann::json::parse(f);
  } catch (const nlohmann::json::exception &e) {
    throw vpMorphException(vpMorphException::ioError, "malformed split file '" + splitFile + "': " + e.what());
  }
  std::vector<Source> out;
  try {
    for (const char *dataset : {"mpeg7", "kimia99"}) {
      const nlohmann::json &d = split.at("datasets").at(dataset);
      for (const nlohmann::json &c : d.at(pool)) {
        std::vector<std::string> files = d.at("images").at(c.get<std::string>()).get<std::vector<std::string>>();
        const std::string salt = std::string("vispmorph-pool-v1:") + dataset + ":";
        std::stable_sort(files.begin(), files.end(), [&](const std::string &a, const std::string &b) {
          return vpMorphBenchHash::fnv1a(salt + a) < vpMorphBenchHash::fnv1a(salt + b);
        });
        for (std::size_t k = 0; k < files.size() && k < perClass; ++k)
          out.push_back({datasetsDir + "/" + dataset + "/" + files[k],
                         std::string(dataset) + "-" + fs::path(files[k]).stem().string()});
      }
    }
  } catch (const nlohmann::json::exception &e) {
    throw vpMorphException(vpMorphException::ioError, "malformed split file '" + splitFile + "': " + e.what());
  }
  return out;
}

const vpMorphBenchObjectSet::Object &vpMorphBenchObjectSet::operator[](const std::string &name) const
{
  for (const Object &o : m_objects)
    if (o.name == name)
      return o;
  throw vpMorphException(vpMorphException::notFoundError, "vpMorphBenchObjectSet: no object '" + name + "'");
}

std::vector<std::string> vpMorphBenchObjectSet::names() const
{
  std::vector<std::string> n;
  for (const Object &o : m_objects)
    n.push_back(o.name);
  return n;
}

void vpMorphBenchObjectSet::setDesiredPose(const std::string &name, const vpHomogeneousMatrix &cdMo)
{
  for (Object &o : m_objects)
    if (o.name == name) {
      o.fixedPose = true;
      o.desiredPose = cdMo;
      return;
    }
  throw vpMorphException(vpMorphException::notFoundError, "vpMorphBenchObjectSet: no object '" + name + "'");
}
