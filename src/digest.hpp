#pragma once
//! FNV-1a (64 bit) digests: the checksum of a checkpoint, and the digest of every row a
//! run writes to a time-stacked dataset of its output. A checkpoint keeps the digests of
//! the rows written up to it, so that a restart can tell a row the file still holds
//! from one a writer killed while HDF5 flushed the file has lost or garbled (README
//! "Restart").
#include <cstddef>
#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <vector>

namespace panoptic {

//! FNV-1a, 64 bit, of `bytes`, continuing from `hash` (the FNV offset basis by default).
inline std::uint64_t fnv1a64(std::span<const std::byte> bytes,
                             std::uint64_t hash = 0xcbf29ce484222325ULL) {
  for (const std::byte b : bytes) {
    hash ^= static_cast<std::uint64_t>(b);
    hash *= 0x100000001b3ULL;
  }
  return hash;
}

//! The digest of one row of doubles (its bytes as stored: IEEE 754, little endian).
inline std::uint64_t row_digest(std::span<const double> row) {
  return fnv1a64(std::as_bytes(row));
}

//! Digests of the rows of an output's stacked datasets, by "group/name" (e.g.
//! "snapshots/St", "timeseries/time"), one per row in row order.
using RowDigests = std::map<std::string, std::vector<std::uint64_t>>;

}  // namespace panoptic
