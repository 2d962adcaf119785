// Batch manifests and shards (app/cli/cli_batch.h).
#include "app/cli/cli_batch.h"

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <sstream>

#include "render/files.h"

namespace sylva {

namespace fs = std::filesystem;

bool parse_shard(const std::string& text, int& index, int& count) {
  const size_t slash = text.find('/');
  if (slash == std::string::npos || slash == 0 || slash + 1 >= text.size()) return false;
  for (size_t k = 0; k < text.size(); ++k)
    if (k != slash && (text[k] < '0' || text[k] > '9')) return false;
  if (slash > 6 || text.size() - slash - 1 > 6) return false;
  index = std::stoi(text.substr(0, slash));
  count = std::stoi(text.substr(slash + 1));
  return index >= 1 && count >= 1 && index <= count && count <= 100000;
}

std::string manifest_path(const std::string& output, int index, int count) {
  const fs::path out(output);
  std::string name = out.stem().string() + "-manifest";
  if (count > 1) name += "-" + std::to_string(index) + "of" + std::to_string(count);
  return (out.parent_path() / (name + ".tsv")).string();
}

std::string manifest_line(const manifest_entry& e) {
  return std::to_string(e.variant) + "\t" + std::to_string(e.seed) + "\t" + e.file + "\t" + std::to_string(e.nodes) + "\t" +
         std::to_string(e.leaves) + "\t" + std::to_string(e.triangles) + "\t" + std::to_string(e.bytes) + "\t" + e.sha256;
}

std::map<std::string, manifest_entry> read_manifest(const std::string& path) {
  std::map<std::string, manifest_entry> out;
  std::string text;
  std::error_code ec;
  if (!fs::exists(path, ec) || !read_file(path, text, uint64_t(64) << 20).empty()) return out;
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream f(line);
    manifest_entry e;
    std::string variant, seed, nodes, leaves, tris, bytes;
    if (!std::getline(f, variant, '\t') || !std::getline(f, seed, '\t') || !std::getline(f, e.file, '\t') ||
        !std::getline(f, nodes, '\t') || !std::getline(f, leaves, '\t') || !std::getline(f, tris, '\t') ||
        !std::getline(f, bytes, '\t') || !std::getline(f, e.sha256))
      continue;   // a torn line (the job was killed mid-write) is redone
    try {
      e.variant = std::stoull(variant), e.seed = std::stoull(seed), e.nodes = std::stoull(nodes);
      e.leaves = std::stoull(leaves), e.triangles = std::stoull(tris), e.bytes = std::stoull(bytes);
    } catch (const std::exception&) {
      continue;
    }
    if (e.sha256.size() == 64) out[e.file] = e;
  }
  return out;
}

std::string write_manifest(const std::string& path, std::vector<manifest_entry> entries) {
  std::sort(entries.begin(), entries.end(), [](const manifest_entry& a, const manifest_entry& b) { return a.variant < b.variant; });
  std::string text = std::string(manifest_header) + "\n";
  for (const manifest_entry& e : entries) text += manifest_line(e) + "\n";
  return write_file_atomic(path, text);
}

bool still_complete(const manifest_entry& e, const std::string& folder) {
  const std::string path = (fs::path(folder) / e.file).string();
  std::error_code ec;
  if (!fs::is_regular_file(path, ec) || fs::file_size(path, ec) != e.bytes || ec) return false;
  return sha256_file(path) == e.sha256;
}

