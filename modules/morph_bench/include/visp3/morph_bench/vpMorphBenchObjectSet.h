/*!
  \file vpMorphBenchObjectSet.h
  \brief The objects of a benchmark: the six tools, any folder of silhouettes, or a pool of the shape datasets.
*/
#ifndef VP_MORPH_BENCH_OBJECT_SET_H
#define VP_MORPH_BENCH_OBJECT_SET_H

#include <string>
#include <vector>

#include <visp3/core/vpHomogeneousMatrix.h>

/*!
  \class vpMorphBenchObjectSet
  \ingroup group_morph_bench
  \brief The benchmark's objects, each with the images its sets need, and the inputs that could not be used.

  An object has a name (its image's file stem), its template image (black on white, as vispmorph-make-data lays
  it out), its deformed variant with how the truth is held there, and its rough-edged variant:
  - tools(): the six tools of DATA/objects as they are, their drawn deformed variants (truth by the largest
    overlap, no mask of an undeformed part), the pliers articulated by DATA/joints/pliers.json;
  - images(): any silhouette images (either polarity, any size), laid out by vpMorphSilhouetteLayout into
    WORK/objects/NAME.png. A NAME-deformed.png beside one is laid out in its frame and used for the deformable set
    (truth: its undeformed part when a NAME-deformed-mask.png of that part is beside it too, else the largest
    overlap); without one a bent variant is generated (vpMorphBendGenerator, seeded by the seed and the name) with
    the mask of its undeformed part. An unreadable, empty or object-less image is skipped with its reason
    (skipped()), the others kept;
  - poolImages(): the images of a pool of data/pools/split.json (see there).
  Every object gets a rough-edged variant WORK/objects/NAME-rough.png (vpMorphSilhouetteLayout::roughened(),
  kRoughPixels across), the "rough" set's object and template.

  \code
  std::vector<vpMorphBenchObjectSet::Source> src = vpMorphBenchObjectSet::listImages("my-silhouettes");
  vpMorphBenchObjectSet objects = vpMorphBenchObjectSet::images(src, "out/objects", 100);
  for (const auto &s : objects.skipped()) std::cerr << s.source << ": " << s.reason << std::endl;
  \endcode
  \sa vpMorphSilhouetteLayout, vpMorphBenchScenario, \ref page_benchmarks
*/
class vpMorphBenchObjectSet
{
public:
  //! How the deformable set's truth is held (vpMorphBenchScenario::truth()).
  enum Truth {
    TRUTH_PART,       //!< the undeformed part lies on the template's (a mask of it, or a generated bend)
    TRUTH_OVERLAP,    //!< the placement of largest overlap with the template (no mask)
    TRUTH_ARTICULATED //!< either part of an articulated object on the template's (its joint file)
  };
  //! One object and its images.
  struct Object
  {
    std::string name;            //!< file stem
    std::string image;           //!< template image
    std::string deformedImage;   //!< deformable set's image
    std::string deformedMask;    //!< its undeformed part (TRUTH_PART), else empty
    std::string roughImage;      //!< rough set's image (object and template)
    std::string jointFile;       //!< TRUTH_ARTICULATED: the joint file
    Truth truth = TRUTH_OVERLAP; //!< how the deformable set's truth is held
    double undeformedShare = 0;  //!< generated bends: the undeformed part's share of the area
    //! A desired pose of its own (a user's taught pose) instead of vpMorphBenchScenario::desiredPose()'s.
    bool fixedPose = false;
    vpHomogeneousMatrix desiredPose; //!< that pose, cdMo, when fixedPose
  };
  //! An input that could not be used.
  struct Skipped
  {
    std::string source; //!< the input (a path)
    std::string reason; //!< why it is not used
  };
  //! An image to lay out and the object's name.
  struct Source
  {
    std::string path; //!< the image file
    std::string name; //!< the object's name
  };
  //! Low-resolution sources of the "rough" set: pixels across the object's longest side.
  static constexpr unsigned int kRoughPixels = 64;

  /*!
    The six tools of \e dataDir/objects, their rough variants written under \e workDir/objects.
    \throw vpMorphException::notFoundError for a missing image.
  */
  static vpMorphBenchObjectSet tools(const std::string &dataDir, const std::string &workDir);
  /*!
    Any silhouette images (see the class description), laid out under \e workDir/objects; \e seed seeds the bends.
    Never throws for an image: one that cannot be used is in skipped(). \throw vpMorphException::ioError when
    \e workDir cannot be written.
  */
  static vpMorphBenchObjectSet images(const std::vector<Source> &sources, const std::string &workDir,
                                      unsigned int seed);
  /*!
    The images of a folder (its .png, .pgm, .ppm, .jpg and .bmp files in name order, the -deformed and
    -deformed-mask variants left to their object) or of a list file (one path a line, relative to the list's
    folder; blank lines and lines starting with # ignored), each named by its file stem.
    \throw vpMorphException::notFoundError when \e dirOrList does not exist, ioError when it cannot be read.
  */
  static std::vector<Source> listImages(const std::string &dirOrList);
  /*!
    The images of pool \e pool ("development" or "evaluation") of \e splitFile (data/pools/split.json) under
    \e datasetsDir (its mpeg7/ and kimia99/ folders): for each class of the pool, in the file's order (MPEG-7's, then
    Kimia-99's), its images ordered by the FNV-1a 64 hash of "vispmorph-pool-v1:" + dataset + ":" + file name, the
    first \e perClass of them. Names are dataset-file stem (mpeg7-apple-7, kimia99-tool04).
    \throw vpMorphException::notFoundError when the split or the datasets' folder is missing (the caller says so and
    skips), badParameterError for an unknown pool or perClass 0, ioError for a malformed split file.
  */
  static std::vector<Source> poolImages(const std::string &splitFile, const std::string &datasetsDir,
                                        const std::string &pool, unsigned int perClass);

  //! The objects, in order.
  const std::vector<Object> &objects() const { return m_objects; }
  //! The inputs skipped, with their reasons.
  const std::vector<Skipped> &skipped() const { return m_skipped; }
  //! Number of objects.
  std::size_t size() const { return m_objects.size(); }
  //! True without objects.
  bool empty() const { return m_objects.empty(); }
  //! \throw vpMorphException::notFoundError for an unknown name.
  const Object &operator[](const std::string &name) const;
  //! The names, in order.
  std::vector<std::string> names() const;
  //! Gives object \e name a desired pose of its own. \throw vpMorphException::notFoundError for an unknown name.
  void setDesiredPose(const std::string &name, const vpHomogeneousMatrix &cdMo);

private:
  std::vector<Object> m_objects;
  std::vector<Skipped> m_skipped;
};

#endif
