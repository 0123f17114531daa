// The shapes of the sample clouds: each samples its surface uniformly and knows the exact
// distance from any point to that surface, so tests can measure a filter's error. Shared by the
// generator (MakeSamples.cxx) and the data tests. Plain C++17.
#ifndef pcbilateral_SampleShapes_h
#define pcbilateral_SampleShapes_h

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <vector>

namespace pcbilateral_samples
{
using Vec3 = std::array<double, 3>;

inline Vec3 operator+(const Vec3& a, const Vec3& b)
{
  return { a[0] + b[0], a[1] + b[1], a[2] + b[2] };
}
inline Vec3 operator-(const Vec3& a, const Vec3& b)
{
  return { a[0] - b[0], a[1] - b[1], a[2] - b[2] };
}
inline Vec3 operator*(double s, const Vec3& a)
{
  return { s * a[0], s * a[1], s * a[2] };
}
inline double Dot(const Vec3& a, const Vec3& b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
inline Vec3 Cross(const Vec3& a, const Vec3& b)
{
  return { a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0] };
}
inline double Norm(const Vec3& a)
{
  return std::sqrt(Dot(a, a));
}

/// A fixed-seed generator whose numbers do not depend on the standard library's distributions.
class Random
{
public:
  explicit Random(std::uint64_t seed)
    : Engine(seed)
  {
  }
  /// Uniform in [0, 1), from the top 53 bits.
  double Uniform() { return static_cast<double>(this->Engine() >> 11) * 0x1.0p-53; }
  double Uniform(double low, double high) { return low + (high - low) * this->Uniform(); }
  /// Standard normal, by Box-Muller.
  double Gaussian()
  {
    const double u = std::max(this->Uniform(), 1e-300);
    return std::sqrt(-2.0 * std::log(u)) * std::cos(2.0 * M_PI * this->Uniform());
  }

private:
  std::mt19937_64 Engine;
};

/// A surface that can be sampled and measured.
class Shape
{
public:
  virtual ~Shape() = default;
  /// A point drawn uniformly on the surface.
  virtual Vec3 Sample(Random& random) const = 0;
  /// Distance from p to the surface.
  virtual double Distance(const Vec3& p) const = 0;
  /// Diagonal of the surface's bounding box (noise levels are fractions of it).
  virtual double Diagonal() const = 0;
  /// Distance from p to the nearest sharp edge (where two faces meet at an angle); infinite
  /// for smooth shapes. Quality measures restrict errors to points near edges with it.
  virtual double EdgeDistance(const Vec3&) const { return std::numeric_limits<double>::infinity(); }
};

/// Distance from p to the segment [a, b].
inline double SegmentDistance(const Vec3& p, const Vec3& a, const Vec3& b)
{
  const Vec3 edge = b - a;
  const double along = std::clamp(Dot(p - a, edge) / Dot(edge, edge), 0.0, 1.0);
  return Norm(p - (a + along * edge));
}

/// A planar polygon (vertices in order, any simple polygon).
class Polygon
{
public:
  explicit Polygon(std::vector<Vec3> vertices)
    : Vertices(std::move(vertices))
  {
    // Newell's normal, and a frame in the plane.
    Vec3 n{ 0, 0, 0 };
    for (std::size_t i = 0; i < this->Vertices.size(); ++i)
    {
      n = n + Cross(this->Vertices[i], this->Vertices[(i + 1) % this->Vertices.size()]);
    }
    this->Area = 0.5 * Norm(n);
    this->Normal = (1.0 / Norm(n)) * n;
    this->U = this->Vertices[1] - this->Vertices[0];
    this->U = (1.0 / Norm(this->U)) * this->U;
    this->V = Cross(this->Normal, this->U);
    for (const Vec3& vertex : this->Vertices)
    {
      this->Planar.push_back(
        { Dot(vertex - this->Vertices[0], this->U), Dot(vertex - this->Vertices[0], this->V) });
    }
    for (const auto& q : this->Planar)
    {
      this->Low[0] = std::min(this->Low[0], q[0]);
      this->Low[1] = std::min(this->Low[1], q[1]);
      this->High[0] = std::max(this->High[0], q[0]);
      this->High[1] = std::max(this->High[1], q[1]);
    }
  }

