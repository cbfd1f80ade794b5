// Image files read with the decoder libraries kept quiet (see image_file.hpp).
#include "vision/image_file.hpp"

#include <array>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "core/error.hpp"

namespace finverse::vision {

namespace {

std::uint32_t crc32(const unsigned char* data, std::size_t n) {
  static const std::array<std::uint32_t, 256> table = [] {
    std::array<std::uint32_t, 256> t{};
    for (std::uint32_t i = 0; i < 256; ++i) {
      std::uint32_t c = i;
      for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
      t[i] = c;
    }
    return t;
  }();
  std::uint32_t c = 0xFFFFFFFFu;
  for (std::size_t i = 0; i < n; ++i) c = table[(c ^ data[i]) & 0xFFu] ^ (c >> 8);
  return c ^ 0xFFFFFFFFu;
}

std::uint32_t big_endian(const unsigned char* p) {
  return (std::uint32_t{p[0]} << 24) | (std::uint32_t{p[1]} << 16) | (std::uint32_t{p[2]} << 8) | std::uint32_t{p[3]};
}

std::string png_problem(const unsigned char* b, std::size_t n) {
  std::size_t at = 8;  // after the signature
  while (true) {
    if (at + 12 > n) return "PNG ends inside a chunk header at byte " + std::to_string(at) + " (truncated)";
    const std::uint32_t length = big_endian(b + at);
    const std::string type(reinterpret_cast<const char*>(b + at + 4), 4);
    if (length > n || at + 12 + length > n)
      return "PNG chunk '" + type + "' at byte " + std::to_string(at) + " runs past the end of the file (truncated)";
    if (crc32(b + at + 4, 4 + length) != big_endian(b + at + 8 + length))
      return "PNG chunk '" + type + "' at byte " + std::to_string(at) + " fails its CRC (corrupted)";
    if (type == "IEND") return {};
    at += 12 + length;
  }
}

}  // namespace

std::string image_structure_problem(const std::string& bytes) {
  const auto* b = reinterpret_cast<const unsigned char*>(bytes.data());
  const std::size_t n = bytes.size();
  static const unsigned char png[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  if (n >= 8 && std::equal(png, png + 8, b)) return png_problem(b, n);
  if (n >= 2 && b[0] == 0xFF && b[1] == 0xD8) {
    if (n < 4 || b[n - 2] != 0xFF || b[n - 1] != 0xD9) return "JPEG without its end-of-image marker (truncated)";
  }
  return {};
}

cv::Mat read_image(const std::filesystem::path& path, int flags) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path.string() + ": cannot read the image file");
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (bytes.empty()) throw Error(path.string() + ": empty image file");
  if (const std::string why = image_structure_problem(bytes); !why.empty()) throw Error(path.string() + ": " + why);
  const std::vector<unsigned char> buffer(bytes.begin(), bytes.end());
  cv::Mat img = cv::imdecode(buffer, flags);
  if (img.empty()) throw Error(path.string() + ": unreadable image");
  return img;
}

}  // namespace finverse::vision
