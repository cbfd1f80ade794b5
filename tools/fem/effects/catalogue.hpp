// The candidate effects, one per file in this directory (issue 34's list): each maker returns the
// effect with its null parameters (the model unchanged) for make_effect() to configure.
#pragma once

#include <memory>

#include "fem/effects/parameterised_effect.hpp"

namespace finverse::fem::effects {

std::unique_ptr<ParameterisedEffect> make_active_stiffening();   // active_stiffening.cpp
std::unique_ptr<ParameterisedEffect> make_root_curvature();      // root_curvature.cpp
std::unique_ptr<ParameterisedEffect> make_rayleigh_damping();    // rayleigh_damping.cpp
std::unique_ptr<ParameterisedEffect> make_distal_softening();    // distal_softening.cpp
std::unique_ptr<ParameterisedEffect> make_density_error();       // density_error.cpp
std::unique_ptr<ParameterisedEffect> make_cupped_rest_shape();   // cupped_rest_shape.cpp

}  // namespace finverse::fem::effects
