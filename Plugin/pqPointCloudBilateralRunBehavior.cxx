#include "pqPointCloudBilateralRunBehavior.h"

#include "pqApplicationCore.h"
#include "pqCoreUtilities.h"
#include "pqDataRepresentation.h"
#include "pqPipelineSource.h"
#include "pqProgressManager.h"
#include "pqRepresentation.h"
#include "pqServer.h"
#include "pqServerManagerModel.h"
#include "pqView.h"
#include "vtkAlgorithm.h"
#include "vtkCallbackCommand.h"
#include "vtkCollection.h"
#include "vtkCommand.h"
#include "vtkDataObject.h"
#include "vtkNew.h"
#include "vtkOutputWindow.h"
#include "vtkPVArrayInformation.h"
#include "vtkPVDataInformation.h"
#include "vtkPVDataSetAttributesInformation.h"
#include "vtkPVProgressHandler.h"
#include "vtkPVRepresentedArrayListSettings.h"
#include "vtkPVSessionBase.h"
#include "vtkSMBoundsDomain.h"
#include "vtkSMPVRepresentationProxy.h"
#include "vtkSMProperty.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMProxy.h"
#include "vtkSMSession.h"
#include "vtkSMSettings.h"
#include "vtkSMStringListDomain.h"
#include "vtkType.h"

#include <QAbstractItemView>
#include <QApplication>
#include <QEvent>
#include <QMouseEvent>
#include <QPointer>
#include <QThread>
#include <QTimer>
#include <QWidget>
#include <QWindow>

#include <algorithm>
#include <cstring>
#include <string>

namespace
{
/// Qt's events are processed at most this often during a run (ParaView's progress interval).
/// 50 ms halved the median gap between two processings of a LAZ read or write (0.065 s against
/// 0.13 s) but not the largest (0.3-0.4 s either way), and no change in the click-to-return
/// times could be told from the noise of a busy machine (docs/speed.md, Abort latency).
constexpr qint64 EventsIntervalMs = 100;

/// What the behavior does for a run of one of this plugin's proxies.
enum class RunKind
{
  Filter,
  Reader,
  Writer
};

/// This plugin's proxies whose runs the behavior follows (PointCloudBilateral.xml.in).
struct WatchedType
{
  const char* Group;
  const char* Name;
  RunKind Kind;
};
constexpr WatchedType WatchedTypes[] = {
  { "filters", "PointCloudBilateralFilter", RunKind::Filter },
  { "sources", "ASPRSLASPointCloudReader", RunKind::Reader },
  { "sources", "PCDPointCloudReader", RunKind::Reader },
  { "sources", "ASCIIPointCloudTextReader", RunKind::Reader },
  { "writers", "LASPointCloudWriter", RunKind::Writer },
  { "writers", "PCDPointCloudWriter", RunKind::Writer },
  { "writers", "PointCloudTextWriter", RunKind::Writer },
};

/// The proxy's kind, or false when it is none of this plugin's proxies above.
bool FindRunKind(vtkSMProxy* proxy, RunKind& kind)
{
  const char* group = proxy ? proxy->GetXMLGroup() : nullptr;
  const char* name = proxy ? proxy->GetXMLName() : nullptr;
  for (const WatchedType& type : WatchedTypes)
  {
    if (group && name && std::strcmp(group, type.Group) == 0 && std::strcmp(name, type.Name) == 0)
    {
      kind = type.Kind;
      return true;
    }
  }
  return false;
}

/// The Output Messages window's note after an aborted run: what is left, and how to run again
/// (the pipeline takes an aborted filter's or reader's run as up to date, so Apply alone would
/// not run it again; each Save Data makes a new writer).
std::string AbortedNote(vtkSMProxy* proxy, RunKind kind)
{
  const std::string label = proxy->GetXMLLabel() ? proxy->GetXMLLabel() : proxy->GetXMLName();
  switch (kind)
  {
    case RunKind::Filter:
      return label +
             ": aborted, the output is empty.\nChange a property and Apply to run it again.";
    case RunKind::Reader:
      return label + ": aborted, the output is empty.\nReload the file (File > Reload Files) to "
                     "read it again.";
    case RunKind::Writer:
      break;
  }
  const char* fileName =
    proxy->GetProperty("FileName") ? vtkSMPropertyHelper(proxy, "FileName").GetAsString() : nullptr;
  return label + ": aborted, " + (fileName ? fileName : "the file") +
         " was not written (nor any part of it).\nSave the data again to write it.";
}

/**
 * Installed on the application while events are processed during a run:
 * - timer events wait until the run has ended (a timer that is not handled fires again later),
 *   so nothing a timer starts (a render of the view, a dialog with its own event loop, such as
 *   the welcome dialog at start-up) runs in the middle of the filter; item views' timers, which
 *   only lay out their rows, are let through;
 * - key and mouse input is dropped unless it is for the progress manager's non-blockable
 *   objects (its progress bar and Abort button). pqProgressManager's own filter means the same
 *   but drops the press that Qt 5 first delivers to the window, so the Abort button never gets
 *   it: the manager's filter is switched off meanwhile (pqProgressManager::unblockEvents), and
 *   this one finds the widget under a window's mouse event.
 * Repaints and queued calls (the Output Messages window showing a warning) are handled.
 */
class RunEventGate : public QObject
{
public:
  explicit RunEventGate(const QList<QPointer<QObject>>& allowed)
    : Allowed(allowed)
  {
  }

