// Measures a cloud's point spacing and noise level, and derives the filter's parameters from
// them (the automatic mode). Plain C++17, no VTK types. The measurement only chooses
// parameters: the filter itself is unchanged.
#ifndef pcbilateral_CloudMeasurement_h
#define pcbilateral_CloudMeasurement_h

#include "PointCloudView.h"
#include "SpacingField.h"

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

namespace pcbilateral
{

struct ScaleMeasurementOptions
{
  /// Points around which the surface is fitted, picked deterministically (stratified by index
  /// with a hashed offset). More gives steadier estimates; the cost grows linearly.
  std::size_t NumberOfSamples = 512;
  /// Optional: the indices of the sample points (into the cloud's points). When empty, the
  /// stratified sample above is used.
  std::vector<std::size_t> SampleIndices;
  /// The fraction of the whole cloud that the given points are, when they are a uniform random
  /// subset of it (e.g. gathered from the processes of a distributed run): the measured density
  /// is divided by it, so that the spacing is that of the whole cloud. 1: the whole cloud.
  double PointFraction = 1.0;
  /// Threads for the fits; 0 uses all cores. Results do not depend on it.
  int NumberOfThreads = 0;
};

/// What MeasureScales found. Lengths are in the cloud's units.
struct CloudScales
{
  /// False when the cloud could not be measured (Problem says why).
  bool Valid = false;
  std::string Problem;
  /// False when there was nothing to measure: too few finite points, or all of them at one
  /// place. (Valid false with Measurable true: a cloud of a shape that has no surface to fit,
  /// such as points on a line.)
  bool Measurable = true;
  /// The mean distance from a point to its nearest neighbour on the noise-free surface,
  /// 1 / (2 sqrt(density)) (exact for points spread at random), averaged over the samples with
  /// weights proportional to the area each sample's point covers (the square of its spacing):
  /// the spacing where most of the surface is, not where most of the points are.
  double PointSpacing = 0.0;
  /// How the nearest-neighbour distance varies across the cloud (SpacingField.h), null when it
  /// could not be measured; shared by the copies of these scales.
  std::shared_ptr<const SpacingField> LocalSpacing;
  /// PointSpacing per unit of LocalSpacing: the median over the fitted samples of their spacing
  /// over the field's value at them. LocalSpacing times this is a spacing in PointSpacing's
  /// sense, anywhere in the cloud.
  double SpacingPerNeighbourDistance = 0.0;
  /// The spread of the sampling: the 5th, 50th and 95th percentiles of the distance from a point
  /// to its nearest neighbour (over a pseudo-random sample of the points), 0 when not measured.
  /// A scan from one position spans a hundred times and more between the first and the last.
  double NearestNeighbourDistance[3] = { 0.0, 0.0, 0.0 };
  std::size_t NumberOfDistanceSamples = 0;
  /// The standard deviation of the points' offsets from the underlying surface (the noise),
  /// curvature removed by a local quadric fit.
  double NoiseSigma = 0.0;
  /// Whether the noise was read at a larger scale than the fits (CloudMeasurement.cxx:
  /// CheckStructuredNoise): where a small ball sees almost none, e.g. the quantised depths of a
  /// depth camera, whose points lie on terraces.
  bool StructuredNoise = false;
  /// The median number of points per unit area of surface.
  double SurfaceDensity = 0.0;
  /// The radius of the neighbourhoods the fits used (about 5 sigma, at least ~50 points).
  double NeighbourhoodRadius = 0.0;
  /// How far the surface is from flat at FlatnessRadius (1.5 times the automatic radius): the
  /// median over the samples of the residual variance a plane fit leaves beyond a quadric fit,
  /// in units of sigma^2 (about 0 on flat parts), and the fraction of samples where it exceeds
  /// 0.5 (edges, strong bends).
  double FlatnessRadius = 0.0;
  double CurvatureExcess = 0.0;
  double FeatureFraction = 0.0;
  /// The fraction of samples where, at FlatnessRadius, even the quadric fit leaves more than
  /// twice the noise's variance: a crease (edge, corner, step, vegetation) that no smooth
  /// surface fits. 0 on smooth surfaces however curved.
  double CreaseFraction = 0.0;
  std::size_t NumberOfSamples = 0;
  /// Samples whose neighbourhood could be fitted (enough points, not an isolated outlier).
  std::size_t NumberOfFittedSamples = 0;
  /// Rounds of the radius/noise fixed point (see CloudMeasurement.cxx).
  int NumberOfRounds = 0;
};

/// Measures the point spacing and the noise level of the finite points of a cloud (ghost
/// points count as points of the surface). Deterministic, independent of the number of threads
/// and of the order of the points (the samples and the fits are chosen and ordered by the
/// points' coordinates, not their indices), unless SampleIndices are given.
CloudScales MeasureScales(const PointCloudView& cloud,
  const ScaleMeasurementOptions& options = ScaleMeasurementOptions());

/// Clouds of more finite points than this are measured on a pseudo-random selection of about
/// this many of them (SelectMeasurementPoints): enough for the fits, and a bounded cost in time,
/// memory and, in a distributed run, communication.
constexpr std::size_t MaximumMeasuredPoints = std::size_t(1) << 19;

/// The fraction of a cloud of numberOfFinitePoints finite points that the automatic mode
/// measures: 1 up to MaximumMeasuredPoints.
double MeasuredFraction(std::size_t numberOfFinitePoints);

/// The finite points of cloud (interleaved x y z) in the measured selection of a cloud whose
/// MeasuredFraction is fraction. A point is selected by a hash of its coordinates, so that the
/// parts of a distributed cloud together select exactly the points the whole cloud would.
std::vector<double> SelectMeasurementPoints(const PointCloudView& cloud, double fraction);

/// Measures the selection of a cloud (SelectMeasurementPoints, gathered from the parts of a
/// distributed cloud in any order) as MeasureWholeCloud measures the whole cloud.
CloudScales MeasureSelection(const std::vector<double>& selection, double fraction, int threads);

/// The automatic mode's measurement of a whole cloud: MeasureScales on its selection, with the
/// selection's PointFraction. MeasureScales does not depend on the order of the points, so the
/// result is the same bits for the cloud in any order, split into parts in any way, on any
/// number of threads.
CloudScales MeasureWholeCloud(const PointCloudView& cloud, int threads);
/// The same, for a cloud whose number of finite points is known (from its MeasureCloud): saves
/// a pass over every point, which asks no progress scope (a tenth of a second on 20 million).
CloudScales MeasureWholeCloud(const PointCloudView& cloud,
  std::size_t numberOfFinitePoints,
  int threads);

} // namespace pcbilateral

#endif
