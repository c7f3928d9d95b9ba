// The rotor tests' blade: a soft helicopter-like blade (flap and edge, pitched so that they couple; twist fields), FEM
// Ny = Nz = 4, Nt = 2, a short run, spun up by a prescribed drive or free under a torque pulse.
#pragma once

#include <string>

namespace hubbeam::test {

/// The blade's scene text with [motion] a spin-up to 6 rad/s in 2 s or (torque) a pulse of motion.tau0 for 0.5 s,
/// and the tables of extra ([gravity], [solver], ...) added.
inline std::string soft_blade_scene(bool torque, const std::string& extra = "")
{
    const std::string motion = torque ? "[motion]\nkind = \"torque\"\ntau0 = 0.0\nduration = 0.5\n"
                                      : "[motion]\nkind = \"spin-up\"\nomega0 = 6.0\nduration = 2.0\n";
    return R"(
[beam]
length = 6.0
density = 1600.0
area = 0.005
second_moment = 4e-5
second_moment_flap = 1e-5
youngs_modulus = 1e10
shear_modulus = 4e9
torsion_constant = 2e-6
pitch = 0.1

[hub]
radius = 0.3
inertia = 40.0

)" + motion + extra +
           R"(
[discretization]
method = "fem"
ny = 4
nx = 0
nz = 4
nt = 2

[output]
t_end = 1.0
dt_out = 0.05
)";
}

}  // namespace hubbeam::test
