// A few checks for the core's tests, which build without VTK or a test framework.
#ifndef pcbilateral_CoreTesting_h
#define pcbilateral_CoreTesting_h

#include <cstdio>
#include <cstdlib>

namespace pcbilateral_testing
{
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

/// ctest counts a test that exits with this status as skipped (SKIP_RETURN_CODE).
constexpr int PCB_SKIP_RETURN_CODE = 77;

#endif
