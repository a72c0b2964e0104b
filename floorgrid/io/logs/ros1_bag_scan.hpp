#pragma once

#include <set>
#include <string>

#include "floorgrid/io/logs/bag_file.hpp"
#include "floorgrid/io/logs/ros1_bag_file.hpp"

namespace floorgrid::io::ros1 {

/// Reads `file` through from its first record to its end, one chunk at a time (one chunk's
/// bytes and its decompressed bytes in memory, buffers reused): counts every connection's
/// messages and hands those on `topics` (all when null) to `visit` (none when null), in file
/// order. Connection records are taken where they stand, inside chunks or in the index.
///
/// A bag without index (index_pos 0: a recording that was not closed) that ends inside a record,
/// or in a compressed chunk that was never finished, is read up to there with a warning. Any
/// other corrupt or truncated record, or a chunk larger than `limits` allow (uncompressed, or
/// by its stated uncompressed size), throws InputError naming the file and byte offset and
/// saying what was read before it.
BagContents scan_bag(BagFile& file, const BagVisitor* visit, const std::set<std::string>* topics,
                     const BagReadLimits& limits);

}  // namespace floorgrid::io::ros1