// ---- SHA-256, FIPS 180-4 §6.2 (message schedule, 64 rounds, the §5.3.3 initial hash value).
namespace {

constexpr std::array<uint32_t, 64> k256 = {
    0x428a2f98, 0x71374491, 0xb5c0fbcf, 0xe9b5dba5, 0x3956c25b, 0x59f111f1, 0x923f82a4, 0xab1c5ed5, 0xd807aa98, 0x12835b01,
    0x243185be, 0x550c7dc3, 0x72be5d74, 0x80deb1fe, 0x9bdc06a7, 0xc19bf174, 0xe49b69c1, 0xefbe4786, 0x0fc19dc6, 0x240ca1cc,
    0x2de92c6f, 0x4a7484aa, 0x5cb0a9dc, 0x76f988da, 0x983e5152, 0xa831c66d, 0xb00327c8, 0xbf597fc7, 0xc6e00bf3, 0xd5a79147,
    0x06ca6351, 0x14292967, 0x27b70a85, 0x2e1b2138, 0x4d2c6dfc, 0x53380d13, 0x650a7354, 0x766a0abb, 0x81c2c92e, 0x92722c85,
    0xa2bfe8a1, 0xa81a664b, 0xc24b8b70, 0xc76c51a3, 0xd192e819, 0xd6990624, 0xf40e3585, 0x106aa070, 0x19a4c116, 0x1e376c08,
    0x2748774c, 0x34b0bcb5, 0x391c0cb3, 0x4ed8aa4a, 0x5b9cca4f, 0x682e6ff3, 0x748f82ee, 0x78a5636f, 0x84c87814, 0x8cc70208,
    0x90befffa, 0xa4506ceb, 0xbef9a3f7, 0xc67178f2};

uint32_t rotr(uint32_t x, int n) { return (x >> n) | (x << (32 - n)); }

void compress(std::array<uint32_t, 8>& h, const unsigned char* block) {
  uint32_t w[64];
  for (int t = 0; t < 16; ++t)
    w[t] = uint32_t(block[4 * t]) << 24 | uint32_t(block[4 * t + 1]) << 16 | uint32_t(block[4 * t + 2]) << 8 | block[4 * t + 3];
  for (int t = 16; t < 64; ++t) {
    const uint32_t s0 = rotr(w[t - 15], 7) ^ rotr(w[t - 15], 18) ^ (w[t - 15] >> 3);
    const uint32_t s1 = rotr(w[t - 2], 17) ^ rotr(w[t - 2], 19) ^ (w[t - 2] >> 10);
    w[t] = w[t - 16] + s0 + w[t - 7] + s1;
  }
  uint32_t a = h[0], b = h[1], c = h[2], d = h[3], e = h[4], f = h[5], g = h[6], hh = h[7];
  for (int t = 0; t < 64; ++t) {
    const uint32_t t1 = hh + (rotr(e, 6) ^ rotr(e, 11) ^ rotr(e, 25)) + ((e & f) ^ (~e & g)) + k256[size_t(t)] + w[t];
    const uint32_t t2 = (rotr(a, 2) ^ rotr(a, 13) ^ rotr(a, 22)) + ((a & b) ^ (a & c) ^ (b & c));
    hh = g, g = f, f = e, e = d + t1, d = c, c = b, b = a, a = t1 + t2;
  }
  h[0] += a, h[1] += b, h[2] += c, h[3] += d, h[4] += e, h[5] += f, h[6] += g, h[7] += hh;
}

}  // namespace

std::string sha256_hex(const std::string& bytes) {
  std::array<uint32_t, 8> h = {0x6a09e667, 0xbb67ae85, 0x3c6ef372, 0xa54ff53a, 0x510e527f, 0x9b05688c, 0x1f83d9ab, 0x5be0cd19};
  const size_t full = bytes.size() / 64 * 64;
  for (size_t at = 0; at < full; at += 64) compress(h, reinterpret_cast<const unsigned char*>(bytes.data()) + at);
  // Padding: 0x80, zeros, the length in bits as 64-bit big-endian (§5.1.1).
  std::string tail = bytes.substr(full);
  tail.push_back(char(0x80));
  while (tail.size() % 64 != 56) tail.push_back('\0');
  const uint64_t bits = uint64_t(bytes.size()) * 8;
  for (int k = 7; k >= 0; --k) tail.push_back(char((bits >> (8 * k)) & 0xff));
  for (size_t at = 0; at < tail.size(); at += 64) compress(h, reinterpret_cast<const unsigned char*>(tail.data()) + at);
  char hex[65];
  for (int k = 0; k < 8; ++k) std::snprintf(hex + 8 * k, 9, "%08x", h[size_t(k)]);
  return std::string(hex, 64);
}

std::string sha256_file(const std::string& path) {
  std::string bytes;
  if (!read_file(path, bytes, uint64_t(16) << 30).empty()) return "";
  return sha256_hex(bytes);
}

}  // namespace sylva
