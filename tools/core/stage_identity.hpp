// Identity of a stage file's content, so that a reader seeing two stage files can tell whether one
// was made from the other (issue 33 "Bad input": a mesh from another template, loads from another
// motion, materials for another mesh). The producer records, for every HDF5 input, its schema and
// a SHA-256 of its datasets (names, shapes, values; no attributes, so a rebuilt tool writing the
// same numbers keeps the identity) in the root `inputs` attribute (core/provenance.cpp); the
// reader recomputes it on the file it was given and refuses a mismatch with one line naming both
// files and what differs (exit 2 through finverse::Error).
#pragma once

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

namespace finverse {

// SHA-256 (hex) over every dataset of an HDF5 file, in sorted path order.
std::string content_digest(const std::filesystem::path& h5_file);

// {"schema", "content_sha256", "shapes": {"points": "[..]", "time": "[..]"}} of an HDF5 stage file.
nlohmann::json stage_identity(const std::filesystem::path& h5_file);

// Throws finverse::Error when `product` records an input of `input`'s schema whose content differs
// from `input` ("<product> was made from another <schema> (<recorded path>: points [..]) than
// <input> (points [..])"). Accepted: `input` itself records the product's input among its own
// inputs (derived from it, one level). No check when `product` records no input of that schema.
void check_made_from(const std::filesystem::path& product, const std::filesystem::path& input);

}  // namespace finverse