  bool eventFilter(QObject* object, QEvent* event) override
  {
    switch (event->type())
    {
      case QEvent::Timer:
        // Except an item view's own timers (its delayed layout): without them the Output
        // Messages window lists a warning only after the run it warns about.
        return qobject_cast<QAbstractItemView*>(object) == nullptr;
      case QEvent::MouseButtonPress:
      case QEvent::MouseButtonRelease:
      case QEvent::MouseButtonDblClick:
      {
        QWidget* target = qobject_cast<QWidget*>(object);
        if (!target && qobject_cast<QWindow*>(object))
        {
          target = QApplication::widgetAt(static_cast<QMouseEvent*>(event)->globalPos());
        }
        for (; target; target = target->parentWidget())
        {
          if (this->Allowed.contains(target))
          {
            return false;
          }
        }
        return true;
      }
      case QEvent::KeyPress:
      case QEvent::KeyRelease:
      case QEvent::ShortcutOverride:
      case QEvent::Wheel:
        return true;
      default:
        return false;
    }
  }

private:
  const QList<QPointer<QObject>>& Allowed;
};

/// A message longer than this is given a shorter first line (about what the Output Messages
/// window shows of a row at its default size).
constexpr std::size_t LongestFirstLine = 80;

/**
 * The filter's error or warning as the Output Messages window should show it. That window sums a
 * message up in one row, cut at the window's width: VTK's "ERROR: In file, line n\nclass (address):
 * text" by the whole text, any other message by its first line. So a long text is split where its
 * explanation begins, at its first ": " or " (" ("the radius 1e-09 is too small for a cloud 1.45
 * wide" / "(it may be at most 1e+08 times smaller): give a larger radius"): the row shows the
 * first clause whole, and the rest, then the filter's name and the source line, open under it.
 */
std::string FormatForOutputMessages(const std::string& vtkText)
{
  // VTK 9.2: "ERROR: In file, line n\nclass (address): text\n\n".
  std::string text = vtkText;
  std::string location;
  const std::size_t in = text.find(": In ");
  const std::size_t lineEnd = text.find('\n');
  if (in != std::string::npos && lineEnd != std::string::npos && in < lineEnd)
  {
    location = ", " + text.substr(in + 5, lineEnd - in - 5);
    text.erase(0, lineEnd + 1);
  }
  const std::size_t object = text.find("): ");
  if (object != std::string::npos && text.find(" (0x") < object)
  {
    text.erase(0, object + 3);
  }
  while (!text.empty() && (text.back() == '\n' || text.back() == ' '))
  {
    text.pop_back();
  }
  if (text.size() > LongestFirstLine)
  {
    const std::size_t split = std::min(text.find(": ", 20), text.find(" (", 20));
    if (split != std::string::npos)
    {
      // "A: B" becomes "A:" and "B"; "A (B): C", "A" and "(B): C".
      const std::size_t rest = text[split] == ':' ? split + 2 : split + 1;
      text = text.substr(0, text[split] == ':' ? split + 1 : split) + "\n" + text.substr(rest);
    }
  }
  return text + "\n(Point Cloud Bilateral Filter" + location + ")";
}

/// Observes the filter's errors and warnings (an observed one is not printed by VTK) and prints
/// them in the form above.
void ShowFilterMessage(vtkObject*, unsigned long event, void*, void* callData)
{
  const char* text = static_cast<const char*>(callData);
  if (!text)
  {
    return;
  }
  const std::string shown = FormatForOutputMessages(text);
  if (event == vtkCommand::ErrorEvent)
  {
    vtkOutputWindow::GetInstance()->DisplayErrorText(shown.c_str());
  }
  else
  {
    vtkOutputWindow::GetInstance()->DisplayWarningText(shown.c_str());
  }
}
/// Whether no display of the view but `display` shows any point.
bool AloneInView(pqDataRepresentation* display)
{
  pqView* view = display->getView();
  if (!view)
  {
    return false;
  }
  for (pqRepresentation* other : view->getRepresentations())
  {
    auto* data = qobject_cast<pqDataRepresentation*>(other);
    vtkPVDataInformation* information = data ? data->getInputDataInformation() : nullptr;
    if (data && data != display && data->isVisible() && information &&
        information->GetNumberOfPoints() > 0)
    {
      return false;
    }
  }
  return true;
}

/// A new display of a cloud with "Colors" (3 unsigned chars a point: the display colours the
/// LAS and PCD readers make from the file's RGB, kept by the filter) shows those colours, as
/// the scanner recorded them, rather than plain grey: coloured by them, not mapped through a
/// colour map (a filter's display inherits its input's colouring, but mapped). A display
/// coloured by another array is left as it is.
void ShowRecordedColours(pqDataRepresentation* display, vtkPVDataInformation* information)
{
  vtkSMProxy* proxy = display->getProxy();
  vtkPVArrayInformation* colours =
    information->GetPointDataInformation()->GetArrayInformation("Colors");
  auto* coloured = vtkSMPVRepresentationProxy::SafeDownCast(proxy);
  if (!colours || colours->GetDataType() != VTK_UNSIGNED_CHAR ||
      colours->GetNumberOfComponents() != 3 || !coloured || !proxy->GetProperty("MapScalars"))
  {
    return;
  }
  if (!vtkSMPVRepresentationProxy::GetUsingScalarColoring(proxy))
  {
    coloured->SetScalarColoring("Colors", vtkDataObject::POINT);
  }
  const char* array = vtkSMPropertyHelper(proxy, "ColorArrayName").GetInputArrayNameToProcess();
  if (array && std::strcmp(array, "Colors") == 0)
  {
    vtkSMPropertyHelper(proxy, "MapScalars").Set(0);
    proxy->UpdateVTKObjects();
  }
}

/// Shows a new display of a cloud as a point cloud: in its recorded colours, and, for points
/// without cells shown as ParaView's default Surface (which draws nothing), as Point Gaussian
/// spheres, as the GUI's Apply shows a PLY cloud. False while its input has no points (an
/// empty output: a first Apply with a bad value, an aborted read): nothing to choose from yet.
bool SetUpPointDisplay(pqDataRepresentation* display)
{
  vtkPVDataInformation* information = display->getInputDataInformation();
  if (!information || information->GetNumberOfPoints() == 0)
  {
    return false;
  }
  ShowRecordedColours(display, information);
  if (information->GetNumberOfCells() != 0)
  {
    display->renderViewEventually();
    return true;
  }
  vtkSMProxy* proxy = display->getProxy();
  vtkSMPropertyHelper type(proxy, "Representation");
  auto* domain = proxy->GetProperty("Representation")->FindDomain<vtkSMStringListDomain>();
  unsigned int index = 0;
  if (!type.GetAsString() || std::strcmp(type.GetAsString(), "Surface") != 0 || !domain ||
      !domain->IsInDomain("Point Gaussian", index))
  {
    return true; // not the default, or not a render view's display
  }
  type.Set("Point Gaussian");
  if (proxy->GetProperty("ShaderPreset"))
  {
    vtkSMPropertyHelper(proxy, "ShaderPreset").Set("Sphere");
  }
  proxy->UpdateVTKObjects();
  display->renderViewEventually();
  return true;
}

/// A display shown while the filter's or reader's output was empty (a first Apply with a bad
/// value, an aborted read) took its Point Gaussian radius from empty bounds (-0.01): the points
/// of every later run would be invisible. Once there are points, such a radius is set again from
/// the data's bounds, as a display made then would have it; and when nothing else is shown, the
/// camera, fitted to nothing then, is fitted to the points (after an aborted read and Reload
/// Files, the cloud was off screen).
void SizePointsToData(pqPipelineSource* source)
{
  for (pqDataRepresentation* display : source->getRepresentations(nullptr))
  {
    vtkSMProxy* proxy = display->getProxy();
    vtkSMProperty* radius = proxy->GetProperty("GaussianRadius");
    vtkPVDataInformation* information = display->getInputDataInformation();
    if (!radius || !information || information->GetNumberOfPoints() == 0 ||
        vtkSMPropertyHelper(radius).GetAsDouble() > 0.0)
    {
      continue;
    }
    if (auto* bounds = radius->FindDomain<vtkSMBoundsDomain>())
    {
      bounds->Update(nullptr); // (from the output's bounds now)
    }
    radius->ResetToDomainDefaults();
    proxy->UpdateVTKObjects();
    if (AloneInView(display))
    {
      display->getView()->resetDisplay();
    }
    display->renderViewEventually();
  }
}
}

