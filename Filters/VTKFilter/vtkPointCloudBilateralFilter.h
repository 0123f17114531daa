/**
 * @class   vtkPointCloudBilateralFilter
 * @brief   denoise a point cloud with the bilateral filter, keeping sharp edges
 *
 * vtkPointCloudBilateralFilter moves each point along its estimated normal toward the
 * neighbours that are close to it both in space and to its tangent plane, as in
 * J. Digne and C. de Franchis, "The Bilateral Filter for Point Clouds", Image Processing On
 * Line 7 (2017), pp. 278-287, https://doi.org/10.5201/ipol.2017.179.
 *
 * For a point p with neighbours q, |q - p| < Radius (p included):
 * - the normal n is the eigenvector of the smallest eigenvalue of the covariance of the
 *   neighbours, each weighted by wd = exp(-|q - p|^2 / (2 sd^2)), sd = Radius / 3;
 * - p moves to p + d n, with d = sum(wd wn h) / sum(wd wn), h = <n, q - p> and
 *   wn = exp(-h^2 / (2 sn^2)), sn = NormalRadius / 3.
 * Each of the NumberOfIterations iterations reads the positions written by the previous one.
 * A point moves by less than Radius per iteration.
 *
 * Parameters, in the paper's terms:
 * - Radius r: the neighbourhood; a few times the point spacing, larger for stronger noise.
 * - NormalRadius rn: how far from the tangent plane a neighbour still counts. Small values
 *   (about the noise level) keep sharp edges; large values (rn >> r) smooth them like a
 *   plain Gaussian filter.
 * - NumberOfIterations N: more iterations denoise more and sharpen edges.
 * Each is automatic when 0 (the default), and each given value overrides only itself. With
 * AutomaticParameters MEASURED (the default) the filter first measures the cloud's point
 * spacing and noise sigma, then applies the automatic rule, written once in the core
 * (ChooseParameters and DescribeAutomaticRule in Filters/Core/Measurement/AutomaticRule.h;
 * docs/parameters.md says where it comes from). With PAPER it takes the paper's heuristic
 * (PaperRadius there: r = sqrt(20 / number of points) times the largest bounding-box extent,
 * rn = r, N = 1).
 * The values actually used, and the measured scales, are readable after an update:
 * GetRadiusUsed(), GetNormalRadiusUsed(), GetNumberOfIterationsUsed(), GetPointSpacing(),
 * GetNoiseSigma().
 *
 * EdgeAware (off by default: the paper's filter) is a mode beyond the paper for sharp edges
 * under strong noise: the normals are filtered bilaterally (neighbours weighted by the
 * agreement of their normals) before the displacement, whose weights also leave out
 * neighbours whose normals disagree. Its defaults are the same r, rn and N; it costs several
 * times the paper's filter.
 *
 * The normals are estimated without orientation. If the input has point normals (or the
 * 3-component point array named by OrientationArrayName), each estimated normal is flipped
 * to agree with it; this changes only the reported normals, never the positions.
 *
 * A point with fewer than 5 neighbours stays where it is. With RemoveIsolatedPoints on, such
 * points are removed instead (for the rest of the run, as the authors' program does), and the
 * output gets a "vtkOriginalPointIds" array giving, for each output point, its input id.
 *
 * The input is any vtkPointSet: a vtkPolyData, a vtkUnstructuredGrid, a vtkStructuredGrid...
 * Only its points matter. Data sets whose points are implicit (vtkImageData,
 * vtkRectilinearGrid) are refused by the pipeline; convert them first if they are clouds.
 *
 * The output is a point cloud: the input's points in the same order (less removed ones),
 * with the same point type, every point-data array passed through, and one vertex cell per
 * point. The input's field data passes through, with more one-value arrays: "BilateralRadius",
 * "BilateralNormalRadius" and "BilateralNumberOfIterations", the parameters used, and, when the
 * cloud was measured, "BilateralPointSpacing", "BilateralNoiseSigma" and the three-component
 * "BilateralNearestNeighbourDistances" (GetNearestNeighbourDistances) and "BilateralSpacingSpread";
 * where the radius followed the density, "BilateralRadiusRange" and "BilateralNormalRadiusRange"
 * (two components each; the point array "BilateralPointRadius" with GeneratePointRadius); and
 * "BilateralMode"
 * ("paper" or "edge-aware"). The input's other cells
 * (lines, polygons, volumes) are not carried over, with one warning. Optional arrays: the estimated
 * normals ("EstimatedNormals", see GenerateEstimatedNormals) and the distance each point
 * moved ("DisplacementLength", see GenerateDisplacementLength).
 *
 * Points with NaN or infinite coordinates are passed through unchanged, are never used as
 * neighbours, and are reported in one warning.
 *
 * Bad parameters or an unusable input are reported by one error (an ErrorEvent); the output is
 * then empty and the update itself succeeds, so a pipeline downstream (a ParaView view) runs on
 * the empty output and shows the next valid result.
 *
 * This class runs on one process: its input is the whole cloud, and it never communicates.
 * vtkPPointCloudBilateralFilter (module FiltersParallelPointCloudBilateral, built when VTK has
 * MPI) filters a cloud split across the processes of an MPI run, with the same result.
 *
 * @warning
 * The filter runs in parallel with OpenMP (NumberOfThreads, 0 for all cores), scheduled by the
 * paper's octree cell colouring. Results are bit-for-bit identical whatever the number of
 * threads. Computation is in double precision, relative to each filtered point, so
 * georeferenced coordinates lose nothing.
 *
 * @sa
 * vtkPPointCloudBilateralFilter vtkPointSmoothingFilter vtkPointCloudTextReader
 * vtkPointCloudTextWriter
 */

