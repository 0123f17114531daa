// The points of PDAL's 1.2-with-color sample, as text that compares across its LAS twin
// (format 3) and its COPC file (format 7), for the LAZ and COPC tests.
#ifndef pcbilateral_LASPointKey_h
#define pcbilateral_LASPointKey_h

#include "LASHeader.h"

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>

/// The twin's points (format 3) or the COPC file's (format 7), as comparable text: real
/// coordinates, intensity, GPS time and colour.
inline std::string PointKey(const pcbilateral::LASHeader& h, const std::uint8_t* record)
{
  const bool format7 = h.PointFormat == 7;
  std::int32_t xyz[3];
  std::uint16_t intensity;
  double time;
  std::uint16_t rgb[3];
  std::memcpy(xyz, record, 12);
  std::memcpy(&intensity, record + 12, 2);
  std::memcpy(&time, record + (format7 ? 22 : 20), 8);
  std::memcpy(rgb, record + (format7 ? 30 : 28), 6);
  char text[200];
  std::snprintf(text,
    sizeof(text),
    "%.2f %.2f %.2f %u %.9f %u %u %u",
    xyz[0] * h.Scale[0] + h.Offset[0],
    xyz[1] * h.Scale[1] + h.Offset[1],
    xyz[2] * h.Scale[2] + h.Offset[2],
    intensity,
    time,
    rgb[0],
    rgb[1],
    rgb[2]);
  return text;
}

#endif
