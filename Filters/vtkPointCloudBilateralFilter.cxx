#include "vtkPointCloudBilateralFilter.h"
#include "vtkPointCloudVertices.h"

#include "BilateralFilter.h"

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
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <cmath>
#include <cstring>
#include <numeric>
#include <vector>

vtkStandardNewMacro(vtkPointCloudBilateralFilter);
vtkCxxSetObjectMacro(vtkPointCloudBilateralFilter, Controller, vtkMultiProcessController);

namespace
{
/// Copies a 3-component array of any value type into interleaved doubles.
struct CopyTuplesToDouble
{
  template<typename ArrayT>
  void operator()(ArrayT* array, std::vector<double>& values) const
  {
    const auto range = vtk::DataArrayValueRange<3>(array);
    values.assign(range.begin(), range.end());
  }
};

void ToDoubles(vtkDataArray* array, std::vector<double>& values)
{
  using Dispatcher = vtkArrayDispatch::DispatchByValueType<vtkArrayDispatch::Reals>;
  CopyTuplesToDouble worker;
  if (!Dispatcher::Execute(array, worker, values))
  {
    worker(array, values); // any other array type, through the generic API
  }
}

/// Writes the kept points' filtered positions into an array of the input's value type.
struct CopyKeptPositions
{
  template<typename ArrayT>
  void operator()(ArrayT* array,
    const std::vector<double>& positions,
    const std::vector<vtkIdType>& kept) const
  {
    using ValueType = vtk::GetAPIType<ArrayT>;
    auto range = vtk::DataArrayValueRange<3>(array);
    for (std::size_t out = 0; out < kept.size(); ++out)
    {
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
} // namespace

vtkPointCloudBilateralFilter::vtkPointCloudBilateralFilter()
{
  this->SetController(vtkMultiProcessController::GetGlobalController());
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
  parameters.RemoveIsolatedPoints = this->RemoveIsolatedPoints;
  parameters.NumberOfThreads = this->NumberOfThreads;
  parameters.ComputeNormals = this->GenerateEstimatedNormals;
  return parameters;
}

int vtkPointCloudBilateralFilter::RequestInformation(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector*)
{
  // ParaView reads the "used" values when the pipeline information is updated, before the data
  // is: resolve them here already, from the input as it is now. RequestData resolves them again
  // the same way.
  vtkPointSet* input = vtkPointSet::GetData(inputVector[0]);
  if (!input || input->GetNumberOfPoints() == 0 || !(this->Radius >= 0.0) ||
      !(this->NormalRadius >= 0.0))
  {
    return 1;
  }
  if (this->Radius == 0.0 && this->IsDistributed())
  {
    // The automatic radius needs the whole cloud's extent, a collective reduction that
    // RequestInformation must not start: RequestData resolves it.
    return 1;
  }
  pcbilateral::CloudExtent extent;
  if (this->Radius == 0.0 || this->NormalRadius == 0.0)
  {
    std::vector<double> positions;
    ToDoubles(input->GetPoints()->GetData(), positions);
    pcbilateral::PointCloudView cloud;
    cloud.NumberOfPoints = static_cast<std::size_t>(input->GetNumberOfPoints());
    cloud.Positions = positions.data();
    extent = pcbilateral::MeasureCloud(cloud);
  }
  const pcbilateral::RadiiUsed radii = pcbilateral::ResolveRadii(this->MakeParameters(), extent);
  this->RadiusUsed = radii.Radius;
  this->NormalRadiusUsed = radii.NormalRadius;
  return 1;
}

vtkPointCloudBilateralFilter::~vtkPointCloudBilateralFilter()
{
  this->SetOrientationArrayName(nullptr);
  this->SetController(nullptr);
}

int vtkPointCloudBilateralFilter::RequestData(vtkInformation*,
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkPointSet* input = vtkPointSet::GetData(inputVector[0]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  this->RadiusUsed = 0.0;
  this->NormalRadiusUsed = 0.0;
  this->ProcessingDepth = 0;
  this->NumberOfRemovedPoints = 0;
  this->NumberOfNonFinitePoints = 0;
  output->Initialize();
  if (!input)
  {
    vtkErrorMacro(<< "the input is not a vtkPointSet");
    if (this->IsDistributed())
    {
      this->RunDistributed({}, this->MakeParameters(), {}, true); // the others are waiting
    }
    return 0;
  }

  const vtkIdType numberOfPoints = input->GetNumberOfPoints();
  std::vector<double> positions;
  if (numberOfPoints > 0)
  {
    ToDoubles(input->GetPoints()->GetData(), positions);
  }

  const pcbilateral::BilateralParameters parameters = this->MakeParameters();
  vtkPointData* inPD = input->GetPointData();
  std::vector<double> orientation;
  if (this->OrientNormals && numberOfPoints > 0)
  {
    vtkDataArray* reference = inPD->GetNormals();
    if (this->OrientationArrayName && *this->OrientationArrayName)
    {
      reference = inPD->GetArray(this->OrientationArrayName);
      if (!reference && std::strcmp(this->OrientationArrayName, "None") != 0)
      {
        vtkWarningMacro(<< "the input has no point array '" << this->OrientationArrayName
                        << "': the estimated normals are not oriented");
      }
    }
    if (reference && reference->GetNumberOfComponents() != 3)
    {
      vtkErrorMacro(<< "the orientation array '"
                    << (reference->GetName() ? reference->GetName() : "(unnamed)") << "' has "
                    << reference->GetNumberOfComponents() << " components, not 3");
      if (this->IsDistributed())
      {
        this->RunDistributed({}, parameters, {}, true); // the others are waiting
      }
      return 0;
    }
    if (reference)
    {
      ToDoubles(reference, orientation);
    }
  }

  pcbilateral::PointCloudView cloud;
  cloud.NumberOfPoints = static_cast<std::size_t>(numberOfPoints);
  cloud.Positions = positions.data();
  cloud.OrientationNormals = orientation.empty() ? nullptr : orientation.data();
  pcbilateral::BilateralObserver observer;
  observer.Progress = [this](double fraction) { this->UpdateProgress(fraction); };
  observer.ShouldAbort = [this]() { return this->GetAbortExecute() != 0; };
  observer.Warning = [this](const std::string& warning) { vtkWarningMacro(<< warning); };

  this->UpdateProgress(0.0);
  const pcbilateral::BilateralResult result =
    this->IsDistributed() ? this->RunDistributed(cloud, parameters, observer)
                          : pcbilateral::RunBilateralFilter(cloud, parameters, observer);
  if (result.Status == pcbilateral::BilateralStatus::Failed)
  {
    vtkErrorMacro(<< result.Error);
    return 0;
  }
  this->RadiusUsed = result.RadiusUsed;
  this->NormalRadiusUsed = result.NormalRadiusUsed;
  this->ProcessingDepth = result.ProcessingDepth;
  this->NumberOfRemovedPoints = static_cast<vtkIdType>(result.NumberOfRemovedPoints);
  this->NumberOfNonFinitePoints = static_cast<vtkIdType>(result.NumberOfNonFinitePoints);
  if (result.Status == pcbilateral::BilateralStatus::Aborted)
  {
    return 1; // an empty output
  }
  if (numberOfPoints == 0)
  {
    // Nothing to filter; the output still has the input's (empty) arrays and field data.
    if (input->GetPoints())
    {
      vtkNew<vtkPoints> none;
      none->SetDataType(input->GetPoints()->GetDataType());
      output->SetPoints(none);
    }
    output->GetPointData()->PassData(inPD);
    output->GetFieldData()->PassData(input->GetFieldData());
    return 1;
  }
  if (HasCellsOtherThanVertices(input))
  {
    vtkWarningMacro(<< "the input's cells (lines, polygons, volumes) are not carried to the "
                       "output, which is a point cloud");
  }

  std::vector<vtkIdType> kept;
  kept.reserve(static_cast<std::size_t>(numberOfPoints));
  for (vtkIdType id = 0; id < numberOfPoints; ++id)
  {
    if (!result.Removed[id])
    {
      kept.push_back(id);
    }
  }
  const auto outputCount = static_cast<vtkIdType>(kept.size());

  vtkNew<vtkPoints> points;
  points->SetDataType(input->GetPoints()->GetDataType());
  points->SetNumberOfPoints(outputCount);
  {
    using Dispatcher = vtkArrayDispatch::DispatchByValueType<vtkArrayDispatch::Reals>;
    CopyKeptPositions worker;
    if (!Dispatcher::Execute(points->GetData(), worker, result.Positions, kept))
    {
      worker(points->GetData(), result.Positions, kept);
    }
  }
  output->SetPoints(points);
  output->SetVerts(vtkPointCloudVertices(outputCount));
  // The radii used travel with the data (ParaView's Information panel shows them).
  output->GetFieldData()->PassData(input->GetFieldData());
  for (const auto& used : { std::make_pair("BilateralRadius", this->RadiusUsed),
         std::make_pair("BilateralNormalRadius", this->NormalRadiusUsed) })
  {
    vtkNew<vtkDoubleArray> value;
    value->SetName(used.first);
    value->InsertNextValue(used.second);
    output->GetFieldData()->AddArray(value);
  }

  vtkPointData* outPD = output->GetPointData();
  if (outputCount == numberOfPoints)
  {
    outPD->PassData(inPD);
  }
  else
  {
    vtkNew<vtkIdList> from;
    from->SetNumberOfIds(outputCount);
    std::copy(kept.begin(), kept.end(), from->GetPointer(0));
    vtkNew<vtkIdList> to;
    to->SetNumberOfIds(outputCount);
    std::iota(to->GetPointer(0), to->GetPointer(0) + outputCount, vtkIdType(0));
    outPD->CopyAllocate(inPD, outputCount);
    outPD->CopyData(inPD, from, to);
  }
  if (this->RemoveIsolatedPoints)
  {
    vtkNew<vtkIdTypeArray> originalIds;
    originalIds->SetName("vtkOriginalPointIds");
    originalIds->SetNumberOfValues(outputCount);
    std::copy(kept.begin(), kept.end(), originalIds->GetPointer(0));
    outPD->AddArray(originalIds);
  }
  if (this->GenerateEstimatedNormals)
  {
    vtkNew<vtkDoubleArray> normals;
    normals->SetName("EstimatedNormals");
    normals->SetNumberOfComponents(3);
    normals->SetNumberOfTuples(outputCount);
    for (vtkIdType out = 0; out < outputCount; ++out)
    {
      normals->SetTypedTuple(out, result.Normals.data() + 3 * kept[out]);
    }
    outPD->AddArray(normals);
  }
  if (this->GenerateDisplacementLength)
  {
    vtkNew<vtkDoubleArray> lengths;
    lengths->SetName("DisplacementLength");
    lengths->SetNumberOfValues(outputCount);
    for (vtkIdType out = 0; out < outputCount; ++out)
    {
      const double* before = positions.data() + 3 * kept[out];
      const double* after = result.Positions.data() + 3 * kept[out];
      const double length = std::sqrt((after[0] - before[0]) * (after[0] - before[0]) +
                                      (after[1] - before[1]) * (after[1] - before[1]) +
                                      (after[2] - before[2]) * (after[2] - before[2]));
      lengths->SetValue(out, std::isfinite(length) ? length : 0.0);
    }
    outPD->AddArray(lengths);
  }
  this->UpdateProgress(1.0);
  return 1;
}

void vtkPointCloudBilateralFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Radius: " << this->Radius << (this->Radius == 0.0 ? " (automatic)" : "") << "\n";
  os << indent << "NormalRadius: " << this->NormalRadius
     << (this->NormalRadius == 0.0 ? " (same as the radius)" : "") << "\n";
  os << indent << "NumberOfIterations: " << this->NumberOfIterations << "\n";
  os << indent << "OrientNormals: " << this->OrientNormals << "\n";
  os << indent << "OrientationArrayName: "
     << (this->OrientationArrayName ? this->OrientationArrayName : "(none: point normals)") << "\n";
  os << indent << "RemoveIsolatedPoints: " << this->RemoveIsolatedPoints << "\n";
  os << indent << "NumberOfThreads: " << this->NumberOfThreads << "\n";
  os << indent << "GenerateEstimatedNormals: " << this->GenerateEstimatedNormals << "\n";
  os << indent << "GenerateDisplacementLength: " << this->GenerateDisplacementLength << "\n";
  os << indent << "Controller: " << this->Controller << "\n";
  os << indent << "RadiusUsed: " << this->RadiusUsed << "\n";
  os << indent << "NormalRadiusUsed: " << this->NormalRadiusUsed << "\n";
  os << indent << "ProcessingDepth: " << this->ProcessingDepth << "\n";
  os << indent << "NumberOfRemovedPoints: " << this->NumberOfRemovedPoints << "\n";
  os << indent << "NumberOfNonFinitePoints: " << this->NumberOfNonFinitePoints << "\n";
}
