// vispmorph-reid's shapes and views: the pool's shapes read from the split, one shape kept of those that are one at
// two sizes, their textures and taught views, and the queries' views drawn, rendered, extracted and recognised.
#ifndef VISPMORPH_REID_VIEWS_H
#define VISPMORPH_REID_VIEWS_H

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include <visp3/morph/vpMorphContour.h>
#include <visp3/morph/vpMorphDatabase.h>
#include <visp3/morph/vpMorphPartRecognizer.h>
#include <visp3/morph/vpMorphRecognition.h>
#include <visp3/morph/vpMorphShapeDistance.h>

//! splitmix64's mixing function.
std::uint64_t mix(std::uint64_t x);
//! FNV-1a of a string.
std::uint64_t hashString(const std::string &s);
//! A deterministic stream per (seed, condition, shape, view), whatever the threads.
std::uint64_t streamSeed(std::uint64_t seed, const std::string &condition, const std::string &shape,
                         std::uint64_t view);

//! One shape of a dataset: its identifier (dataset:file stem), class and image.
struct Shape
{
  std::string id, cls;
  std::filesystem::path image;
};

//! A shape of the run: its texture, its taught view, and whether its template is in the database.
struct Entry
{
  Shape shape;
  std::filesystem::path texture;
  vpMorphContour taught;
  bool present = true;
};

//! One query (a view of one shape under one condition) and each model's answer.
struct Query
{
  std::size_t entry = 0, view = 0;
  std::string condition;
  vpMorphContour contour; // empty when no object was seen
  std::vector<vpMorphRecognition> answers;
  std::vector<double> ms; // CPU time of recognize(), per model
};

//! The split file (data/pools/split.json). \throw vpMorphException::ioError when unreadable or malformed.
nlohmann::json readSplit(const std::string &path);
//! The classes of a pool of a dataset, in the split's order, each with its images (duplicates already left out).
//! \throw vpMorphException::ioError on a pool or an image missing.
std::vector<std::vector<Shape>> poolClasses(const nlohmann::json &split, const std::string &dataset,
                                            const std::string &pool, const std::filesystem::path &datasets);
//! A progress callback that prints \e what and the count every twentieth of the total.
vpMorphShapeDistance::Progress every(const std::string &what);
/*!
  Shapes of one class that are one shape at two sizes (or turned): vpMorphRigidCheck::similarityDeviation() of their
  images' outlines within sqrt(2) px of the coarser image (the digitisation bound of two images of one outline). Each
  group keeps its first shape in the split's order; the others are left out of the run and returned (shape, kept).
*/
std::vector<std::pair<std::string, std::string>> mergeSimilar(std::vector<std::vector<Shape>> &classes,
                                                              unsigned int threads);
//! The textures and taught views of \e shapes (all cores); \e texDir receives the textures.
std::vector<Entry> teachAll(const std::vector<Shape> &shapes, const std::vector<bool> &present,
                            const std::filesystem::path &texDir, unsigned int threads);
//! Renders and extracts every query's view (all cores); a view without object stays empty.
void extractQueries(std::vector<Query> &queries, const std::vector<Entry> &entries, std::uint64_t seed,
                    unsigned int threads);
//! A model under test: its database, and for a model "part+DISTANCE" the vpMorphPartRecognizer over it.
struct Model
{
  vpMorphDatabase db;
  std::shared_ptr<const vpMorphPartRecognizer> part;
  vpMorphRecognition recognize(const vpMorphContour &c) const { return part ? part->recognize(c) : db.recognize(c); }
};
//! Recognises every query with every model on \e threads threads, each recognition timed on its own thread: the
//! fastest of \e repetitions recognitions (the answer is the same each time; the machine's noise is not).
void recognizeQueries(std::vector<Query> &queries, const std::vector<Model> &models, unsigned int threads,
                      unsigned int repetitions = 1);

#endif
