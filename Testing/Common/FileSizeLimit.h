// A limit on the size of the files the process writes, as a full file system would set, for
// the tests of failed writes (POSIX).
#ifndef pcbilateral_FileSizeLimit_h
#define pcbilateral_FileSizeLimit_h

#include <csignal>
#include <sys/resource.h>

namespace pcbilateral_testing
{

/// While it lives, writes beyond `bytes` fail with EFBIG instead of ending the process (SIGXFSZ
/// is ignored); the limit and the signal's handler are restored when it goes.
class FileSizeLimit
{
public:
  explicit FileSizeLimit(rlim_t bytes)
  {
    getrlimit(RLIMIT_FSIZE, &this->Previous);
    rlimit limited = this->Previous;
    limited.rlim_cur = bytes;
    this->Handler = std::signal(SIGXFSZ, SIG_IGN);
    setrlimit(RLIMIT_FSIZE, &limited);
  }
  ~FileSizeLimit()
  {
    setrlimit(RLIMIT_FSIZE, &this->Previous);
    std::signal(SIGXFSZ, this->Handler);
  }
  FileSizeLimit(const FileSizeLimit&) = delete;
  FileSizeLimit& operator=(const FileSizeLimit&) = delete;

private:
  rlimit Previous;
  void (*Handler)(int);
};

} // namespace pcbilateral_testing

#endif