  double GetArea() const { return this->Area; }
  const std::vector<Vec3>& GetVertices() const { return this->Vertices; }
  const Vec3& GetNormal() const { return this->Normal; }

  bool Contains(double s, double t) const
  {
    bool inside = false;
    for (std::size_t i = 0, j = this->Planar.size() - 1; i < this->Planar.size(); j = i++)
    {
      const auto& a = this->Planar[i];
      const auto& b = this->Planar[j];
      if ((a[1] > t) != (b[1] > t) && s < (b[0] - a[0]) * (t - a[1]) / (b[1] - a[1]) + a[0])
      {
        inside = !inside;
      }
    }
    return inside;
  }

  Vec3 Sample(Random& random) const
  {
    for (;;)
    {
      const double s = random.Uniform(this->Low[0], this->High[0]);
      const double t = random.Uniform(this->Low[1], this->High[1]);
      if (this->Contains(s, t))
      {
        return this->Vertices[0] + s * this->U + t * this->V;
      }
    }
  }

  double Distance(const Vec3& p) const
  {
    const Vec3 d = p - this->Vertices[0];
    if (this->Contains(Dot(d, this->U), Dot(d, this->V)))
    {
      return std::abs(Dot(d, this->Normal));
    }
    double best = 1e300;
    for (std::size_t i = 0; i < this->Vertices.size(); ++i)
    {
      const Vec3& a = this->Vertices[i];
      const Vec3 edge = this->Vertices[(i + 1) % this->Vertices.size()] - a;
      const double along = std::clamp(Dot(p - a, edge) / Dot(edge, edge), 0.0, 1.0);
      best = std::min(best, Norm(p - (a + along * edge)));
    }
    return best;
  }

private:
  std::vector<Vec3> Vertices;
  std::vector<std::array<double, 2>> Planar;
  Vec3 Normal, U, V;
  double Area = 0;
  double Low[2] = { 1e300, 1e300 };
  double High[2] = { -1e300, -1e300 };
};

/// A surface made of planar polygons, sampled in proportion to their areas.
class Polyhedron : public Shape
{
public:
  explicit Polyhedron(std::vector<Polygon> faces)
    : Faces(std::move(faces))
  {
    double total = 0;
    for (const Polygon& face : this->Faces)
    {
      total += face.GetArea();
      this->CumulativeArea.push_back(total);
    }
  }
  Vec3 Sample(Random& random) const override
  {
    const double pick = random.Uniform(0, this->CumulativeArea.back());
    const auto face =
      std::upper_bound(this->CumulativeArea.begin(), this->CumulativeArea.end(), pick) -
      this->CumulativeArea.begin();
    return this->Faces[std::min<std::size_t>(face, this->Faces.size() - 1)].Sample(random);
  }
  double Distance(const Vec3& p) const override
  {
    double best = 1e300;
    for (const Polygon& face : this->Faces)
    {
      best = std::min(best, face.Distance(p));
    }
    return best;
  }
  double Diagonal() const override { return this->BoxDiagonal; }
  double BoxDiagonal = 1.0;

  /// The sharp edges are the sides shared by two faces that are not coplanar (open borders
  /// are not edges: nothing meets there).
  double EdgeDistance(const Vec3& p) const override
  {
    if (!this->SharpEdgesFound)
    {
      this->FindSharpEdges();
    }
    double best = std::numeric_limits<double>::infinity();
    for (const auto& edge : this->SharpEdges)
    {
      best = std::min(best, SegmentDistance(p, edge[0], edge[1]));
    }
    return best;
  }

private:
  void FindSharpEdges() const
  {
    // Faces built from the same profile share vertices bit for bit, so sides match exactly.
    for (std::size_t f = 0; f < this->Faces.size(); ++f)
    {
      const auto& a = this->Faces[f].GetVertices();
      for (std::size_t i = 0; i < a.size(); ++i)
      {
        const Vec3& a0 = a[i];
        const Vec3& a1 = a[(i + 1) % a.size()];
        for (std::size_t g = f + 1; g < this->Faces.size(); ++g)
        {
          const auto& b = this->Faces[g].GetVertices();
          for (std::size_t j = 0; j < b.size(); ++j)
          {
            const Vec3& b0 = b[j];
            const Vec3& b1 = b[(j + 1) % b.size()];
            const bool shared = (a0 == b0 && a1 == b1) || (a0 == b1 && a1 == b0);
            if (shared &&
                std::abs(Dot(this->Faces[f].GetNormal(), this->Faces[g].GetNormal())) < 0.9999)
            {
              this->SharpEdges.push_back({ a0, a1 });
            }
          }
        }
      }
    }
    this->SharpEdgesFound = true;
  }

