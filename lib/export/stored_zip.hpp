// A zip archive whose entries are stored uncompressed (method 0), as numpy.savez writes .npz
// files: local headers with CRC-32 and sizes, a central directory, its end record. No zip64:
// entries and the whole archive must stay below 4 GiB, and fewer than 65535 entries.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace relume {

// The archive bytes of `entries` (name, contents), in order. Every entry gets the DOS time
// 1980-01-01 00:00, so equal inputs give equal archives. Throws Error naming the entry when a
// size does not fit the format, or for an empty or duplicate name.
std::string stored_zip(const std::vector<std::pair<std::string, std::string>>& entries);

}  // namespace relume
