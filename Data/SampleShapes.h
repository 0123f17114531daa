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
};

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

private:
  std::vector<Polygon> Faces;
  std::vector<double> CumulativeArea;
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
