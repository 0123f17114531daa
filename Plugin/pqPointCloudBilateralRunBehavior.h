/**
 * @class   pqPointCloudBilateralRunBehavior
 * @brief   keeps ParaView 5.11's GUI alive while this plugin's filter, readers and writers run,
 *          and makes its Abort button stop them
 *
 * In ParaView 5.11 a filter, reader or writer runs on the GUI thread (built-in session) and the
 * GUI does not process events meanwhile: its progress manager's call to processEvents is
 * commented out, and its Abort button only emits pqProgressManager::abort(), which nothing in
 * 5.11 receives. So during a long run the window does not repaint, the Output Messages window
 * shows the run's warnings only after it, and Abort does nothing. ParaView 5.12 does both in its
 * progress manager; this auto-start object does the same for this plugin's algorithms only: the
 * Point Cloud Bilateral Filter, the LAS/LAZ, PCD and text readers (File > Open, Apply, File >
 * Reload Files) and the LAS/LAZ, PCD and text writers (File > Save Data, or SaveData in Python):
 * - while one of them executes, Abort is enabled, and its progress events (one per 0.05-0.1 s
 *   or so) let Qt process its pending events, at most every 0.1 s, timers excepted (they fire
 *   after the run). The progress manager's event filter still drops key and mouse presses
 *   everywhere but on the progress bar and its Abort button, so nothing else can be started
 *   meanwhile;
 * - pqProgressManager::abort() (the Abort button) sets the running algorithm's AbortExecute
 *   flag, which it polls from its calling thread; the run stops, a filter's or reader's output is
 *   empty, and a writer leaves no file (it writes beside the file and renames once complete).
 *   A message in the Output Messages window says how to run it again (change a property and
 *   Apply; Reload Files; save again);
 * - the progress bar names each of them by its label in the menus ("LAS Point Cloud Reader"),
 *   not by its class.
 * A writer is no pipeline source: ParaView's Save Data creates its proxy through the writer
 * factory and never registers it. So the behavior watches the session's remote objects as they
 * are registered (vtkPVSessionBase::RegisterRemoteObjectEvent), keeps this plugin's proxies, and
 * observes each one's VTK object when the session prepares progress (the start of every update,
 * write or render, before the algorithm runs): by then the object exists, and a reader's object
 * recreated by Reload Files is observed anew.
 * Only in a built-in session: with a remote server the algorithms run in another process.
 *
 * A new display of a cloud with display colours ("Colors", 3 unsigned chars: what the LAS and
 * PCD readers make of a file's RGB, kept by the filter) shows them as they are (coloured by
 * them, Map Scalars off), not plain grey; a display coloured by another array is left alone.
 *
 * It also shows point clouds without cells: ParaView 5.11 reads a PLY scan without faces (and a
 * VTP without vertex cells) as points with no cells, which its default Surface representation,
 * and Points too, draw as nothing, so a new user takes the file for empty. A new display in a
 * render view whose data has points but no cells gets the Point Gaussian representation (it
 * draws points, not cells) with the sphere shader; the user may change it as usual.
 *
 * After each run it refreshes the filter's information properties (Radius Used, Normal Radius
 * Used): the Properties panel reads them when Apply pushes the properties, before the run, so
 * they showed the previous run's values. And once a filter's or reader's output has points
 * again after a display was first shown on an empty one (a bad first Apply, an aborted read),
 * it sizes the Point Gaussian points to the data and, when the view shows nothing else, fits
 * the camera to them (both were fitted to empty bounds).
 *
 * It gives the filter's long errors and warnings a short first line: the Output Messages window
 * sums a VTK message up by its whole text in one row, cut at the window's width, and any other
 * message by its first line (see FormatForOutputMessages in the .cxx).
 *
 * And it keeps the filter's field arrays BilateralRadius and BilateralNormalRadius (one value
 * each) out of the colour-by lists, and makes the Point Cloud Text Reader the default reader of
 * .xyz files, and the LAS reader that of .las and .laz files, so that GDAL's raster reader is not
 * asked and prints nothing (ParaView's "default reader" setting, below the user's settings).
 */
#ifndef pqPointCloudBilateralRunBehavior_h
#define pqPointCloudBilateralRunBehavior_h

#include <QElapsedTimer>
#include <QList>
#include <QObject>
#include <QPointer>

#include "vtkWeakPointer.h"

#include <vector>

class pqDataRepresentation;
class pqPipelineSource;
class pqRepresentation;
class pqServer;
class vtkAlgorithm;
class vtkObject;
class vtkSMProxy;

class pqPointCloudBilateralRunBehavior : public QObject
{
  Q_OBJECT
  typedef QObject Superclass;

public:
  pqPointCloudBilateralRunBehavior(QObject* parent = nullptr);
  ~pqPointCloudBilateralRunBehavior() override;

  // The plugin's auto-start hooks.
  void startup();
  void shutdown();

private Q_SLOTS:
  void onServerAdded(pqServer* server);
  void onRemoteObjectRegistered(vtkObject* session, unsigned long event, void* globalId);
  void onProgressPrepared();
  void onSourceAdded(pqPipelineSource* source);
  void onRepresentationAdded(pqRepresentation* representation);
  void onDataUpdated(pqPipelineSource* source);
  void onRunStarted(vtkObject* algorithm);
  void onRunProgress(vtkObject* algorithm);
  void onRunEnded(vtkObject* algorithm);
  void onAbort();

private:
  struct WatchedProxy;
  void Watch(vtkSMProxy* proxy);
  void ObserveWatchedObjects();
  void Observe(WatchedProxy& watched, vtkAlgorithm* algorithm);
  const WatchedProxy* FindWatched(vtkObject* algorithm) const;

  /// This plugin's proxies (the filter's, readers' and writers'), each with the VTK object
  /// observed.
  std::vector<WatchedProxy> Watched;
  vtkWeakPointer<vtkAlgorithm> Running;
  /// Displays first shown on an empty input, to be set up as point clouds once it has points.
  QList<QPointer<pqDataRepresentation>> ShownEmpty;
  /// Whether Abort was pressed during the running algorithm's run (the readers and writers clear
  /// their flag as their run ends).
  bool AbortAsked = false;
  QElapsedTimer SinceEvents;
  bool InEvents = false;

  Q_DISABLE_COPY(pqPointCloudBilateralRunBehavior)
};

#endif
