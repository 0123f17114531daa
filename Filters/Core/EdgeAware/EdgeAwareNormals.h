// The edge-aware mode, beyond the paper (issue 15): one iteration of the bilateral filter whose
// normals are first filtered bilaterally, so that near a sharp edge a point moves along the
// normal of its own side rather than along the tilted normal of a plane fitted across the edge.
// Plain C++17, no VTK types.
//
// One iteration, on the positions of the previous one (all sums in double, on offsets from the
// point being computed):
//  1. every point's normal n_i: the paper's weighted regression plane over |q - p| < r, with
//     the distance weight exp(-|q - p|^2 / (2 sd^2)), sd = r / 3 (the same fit as Algorithm 1),
//     then EdgeAwareRefits refits with the weights multiplied by beta(-res^2 / (2 sn^2)), sn =
//     rn / 3, beta(x) = max(0, 1 + x / 4)^4 (shaped like exp(x) near 0, without its cost), res
//     the neighbour's height over the last plane (through the weighted mean): the
//     plane of a neighbourhood that straddles an edge is tilted, and the refit leaves out the
//     points farthest from it, those of the other face (an iteratively reweighted fit, as in
//     robust moving least squares);
//  2. EdgeAwareNormalPasses times, the normals filtered bilaterally (Jones et al., "Non-iterative,
//     feature-preserving mesh smoothing", SIGGRAPH 2003; Zheng et al., "Bilateral normal
//     filtering for mesh denoising", IEEE TVCG 2011; Huang et al., "Edge-aware point set
//     resampling", ACM TOG 2013, for point sets):
//       m_i = normalise( sum_j exp(-|p_j - p_i|^2 / (2 sd^2)) psi(n_i, n_j) s_ij n_j )
//     with s_ij = sign(n_i . n_j) (the fitted normals are not oriented) and the agreement weight
//     psi = exp(-((1 - |n_i . n_j|) / (1 - cos theta))^2), theta = EdgeAwareNormalAngle: the
//     neighbours across an edge, whose normals disagree, hardly count, so the normal of a point
//     near an edge turns toward its own side's;
//  3. the move, with the weights w_j = exp(-|q - p|^2 / (2 sd^2)) exp(-h_j^2 / (2 sn^2))
//     psi(m_i, m_j) (the agreement of the filtered normals leaves out the other side of an
//     edge, which the height weight alone cannot when the noise is as thick as the feature):
//       p + a_i (sum w_j h_j / sum w_j) m_i + (1 - a_i) sum w_j <m_j, q_j - p> m_j / sum w_j,
//     - h_j = <(m_i + s_ij m_j) / 2, q_j - p> the height along the mean of the two normals,
//       which keeps curved surfaces from shrinking (the chord between two points of a sphere is
//       orthogonal to the sum of their normals; on a plane h is the paper's <m_i, q_j - p>);
//     - <m_j, q_j - p> m_j the move onto the neighbour's own tangent plane (Huang et al. 2013's
//       projection), which keeps a point on its own face up to an edge but swells a convex
//       smooth surface (the tangent planes lie outside it);
//     - a_i the share of the first: 1 where at least EdgeAwareSmoothAgreement of the
//       neighbourhood (weighted by max(0, 1 - |q - p|^2 / r^2)^4) has normals within about
//       EdgeAwareSmoothAngle of m_i (weighted by beta of psi's exponent at that angle; smooth),
//       0 where at most EdgeAwareEdgeAgreement does (an edge), linear between.
//
// Each step reads the neighbours' results of the step before, so a point's result depends on
// the points within EdgeAwareReachInRadii radii of it: that is the ghost margin of a
// distributed run. Neighbours are visited in an order fixed by their coordinates alone (a grid
// of cell size r anchored at the whole cloud's lower corner, then coordinates within a cell),
// so the bits depend neither on the number of threads nor on how the cloud is split or
// numbered. The per-point arithmetic of the three steps is the kernel's (EdgeAwareKernel in
// BilateralKernel.h): vectorised like the paper's kernel, with its exponential and its partial
// sums per lane added in a fixed tree, so the same bits in every build.
#ifndef pcbilateral_EdgeAwareNormals_h
#define pcbilateral_EdgeAwareNormals_h

#include "PointState.h"

#include <cstdint>
#include <functional>

namespace pcbilateral
{

/// Passes of bilateral normal filtering per iteration (step 2). Chosen by measurement
/// (Testing/Benchmark/pcb_edges.cxx; three passes did not do better on the 3-sigma edge band).
constexpr int EdgeAwareNormalPasses = 1;
/// The angle theta of the normal agreement weight, in degrees. Chosen by measurement.
constexpr double EdgeAwareNormalAngle = 10.0;
/// Refits of step 1's plane with the residual weight. Chosen by measurement (two gain little
/// over one on pcb_edges's shapes and cost a pass more).
constexpr int EdgeAwareRefits = 1;
/// The wider angle of the agreement that tells a smooth neighbourhood from an edge in step 3,
/// in degrees, and the shares of agreeing neighbours (by distance weight) at and below which
/// the move is the mean-normal height's alone (smooth) or the tangent-plane projection's alone
/// (edge). Chosen by measurement.
constexpr double EdgeAwareSmoothAngle = 25.0;
constexpr double EdgeAwareSmoothAgreement = 0.9;
constexpr double EdgeAwareEdgeAgreement = 0.5;
/// How far, in radii, the points an iteration reads lie from the points it moves.
constexpr int EdgeAwareReachInRadii = EdgeAwareNormalPasses + 2;

struct EdgeAwareSettings
{
  double Radius = 0.0;
  double NormalRadius = 0.0;
  /// The grid's anchor: the lower corner of the whole cloud, the same for every part of it.
  double Origin[3] = { 0.0, 0.0, 0.0 };
  /// How far from Origin the points can be during the whole run (the whole cloud's largest
  /// extent and its moves): sets the margin of the grid's cells for rounding.
  double CloudReach = 0.0;
  bool RemoveIsolatedPoints = false;
  int NumberOfThreads = 1;
  /// Polled from the calling thread; may be empty.
  std::function<bool()> ShouldAbort;
  /// The fraction of the iteration done, from the calling thread; may be empty.
  std::function<void(double)> Progress;
};

/**
 * One edge-aware iteration over `state` (positions by id, the last ones from FirstGhost on
 * ghosts: neighbours only, never moved). Moves the points in place; removed points and points
 * with a non-finite coordinate are neither moved nor neighbours. Points with fewer than
 * MinimumNeighbourCount neighbours stay (or are removed, with RemoveIsolatedPoints). When
 * state.Normals is not empty it receives the filtered normals m_i (flipped to agree with
 * state.OrientationNormals when given; zero where none was estimated).
 * Returns false if aborted (the positions are then unchanged). `evaluations` receives the
 * number of neighbours visited.
 */
bool RunEdgeAwareIteration(PointState& state,
  const EdgeAwareSettings& settings,
  std::uint64_t& evaluations);

} // namespace pcbilateral

#endif
