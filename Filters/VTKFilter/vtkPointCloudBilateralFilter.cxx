#include "vtkPointCloudBilateralFilter.h"
#include "vtkPointCloudVertices.h"

#include "BilateralFilter.h"
#include "ChosenPoints.h"

#include "vtkArrayDispatch.h"
#include "vtkCellArray.h"
#include "vtkCellType.h"
#include "vtkDataArrayRange.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkIdList.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkStringArray.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <numeric>
#include <sstream>
#include <thread>
#include <utility>
#include <vector>

vtkStandardNewMacro(vtkPointCloudBilateralFilter);

namespace
{
/// The share of the filter's progress the core's run takes; the hand-over of its result and the
/// output's copies take the rest (reported as they go, see AskAbort).
constexpr double KernelShare = 0.99;

/// Copies a 3-component array of any value type into interleaved doubles, a million values at
/// a time, asking `stop` before each (20 million points are 480 MB: a run's abort is asked
/// within the copy); stops with the values copied so far.
struct CopyTuplesToDouble
{
  template<typename ArrayT>
  void operator()(ArrayT* array,
    std::vector<double>& values,
    const std::function<bool()>& stop) const
  {
    const auto range = vtk::DataArrayValueRange<3>(array);
    const auto size = static_cast<std::ptrdiff_t>(range.size());
    values.clear();
    values.reserve(static_cast<std::size_t>(size));
    constexpr std::ptrdiff_t Block = std::ptrdiff_t(1) << 20;
    for (std::ptrdiff_t first = 0; first < size && !stop(); first += Block)
    {
      values.insert(
        values.end(), range.begin() + first, range.begin() + std::min(size, first + Block));
    }
  }
};

void ToDoubles(vtkDataArray* array, std::vector<double>& values, const std::function<bool()>& stop)
{
  using Dispatcher = vtkArrayDispatch::DispatchByValueType<vtkArrayDispatch::Reals>;
  CopyTuplesToDouble worker;
  if (!Dispatcher::Execute(array, worker, values, stop))
  {
    worker(array, values, stop); // any other array type, through the generic API
  }
}

/// Writes the kept points' filtered positions into an array of the input's value type.
struct CopyKeptPositions
{
  template<typename ArrayT>
  void operator()(ArrayT* array,
    const std::vector<double>& positions,
    const std::vector<vtkIdType>& kept,
    const std::function<bool()>& stop) const
  {
    using ValueType = vtk::GetAPIType<ArrayT>;
    auto range = vtk::DataArrayValueRange<3>(array);
    for (std::size_t out = 0; out < kept.size(); ++out)
    {
      if ((out & 0xFFFFF) == 0 && stop())
      {
        return; // (asked every million points)
      }
      const double* p = positions.data() + 3 * kept[out];
      for (int axis = 0; axis < 3; ++axis)
      {
        range[3 * out + axis] = static_cast<ValueType>(p[axis]);
      }
    }
  }
};

bool HasCellsOtherThanVertices(vtkPointSet* input)
{
  if (auto* polyData = vtkPolyData::SafeDownCast(input))
  {
    return polyData->GetNumberOfLines() + polyData->GetNumberOfPolys() +
             polyData->GetNumberOfStrips() >
           0;
  }
  for (vtkIdType cell = 0; cell < input->GetNumberOfCells(); ++cell)
  {
    const int type = input->GetCellType(cell);
    if (type != VTK_VERTEX && type != VTK_POLY_VERTEX)
    {
      return true;
    }
  }
  return false;
}

/// The output of an input without points: none, of the input's point type, with the input's
/// (empty) arrays and field data.
void PassEmptyInput(vtkPointSet* input, vtkPolyData* output)
{
  if (input->GetPoints())
  {
    vtkNew<vtkPoints> none;
    none->SetDataType(input->GetPoints()->GetDataType());
    output->SetPoints(none);
  }
  output->GetPointData()->PassData(input->GetPointData());
  output->GetFieldData()->PassData(input->GetFieldData());
}

/// The ids of the input's points that the run kept, in order (asking `stop` every million
/// points: when it says stop, the ids so far).
std::vector<vtkIdType> KeptPointIds(const std::vector<std::uint8_t>& removed,
  vtkIdType count,
  const std::function<bool()>& stop)
{
  std::vector<vtkIdType> kept;
  kept.reserve(static_cast<std::size_t>(count));
  for (vtkIdType id = 0; id < count; ++id)
  {
    if ((id & 0xFFFFF) == 0 && stop())
    {
      break;
    }
    if (!removed[id])
    {
      kept.push_back(id);
    }
  }
  return kept;
}

/// The kept points' filtered positions, as points of the input's type.
vtkSmartPointer<vtkPoints> KeptPoints(int dataType,
  const std::vector<double>& positions,
  const std::vector<vtkIdType>& kept,
  const std::function<bool()>& stop)
{
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetDataType(dataType);
  points->SetNumberOfPoints(static_cast<vtkIdType>(kept.size()));
  using Dispatcher = vtkArrayDispatch::DispatchByValueType<vtkArrayDispatch::Reals>;
  CopyKeptPositions worker;
  if (!Dispatcher::Execute(points->GetData(), worker, positions, kept, stop))
  {
    worker(points->GetData(), positions, kept, stop);
  }
  return points;
}

/// A field-data array of one tuple.
void AddTuple(vtkFieldData* fieldData,
  const char* name,
  const double* values,
  const std::vector<const char*>& components)
{
  vtkNew<vtkDoubleArray> array;
  array->SetName(name);
  array->SetNumberOfComponents(static_cast<int>(components.size()));
  for (std::size_t c = 0; c < components.size(); ++c)
  {
    array->SetComponentName(static_cast<vtkIdType>(c), components[c]);
  }
  array->InsertNextTuple(values);
  fieldData->AddArray(array);
}

/// One-value arrays of the radii and iterations used, and of the measured scales when the
/// cloud was measured; the mode, and the radii's ranges where the radius followed the density.
void AddParametersUsed(const pcbilateral::BilateralResult& result,
  bool edgeAware,
  vtkFieldData* fieldData)
{
  std::vector<std::pair<const char*, double>> used = { { "BilateralRadius", result.RadiusUsed },
    { "BilateralNormalRadius", result.NormalRadiusUsed },
    { "BilateralNumberOfIterations", result.NumberOfIterationsUsed } };
  if (result.Measured)
  {
    used.emplace_back("BilateralPointSpacing", result.PointSpacing);
    used.emplace_back("BilateralNoiseSigma", result.NoiseSigma);
    used.emplace_back("BilateralSpacingSpread", result.SpacingSpread);
    AddTuple(fieldData,
      "BilateralNearestNeighbourDistances",
      result.NearestNeighbourDistance,
      { "5th percentile", "median", "95th percentile" });
  }
  if (result.RadiusFollowsDensity)
  {
    AddTuple(fieldData, "BilateralRadiusRange", result.RadiusRange, { "smallest", "largest" });
    AddTuple(
      fieldData, "BilateralNormalRadiusRange", result.NormalRadiusRange, { "smallest", "largest" });
  }
  for (const auto& [name, number] : used)
  {
    vtkNew<vtkDoubleArray> value;
    value->SetName(name);
    value->InsertNextValue(number);
    fieldData->AddArray(value);
  }
  vtkNew<vtkStringArray> mode;
  mode->SetName("BilateralMode");
  mode->InsertNextValue(edgeAware ? "edge-aware" : "paper");
  fieldData->AddArray(mode);
}

/// The input's point arrays (of `count` points), for the kept points.
void CopyKeptPointData(vtkPointData* inPD,
  vtkIdType count,
  const std::vector<vtkIdType>& kept,
  vtkPointData* outPD)
{
  const auto outputCount = static_cast<vtkIdType>(kept.size());
  if (outputCount == count)
  {
    outPD->PassData(inPD);
    return;
  }
  vtkNew<vtkIdList> from;
  from->SetNumberOfIds(outputCount);
  std::copy(kept.begin(), kept.end(), from->GetPointer(0));
  vtkNew<vtkIdList> to;
  to->SetNumberOfIds(outputCount);
  std::iota(to->GetPointer(0), to->GetPointer(0) + outputCount, vtkIdType(0));
  outPD->CopyAllocate(inPD, outputCount);
  outPD->CopyData(inPD, from, to);
}

/// "vtkOriginalPointIds": each output point's id in the input.
vtkSmartPointer<vtkIdTypeArray> OriginalIds(const std::vector<vtkIdType>& kept)
{
  auto originalIds = vtkSmartPointer<vtkIdTypeArray>::New();
  originalIds->SetName("vtkOriginalPointIds");
  originalIds->SetNumberOfValues(static_cast<vtkIdType>(kept.size()));
  std::copy(kept.begin(), kept.end(), originalIds->GetPointer(0));
  return originalIds;
}

/// "EstimatedNormals": the kept points' normals of the last iteration.
vtkSmartPointer<vtkDoubleArray> EstimatedNormals(const std::vector<double>& normals,
  const std::vector<vtkIdType>& kept)
{
  auto estimated = vtkSmartPointer<vtkDoubleArray>::New();
  estimated->SetName("EstimatedNormals");
  estimated->SetNumberOfComponents(3);
  estimated->SetNumberOfTuples(static_cast<vtkIdType>(kept.size()));
  for (std::size_t out = 0; out < kept.size(); ++out)
  {
    estimated->SetTypedTuple(static_cast<vtkIdType>(out), normals.data() + 3 * kept[out]);
  }
  return estimated;
}

/// "DisplacementLength": how far each kept point moved (0 for a non-finite one).
vtkSmartPointer<vtkDoubleArray> DisplacementLengths(const double* before,
  const std::vector<double>& after,
  const std::vector<vtkIdType>& kept)
{
  auto lengths = vtkSmartPointer<vtkDoubleArray>::New();
  lengths->SetName("DisplacementLength");
  lengths->SetNumberOfValues(static_cast<vtkIdType>(kept.size()));
  for (std::size_t out = 0; out < kept.size(); ++out)
  {
    const double* from = before + 3 * kept[out];
    const double* to = after.data() + 3 * kept[out];
    const double length =
      std::sqrt((to[0] - from[0]) * (to[0] - from[0]) + (to[1] - from[1]) * (to[1] - from[1]) +
                (to[2] - from[2]) * (to[2] - from[2]));
    lengths->SetValue(static_cast<vtkIdType>(out), std::isfinite(length) ? length : 0.0);
  }
  return lengths;
}
} // namespace

