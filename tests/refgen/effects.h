// effects.h -- internal to refgen: effect definitions (effects.cpp) used by
// the scenario builder (scenario.cpp).
#ifndef RTB_TESTS_REFGEN_EFFECTS_H
#define RTB_TESTS_REFGEN_EFFECTS_H

#include <string>

#include "refgen.h"
#include "rng.h"

namespace refgen {

// Adds one effect to the scenario, its size drawn from rng. Throws
// std::invalid_argument for an unknown name.
void apply_effect(Scenario &sc, const std::string &effect, Rng &rng);
// Throws std::invalid_argument for combinations the generator does not model.
void check_combination(const Scenario &sc);

}  // namespace refgen

#endif
