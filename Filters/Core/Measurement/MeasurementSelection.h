// The automatic mode's selection: which points of a large cloud are measured, chosen by a hash
// of their coordinates so that every part of a distributed or streamed cloud selects exactly the
// points the whole cloud would. Private to the measurement (CloudMeasurement.h declares what
// others use: MeasuredFraction, SelectMeasurementPoints).
#ifndef pcbilateral_MeasurementSelection_h
#define pcbilateral_MeasurementSelection_h

#include "PointCloudView.h"

#include <cstdint>
#include <vector>

namespace pcbilateral
{

/// A fixed pseudo-random key per point, from its coordinates alone: the same point gets the same
/// key whatever its index, in whichever part of a distributed cloud it is.
std::uint64_t MeasurementKey(const double* p);

/// The selection's bound for a fraction in (0, 1): a point is selected when a second hash of its
/// MeasurementKey is below it, exactly the keys whose value as a double is below fraction x 2^64
/// (the conversion to double never decreases as the key grows, so those keys are all the keys
/// below one bound); 0 (nothing) for a fraction not above 0, the largest key for 1 and more. Keys
/// are compared as integers: without an instruction for it (before AVX-512), converting a 64-bit
/// unsigned key to double branches on its top bit, a branch mispredicted for half the points.
std::uint64_t SelectionBound(double fraction);

/// SelectMeasurementPoints, and the selected points' MeasurementKey when keys is not null.
std::vector<double> SelectWithKeys(const PointCloudView& cloud,
  double fraction,
  std::vector<std::uint64_t>* keys);

} // namespace pcbilateral

#endif
