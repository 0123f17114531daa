// The temporary files of an out-of-core run: a folder of their own, removed with them on every
// exit, including SIGINT, SIGTERM and SIGHUP. Plain C++17 (POSIX). Private to Streaming/.
#ifndef pcbilateral_TemporaryFiles_h
#define pcbilateral_TemporaryFiles_h

#include <cstddef>
#include <string>

namespace pcbilateral
{

/**
 * A folder made in `parent` (mkdtemp) for files named by number; the destructor removes them and
 * the folder. Their paths are also kept in fixed memory that a signal handler can read (one
 * folder at a time), so that RemoveTemporaryFilesOnSignals can remove them.
 */
class TemporaryFiles
{
public:
  static constexpr std::size_t MaximumFiles = 640;
  TemporaryFiles() = default;
  ~TemporaryFiles();
  TemporaryFiles(const TemporaryFiles&) = delete;
  TemporaryFiles& operator=(const TemporaryFiles&) = delete;

  /// Makes the folder; an empty string or a one-line message.
  std::string Create(const std::string& parent);
  const std::string& GetFolder() const { return this->Folder; }
  /// The path of file `number` (below MaximumFiles), registered for removal.
  std::string PathOf(std::size_t number);
  /// Removes the files and the folder now.
  void RemoveAll();

private:
  std::string Folder;
};

} // namespace pcbilateral

#endif