struct pqPointCloudBilateralRunBehavior::WatchedProxy
{
  vtkWeakPointer<vtkSMProxy> Proxy;
  RunKind Kind;
  /// The proxy's VTK object the run slots are connected to (a reload makes a new one).
  vtkWeakPointer<vtkAlgorithm> Observed;
};

pqPointCloudBilateralRunBehavior::pqPointCloudBilateralRunBehavior(QObject* parent)
  : Superclass(parent)
{
}

pqPointCloudBilateralRunBehavior::~pqPointCloudBilateralRunBehavior() = default;

void pqPointCloudBilateralRunBehavior::startup()
{
  pqApplicationCore* core = pqApplicationCore::instance();
  pqServerManagerModel* model = core->getServerManagerModel();
  QObject::connect(model,
    &pqServerManagerModel::sourceAdded,
    this,
    &pqPointCloudBilateralRunBehavior::onSourceAdded);
  QObject::connect(model,
    &pqServerManagerModel::serverAdded,
    this,
    &pqPointCloudBilateralRunBehavior::onServerAdded);
  for (pqServer* server : model->findItems<pqServer*>())
  {
    this->onServerAdded(server);
  }
  for (pqPipelineSource* source : model->findItems<pqPipelineSource*>())
  {
    this->onSourceAdded(source); // filters made before the plugin was loaded
  }
  // The parameters and scales the filter records in its output's field data are for the
  // Information panel and for scripts, not for colouring: keep them out of the colour-by lists
  // (ParaView's "Filter Expressions" of the colour array list; editing that setting in the
  // Settings dialog replaces this until the next start).
  vtkPVRepresentedArrayListSettings* colourArrays =
    vtkPVRepresentedArrayListSettings::GetInstance();
  // Likewise the file headers the LAS and PCD readers keep in field data ("LAS Scale", "PCD
  // Viewpoint"...), which crowded the list of a LAS file's attributes.
  const int count = colourArrays->GetNumberOfFilterExpressions();
  colourArrays->SetNumberOfFilterExpressions(count + 2);
  colourArrays->SetFilterExpression(count,
    "^Bilateral(Radius|NormalRadius|NumberOfIterations|PointSpacing|NoiseSigma|"
    "NearestNeighbourDistances|SpacingSpread|RadiusRange|NormalRadiusRange|Mode)$");
  colourArrays->SetFilterExpression(count + 1, "^(LAS|PCD) [A-Z]");
  // A .xyz file opens with the Point Cloud Text Reader: ParaView 5.11's open dialog offers the
  // PLOT3D reader first (it claims .xyz too, and gives an empty multiblock for a point file).
  // A .las or .laz file opens with the LAS reader without asking the other readers that claim
  // the extension: GDAL's raster reader, asked, printed "ERROR 4: ... not recognized".
  // This is ParaView's "default reader" setting, at a priority below the user's own settings
  // (which then win) and never saved to them.
  vtkSMSettings::GetInstance()->AddCollectionFromString(
    R"json({ "settings": { "RepresentedArrayListSettings": { "ReaderDetails": [
      "*.xyz", "Point Cloud Text Files", "ASCIIPointCloudTextReader",
      "*.las *.laz", "LAS and LAZ point cloud", "ASPRSLASPointCloudReader" ] } } })json",
    0.1);
  QObject::connect(core->getProgressManager(),
    &pqProgressManager::abort,
    this,
    &pqPointCloudBilateralRunBehavior::onAbort);
}

