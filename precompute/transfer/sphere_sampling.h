// Direction sets for the transfer bake: deterministic, well distributed, and decorrelated
// between neighbouring vertices.
//
// Every vertex casts the same spherical Fibonacci lattice (Swinbank and Purser 2006; Keinert et
// al. 2015, "Spherical Fibonacci mapping"): N points of equal area, far more even than random
// points, so a sum over them integrates smooth functions with an error falling faster than
// 1/sqrt(N). Each vertex turns the lattice by its own rotation, drawn uniformly from SO(3) by a
// counter-based generator keyed on (seed, vertex): shadow edges then show as fine noise instead
// of the bands a shared lattice leaves on a surface, and the rotation stays the same from frame
// to frame, so a deforming clump does not flicker from resampling.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

namespace meadow::transfer {

// `count` unit directions over the whole sphere; point i has y = 1 - (2i + 1) / count.
std::vector<glm::dvec3> sphericalFibonacci(uint32_t count);

// `count` unit directions over the upper hemisphere (y > 0), equal area: y = 1 - (i + 0.5) / count.
std::vector<glm::dvec3> hemisphericalFibonacci(uint32_t count);

// A rotation drawn uniformly from SO(3) (Shoemake 1992, uniform random quaternions) for stream
// `stream` of `seed`: the same numbers on every machine.
glm::dmat3 randomRotation(uint64_t seed, uint64_t stream);

// A rotation about +y by a uniform random angle: turns a hemisphere set without tilting it.
glm::dmat3 randomAzimuthRotation(uint64_t seed, uint64_t stream);

// Lambertian convolution weight A_l (Ramamoorthi and Hanrahan 2001): pi, 2 pi / 3, then 0 for odd
// l > 1 and 2 pi (-1)^(l/2 - 1) / ((l + 2)(l - 1)) * l! / (2^l ((l/2)!)^2) for even l.
double lambertWeight(int l);

} // namespace meadow::transfer
