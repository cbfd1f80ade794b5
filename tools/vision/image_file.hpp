// Image files read with the decoder libraries kept quiet (issue 46): libpng and libjpeg print
// their own warnings ("libpng warning: ... chunk data is too large") before our error line. The
// file's structure is checked first, so that a broken file never reaches them:
//   PNG   the signature, then every chunk's length, type and CRC-32 up to IEND;
//   JPEG  the start-of-image marker first and the end-of-image marker last (a truncated file).
// Other formats go to OpenCV as they are.
#pragma once

#include <filesystem>
#include <string>

#include <opencv2/core.hpp>

namespace finverse::vision {

// Why the bytes are not a complete PNG or JPEG; empty when they are (or are neither).
std::string image_structure_problem(const std::string& bytes);

// cv::imdecode of the file's bytes with `flags` (cv::IMREAD_*); throws finverse::Error naming the
// file for an unreadable, broken or undecodable file.
cv::Mat read_image(const std::filesystem::path& path, int flags);

}  // namespace finverse::vision