void pqPointCloudBilateralRunBehavior::shutdown()
{
  this->disconnect();
}

void pqPointCloudBilateralRunBehavior::onSourceAdded(pqPipelineSource* source)
{
  if (!source)
  {
    return;
  }
  QObject::connect(source,
    &pqPipelineSource::representationAdded,
    this,
    [this](pqPipelineSource*, pqDataRepresentation* display, int)
    { this->onRepresentationAdded(display); });
  // After each update, once the pipeline has returned (its data information is then new).
  QObject::connect(source,
    QOverload<pqPipelineSource*>::of(&pqPipelineSource::dataUpdated),
    this,
    &pqPointCloudBilateralRunBehavior::onDataUpdated);
  for (pqDataRepresentation* display : source->getRepresentations(nullptr))
  {
    this->onRepresentationAdded(display); // shown before the plugin's GUI part started
  }

  if (!source->getServer()->isRemote())
  {
    this->Watch(source->getProxy()); // (made before the plugin was loaded)
    this->ObserveWatchedObjects();
  }
}

void pqPointCloudBilateralRunBehavior::onServerAdded(pqServer* server)
{
  if (!server || server->isRemote())
  {
    return;
  }
  vtkSMSession* session = server->session();
  pqCoreUtilities::connect(session,
    vtkPVSessionBase::RegisterRemoteObjectEvent,
    this,
    SLOT(onRemoteObjectRegistered(vtkObject*, unsigned long, void*)));
  pqCoreUtilities::connect(
    session->GetProgressHandler(), vtkCommand::StartEvent, this, SLOT(onProgressPrepared()));
  vtkNew<vtkCollection> existing;
  session->GetAllRemoteObjects(existing);
  for (int k = 0; k < existing->GetNumberOfItems(); ++k)
  {
    this->Watch(vtkSMProxy::SafeDownCast(existing->GetItemAsObject(k)));
  }
  this->ObserveWatchedObjects();
}

