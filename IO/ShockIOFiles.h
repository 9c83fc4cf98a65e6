/**
 * @file   ShockIOFiles.h
 * @brief  Files as the readers and writers of this library see them: the
 *         checks before reading and writing, whole-file reading, and outputs
 *         that replace their target only when complete.
 *
 * Every function reports a problem as one line naming the file in `error`.
 */
#ifndef ShockIOFiles_h
#define ShockIOFiles_h

#include "ShockIOMessages.h"

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace shockio
{

/**
 * The default limit on the samples a file may declare: pixels or voxels of an
 * image, points or cells of a mesh. Readers refuse files declaring more before
 * anything is allocated.
 */
inline constexpr std::uint64_t DefaultMaxSamples = 100000000;

/// Whether `path` exists, is a regular file, opens for reading and is not empty; else sets `error`.
bool CheckReadable(const std::string& path, std::string& error);

/// Whether `path` can be written: its directory exists and it is a regular file if it exists; else sets `error`.
bool CheckWritable(const std::string& path, std::string& error);

/// The lower-case extension of `path`, with its dot ("" if none).
std::string LowerExtension(const std::string& path);

/**
 * The entry of a format table (items with a `name` and a list of lower-case
 * `extensions` without the dot) that the extension of `path` names, in any
 * letter case; else null with `error` set, listing the known extensions.
 */
template <typename Format>
const Format* FormatOfPath(
  const std::vector<Format>& formats, const std::string& path, const char* kind, std::string& error)
{
  const std::string extension = LowerExtension(path);
  std::string known;
  for (const Format& format : formats)
  {
    for (const std::string& candidate : format.extensions)
    {
      if (extension == "." + candidate)
      {
        return &format;
      }
      known += (known.empty() ? "" : ", ") + candidate;
    }
  }
  error = path + ": " +
    (extension.empty() ? std::string("no file extension")
                       : "unknown extension '" + extension + "'") +
    " (" + kind + " files are: " + known + ")";
  return nullptr;
}

/// Reads the whole file into `text`; false with `error` set on failure.
bool ReadFile(const std::string& path, std::string& text, std::string& error);

/**
 * The file an output is written to: a new temporary file beside `target` (same
 * directory, so that renaming it is atomic; same lower-case extension, which
 * some VTK writers require), renamed over the target by Commit(). Until then,
 * and whatever happens to the write (a full disk, an error), an existing
 * target, which may be the input file, is left untouched; the destructor
 * removes the temporary file unless it was committed.
 */
class OutputFile
{
public:
  explicit OutputFile(std::string target);
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  /// Whether the temporary file could be created; else `error` is set.
  bool Open(std::string& error);
  /// The temporary file to write.
  const std::string& Path() const { return this->Temporary; }
  /// Flushes the temporary file to disk and renames it over the target; false with `error` set on failure.
  bool Commit(std::string& error);

private:
  std::string Target;
  std::string Temporary;
  bool Committed = false;
};

/// Writes `text` as the file `path` (through an OutputFile); false with `error` set on failure.
bool WriteFile(const std::string& path, const std::string& text, std::string& error);

/// Checks a file just written (under its temporary name) before it replaces its target.
using WrittenFileCheck = std::function<bool(const std::string& written)>;

/**
 * Runs a VTK writer (of any kind: vtkWriter, vtkImageWriter) whose input is
 * set on `path`, through an OutputFile: `trap` watches it, and the target is
 * replaced only if the writer reports no error and `check` (when given) finds
 * the written file complete; many VTK writers ignore failed writes (a full
 * disk), so reading the file back is the check that holds. False with `error`
 * set on failure; an existing target is then untouched.
 */
template <typename Writer>
bool RunWriter(Writer* writer, const std::string& path, MessageTrap* trap, std::string& error,
  const WrittenFileCheck& check = {})
{
  OutputFile output(path);
  if (!output.Open(error))
  {
    return false;
  }
  writer->SetFileName(output.Path().c_str());
  trap->Watch(writer);
  writer->Write();
  if (writer->GetErrorCode() != 0 || (check && !check(output.Path())))
  {
    error = path + ": writing failed (is the disk full?)";
    return false;
  }
  return output.Commit(error);
}

} // namespace shockio

#endif
