// A PCD file's layout as field data, shared by the PCD reader (which stores it) and writer
// (which writes the cloud back that way), and the PCD value types as VTK's. Internal: not
// wrapped, not installed.
#ifndef vtkPCDPointCloudFieldData_h
#define vtkPCDPointCloudFieldData_h

#include "PCDFile.h"

#include <string>

class vtkDataArray;
class vtkFieldData;

/// The VTK type (VTK_FLOAT, VTK_UNSIGNED_CHAR...) of a PCD field's values.
int vtkPCDArrayType(const pcbilateral::PCDField& field);

/// The PCD type ('I', 'U' or 'F') and size of a VTK array's values; false for a type PCD does
/// not hold (bits, strings).
bool vtkPCDFieldType(vtkDataArray* array, pcbilateral::PCDField& field);

/// Stores the fields (types, sizes, counts, padding), WIDTH, HEIGHT, VIEWPOINT and the encoding
/// as "PCD Fields", "PCD Width", "PCD Height", "PCD Viewpoint" and "PCD Data".
void vtkPCDStoreLayout(const pcbilateral::PCDHeader& header, vtkFieldData* fieldData);

/// Rebuilds what vtkPCDStoreLayout stored; false when the field data has none (or a damaged
/// one), `header` then PCDHeader's defaults.
bool vtkPCDLoadLayout(vtkFieldData* fieldData, pcbilateral::PCDHeader& header);

#endif