void pqPointCloudBilateralRunBehavior::onRemoteObjectRegistered(vtkObject* session,
  unsigned long,
  void* globalId)
{
  auto* base = vtkPVSessionBase::SafeDownCast(session);
  if (base && globalId)
  {
    // A new proxy gets its id as its VTK objects are about to be made: watched now, observed
    // once they exist (onProgressPrepared).
    this->Watch(
      vtkSMProxy::SafeDownCast(base->GetRemoteObject(*static_cast<vtkTypeUInt32*>(globalId))));
  }
}

void pqPointCloudBilateralRunBehavior::onProgressPrepared()
{
  // The start of an update, a write or a render, before any algorithm runs in it.
  this->ObserveWatchedObjects();
}

void pqPointCloudBilateralRunBehavior::Watch(vtkSMProxy* proxy)
{
  RunKind kind;
  if (!FindRunKind(proxy, kind))
  {
    return;
  }
  for (const WatchedProxy& watched : this->Watched)
  {
    if (watched.Proxy == proxy)
    {
      return;
    }
  }
  this->Watched.push_back(WatchedProxy{ proxy, kind, nullptr });
}

void pqPointCloudBilateralRunBehavior::ObserveWatchedObjects()
{
  auto gone = [](const WatchedProxy& watched) { return watched.Proxy == nullptr; };
  this->Watched.erase(
    std::remove_if(this->Watched.begin(), this->Watched.end(), gone), this->Watched.end());
  for (WatchedProxy& watched : this->Watched)
  {
    vtkSMProxy* proxy = watched.Proxy;
    // Only objects already made: asking a proxy for its object would make it.
    if (proxy->IsPrototype() || !proxy->GetObjectsCreated())
    {
      continue;
    }
    auto* algorithm = vtkAlgorithm::SafeDownCast(proxy->GetClientSideObject());
    if (algorithm && algorithm != watched.Observed)
    {
      this->Observe(watched, algorithm);
    }
  }
}

