#include "correct/correct.hpp"
#include "solve/api.hpp"

LINEQUAD_DEFINE_SOLVER(correct32, Correct32)