struct vtkPointCloudBilateralFilter::InputCloud
{
  /// The input's positions as interleaved doubles: the input's own array when it holds them so
  /// (a LAS reader's), else PositionsCopy. (A copy of 20 million points is 480 MB to fill
  /// before the run and to free after it, an aborted one's too.)
  const double* Positions = nullptr;
  std::size_t NumberOfPoints = 0;
  std::vector<double> PositionsCopy;
  std::vector<double> Orientation;

  pcbilateral::PointCloudView View() const
  {
    pcbilateral::PointCloudView view;
    view.NumberOfPoints = this->NumberOfPoints;
    view.Positions = this->Positions;
    view.OrientationNormals = this->Orientation.empty() ? nullptr : this->Orientation.data();
    return view;
  }
};

vtkPointCloudBilateralFilter::vtkPointCloudBilateralFilter()
{
  const pcbilateral::BilateralParameters defaults;
  this->Radius = defaults.Radius;
  this->NormalRadius = defaults.NormalRadius;
  this->NumberOfIterations = defaults.NumberOfIterations;
  this->AutomaticParameters = static_cast<int>(defaults.Automatic);
  this->RemoveIsolatedPoints = defaults.RemoveIsolatedPoints;
  this->NumberOfThreads = defaults.NumberOfThreads;
  this->EdgeAware = defaults.EdgeAware;
  this->SetClassArrayName("Classification");
  // What ParaView's progress bar shows (the class name otherwise).
  this->SetProgressText("Point Cloud Bilateral Filter");
}

