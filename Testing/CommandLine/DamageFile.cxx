// Makes damaged copies of files for the command-line tests (CMake cannot write binary bytes):
//   DamageFile truncate IN OUT KEEP        the first KEEP bytes of IN (negative: all but -KEEP)
//   DamageFile patch IN OUT OFFSET HEX...  IN with bytes from OFFSET replaced (hex pairs)
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

int main(int argc, char* argv[])
{
  if (argc < 5)
  {
    std::fprintf(stderr, "usage: DamageFile truncate IN OUT KEEP | patch IN OUT OFFSET HEX...\n");
    return 2;
  }
  std::ifstream in(argv[2], std::ios::binary);
  std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string mode = argv[1];
  const long long number = std::atoll(argv[4]);
  if (mode == "truncate")
  {
    const long long keep = number < 0 ? static_cast<long long>(bytes.size()) + number : number;
    if (keep < 0 || keep > static_cast<long long>(bytes.size()))
    {
      return 2;
    }
    bytes.resize(static_cast<std::size_t>(keep));
  }
  else if (mode == "patch")
  {
    for (int k = 5; k < argc; ++k)
    {
      const std::size_t at = static_cast<std::size_t>(number) + (k - 5);
      if (at >= bytes.size())
      {
        return 2;
      }
      bytes[at] = static_cast<char>(std::strtol(argv[k], nullptr, 16));
    }
  }
  else
  {
    return 2;
  }
  std::ofstream out(argv[3], std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  return out ? 0 : 1;
}
