#include "solve/api.hpp"
#include "solve/solve.hpp"

LINEQUAD_DEFINE_SOLVER(stable32, Stable32)