vtkPointCloudBilateralFilter::~vtkPointCloudBilateralFilter()
{
  this->SetOrientationArrayName(nullptr);
  this->SetClassArrayName(nullptr);
}

void vtkPointCloudBilateralFilter::AddClass(long long value)
{
  this->Classes.push_back(value);
  this->Modified();
}

void vtkPointCloudBilateralFilter::RemoveAllClasses()
{
  if (!this->Classes.empty())
  {
    this->Classes.clear();
    this->Modified();
  }
}

int vtkPointCloudBilateralFilter::GetNumberOfClasses() const
{
  return static_cast<int>(this->Classes.size());
}

long long vtkPointCloudBilateralFilter::GetClass(int index) const
{
  return index >= 0 && index < this->GetNumberOfClasses()
           ? this->Classes[static_cast<std::size_t>(index)]
           : 0;
}

int vtkPointCloudBilateralFilter::FillInputPortInformation(int, vtkInformation* info)
{
  // Any data set with explicit points; the output is a vtkPolyData point cloud.
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPointSet");
  return 1;
}

pcbilateral::BilateralParameters vtkPointCloudBilateralFilter::MakeParameters() const
{
  pcbilateral::BilateralParameters parameters;
  parameters.Radius = this->Radius;
  parameters.NormalRadius = this->NormalRadius;
  parameters.NumberOfIterations = this->NumberOfIterations;
  // An out-of-range value is the core's to report (CheckParameters).
  parameters.Automatic = static_cast<pcbilateral::AutomaticParameters>(this->AutomaticParameters);
  parameters.RemoveIsolatedPoints = this->RemoveIsolatedPoints;
  parameters.NumberOfThreads = this->NumberOfThreads;
  parameters.ComputeNormals = this->GenerateEstimatedNormals;
  parameters.EdgeAware = this->EdgeAware;
  return parameters;
}

