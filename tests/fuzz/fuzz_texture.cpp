// libFuzzer: a user's texture (PNG, JPEG, PGM, ... whatever stb reads) through the project's checked
// loader; a decoded image has its stated size, and encodes back to a PNG that decodes the same.
#include <cstdint>
#include <string>

#include "render/assets/textures.h"
#include "tests/fuzz/fuzz_common.h"

using namespace sylva;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  image img;
  const std::string e = decode_user_texture(bytes, img);
  if (!e.empty()) {
    fuzz_check(img.pixels.empty(), "a refused texture leaves the image alone");
    return 0;
  }
  fuzz_check(img.width >= 1 && img.height >= 1, "a decoded texture is not empty");
  fuzz_check(img.width <= max_texture_pixels && img.height <= max_texture_pixels, "a decoded texture is within the limit");
  fuzz_check(img.channels == 4 && img.pixels.size() == size_t(img.width) * size_t(img.height) * 4,
             "a decoded texture holds width x height RGBA pixels");
  if (size_t(img.width) * size_t(img.height) > (1u << 16)) return 0;   // re-encoding big ones costs more than it finds
  std::string png;
  fuzz_check(encode_png(img, png).empty(), "a decoded texture encodes as PNG");
  image back;
  fuzz_check(decode_user_texture(png, back).empty(), "its PNG loads back");
  fuzz_check(back.width == img.width && back.height == img.height && back.pixels == img.pixels, "PNG round trip is exact");
  return 0;
}
