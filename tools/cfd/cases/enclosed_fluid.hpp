// Flows inside walls in a case file (`case: flow`; data/cases/cfd/README.md): a closed body with
// `fluid: inside` (a pipe, a junction) bounds the fluid, its solid is everything outside it, and
// it may cross the domain's sides; where a pipe crosses an inlet side, the side's `pipes:` list
// gives each cross-section its parabola u = U (1 - r^2 / R^2). Reading those lists, the inflow
// they make, and the checks that name the file's key when the geometry does not fit: an inlet disc
// that is not a pipe's cross-section, a body that sticks through a wall (docs/studies/pipe_flow.md).
#pragma once

#include <string>
#include <vector>

#include "cfd/cases/case_reader.hpp"
#include "cfd/cases/flow_case.hpp"

namespace finverse::cfd::cases {

// The pipes: list of inlet side `side` (0..5: x_lo .. z_hi) at key `at`: each {centre: [x, y, z]
// on the side's plane, radius, velocity: the centreline speed into the domain}.
std::vector<PipeInlet> read_pipe_inlets(const Reader& r, const YAML::Node& list, const std::string& at,
                                        const FlowCaseSpec& s, int side);

// The inflow of side `side` through its pipes' discs (zero outside them), directed into the domain.
VelocityFunction pipe_inflow(const std::vector<PipeInlet>& pipes, int side);

// After the bodies and boundaries are read: every inlet disc lies on a cross-section of a body that
// encloses the fluid and fills it; no other body reaches into such a body's wall. `root` locates
// the keys for the messages.
void check_enclosed_fluid(const Reader& r, const YAML::Node& root, const FlowCaseSpec& s);

}  // namespace finverse::cfd::cases
