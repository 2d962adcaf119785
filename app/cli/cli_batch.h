// `sylva export … --seeds A-B [--shard I/N]`: the batch's manifest (one line per file: variant,
// seed, file, counts, size, SHA-256), shards of a deterministic variant list, and resuming.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace sylva {

struct manifest_entry {
  size_t variant = 0;        // 1-based index in the whole (unsharded) batch
  uint64_t seed = 0;
  std::string file;          // the main file's name (no folder), as the batch names it
  size_t nodes = 0, leaves = 0, triangles = 0, bytes = 0;
  std::string sha256;        // of the main file
};

// "I/N" with 1 <= I <= N <= 100000.
bool parse_shard(const std::string& text, int& index, int& count);
// Variant k (0-based) belongs to shard I of N when k % N == I - 1: shards interleave, so each gets
// a like share of a sweep whose cost grows along it.
inline bool in_shard(size_t k, int index, int count) { return count <= 1 || int(k % size_t(count)) == index - 1; }

// OUT's folder / STEM-manifest.tsv, or STEM-manifest-IofN.tsv for a shard.
std::string manifest_path(const std::string& output, int index, int count);

// The lines of a manifest by file name (an absent or unreadable manifest is empty).
std::map<std::string, manifest_entry> read_manifest(const std::string& path);
// The whole manifest, sorted by variant, written atomically. "" or the error.
std::string write_manifest(const std::string& path, std::vector<manifest_entry> entries);
std::string manifest_line(const manifest_entry& e);
inline constexpr const char* manifest_header = "# sylva manifest\tvariant\tseed\tfile\tnodes\tleaves\ttriangles\tbytes\tsha256";

// SHA-256 (FIPS 180-4) of a file's bytes, as 64 hex digits; "" when it cannot be read.
std::string sha256_file(const std::string& path);
std::string sha256_hex(const std::string& bytes);

// The entry's file is there with the recorded size and hash: a rerun can skip it.
bool still_complete(const manifest_entry& e, const std::string& folder);

}  // namespace sylva