  std::vector<Polygon> Faces;
  std::vector<double> CumulativeArea;
  mutable std::vector<std::array<Vec3, 2>> SharpEdges;
  mutable bool SharpEdgesFound = false;
};

/// A prism: a polygon in the x-z plane extruded along y from -halfDepth to halfDepth.
inline std::unique_ptr<Polyhedron> Prism(const std::vector<std::array<double, 2>>& profile,
  double halfDepth,
  bool closed = true)
{
  std::vector<Polygon> faces;
  std::vector<Vec3> front, back;
  double low[3] = { 1e300, -halfDepth, 1e300 }, high[3] = { -1e300, halfDepth, -1e300 };
  for (const auto& q : profile)
  {
    front.push_back({ q[0], -halfDepth, q[1] });
    back.push_back({ q[0], halfDepth, q[1] });
    low[0] = std::min(low[0], q[0]);
    high[0] = std::max(high[0], q[0]);
    low[2] = std::min(low[2], q[1]);
    high[2] = std::max(high[2], q[1]);
  }
  const std::size_t sides = closed ? profile.size() : profile.size() - 1;
  for (std::size_t i = 0; i < sides; ++i)
  {
    const std::size_t j = (i + 1) % profile.size();
    faces.emplace_back(std::vector<Vec3>{ front[i], front[j], back[j], back[i] });
  }
  if (closed)
  {
    faces.emplace_back(front);
    faces.emplace_back(back);
  }
  auto prism = std::make_unique<Polyhedron>(std::move(faces));
  prism->BoxDiagonal = Norm(Vec3{ high[0] - low[0], high[1] - low[1], high[2] - low[2] });
  return prism;
}

/// The sphere of radius 0.5 at the origin.
class Sphere : public Shape
{
public:
  Vec3 Sample(Random& random) const override
  {
    const double z = random.Uniform(-1, 1);
    const double angle = random.Uniform(0, 2 * M_PI);
    const double ring = std::sqrt(1 - z * z);
    return { 0.5 * ring * std::cos(angle), 0.5 * ring * std::sin(angle), 0.5 * z };
  }
  double Distance(const Vec3& p) const override { return std::abs(Norm(p) - 0.5); }
  double Diagonal() const override { return std::sqrt(3.0); }
};

/// A scanned-terrain-like patch: z = h(x, y) over the unit square, sampled uniformly in x, y
/// (what a LiDAR sees from above). The distance is measured vertically, slightly over-stating
/// it on slopes.
class Terrain : public Shape
{
public:
  static double Height(double x, double y)
  {
    return 0.08 * std::sin(2.5 * x) * std::cos(3.0 * y) + 0.05 * x * y;
  }
  Vec3 Sample(Random& random) const override
  {
    const double x = random.Uniform(), y = random.Uniform();
    return { x, y, Height(x, y) };
  }
  double Distance(const Vec3& p) const override { return std::abs(p[2] - Height(p[0], p[1])); }
  double Diagonal() const override { return std::sqrt(2.0 + 0.15 * 0.15); }
};

/// The unit cube [-0.5, 0.5]^3.
inline std::unique_ptr<Shape> Cube()
{
  auto cube = Prism({ { -0.5, -0.5 }, { 0.5, -0.5 }, { 0.5, 0.5 }, { -0.5, 0.5 } }, 0.5);
  return cube;
}

/// The paper's sharp edge (Figure 6): two unit squares meeting at a 90-degree ridge along y.
inline std::unique_ptr<Shape> SharpEdge()
{
  const double h = std::sqrt(0.5);
  return Prism({ { -h, -h }, { 0.0, 0.0 }, { h, -h } }, 0.5, false);
}

/// A CAD-like part in the spirit of the fandisk: a block with a step (a concave edge), a
/// slanted face meeting the top at an obtuse angle, and right-angled edges and corners.
inline std::unique_ptr<Shape> CadPart()
{
  return Prism({ { -0.5, 0.0 },
                 { 0.5, 0.0 },
                 { 0.5, 0.25 },
                 { 0.15, 0.25 },
                 { 0.15, 0.45 },
                 { -0.15, 0.45 },
                 { -0.5, 0.2 } },
    0.3);
}

/// The square [-0.5, 0.5]^2 in the plane z = 0 (open: its border is not an edge).
class Plane : public Shape
{
public:
  Vec3 Sample(Random& random) const override
  {
    const double x = random.Uniform(-0.5, 0.5);
    const double y = random.Uniform(-0.5, 0.5);
    return { x, y, 0.0 };
  }
  double Distance(const Vec3& p) const override
  {
    const double dx = std::max(0.0, std::abs(p[0]) - 0.5);
    const double dy = std::max(0.0, std::abs(p[1]) - 0.5);
    return std::sqrt(dx * dx + dy * dy + p[2] * p[2]);
  }
  double Diagonal() const override { return std::sqrt(2.0); }
};

/// The side of a cylinder of radius 0.4 around the z axis, z in [-0.5, 0.5], open at both ends,
/// cut by the plane x = Cut: the part with x > Cut is replaced by a flat strip, which meets the
/// round part at two sharp edges (lines parallel to z). Cut >= 0.4 gives the whole cylinder.
class CutCylinder : public Shape
{
public:
  explicit CutCylinder(double cut = 1.0)
    : Cut(std::min(cut, Radius))
    , HalfWidth(std::sqrt(Radius * Radius - std::min(cut, Radius) * std::min(cut, Radius)))
    , ArcAngle(std::acos(std::min(cut, Radius) / Radius))
  {
  }
  Vec3 Sample(Random& random) const override
  {
    const double arcLength = Radius * (2.0 * M_PI - 2.0 * this->ArcAngle);
    const double stripWidth = 2.0 * this->HalfWidth;
    const double pick = random.Uniform(0.0, arcLength + stripWidth);
    const double z = random.Uniform(-0.5, 0.5);
    if (pick < arcLength)
    {
      const double angle = this->ArcAngle + pick / Radius;
      return { Radius * std::cos(angle), Radius * std::sin(angle), z };
    }
    return { this->Cut, pick - arcLength - this->HalfWidth, z };
  }
  double Distance(const Vec3& p) const override
  {
    // An extrusion along z: the distance in the cross-section, combined with the overshoot in z.
    const double dz = std::max(0.0, std::abs(p[2]) - 0.5);
    const double d = this->CrossSectionDistance(p[0], p[1]);
    return std::sqrt(d * d + dz * dz);
  }
  double EdgeDistance(const Vec3& p) const override
  {
    if (this->HalfWidth == 0.0)
    {
      return std::numeric_limits<double>::infinity();
    }
    const double dz = std::max(0.0, std::abs(p[2]) - 0.5);
    const double d = std::hypot(p[0] - this->Cut, std::abs(p[1]) - this->HalfWidth);
    return std::sqrt(d * d + dz * dz);
  }
  double Diagonal() const override
  {
    const double width = Radius + this->Cut;
    return std::sqrt(width * width + 4.0 * Radius * Radius + 1.0);
  }

private:
  double CrossSectionDistance(double x, double y) const
  {
    const double corner = std::hypot(x - this->Cut, std::abs(y) - this->HalfWidth);
    // The arc covers the angles outside (-ArcAngle, ArcAngle).
    const double angle = std::abs(std::atan2(y, x));
    const double toArc = angle >= this->ArcAngle ? std::abs(std::hypot(x, y) - Radius) : corner;
    const double toStrip = this->HalfWidth > 0.0
                             ? (std::abs(y) <= this->HalfWidth ? std::abs(x - this->Cut) : corner)
                             : std::numeric_limits<double>::infinity();
    return std::min(toArc, toStrip);
  }