void pqPointCloudBilateralRunBehavior::Observe(WatchedProxy& watched, vtkAlgorithm* algorithm)
{
  watched.Observed = algorithm;
  // The progress bar names a run by its algorithm's progress text, or else by its class
  // ("vtkPLASPointCloudReader"): give it the label the menus and the panel show.
  if (const char* label = watched.Proxy->GetXMLLabel())
  {
    algorithm->SetProgressText(label);
  }
  if (watched.Kind == RunKind::Filter)
  {
    vtkNew<vtkCallbackCommand> showMessage;
    showMessage->SetCallback(&ShowFilterMessage);
    algorithm->AddObserver(vtkCommand::ErrorEvent, showMessage);
    algorithm->AddObserver(vtkCommand::WarningEvent, showMessage);
  }
  // The connections end with either object.
  pqCoreUtilities::connect(algorithm, vtkCommand::StartEvent, this, SLOT(onRunStarted(vtkObject*)));
  pqCoreUtilities::connect(
    algorithm, vtkCommand::ProgressEvent, this, SLOT(onRunProgress(vtkObject*)));
  pqCoreUtilities::connect(algorithm, vtkCommand::EndEvent, this, SLOT(onRunEnded(vtkObject*)));
}

const pqPointCloudBilateralRunBehavior::WatchedProxy* pqPointCloudBilateralRunBehavior::FindWatched(
  vtkObject* algorithm) const
{
  for (const WatchedProxy& watched : this->Watched)
  {
    if (algorithm && watched.Observed == algorithm && watched.Proxy)
    {
      return &watched;
    }
  }
  return nullptr;
}

void pqPointCloudBilateralRunBehavior::onRepresentationAdded(pqRepresentation* representation)
{
  QPointer<pqDataRepresentation> display = qobject_cast<pqDataRepresentation*>(representation);
  if (!display || !display->getProxy()->GetProperty("Representation"))
  {
    return;
  }
  // Now, while ParaView's Show still runs: a queued call would come after a script's next lines.
  if (vtkPVDataInformation* information = display->getInputDataInformation())
  {
    ShowRecordedColours(display, information);
  }
  if (!display->getInputDataInformation() ||
      display->getInputDataInformation()->GetNumberOfPoints() == 0)
  {
    this->ShownEmpty.push_back(display); // set up once its input has points (onDataUpdated)
  }
  // Once ParaView has set the new display up: Show chooses its representation type after
  // registering it.
  QTimer::singleShot(0,
    this,
    [this, display]()
    {
      if (display && SetUpPointDisplay(display))
      {
        this->ShownEmpty.removeAll(display);
      }
    });
}

