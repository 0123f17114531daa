#include "ChosenPoints.h"

#include <algorithm>

namespace pcbilateral
{

ChosenPoints::ChosenPoints(const PointCloudView& cloud, const std::vector<std::uint8_t>& chosen)
  : Cloud(cloud)
{
  for (std::size_t i = 0; i < cloud.NumberOfPoints && i < chosen.size(); ++i)
  {
    if (chosen[i])
    {
      this->Ids.push_back(i);
    }
  }
  this->Positions.resize(3 * this->Ids.size());
  if (cloud.OrientationNormals != nullptr)
  {
    this->Orientation.resize(3 * this->Ids.size());
  }
  for (std::size_t k = 0; k < this->Ids.size(); ++k)
  {
    std::copy_n(cloud.Positions + 3 * this->Ids[k], 3, &this->Positions[3 * k]);
    if (cloud.OrientationNormals != nullptr)
    {
      std::copy_n(cloud.OrientationNormals + 3 * this->Ids[k], 3, &this->Orientation[3 * k]);
    }
  }
}

PointCloudView ChosenPoints::View() const
{
  PointCloudView view;
  view.NumberOfPoints = this->Ids.size();
  view.Positions = this->Positions.data();
  view.OrientationNormals = this->Orientation.empty() ? nullptr : this->Orientation.data();
  return view;
}

BilateralResult ChosenPoints::SpreadResult(BilateralResult chosenResult, bool withNormals) const
{
  BilateralResult result = std::move(chosenResult);
  if (result.Status != BilateralStatus::Completed)
  {
    return result;
  }
  const std::size_t n = this->Cloud.NumberOfPoints;
  // Each per-point array, the chosen points' values at their ids and `other` elsewhere.
  auto spread = [&](auto& values, std::size_t components, auto other)
  {
    auto whole = values;
    whole.assign(components * n, other);
    values.resize(components * this->Ids.size(), other);
    for (std::size_t k = 0; k < this->Ids.size(); ++k)
    {
      std::copy_n(&values[components * k], components, &whole[components * this->Ids[k]]);
    }
    values.swap(whole);
  };
  if (withNormals)
  {
    spread(result.Normals, 3, 0.0);
  }
  spread(result.Removed, 1, std::uint8_t(0));
  if (!result.PointRadius.empty())
  {
    spread(result.PointRadius, 1, 0.0);
  }
  std::vector<double> positions(this->Cloud.Positions, this->Cloud.Positions + 3 * n);
  for (std::size_t k = 0; k < this->Ids.size(); ++k)
  {
    std::copy_n(&result.Positions[3 * k], 3, &positions[3 * this->Ids[k]]);
  }
  result.Positions.swap(positions);
  return result;
}

} // namespace pcbilateral
