// Version of the build: the project version and `git describe` of the tree it was built from.
// The definitions are generated at build time (cmake/write_version.cmake).
#pragma once

namespace finverse {
const char* version_string();
const char* git_describe();
}  // namespace finverse