void pqPointCloudBilateralRunBehavior::onDataUpdated(pqPipelineSource* source)
{
  RunKind kind;
  if (FindRunKind(source->getProxy(), kind) && kind != RunKind::Writer)
  {
    source->getProxy()->UpdatePropertyInformation(); // the Properties panel's read-outs
  }
  for (const QPointer<pqDataRepresentation>& display : QList(this->ShownEmpty))
  {
    if (!display)
    {
      this->ShownEmpty.removeAll(display);
    }
    else if (display->getInput() == source && SetUpPointDisplay(display))
    {
      this->ShownEmpty.removeAll(display);
    }
  }
  SizePointsToData(source);
}

void pqPointCloudBilateralRunBehavior::onRunStarted(vtkObject* algorithm)
{
  // (A writer's run starts twice: the pipeline's StartEvent, then vtkWriter's own.)
  if (algorithm != this->Running)
  {
    this->AbortAsked = false;
  }
  this->Running = vtkAlgorithm::SafeDownCast(algorithm);
  this->SinceEvents.start();
  pqApplicationCore::instance()->getProgressManager()->setEnableAbort(true);
}

void pqPointCloudBilateralRunBehavior::onRunProgress(vtkObject* algorithm)
{
  // The algorithm reports from its calling thread, the GUI's; a nested event loop is only safe
  // there and only once at a time. Not at the run's end (progress 1, reported by the pipeline
  // once the algorithm has returned): an Abort pressed then would come after its last check and
  // stop its next run at once.
  if (algorithm != this->Running || this->InEvents ||
      QThread::currentThread() != QCoreApplication::instance()->thread() ||
      this->SinceEvents.elapsed() < EventsIntervalMs || this->Running->GetProgress() >= 1.0)
  {
    return;
  }
  this->InEvents = true;
  pqProgressManager* progress = pqApplicationCore::instance()->getProgressManager();
  RunEventGate gate(progress->nonBlockableObjects());
  QCoreApplication::instance()->installEventFilter(&gate);
  const bool wasUnblocked = progress->unblockEvents(true);
  QCoreApplication::processEvents(QEventLoop::ExcludeSocketNotifiers);
  progress->unblockEvents(wasUnblocked);
  QCoreApplication::instance()->removeEventFilter(&gate);
  this->InEvents = false;
  this->SinceEvents.start();
}

void pqPointCloudBilateralRunBehavior::onRunEnded(vtkObject* algorithm)
{
  const WatchedProxy* watched = this->FindWatched(algorithm);
  if (algorithm != this->Running)
  {
    return;
  }
  this->Running = nullptr;
  pqApplicationCore::instance()->getProgressManager()->setEnableAbort(false);
  // The filter's flag stays set until its next run; the readers' and writers' is cleared as
  // their run ends, and an Abort seen by their progress event is always seen by their next check.
  if (watched && (this->AbortAsked || static_cast<vtkAlgorithm*>(algorithm)->GetAbortExecute()))
  {
    vtkOutputWindow::GetInstance()->DisplayWarningText(
      AbortedNote(watched->Proxy, watched->Kind).c_str());
  }
  this->AbortAsked = false;
}

void pqPointCloudBilateralRunBehavior::onAbort()
{
  if (this->Running)
  {
    // Polled by the algorithm at its progress points; the run ends with an empty output (a
    // writer's with no file).
    this->Running->SetAbortExecute(1);
    this->AbortAsked = true;
  }
}
