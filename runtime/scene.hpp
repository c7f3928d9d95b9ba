// Scene: everything one simulation needs, read and validated from a TOML file (format in README.md).
#pragma once

#include <stdexcept>
#include <string>

#include "make_model.hpp"
#include "motion.hpp"
#include "variant.hpp"

namespace hubbeam {

struct SolverOptions {
    std::string stepper = "msadams";  // a GSL odeiv2 step type name (see integrate.hpp)
    double rtol = 1e-8;
    double atol = 1e-10;
    double h0 = 1e-4;  // first trial step (s)
};

struct OutputOptions {
    double t_end = 30.0;   // s
    double dt_out = 0.01;  // s; rows fall on exact multiples of dt_out
    std::string file;      // CSV path; empty: derived from the scene name by the command line
};

struct Scene {
    std::string path;  // the file it came from, for messages
    Parameters parameters;
    Motion motion;
    VariantKey variant;  // drive follows motion
    ModelSource source = ModelSource::automatic;
    SolverOptions solver;
    OutputOptions output;
};

/// Bad scene input: what() is one line "FILE: KEY: expected ..., got ...".
struct SceneError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

/// Reads and validates a scene file; throws SceneError before any computation.
Scene load_scene(const std::string& path);
/// Re-checks a scene after command-line overrides (DOF counts, tolerances, times); throws SceneError with
/// the option or key named.
void validate(const Scene& scene);

}  // namespace hubbeam
