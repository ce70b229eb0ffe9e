// linequad: a line against a cylinder, an elliptic cylinder or an elliptic cone, with solvers
// from the textbook quadratic (seed) to the correctly rounded exact answer (correct).
//   shapes.hpp   Line, Interval, the shapes, Shape
//   result.hpp   Result, Hit, Query, Error
//   prepared.hpp prepare(): a shape checked and set up once for many lines
//   solvers.hpp  seed, stable, certified, correct; solvers by name
//   batch.hpp    many lines against one shape (AVX2)
#pragma once

#include "linequad/batch.hpp"
#include "linequad/prepared.hpp"
#include "linequad/result.hpp"
#include "linequad/scene.hpp"
#include "linequad/shapes.hpp"
#include "linequad/solvers.hpp"
#include "linequad/spawn.hpp"
#include "linequad/surfaces.hpp"
#include "linequad/vec3.hpp"