pcbilateral::BilateralObserver vtkPointCloudBilateralFilter::MakeObserver()
{
  pcbilateral::BilateralObserver observer;
  observer.Progress = [this](double fraction)
  {
    if (fraction >= 1.0)
    {
      // (The core paces its phase reports: the last iteration's end may not be among them.)
      this->PhaseFraction = 1.0;
      this->LastFinishingReport = std::chrono::steady_clock::time_point();
      this->IterationsDone = true;
    }
    this->UpdateProgress(KernelShare * fraction);
  };
  observer.ShouldAbort = [this]() { return this->AskAbort(); };
  observer.DiscardsAbortedResult = true; // (an aborted run's output is empty)
  observer.PhaseProgress = [this](const std::string& phase, double fraction)
  {
    this->ProgressPhase = phase;
    this->PhaseFraction = fraction;
  };
  observer.Warning = [this](const std::string& warning) { vtkWarningMacro(<< warning); };
  observer.ParametersChosen = [this](const pcbilateral::BilateralResult& chosen)
  {
    this->RecordRunInformation(chosen);
    this->InvokeEvent(ParametersChosenEvent);
  };
  return observer;
}

int vtkPointCloudBilateralFilter::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  // An abort asked of an earlier run ends there: VTK 9.2 never clears the flag, and every later
  // update would stop at once. (Set directly: SetAbortExecute would mark the filter modified.)
  this->AbortExecute = 0;
  this->IterationsDone = false;
  this->RunningThread = std::this_thread::get_id();
  vtkPointSet* input = vtkPointSet::GetData(inputVector[0]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  output->Initialize();
  this->RecordRunInformation(pcbilateral::BilateralResult());

  InputCloud cloud;
  std::vector<std::uint8_t> chosen;
  std::string problem = this->PrepareInput(input, cloud);
  if (problem.empty() && !this->GetAbortExecute())
  {
    problem = this->ChooseClasses(input, chosen);
  }
  if (this->GetAbortExecute())
  {
    return this->EndAborted(output); // (asked within the copies above)
  }
  if (!problem.empty())
  {
    vtkErrorMacro(<< problem);
  }

  const pcbilateral::BilateralObserver observer = this->MakeObserver();
  this->UpdateProgress(0.0);
  const pcbilateral::BilateralResult result =
    this->RunOnChosen(cloud, chosen, observer, problem.empty());
  if (result.Status == pcbilateral::BilateralStatus::Failed)
  {
    if (problem.empty())
    {
      vtkErrorMacro(<< result.Error);
    }
    this->LastRunSummary = "failed: " + (problem.empty() ? result.Error : problem);
    this->RecordRunInformation(pcbilateral::BilateralResult()); // (ParametersChosen set them)
    // A failed run is reported once, above, and gives an empty output; the request itself
    // succeeds. Returning 0 would add the executive's "returned failure for request" dump of
    // pipeline internals, and in ParaView it stops the update before the representation: the
    // representation is then marked up to date without having run, so later valid runs were
    // never shown (the render and the Information panel kept the data from before the error).
    this->UpdateProgress(1.0);
    return 1;
  }
  this->RecordRunInformation(result);
  // An aborted run leaves the output empty; so does an abort asked while the output is built
  // (the copies of 20 million points' arrays take a good part of a second: BuildOutput asks).
  if (result.Status != pcbilateral::BilateralStatus::Completed || this->GetAbortExecute() ||
      !this->BuildOutput(input, cloud, result, output))
  {
    return this->EndAborted(output);
  }
  // An empty cloud completes with nothing chosen: "r 0, rn 0, N 1 (paper's rule)" misled.
  this->LastRunSummary = input->GetNumberOfPoints() == 0
                           ? "nothing to filter: the input has no points"
                           : this->DescribeRun(result);
  this->UpdateProgress(1.0);
  return 1;
}

