// A few checks for the core's tests, which build without VTK or a test framework.
#ifndef pcbilateral_CoreTesting_h
#define pcbilateral_CoreTesting_h

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace pcbilateral_testing
{
/// Whether two arrays of doubles hold the same bits (NaN equal to the same NaN, -0 not to 0).
inline bool SameBits(const std::vector<double>& a, const std::vector<double>& b)
{
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}

/// A file's bytes (empty when it cannot be read).
inline std::string FileContents(const std::string& path)
{
  std::ifstream file(path, std::ios::binary);
  std::ostringstream bytes;
  bytes << file.rdbuf();
  return bytes.str();
}

/// Writes `bytes` as the whole file at `path`; returns the path.
inline std::string WriteFileContents(const std::string& path, const std::string& bytes)
{
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

inline int& FailureCount()
{
  static int failures = 0;
  return failures;
}
} // namespace pcbilateral_testing

/// Records a failure with its location and message, and goes on.
#define PCB_CHECK(condition, ...)                                                                  \
  do                                                                                               \
  {                                                                                                \
    if (!(condition))                                                                              \
    {                                                                                              \
      std::fprintf(stderr, "%s:%d: check failed: %s: ", __FILE__, __LINE__, #condition);           \
      std::fprintf(stderr, __VA_ARGS__);                                                           \
      std::fprintf(stderr, "\n");                                                                  \
      ++pcbilateral_testing::FailureCount();                                                       \
    }                                                                                              \
  } while (false)

/// The exit status of a test: non-zero when a check failed.
#define PCB_TEST_RESULT()                                                                          \
  (pcbilateral_testing::FailureCount() == 0                                                        \
      ? (std::printf("all checks passed\n"), EXIT_SUCCESS)                                         \
      : (std::printf("%d check(s) failed\n", pcbilateral_testing::FailureCount()), EXIT_FAILURE))

/// Runs the case named by the first argument (a test program holding several ctest cases) and
/// returns the exit status.
inline int RunNamedCase(int argc,
  char* argv[],
  const std::map<std::string, std::function<void()>>& cases)
{
  const auto found = argc > 1 ? cases.find(argv[1]) : cases.end();
  if (found == cases.end())
  {
    std::fprintf(stderr, "usage: %s CASE, one of:", argv[0]);
    for (const auto& entry : cases)
    {
      std::fprintf(stderr, " %s", entry.first.c_str());
    }
    std::fprintf(stderr, "\n");
    return EXIT_FAILURE;
  }
  found->second();
  std::printf("%s: ", found->first.c_str());
  return PCB_TEST_RESULT();
}

/// ctest counts a test that exits with this status as skipped (SKIP_RETURN_CODE).
constexpr int PCB_SKIP_RETURN_CODE = 77;

#endif
