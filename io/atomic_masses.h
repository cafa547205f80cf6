#pragma once
// The elements' symbols and atomic masses, for files that give a species and momenta but no
// masses (ASE writes momenta and takes each atom's mass from its element). The numbers are the
// table ASE 3.22 uses, ase.data.atomic_masses (atomic_masses_iupac2016: IUPAC 2016 standard
// atomic weights, with the mass of the longest-lived isotope for elements without a stable one),
// so that our speeds are ASE's get_velocities().
#include <optional>
#include <string_view>

namespace gs {

// Z of a chemical symbol, matched as ASE matches it (first letter upper, the rest lower: "AR"
// and "ar" are argon); 0 for ASE's dummy element X; nullopt for names that are no element.
std::optional<int> atomic_number(std::string_view symbol);
// The mass of element Z (1..118) in atomic mass units; nullopt outside that range (X included).
std::optional<double> atomic_mass(long long z);
// The symbol of element Z (1..118), "X" otherwise.
std::string_view element_symbol(long long z);

}  // namespace gs
