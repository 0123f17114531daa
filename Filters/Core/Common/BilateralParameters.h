// The filter's parameters in the paper's terms, their limits and their one check. Below the
// run and the measurement, which both read them. Plain C++17, no VTK types.
#ifndef pcbilateral_BilateralParameters_h
#define pcbilateral_BilateralParameters_h

#include <string>

namespace pcbilateral
{

/// Limits every front end enforces (the VTK class, the ParaView XML and the command line read
/// them from here, so that they cannot disagree).
namespace limits
{
/// More iterations than this are refused: the paper uses a few, and each one may move the points
/// by up to the radius, so that thousands would only collapse the cloud, slowly.
constexpr int MaximumIterations = 1000;
/// More threads than this are refused: the largest machines have a few hundred hardware
/// threads, the result is the same for any count, and beyond the hardware's threads each one
/// only adds its start and its share of the synchronisation (an absurd count, a typo for a
/// radius say, would start thousands of threads or fail to).
constexpr int MaximumThreads = 1024;
} // namespace limits

/// How the parameters left at 0 (automatic) are chosen.
enum class AutomaticParameters
{
  /// From the cloud's measured point spacing and noise: the automatic rule, ChooseParameters in
  /// Measurement/AutomaticRule.h (its documentation is the one description of the rule).
  Measured = 0,
  /// The paper's heuristic (PaperRadius in Measurement/AutomaticRule.h): r = sqrt(20 / number
  /// of points) x the bounding box's largest extent, rn = r, N = 1 (the authors' program).
  Paper = 1
};

/// Parameters in the paper's terms (section 5). The member initialisers are the defaults of
/// every front end: all automatic.
struct BilateralParameters
{
  /// Neighbourhood radius r; sd = r / 3. Zero means automatic (see Automatic).
  double Radius = 0.0;
  /// Normal radius rn, the thickness of the slab around the tangent plane; sn = rn / 3. Zero
  /// means automatic (see Automatic).
  double NormalRadius = 0.0;
  /// Number of iterations N; each reads the positions written by the previous one. Zero means
  /// automatic (see Automatic).
  int NumberOfIterations = 0;
  /// How the parameters left at 0 are chosen; each given parameter overrides only itself.
  AutomaticParameters Automatic = AutomaticParameters::Measured;
  /// Points with fewer than 5 neighbours (or a zero weight sum) stay where they are; with this
  /// on they are removed for the rest of the run instead, as the authors' program does.
  bool RemoveIsolatedPoints = false;
  /// Threads for the parallel loops; 0 uses all cores, at most limits::MaximumThreads. Results
  /// do not depend on it.
  int NumberOfThreads = 0;
  /// Also return the estimated normals of the last iteration.
  bool ComputeNormals = false;
  /// Edge-aware mode, beyond the paper (EdgeAware/EdgeAwareNormals.h): the normals are filtered
  /// bilaterally before the displacement, which keeps sharp edges under strong noise. Off: the
  /// paper's filter, bit for bit.
  bool EdgeAware = false;
};

/// Why these parameters cannot run, in words for the user, or empty. The one check of every
/// front end (a BilateralRun makes it first).
std::string CheckParameters(const BilateralParameters& parameters);

} // namespace pcbilateral

#endif
