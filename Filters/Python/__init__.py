"""The bilateral filter for point clouds (Digne & de Franchis, IPOL 2017) for VTK.

    from pointcloudbilateral import vtkPointCloudBilateralFilter

Classes: vtkPointCloudBilateralFilter, vtkPointCloudTextReader, vtkPointCloudTextWriter,
vtkLASPointCloudReader, vtkLASPointCloudWriter (LAS files), vtkPCDPointCloudReader,
vtkPCDPointCloudWriter (PCL's PCD files), vtkPointCloudFileIO, which picks a
reader or writer by extension and checks files before reading them, and
vtkPPointCloudBilateralFilter and vtkPLASPointCloudWriter (distributed runs under MPI: the
filter, and one LAS/LAZ file written by every process) when the package was built with MPI::

    io = vtkPointCloudFileIO()
    cloud = vtkPolyData()
    if not io.Read("in.las", cloud):
        raise SystemExit(io.GetErrorMessage())
They work in pipelines with ParaView's ``vtkmodules``.
"""
# The wrapped classes derive from VTK classes: their Python modules must be loaded first.
import vtkmodules.vtkCommonCore  # noqa: F401
import vtkmodules.vtkCommonDataModel  # noqa: F401
import vtkmodules.vtkCommonExecutionModel  # noqa: F401
import vtkmodules.vtkIOCore  # noqa: F401
import vtkmodules.vtkIOPLY  # noqa: F401
import vtkmodules.vtkIOXML  # noqa: F401

from .vtkFiltersPointCloudBilateral import vtkPointCloudBilateralFilter  # noqa: F401
from .vtkIOPointCloudBilateral import (  # noqa: F401
    vtkLASPointCloudReader,
    vtkLASPointCloudWriter,
    vtkPCDPointCloudReader,
    vtkPCDPointCloudWriter,
    vtkPointCloudFileIO,
    vtkPointCloudTextReader,
    vtkPointCloudTextWriter,
)

try:
    # Distributed runs, built when VTK has MPI.
    import vtkmodules.vtkParallelCore  # noqa: F401
    from .vtkFiltersParallelPointCloudBilateral import vtkPPointCloudBilateralFilter  # noqa: F401
    from .vtkIOParallelPointCloudBilateral import (  # noqa: F401
        vtkPLASPointCloudReader,
        vtkPLASPointCloudWriter,
        vtkPPCDPointCloudReader,
        vtkPPointCloudTextReader,
    )
except ImportError:
    pass

__all__ = [
    "vtkLASPointCloudReader",
    "vtkLASPointCloudWriter",
    "vtkPCDPointCloudReader",
    "vtkPCDPointCloudWriter",
    "vtkPointCloudBilateralFilter",
    "vtkPointCloudFileIO",
    "vtkPointCloudTextReader",
    "vtkPointCloudTextWriter",
] + [name for name in ("vtkPPointCloudBilateralFilter", "vtkPLASPointCloudWriter",
                                 "vtkPLASPointCloudReader", "vtkPPCDPointCloudReader",
                                 "vtkPPointCloudTextReader")
     if name in globals()]
