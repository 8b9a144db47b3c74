#pragma once
// The container the methods' solution files share (include/radiosity/solution_file.h): magic,
// version, method, key, settings, the method's payload, checksum.

#include <radiosity/solution_file.h>

#include <span>
#include <stdexcept>
#include <string>

#include "core/binary_io.h"

namespace rad {

/// The start of a file: magic, version, method, the key of `scene` and `lights`, `settings`.
std::string solutionFileStart(const std::string& method, const Scene& scene,
                              std::span<const Light> lights, const SolverSettings& settings);
/// Appends the checksum and writes `bytes` to `path` atomically. Throws std::runtime_error.
void writeSolutionFile(const std::string& path, std::string& bytes);

/// A whole file, checked, and where its payload lies.
struct SolutionFile {
  std::string path, bytes;
  SolutionFileInfo info;
  Key128 key;
  size_t payloadBegin = 0, payloadEnd = 0;

  /// Reads and checks the file; throws InputError(path, why).
  explicit SolutionFile(const std::string& path);
  /// Throws InputError unless the file is of `method` and of this scene and these lights.
  void checkFor(const std::string& method, const Scene& scene, std::span<const Light> lights) const;
  ByteReader payload() const { return ByteReader(bytes, payloadBegin, payloadEnd); }
  /// Calls read(payload()); a payload cut short or a bad light-group scale in it is refused.
  template <class Read>
  void readPayload(Read&& read) const {
    try {
      read(payload());
    } catch (const std::out_of_range&) {
      refuse("its arrays are cut short");
    } catch (const std::invalid_argument& e) {  // a light group's scale
      refuse(e.what());
    }
  }
  /// The next `count` colours of an irradiance or radiosity array (`what` names it), refused
  /// (InputError naming it) unless every component is finite and not negative
  /// (allFiniteNonNegative, the check the form-factor cache's values get).
  std::vector<Color> radiometry(ByteReader& in, uint64_t count, const char* what) const;
  /// Throws InputError(path, "<what>: " + why): the payload does not fit the scene.
  [[noreturn]] void refuse(const std::string& why) const;
};

}  // namespace rad