  static constexpr double Radius = 0.4;
  double Cut, HalfWidth, ArcAngle;
};

/// Uneven, scan-line-like density: a point of the shape's uniform sampling is kept with a
/// probability that varies in bands across x (scan lines, 4:1 from densest to sparsest, period
/// 0.15) and falls off with the squared distance to a scanner at (1.5, -2, 1.5), as in a
/// terrestrial scan.
inline Vec3 SampleScanLines(const Shape& shape, Random& random)
{
  const Vec3 scanner{ 1.5, -2.0, 1.5 };
  for (;;)
  {
    const Vec3 p = shape.Sample(random);
    const double band = 0.25 + 0.75 * 0.5 * (1.0 + std::cos(2.0 * M_PI * p[0] / 0.15));
    const Vec3 d = p - scanner;
    const double falloff = std::min(1.0, 4.0 / Dot(d, d));
    if (random.Uniform() < band * falloff)
    {
      return p;
    }
  }
}

/// A generated noisy cloud with its ground truth, for tests and benchmarks.
struct NoisyCloud
{
  std::vector<double> Positions; // x y z per point, with noise and outliers
  std::vector<double> Clean;     // the same points before noise (outliers: where they were)
  std::vector<std::uint8_t> Outlier;
  double Sigma = 0.0; // the noise's standard deviation per coordinate
  std::size_t NumberOfPoints() const { return this->Outlier.size(); }
};

/// n points of the shape (uniform or scan-line density) with Gaussian noise of standard
/// deviation noiseFraction x diagonal on each coordinate; a fraction of them, picked at random,
/// are then replaced by outliers drawn uniformly in the clean cloud's bounding box grown by 10%.
inline NoisyCloud MakeNoisyCloud(const Shape& shape,
  std::size_t n,
  double noiseFraction,
  bool scanLines,
  double outlierFraction,
  std::uint64_t seed)
{
  Random random(seed);
  NoisyCloud cloud;
  cloud.Sigma = noiseFraction * shape.Diagonal();
  cloud.Positions.resize(3 * n);
  cloud.Clean.resize(3 * n);
  cloud.Outlier.assign(n, 0);
  double low[3] = { 1e300, 1e300, 1e300 }, high[3] = { -1e300, -1e300, -1e300 };
  for (std::size_t i = 0; i < n; ++i)
  {
    const Vec3 p = scanLines ? SampleScanLines(shape, random) : shape.Sample(random);
    for (int axis = 0; axis < 3; ++axis)
    {
      cloud.Clean[3 * i + axis] = p[axis];
      cloud.Positions[3 * i + axis] = p[axis] + cloud.Sigma * random.Gaussian();
      low[axis] = std::min(low[axis], p[axis]);
      high[axis] = std::max(high[axis], p[axis]);
    }
  }
  for (std::size_t i = 0; i < n; ++i)
  {
    if (random.Uniform() < outlierFraction)
    {
      cloud.Outlier[i] = 1;
      for (int axis = 0; axis < 3; ++axis)
      {
        const double margin = 0.1 * (high[axis] - low[axis]);
        cloud.Positions[3 * i + axis] = random.Uniform(low[axis] - margin, high[axis] + margin);
      }
    }
  }
  return cloud;
}

/// The samples: shape, file stem, number of points, noise as a fraction of the diagonal.
struct SampleSpec
{
  std::string Name;
  std::function<std::unique_ptr<Shape>()> Make;
  std::size_t Points;
  double Noise;
  bool Attributes; // colours and intensity
};

inline std::vector<SampleSpec> Samples()
{
  auto sphere = [] { return std::unique_ptr<Shape>(new Sphere()); };
  auto terrain = [] { return std::unique_ptr<Shape>(new Terrain()); };
  return {
    { "sharp_edge_noise0.5", SharpEdge, 20000, 0.005, false },
    { "sharp_edge_noise0.1", SharpEdge, 20000, 0.001, false },
    { "cube_noise0.5", Cube, 40000, 0.005, false },
    { "cube_noise0.1", Cube, 40000, 0.001, false },
    { "sphere_noise0.5", sphere, 30000, 0.005, false },
    { "sphere_noise0.1", sphere, 30000, 0.001, false },
    { "cad_part_noise0.3", CadPart, 40000, 0.003, false },
    { "terrain_rgb_intensity", terrain, 30000, 0.003, true },
  };
}
} // namespace pcbilateral_samples

#endif
