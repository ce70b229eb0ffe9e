#include "solve/api.hpp"
#include "solve/solve.hpp"

LINEQUAD_DEFINE_SOLVER(seed32, Seed32)
