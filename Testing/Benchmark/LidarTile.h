// The airborne-LiDAR-like tile of the benchmarks, generated a block at a time so that a tile of
// any size (200,000,000 points and more) is written without ever being in memory.
#ifndef pcbilateral_LidarTile_h
#define pcbilateral_LidarTile_h

#include "SampleShapes.h"

#include <cstddef>
#include <string>

namespace pcbilateral_benchmark
{

/**
 * An airborne LiDAR tile in metres: one point per square metre, uniformly at random over a
 * 5000 m x (points / 5000) m rectangle at georeferenced coordinates (UTM-like offsets), seen
 * from above: rolling ground (hills of some 20 m over kilometres) and, on a 60 m grid of
 * blocks, buildings with flat roofs 4 to 25 m high and 15 to 45 m wide in about half of the
 * blocks, whose roofs hide the ground below (no wall points, as from nadir). Vertical noise of
 * 5 cm, as in survey-grade LiDAR.
 *
 * The points come in one sequence from one seed: any split into blocks gives the same points.
 */
class LidarTile
{
public:
  explicit LidarTile(std::size_t points);

  /// The next `count` points of the tile, x y z after one another, into `xyz`.
  void Next(std::size_t count, double* xyz);

private:
  pcbilateral_samples::Random Generator;
  double Depth;
};

/**
 * Writes the tile of `points` points to `path`, LAZ when it ends in ".laz" (any case), LAS
 * otherwise (point format 1, millimetre scale), generating and writing one block at a time:
 * one pass for the bounds (the header's offsets), one to write. Returns an empty string or
 * a one-line message; on failure no file is left.
 */
std::string WriteLidarTile(const std::string& path, std::size_t points);

} // namespace pcbilateral_benchmark

#endif
