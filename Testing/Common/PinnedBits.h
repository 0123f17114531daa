// The pinned-output checks of the core's tests: a run's output bits, fingerprinted, must be the
// same for every kernel build this machine runs and every number of threads.
#ifndef pcbilateral_PinnedBits_h
#define pcbilateral_PinnedBits_h

#include "BilateralKernel.h"
#include "CoreTesting.h"

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <functional>
#include <initializer_list>
#include <vector>

namespace pcbilateral_testing
{

/// FNV-1a over the bytes of the values: a fingerprint of a run's output bits.
inline std::uint64_t HashBits(const std::vector<double>& values)
{
  std::uint64_t hash = 14695981039346656037ULL;
  for (const double value : values)
  {
    unsigned char bytes[sizeof(double)];
    std::memcpy(bytes, &value, sizeof(value));
    for (const unsigned char byte : bytes)
    {
      hash = (hash ^ byte) * 1099511628211ULL;
    }
  }
  return hash;
}

/**
 * Runs `run(threads)` (a fingerprint of one run's output) in every kernel build available here
 * and with each number of threads, prints each fingerprint and checks it is `expected`; the
 * best build is selected again afterwards.
 */
inline void CheckPinnedBits(std::uint64_t expected,
  std::initializer_list<int> threadCounts,
  const std::function<std::uint64_t(int)>& run)
{
  using namespace pcbilateral;
  const KernelInstructionSet best = GetKernelInstructionSet();
  for (const auto set :
    { KernelInstructionSet::Generic, KernelInstructionSet::Avx2, KernelInstructionSet::Avx512 })
  {
    if (!SetKernelInstructionSet(set))
    {
      std::printf("%s: not available here\n", GetName(set));
      continue;
    }
    for (const int threads : threadCounts)
    {
      const std::uint64_t hash = run(threads);
      std::printf("%s, %d thread(s): 0x%016llx\n",
        GetName(set),
        threads,
        static_cast<unsigned long long>(hash));
      PCB_CHECK(hash == expected,
        "%s, %d thread(s): output hash 0x%016llx, expected 0x%016llx",
        GetName(set),
        threads,
        static_cast<unsigned long long>(hash),
        static_cast<unsigned long long>(expected));
    }
  }
  SetKernelInstructionSet(best);
}

} // namespace pcbilateral_testing

#endif
