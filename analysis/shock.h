#pragma once
// The density jump across the front of the elastic blast (r = 1) from the Rankine-Hugoniot
// relations of a hard-sphere gas.
//
// A shock of speed D running into gas at rest at number density n0 (unit masses): mass
// n0 D = n1 (D - u1), momentum p1 = n0 D u1, energy e1 = (p1 / 2) (1/n0 - 1/n1) per unit mass.
// The gas ahead is at rest, so p0 = 0 and e0 = 0 exactly: the strong-shock limit needs no
// approximation here. Behind the front the gas is assumed in local equilibrium, with the
// hard-sphere equation of state p1 = n1 T1 Z(phi1) and the purely kinetic e1 = d T1 / 2. Then
//   X = n1 / n0 = 1 + d / Z(X phi0),
// an implicit equation because Z is taken at the shocked packing X phi0 (for an ideal gas Z = 1
// and X = d + 1, the textbook (gamma + 1)/(gamma - 1)). Z: Henderson (Mol. Phys. 30, 971, 1975)
// in 2D, Carnahan-Starling (J. Chem. Phys. 51, 635, 1969) in 3D. At n0 = 0.25: X = 1.815 (2D),
// 1.950 (3D). The blast's shell is that of a planar steady shock only at its front; its peak
// density in binned, averaged profiles approaches X from below as the shell outgrows the bins.

namespace gs {

// Packing fraction of unit-diameter discs (2D) or spheres (3D) at number density n.
double packing_fraction(int dim, double number_density);

// Z = p / (n T) of hard discs (Henderson) or spheres (Carnahan-Starling) at packing eta.
double hard_sphere_compressibility(int dim, double eta);

// The compression ratio X above for a gas at rest at number density n0; UserError unless
// dim is 2 or 3 and 0 < n0 with the packing below 0.5.
double strong_shock_compression(int dim, double number_density);

}  // namespace gs