bool vtkPointCloudBilateralFilter::AskAbort()
{
  if (this->IterationsDone && std::this_thread::get_id() == this->RunningThread)
  {
    const auto now = std::chrono::steady_clock::now();
    if (now - this->LastFinishingReport >= std::chrono::milliseconds(50))
    {
      this->LastFinishingReport = now;
      this->UpdateProgress(0.5 * (KernelShare + 1.0));
    }
  }
  return this->GetAbortExecute() != 0;
}

int vtkPointCloudBilateralFilter::EndAborted(vtkPolyData* output)
{
  output->Initialize();
  this->LastRunSummary = "aborted";
  this->UpdateProgress(1.0);
  return 1;
}

std::string vtkPointCloudBilateralFilter::PrepareInput(vtkPointSet* input, InputCloud& cloud)
{
  if (!input)
  {
    return "the input is not a vtkPointSet";
  }
  if (input->GetNumberOfPoints() == 0)
  {
    return std::string();
  }
  const std::function<bool()> stop = [this]() { return this->GetAbortExecute() != 0; };
  vtkDataArray* points = input->GetPoints()->GetData();
  if (auto* doubles = vtkDoubleArray::SafeDownCast(points))
  {
    cloud.Positions = doubles->GetPointer(0);
    cloud.NumberOfPoints = static_cast<std::size_t>(doubles->GetNumberOfTuples());
  }
  else
  {
    ToDoubles(points, cloud.PositionsCopy, stop);
    cloud.Positions = cloud.PositionsCopy.data();
    cloud.NumberOfPoints = cloud.PositionsCopy.size() / 3;
  }
  if (!this->OrientNormals)
  {
    return std::string();
  }
  vtkPointData* pointData = input->GetPointData();
  vtkDataArray* reference = pointData->GetNormals();
  if (this->OrientationArrayName && *this->OrientationArrayName)
  {
    reference = pointData->GetArray(this->OrientationArrayName);
    if (!reference)
    {
      vtkWarningMacro(<< "the input has no point array '" << this->OrientationArrayName
                      << "': the estimated normals are not oriented");
    }
  }
  if (reference && reference->GetNumberOfComponents() != 3)
  {
    return std::string("the orientation array '") +
           (reference->GetName() ? reference->GetName() : "(unnamed)") + "' has " +
           std::to_string(reference->GetNumberOfComponents()) + " components, not 3";
  }
  if (reference)
  {
    ToDoubles(reference, cloud.Orientation, stop);
  }
  return std::string();
}