#ifndef vtkPointCloudBilateralFilter_h
#define vtkPointCloudBilateralFilter_h

#include "vtkCommand.h"                          // For ParametersChosenEvent
#include "vtkFiltersPointCloudBilateralModule.h" // For export macro
#include "vtkPolyDataAlgorithm.h"

#include <atomic>  // For IterationsDone
#include <chrono>  // For LastFinishingReport
#include <cstdint> // For ChooseClasses
#include <string>  // For PrepareInput
#include <thread>  // For RunningThread
#include <vector>  // For Classes

class vtkPointSet;
namespace pcbilateral
{
struct BilateralObserver;
struct BilateralParameters;
struct BilateralResult;
struct PointCloudView;
}

class VTKFILTERSPOINTCLOUDBILATERAL_EXPORT vtkPointCloudBilateralFilter
  : public vtkPolyDataAlgorithm
{
public:
  static vtkPointCloudBilateralFilter* New();
  vtkTypeMacro(vtkPointCloudBilateralFilter, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum AutomaticParametersChoice
  {
    MEASURED = 0,
    PAPER = 1
  };

  /**
   * Invoked during an update once the parameters are resolved (measured and chosen), before the
   * first iteration: the getters below (GetRadiusUsed, GetPointSpacing, ...) then hold this run's
   * values, so a front end can say what was chosen while the filter still runs.
   */
  enum
  {
    ParametersChosenEvent = vtkCommand::UserEvent + 179
  };

  ///@{
  /**
   * How the parameters left at 0 are chosen: MEASURED (the default) from the cloud's measured
   * point spacing and noise, PAPER by the paper's heuristic (see the class description).
   */
  vtkSetMacro(AutomaticParameters, int);
  vtkGetMacro(AutomaticParameters, int);
  void SetAutomaticParametersToMeasured() { this->SetAutomaticParameters(MEASURED); }
  void SetAutomaticParametersToPaper() { this->SetAutomaticParameters(PAPER); }
  ///@}

  ///@{
  /**
   * Neighbourhood radius r, in the input's length unit; 0 means automatic (the default).
   * Negative or non-finite values are an error.
   */
  vtkSetMacro(Radius, double);
  vtkGetMacro(Radius, double);
  ///@}

  ///@{
  /**
   * Normal radius rn, in the input's length unit; 0 means automatic (the default). Negative or
   * non-finite values are an error.
   */
  vtkSetMacro(NormalRadius, double);
  vtkGetMacro(NormalRadius, double);
  ///@}

  ///@{
  /**
   * Number of iterations N; 0 means automatic (the default). Negative values and more than
   * 1000 are an error.
   */
  vtkSetMacro(NumberOfIterations, int);
  vtkGetMacro(NumberOfIterations, int);
  ///@}

  ///@{
  /**
   * Flip the estimated normals to agree with reference normals (default on). The reference is
   * the point array named by OrientationArrayName if set, else the input's point normals; with
   * neither, normals keep the arbitrary sign of the eigen solver. A name that is not a point
   * array of the input means no orientation, with a warning.
   */
  vtkSetMacro(OrientNormals, bool);
  vtkGetMacro(OrientNormals, bool);
  vtkBooleanMacro(OrientNormals, bool);
  vtkSetStringMacro(OrientationArrayName);
  vtkGetStringMacro(OrientationArrayName);
  ///@}

  ///@{
  /**
   * Remove points with fewer than 5 neighbours (or a zero weight sum) instead of leaving them
   * where they are (default off). The output then has a "vtkOriginalPointIds" array.
   */
  vtkSetMacro(RemoveIsolatedPoints, bool);
  vtkGetMacro(RemoveIsolatedPoints, bool);
  vtkBooleanMacro(RemoveIsolatedPoints, bool);
  ///@}

  ///@{
  /**
   * Edge-aware mode, beyond the paper (default off: the paper's filter, bit for bit): the
   * normals are filtered bilaterally before the displacement, so that points near a sharp edge
   * move along the normal of their own side; it keeps edges sharper under strong noise. See
   * EdgeAwareNormals.h in the core and docs/edge-aware.md.
   */
  vtkSetMacro(EdgeAware, bool);
  vtkGetMacro(EdgeAware, bool);
  vtkBooleanMacro(EdgeAware, bool);
  ///@}

  ///@{
  /**
   * Filter only the points whose value in the one-component integer point array
   * ClassArrayName (default "Classification": the LAS readers' class, without its flag bits) is
   * one of the Classes, as PDAL users limit a filter with `where` (smoothing trees into walls
   * helps no one). The other points keep their exact coordinates and are never neighbours, so no
   * class pulls another; the automatic parameters are measured on the chosen points, which get
   * exactly the bits a cloud of them alone would. No class (the default): every point is
   * filtered. With classes, a missing, multi-component or non-integer array is an error.
   */
  vtkSetStringMacro(ClassArrayName);
  vtkGetStringMacro(ClassArrayName);
  void AddClass(long long value);
  void RemoveAllClasses();
  int GetNumberOfClasses() const;
  long long GetClass(int index) const;
  ///@}

  /**
   * The number of points the last update filtered: the chosen classes' points, or every point
   * when no class was given.
   */
  vtkGetMacro(NumberOfFilteredPoints, vtkIdType);

  ///@{
  /**
   * Number of threads; 0 (the default) uses all cores. The result does not depend on it.
   */
  vtkSetClampMacro(NumberOfThreads, int, 0, VTK_INT_MAX);
  vtkGetMacro(NumberOfThreads, int);
  ///@}

  ///@{
  /**
   * Add the estimated unit normals of the last iteration as the point array
   * "EstimatedNormals" (default off). Zero for points that had too few neighbours.
   */
  vtkSetMacro(GenerateEstimatedNormals, bool);
  vtkGetMacro(GenerateEstimatedNormals, bool);
  vtkBooleanMacro(GenerateEstimatedNormals, bool);
  ///@}

  ///@{
  /**
   * Add the distance between each output point and its input position as the point array
   * "DisplacementLength" (default off).
   */
  vtkSetMacro(GenerateDisplacementLength, bool);
  vtkGetMacro(GenerateDisplacementLength, bool);
  vtkBooleanMacro(GenerateDisplacementLength, bool);
  ///@}

  ///@{
  /**
   * Where the automatic radius followed the density (GetRadiusFollowsDensity), add each point's
   * radius as the point array "BilateralPointRadius" (default off; nothing is added where the
   * radius is one for all).
   */
  vtkSetMacro(GeneratePointRadius, bool);
  vtkGetMacro(GeneratePointRadius, bool);
  vtkBooleanMacro(GeneratePointRadius, bool);
  ///@}

  ///@{
  /**
   * What the last update used and did: the radius, normal radius and number of iterations
   * (after the automatic choices), the point spacing and noise sigma measured for them (0 when
   * the cloud was not measured: every parameter given, the paper's heuristic, or a cloud too
   * small to measure), the octree's processing depth, and the numbers of removed and
   * non-finite points. Zero until an update has run the filter, and after an update that failed.
   */
  vtkGetMacro(RadiusUsed, double);
  vtkGetMacro(NormalRadiusUsed, double);
  vtkGetMacro(NumberOfIterationsUsed, int);
  vtkGetMacro(PointSpacing, double);
  vtkGetMacro(NoiseSigma, double);
  vtkGetMacro(ProcessingDepth, int);
  vtkGetMacro(NumberOfRemovedPoints, vtkIdType);
  vtkGetMacro(NumberOfNonFinitePoints, vtkIdType);
  ///@}

  /**
   * The spread of the cloud's sampling, measured with its spacing and noise: the 5th, 50th and
   * 95th percentiles of the distance from a point to its nearest neighbour (zeros when the cloud
   * was not measured). Evenly sampled clouds have them close together; a scan from one position
   * spans a hundred times and more.
   */
  vtkGetVector3Macro(NearestNeighbourDistances, double);

  ///@{
  /**
   * Whether the last update's automatic radius followed the density: on a cloud whose local
   * spacing varies more than a few times (SpacingSpread: the 95th over the 5th percentile of the
   * local spacing, read on a coarse grid), each point's radius comes from its local spacing
   * (beyond the paper; given radii are never changed). RadiusRange and NormalRadiusRange are then
   * the smallest and largest used, and the output has the point array "BilateralPointRadius";
   * RadiusUsed stays the radius at the whole cloud's spacing. The rule: pcbilateral::
   * DescribeAutomaticRule (Filters/Core/Measurement/AutomaticRule.h).
   */
  vtkGetMacro(RadiusFollowsDensity, bool);
  vtkGetVector2Macro(RadiusRange, double);
  vtkGetVector2Macro(NormalRadiusRange, double);
  vtkGetMacro(SpacingSpread, double);
  ///@}

  /**
   * The last update in one line, for a user interface: "not run yet" before the first, then the
   * parameters used and where they came from (e.g. "r 0.0628, rn 0.0471, N 2 (measured)": from
   * the measured scales; "(paper's rule)", "(given)"), "failed: " and the error, "aborted", or
   * "nothing to filter: the input has no points".
   */
  const char* GetLastRunSummary() const { return this->LastRunSummary.c_str(); }

  /// In a ProgressEvent observer: the phase of the run ("measuring", "iteration 2 of 3") and
  /// the fraction of it done, as pcbilateral's progress bar shows them (GetProgress() is the
  /// whole run's fraction, 0 while measuring).
  const char* GetProgressPhase() const { return this->ProgressPhase.c_str(); }
  double GetPhaseProgress() const { return this->PhaseFraction; }

protected:
  vtkPointCloudBilateralFilter();
  ~vtkPointCloudBilateralFilter() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  /**
   * Runs the core on the prepared points. `preparedHere` is false when this process could not
   * prepare its input (its error is reported already): the run then fails, but an override that
   * communicates (vtkPPointCloudBilateralFilter) still takes part, so that no other process is
   * left waiting. RequestData calls it exactly once per update.
   */
  virtual pcbilateral::BilateralResult RunCore(const pcbilateral::PointCloudView& cloud,
    const pcbilateral::BilateralParameters& parameters,
    const pcbilateral::BilateralObserver& observer,
    bool preparedHere);

  // The defaults are the core's (pcbilateral::BilateralParameters), set by the constructor.
  double Radius;
  double NormalRadius;
  int NumberOfIterations;
  int AutomaticParameters;
  bool OrientNormals = true;
  char* OrientationArrayName = nullptr;
  bool RemoveIsolatedPoints;
  int NumberOfThreads;
  bool GenerateEstimatedNormals = false;
  bool GenerateDisplacementLength = false;
  bool GeneratePointRadius = false;
  bool EdgeAware;
  char* ClassArrayName = nullptr;
  std::vector<long long> Classes;

  double RadiusUsed = 0.0;
  double NormalRadiusUsed = 0.0;
  int NumberOfIterationsUsed = 0;
  double PointSpacing = 0.0;
  double NoiseSigma = 0.0;
  double NearestNeighbourDistances[3] = { 0.0, 0.0, 0.0 };
  bool RadiusFollowsDensity = false;
  double RadiusRange[2] = { 0.0, 0.0 };
  double NormalRadiusRange[2] = { 0.0, 0.0 };
  double SpacingSpread = 0.0;
  int ProcessingDepth = 0;
  vtkIdType NumberOfRemovedPoints = 0;
  vtkIdType NumberOfNonFinitePoints = 0;
  vtkIdType NumberOfFilteredPoints = 0;
  std::string LastRunSummary = "not run yet";
  std::string ProgressPhase;
  double PhaseFraction = 0.0;

private:
  struct InputCloud;
  pcbilateral::BilateralParameters MakeParameters() const;
  /// The input's positions and orientation normals as doubles; why they cannot be had, or empty.
  std::string PrepareInput(vtkPointSet* input, InputCloud& cloud);
  /// With Classes: one flag per input point, set for the chosen ones; why they cannot be told,
  /// or empty. Without: no flags (every point is filtered).
  std::string ChooseClasses(vtkPointSet* input, std::vector<std::uint8_t>& chosen) const;
  /// RunCore on the chosen points only (all of them when chosen is empty), the result spread
  /// back over the whole cloud.
  pcbilateral::BilateralResult RunOnChosen(const InputCloud& cloud,
    const std::vector<std::uint8_t>& chosen,
    const pcbilateral::BilateralObserver& observer,
    bool preparedHere);
  void RecordRunInformation(const pcbilateral::BilateralResult& result);
  std::string DescribeRun(const pcbilateral::BilateralResult& result) const;
  /// The output point cloud: the kept points, their arrays, the arrays the filter adds.
  /// The core run's observer: its progress, abort, warnings and chosen parameters reported as
  /// this filter's.
  pcbilateral::BilateralObserver MakeObserver();
  /// Ends an aborted run: an empty output. Returns RequestData's 1.
  int EndAborted(vtkPolyData* output);
  /// Whether an abort was asked. Once the core's iterations are done (their progress runs to
  /// KernelShare), the result's hand-over and the output's copies take a good part of a second
  /// on tens of millions of points: asked then, on the thread that runs the filter, it also
  /// reports progress (a value below 1) at most every 50 ms, so that ParaView, which sees an
  /// Abort click only while a run reports progress, can stop them.
  bool AskAbort();
  std::atomic<bool> IterationsDone{ false };
  std::thread::id RunningThread;
  std::chrono::steady_clock::time_point LastFinishingReport;
  /// Fills the output; false if an abort was asked meanwhile (asked between its copies).
  bool BuildOutput(vtkPointSet* input,
    const InputCloud& cloud,
    const pcbilateral::BilateralResult& result,
    vtkPolyData* output);

  vtkPointCloudBilateralFilter(const vtkPointCloudBilateralFilter&) = delete;
  void operator=(const vtkPointCloudBilateralFilter&) = delete;
};

#endif
