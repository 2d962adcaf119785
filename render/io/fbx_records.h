// Binary FBX 7.x node records, read and written whole: the FBX exporter post-processes assimp's
// file with them (closing every record as Blender's importer demands, and the LOD group assimp
// cannot write), and the tests read files back with them.
// A record: u64 end offset, u64 property count, u64 property bytes, u8 name length, the name, the
// properties (a type code and its value each), its children, and a 25-byte null record after them.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace sylva::fbx {

struct property {
  char type = 0;     // 'S' string, 'R' raw, 'Y' i16, 'C' bool, 'I' i32, 'F' f32, 'D' f64, 'L' i64, f/d/l/i/b arrays
  std::string raw;   // the bytes after the type code, as the file has them
};

struct record {
  std::string name;
  std::vector<property> props;
  std::vector<record> children;
  bool closed = false;   // the file had the null record after the children (written whenever there are children)
};

struct document {
  std::string header;          // the 27 bytes before the first record
  std::vector<record> top;
  std::string footer;          // the top level's null record and what follows it
};

// Parses `bytes` (binary FBX 7.5 or later: 64-bit offsets). "" on success, else why not.
std::string parse(const std::string& bytes, document& out);
// The file's bytes again, every record with children closed by its null record.
std::string write(const document& d);

property str(std::string_view s);
property i64(int64_t v);
property i32(int32_t v);
property f64(double v);
// The property as a string ("" unless 'S' or 'R'), an integer ('Y', 'C', 'I', 'L'; else 0) or a
// number (also 'F' and 'D').
std::string as_string(const property& p);
int64_t as_int(const property& p);
double as_double(const property& p);

// The first child named `name`, or null.
const record* child(const record& r, std::string_view name);
record* child(record& r, std::string_view name);
const record* find(const std::vector<record>& rs, std::string_view name);
record* find(std::vector<record>& rs, std::string_view name);
// An object's name without its class: "tree\0\1Model" -> "tree".
std::string object_name(const record& r);

// Turns the Null model `group` (an object of Objects) into an FBX LOD group: its type becomes
// "LodGroup" and a LodGroup NodeAttribute is connected to it, with `thresholds` (one per level
// but the last, in percent of screen size: ThresholdsUsedAsPercentage) and every level shown by
// its LOD ("DisplayLevels" UseLOD). The levels are the model's children in connection order.
// "" on success, else why not (no such model, no Objects or Connections, or the model does not
// hold exactly thresholds.size() + 1 children).
std::string make_lod_group(document& d, const std::string& group, const std::vector<double>& thresholds);

}  // namespace sylva::fbx