namespace
{
bool IsIntegerType(int type)
{
  switch (type)
  {
    case VTK_CHAR:
    case VTK_SIGNED_CHAR:
    case VTK_UNSIGNED_CHAR:
    case VTK_SHORT:
    case VTK_UNSIGNED_SHORT:
    case VTK_INT:
    case VTK_UNSIGNED_INT:
    case VTK_LONG:
    case VTK_UNSIGNED_LONG:
    case VTK_LONG_LONG:
    case VTK_UNSIGNED_LONG_LONG:
    case VTK_ID_TYPE:
      return true;
    default:
      return false;
  }
}
} // namespace

std::string vtkPointCloudBilateralFilter::ChooseClasses(vtkPointSet* input,
  std::vector<std::uint8_t>& chosen) const
{
  chosen.clear();
  if (this->Classes.empty() || input == nullptr || input->GetNumberOfPoints() == 0)
  {
    return std::string();
  }
  const std::string name = this->ClassArrayName ? this->ClassArrayName : "";
  vtkDataArray* array = input->GetPointData()->GetArray(name.c_str());
  if (array == nullptr)
  {
    return "classes were chosen, but the input has no point array '" + name + "'";
  }
  if (array->GetNumberOfComponents() != 1 || !IsIntegerType(array->GetDataType()))
  {
    return "the class array '" + name + "' must hold one integer per point (it has " +
           std::to_string(array->GetNumberOfComponents()) + " component(s) of type " +
           array->GetDataTypeAsString() + ")";
  }
  const vtkIdType n = input->GetNumberOfPoints();
  chosen.assign(static_cast<std::size_t>(n), 0);
  for (vtkIdType i = 0; i < n; ++i)
  {
    // (Exact: integers read as doubles, below 2^53.)
    const double value = array->GetTuple1(i);
    chosen[static_cast<std::size_t>(i)] =
      std::find_if(this->Classes.begin(),
        this->Classes.end(),
        [&](long long c) { return static_cast<double>(c) == value; }) != this->Classes.end();
  }
  return std::string();
}

pcbilateral::BilateralResult vtkPointCloudBilateralFilter::RunOnChosen(const InputCloud& cloud,
  const std::vector<std::uint8_t>& chosen,
  const pcbilateral::BilateralObserver& observer,
  bool preparedHere)
{
  if (chosen.empty())
  {
    this->NumberOfFilteredPoints = static_cast<vtkIdType>(cloud.NumberOfPoints);
    return this->RunCore(cloud.View(), this->MakeParameters(), observer, preparedHere);
  }
  const pcbilateral::ChosenPoints subset(cloud.View(), chosen);
  this->NumberOfFilteredPoints = static_cast<vtkIdType>(subset.GetNumberOfChosenPoints());
  if (subset.GetNumberOfChosenPoints() == 0)
  {
    vtkWarningMacro(<< "no point has one of the chosen classes in '" << this->ClassArrayName
                    << "': every point is passed through unchanged");
  }
  const pcbilateral::BilateralParameters parameters = this->MakeParameters();
  pcbilateral::BilateralResult result = subset.SpreadResult(
    this->RunCore(subset.View(), parameters, observer, preparedHere), parameters.ComputeNormals);
  if (result.Status == pcbilateral::BilateralStatus::Failed && preparedHere)
  {
    result.Error += " (on the " + std::to_string(subset.GetNumberOfChosenPoints()) +
                    " points of the chosen classes)";
  }
  return result;
}

pcbilateral::BilateralResult vtkPointCloudBilateralFilter::RunCore(
  const pcbilateral::PointCloudView& cloud,
  const pcbilateral::BilateralParameters& parameters,
  const pcbilateral::BilateralObserver& observer,
  bool preparedHere)
{
  if (!preparedHere)
  {
    return pcbilateral::BilateralResult(); // Failed; the error is reported already
  }
  return pcbilateral::RunBilateralFilter(cloud, parameters, observer);
}

