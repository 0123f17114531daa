// The LAS header and variable-length records as field data, shared by the LAS reader (which
// stores them) and writer (which writes them back). Internal: not wrapped, not installed.
#ifndef vtkLASPointCloudFieldData_h
#define vtkLASPointCloudFieldData_h

#include "LASHeader.h"

#include <string>

class vtkFieldData;

/// The VTK type (VTK_UNSIGNED_CHAR...) of a LAS value type.
int vtkLASArrayType(pcbilateral::LASValueType type);

/// Stores the header's identifiers, version, point format, record length, scales, offsets
/// and the (E)VLRs as "LAS ..." arrays.
void vtkLASStoreFileInfo(const pcbilateral::LASFileInfo& info, vtkFieldData* fieldData);

/**
 * Rebuilds what vtkLASStoreFileInfo stored, with the dimensions of its point format. Returns
 * false when the field data has no LAS header; `problem` says what is wrong when it has one
 * that cannot be used (then also false).
 */
bool vtkLASLoadFileInfo(vtkFieldData* fieldData,
  pcbilateral::LASFileInfo& info,
  std::string& problem);

/// What a cloud's field data holds that only a LAS (or VTP) file keeps: a LAS file's scale and
/// offset and its coordinate system, in words; empty when nothing. The writers of other formats
/// warn with it.
std::string vtkLASInformationNotHeld(vtkFieldData* fieldData);

#endif
