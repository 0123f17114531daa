#include "LASRecord.h"

#include "LASBinary.h"
#include "LASRecordBytes.h"

#include <algorithm>

namespace pcbilateral
{
namespace las
{

std::uint64_t RecordDataLength(const std::uint8_t* at, bool extended)
{
  return extended ? Load<std::uint64_t>(at + 20) : Load<std::uint16_t>(at + 20);
}

LASRecord DecodeRecord(const std::uint8_t* at, bool extended, std::uint64_t length)
{
  const std::size_t headerSize = RecordHeaderSize(extended);
  LASRecord record;
  record.Extended = extended;
  record.Reserved = Load<std::uint16_t>(at);
  record.UserId = FixedString(at + 2, 16);
  record.RecordId = Load<std::uint16_t>(at + 18);
  record.Description = FixedString(at + (extended ? 28 : 22), 32);
  record.Data.assign(at + headerSize, at + headerSize + length);
  return record;
}

void AppendRecord(std::vector<std::uint8_t>& out, const LASRecord& record, bool extended)
{
  const std::size_t headerSize = RecordHeaderSize(extended);
  const std::size_t at = out.size();
  out.resize(at + headerSize + record.Data.size(), 0);
  std::uint8_t* d = out.data() + at;
  Store<std::uint16_t>(d, record.Reserved);
  StoreString(d + 2, record.UserId, 16);
  Store<std::uint16_t>(d + 18, record.RecordId);
  if (extended)
  {
    Store<std::uint64_t>(d + 20, record.Data.size());
    StoreString(d + 28, record.Description, 32);
  }
  else
  {
    Store<std::uint16_t>(d + 20, static_cast<std::uint16_t>(record.Data.size()));
    StoreString(d + 22, record.Description, 32);
  }
  std::copy(record.Data.begin(), record.Data.end(), d + headerSize);
}

} // namespace las

std::vector<std::uint8_t> EncodeLASRecords(const std::vector<LASRecord>& records, bool extended)
{
  std::vector<std::uint8_t> bytes;
  for (const LASRecord& record : records)
  {
    las::AppendRecord(bytes, record, extended);
  }
  return bytes;
}

bool DecodeLASRecords(const std::uint8_t* bytes,
  std::size_t size,
  bool extended,
  std::vector<LASRecord>& records)
{
  records.clear();
  const std::size_t headerSize = las::RecordHeaderSize(extended);
  for (std::size_t at = 0; at < size;)
  {
    if (size - at < headerSize)
    {
      return false;
    }
    const std::uint64_t length = las::RecordDataLength(bytes + at, extended);
    if (length > size - at - headerSize)
    {
      return false;
    }
    records.push_back(las::DecodeRecord(bytes + at, extended, length));
    at += headerSize + length;
  }
  return true;
}

} // namespace pcbilateral
