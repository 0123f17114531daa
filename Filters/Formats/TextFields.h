// Fields of a line of text separated by blanks, scanned in place (no stream, no copy), for the
// text format's parser and the check of ASCII PLY files. Plain C++17; private to the formats
// library.
#ifndef pcbilateral_TextFields_h
#define pcbilateral_TextFields_h

#include <cstddef>
#include <cstring>

namespace pcbilateral
{

/// The blanks between fields: those of std::isspace but the line break, in the C locale.
inline bool IsSpace(char c)
{
  return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

inline const char* SkipSpaces(const char* c, const char* end)
{
  while (c < end && IsSpace(*c))
  {
    ++c;
  }
  return c;
}

inline const char* SkipField(const char* c, const char* end)
{
  while (c < end && !IsSpace(*c))
  {
    ++c;
  }
  return c;
}

inline const char* LineEnd(const char* line, const char* end)
{
  const char* found = static_cast<const char*>(std::memchr(line, '\n', end - line));
  return found ? found : end;
}

/// The number of blank-separated fields of [line, lineEnd).
inline std::size_t CountFields(const char* line, const char* lineEnd)
{
  std::size_t count = 0;
  for (const char* c = SkipSpaces(line, lineEnd); c < lineEnd; c = SkipSpaces(c, lineEnd))
  {
    c = SkipField(c, lineEnd);
    ++count;
  }
  return count;
}

} // namespace pcbilateral

#endif
