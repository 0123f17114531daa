// The ground truth the quality benchmarks (pcb_quality, pcb_edges) judge a filtered cloud against:
// the RMS distance of its points to the exact surface, and the same near sharp edges (two bands).
#ifndef pcbilateral_benchmark_GroundTruth_h
#define pcbilateral_benchmark_GroundTruth_h

#include "BenchmarkTiming.h"
#include "BilateralFilter.h"
#include "CloudView.h"
#include "SampleShapes.h"

#include <cmath>
#include <cstdint>
#include <vector>

namespace pcbilateral_benchmark
{
using namespace pcbilateral_samples;

struct Quality
{
  double Rms = 0.0;
  /// Over the points whose noise-free position is within 3 sigma of a sharp edge: the band where
  /// a filter rounds an edge.
  double EdgeRms = 0.0;
  /// Over the wide band, 3 sigma + 3% of the diagonal: about three times as many points, most of
  /// them on flat ground a plane fit already handles (the band of the first measurements).
  double WideEdgeRms = 0.0;
};

/// A noisy cloud of a shape, and which of its points are near a sharp edge: those whose
/// noise-free position is within 3 sigma of one (NearEdge), and within 3 sigma + 3% of the
/// diagonal (NearEdgeWide); outliers never are.
struct Truth
{
  const Shape* Surface = nullptr;
  const NoisyCloud* Cloud = nullptr;
  std::vector<std::uint8_t> NearEdge, NearEdgeWide;
  std::size_t EdgePoints = 0, WideEdgePoints = 0;
  /// The unit of the measures: 1 for the cloud's own, 1e3 / diagonal for thousandths of it.
  double Unit = 1.0;

  Truth(const Shape& surface, const NoisyCloud& cloud, double unit = 1.0)
    : Surface(&surface)
    , Cloud(&cloud)
    , NearEdge(cloud.NumberOfPoints(), 0)
    , NearEdgeWide(cloud.NumberOfPoints(), 0)
    , Unit(unit)
  {
    const double band = 3.0 * cloud.Sigma;
    const double wideBand = band + 0.03 * surface.Diagonal();
    for (std::size_t i = 0; i < cloud.NumberOfPoints(); ++i)
    {
      const Vec3 clean{ cloud.Clean[3 * i], cloud.Clean[3 * i + 1], cloud.Clean[3 * i + 2] };
      const double distance = cloud.Outlier[i] ? 1e300 : surface.EdgeDistance(clean);
      this->NearEdge[i] = distance <= band;
      this->NearEdgeWide[i] = distance <= wideBand;
      this->EdgePoints += this->NearEdge[i];
      this->WideEdgePoints += this->NearEdgeWide[i];
    }
  }

  /// The RMS distances of the given positions (the cloud's points, filtered) to the surface,
  /// outliers left out.
  Quality Measure(const std::vector<double>& positions) const
  {
    double sum = 0.0, edgeSum = 0.0, wideSum = 0.0;
    std::size_t count = 0;
    for (std::size_t i = 0; i < this->Cloud->NumberOfPoints(); ++i)
    {
      if (this->Cloud->Outlier[i])
      {
        continue;
      }
      const double d =
        this->Surface->Distance({ positions[3 * i], positions[3 * i + 1], positions[3 * i + 2] });
      sum += d * d;
      ++count;
      edgeSum += this->NearEdge[i] ? d * d : 0.0;
      wideSum += this->NearEdgeWide[i] ? d * d : 0.0;
    }
    Quality quality;
    quality.Rms = this->Unit * std::sqrt(sum / static_cast<double>(count));
    quality.EdgeRms = this->EdgePoints
                        ? this->Unit * std::sqrt(edgeSum / static_cast<double>(this->EdgePoints))
                        : 0.0;
    quality.WideEdgeRms =
      this->WideEdgePoints
        ? this->Unit * std::sqrt(wideSum / static_cast<double>(this->WideEdgePoints))
        : 0.0;
    return quality;
  }
};
} // namespace pcbilateral_benchmark

#endif