void vtkPointCloudBilateralFilter::RecordRunInformation(const pcbilateral::BilateralResult& result)
{
  this->RadiusUsed = result.RadiusUsed;
  this->NormalRadiusUsed = result.NormalRadiusUsed;
  this->NumberOfIterationsUsed = result.NumberOfIterationsUsed;
  this->PointSpacing = result.PointSpacing;
  this->NoiseSigma = result.NoiseSigma;
  std::copy_n(result.NearestNeighbourDistance, 3, this->NearestNeighbourDistances);
  this->RadiusFollowsDensity = result.RadiusFollowsDensity;
  std::copy_n(result.RadiusRange, 2, this->RadiusRange);
  std::copy_n(result.NormalRadiusRange, 2, this->NormalRadiusRange);
  this->SpacingSpread = result.SpacingSpread;
  this->ProcessingDepth = result.ProcessingDepth;
  this->NumberOfRemovedPoints = static_cast<vtkIdType>(result.NumberOfRemovedPoints);
  this->NumberOfNonFinitePoints = static_cast<vtkIdType>(result.NumberOfNonFinitePoints);
}

std::string vtkPointCloudBilateralFilter::DescribeRun(
  const pcbilateral::BilateralResult& result) const
{
  // Short enough for the Properties panel's field; the measured scales have their own getters.
  // Where some parameters were given and others automatic, each says which it was.
  const char* automatic = result.Measured ? " (measured)" : " (paper's rule)";
  const bool given[3] = {
    this->Radius > 0.0, this->NormalRadius > 0.0, this->NumberOfIterations > 0
  };
  const bool mixed = !(given[0] == given[1] && given[1] == given[2]);
  auto source = [&](int k) { return mixed ? (given[k] ? " (given)" : automatic) : ""; };
  std::ostringstream summary;
  summary.precision(3);
  if (result.RadiusFollowsDensity)
  {
    summary << "r " << result.RadiusRange[0] << "-" << result.RadiusRange[1] << " (follows density)"
            << (mixed ? automatic : "") << ", rn " << result.NormalRadiusRange[0];
    if (result.NormalRadiusRange[1] != result.NormalRadiusRange[0])
    {
      summary << "-" << result.NormalRadiusRange[1];
    }
  }
  else
  {
    summary << "r " << result.RadiusUsed << source(0) << ", rn " << result.NormalRadiusUsed;
  }
  summary << source(1) << ", N " << result.NumberOfIterationsUsed << source(2);
  if (!mixed)
  {
    summary << (given[0] ? " (given)" : automatic);
  }
  if (this->EdgeAware)
  {
    summary << "; edge-aware"; // its rules choose other parameters than the paper's mode's
  }
  if (!this->Classes.empty())
  {
    summary << "; " << this->NumberOfFilteredPoints << " points of the chosen classes";
  }
  return summary.str();
}

bool vtkPointCloudBilateralFilter::BuildOutput(vtkPointSet* input,
  const InputCloud& cloud,
  const pcbilateral::BilateralResult& result,
  vtkPolyData* output)
{
  if (input->GetNumberOfPoints() == 0)
  {
    PassEmptyInput(input, output);
    return true;
  }
  if (HasCellsOtherThanVertices(input))
  {
    vtkWarningMacro(<< "the input's cells (lines, polygons, volumes) are not carried to the "
                       "output, which is a point cloud");
  }
  const std::function<bool()> stop = [this]() { return this->AskAbort(); };
  const std::vector<vtkIdType> kept =
    KeptPointIds(result.Removed, input->GetNumberOfPoints(), stop);
  const auto outputCount = static_cast<vtkIdType>(kept.size());
  if (stop())
  {
    return false;
  }
  output->SetPoints(KeptPoints(input->GetPoints()->GetDataType(), result.Positions, kept, stop));
  const vtkSmartPointer<vtkCellArray> vertices = vtkPointCloudVertices(outputCount, stop);
  if (!vertices)
  {
    return false;
  }
  output->SetVerts(vertices);
  // The parameters used and the scales they came from travel with the data (ParaView's
  // Information panel shows them).
  output->GetFieldData()->PassData(input->GetFieldData());
  AddParametersUsed(result, this->EdgeAware, output->GetFieldData());

  vtkPointData* outPD = output->GetPointData();
  if (stop())
  {
    return false;
  }
  CopyKeptPointData(input->GetPointData(), input->GetNumberOfPoints(), kept, outPD);
  if (this->RemoveIsolatedPoints)
  {
    outPD->AddArray(OriginalIds(kept));
  }
  if (this->GenerateEstimatedNormals)
  {
    outPD->AddArray(EstimatedNormals(result.Normals, kept));
  }
  if (this->GenerateDisplacementLength)
  {
    outPD->AddArray(DisplacementLengths(cloud.Positions, result.Positions, kept));
  }
  if (this->GeneratePointRadius && !result.PointRadius.empty())
  {
    vtkNew<vtkDoubleArray> radii;
    radii->SetName("BilateralPointRadius");
    radii->SetNumberOfValues(outputCount);
    for (vtkIdType k = 0; k < outputCount; ++k)
    {
      radii->SetValue(k, result.PointRadius[static_cast<std::size_t>(kept[k])]);
    }
    outPD->AddArray(radii);
  }
  return !stop();
}

void vtkPointCloudBilateralFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "AutomaticParameters: "
     << (this->AutomaticParameters == MEASURED
            ? "measured"
            : (this->AutomaticParameters == PAPER ? "paper" : "(invalid)"))
     << "\n";
  os << indent << "Radius: " << this->Radius << (this->Radius == 0.0 ? " (automatic)" : "") << "\n";
  os << indent << "NormalRadius: " << this->NormalRadius
     << (this->NormalRadius == 0.0 ? " (automatic)" : "") << "\n";
  os << indent << "NumberOfIterations: " << this->NumberOfIterations
     << (this->NumberOfIterations == 0 ? " (automatic)" : "") << "\n";
  os << indent << "OrientNormals: " << this->OrientNormals << "\n";
  os << indent << "OrientationArrayName: "
     << (this->OrientationArrayName ? this->OrientationArrayName : "(none: point normals)") << "\n";
  os << indent << "RemoveIsolatedPoints: " << this->RemoveIsolatedPoints << "\n";
  os << indent << "NumberOfThreads: " << this->NumberOfThreads << "\n";
  os << indent << "GenerateEstimatedNormals: " << this->GenerateEstimatedNormals << "\n";
  os << indent << "GenerateDisplacementLength: " << this->GenerateDisplacementLength << "\n";
  os << indent << "GeneratePointRadius: " << this->GeneratePointRadius << "\n";
  os << indent << "EdgeAware: " << this->EdgeAware << "\n";
  os << indent << "ClassArrayName: " << (this->ClassArrayName ? this->ClassArrayName : "(none)")
     << "\n";
  os << indent << "Classes:";
  for (long long value : this->Classes)
  {
    os << " " << value;
  }
  os << (this->Classes.empty() ? " (none: every point is filtered)\n" : "\n");
  os << indent << "RadiusUsed: " << this->RadiusUsed << "\n";
  os << indent << "NormalRadiusUsed: " << this->NormalRadiusUsed << "\n";
  os << indent << "NumberOfIterationsUsed: " << this->NumberOfIterationsUsed << "\n";
  os << indent << "PointSpacing: " << this->PointSpacing << "\n";
  os << indent << "NoiseSigma: " << this->NoiseSigma << "\n";
  os << indent << "NearestNeighbourDistances: " << this->NearestNeighbourDistances[0] << " "
     << this->NearestNeighbourDistances[1] << " " << this->NearestNeighbourDistances[2] << "\n";
  os << indent << "RadiusFollowsDensity: " << this->RadiusFollowsDensity << "\n";
  os << indent << "RadiusRange: " << this->RadiusRange[0] << " " << this->RadiusRange[1] << "\n";
  os << indent << "NormalRadiusRange: " << this->NormalRadiusRange[0] << " "
     << this->NormalRadiusRange[1] << "\n";
  os << indent << "SpacingSpread: " << this->SpacingSpread << "\n";
  os << indent << "ProcessingDepth: " << this->ProcessingDepth << "\n";
  os << indent << "NumberOfRemovedPoints: " << this->NumberOfRemovedPoints << "\n";
  os << indent << "NumberOfNonFinitePoints: " << this->NumberOfNonFinitePoints << "\n";
  os << indent << "LastRunSummary: " << this->LastRunSummary << "\n";
}
