// Stage "emit": C++ source for a variant's kernels. Every output is a polynomial in the run-time variables
// (q, qd, u) whose coefficients depend on the parameters only: those coefficients are computed once per
// parameter set by a coefficients kernel (deduplicated), monomials of the variables are formed once per
// call as const temporaries, and each output is written exactly once. The printer is strict: any node
// that is not a sum of numeric * symbol^integer products is an error, never printed approximately.
#pragma once

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <ginac/ginac.h>

namespace hubbeam::gen {

struct EmitError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

/// A run-time input of the kernels: a symbol and the C expression that reads it (e.g. "q[3]").
struct Input {
    GiNaC::symbol symbol;
    std::string read;
};

/// One kernel: out[i] = values[i], documented by a shape comment.
struct KernelSpec {
    std::string name;  // suffix, e.g. "mass"
    std::string out;   // e.g. "M[81]"
    std::string doc;   // e.g. "row-major, M = d2T/dqd2"
    std::vector<GiNaC::ex> values;
};

struct EmittedCode {
    std::string text;  // function definitions
    int ncoeff = 0;
    bool constant(const std::string& kernel) const;  // the kernel's outputs depend on no variable
    std::vector<std::string> constant_kernels;
};

/// Emits `<prefix>_coefficients(p, c)` and `<prefix>_<kernel>(c, u, q, qd, out)` for each kernel.
/// parameters: read from p (their `read` may combine entries, e.g. "p[1] * p[2]" for m = rho S);
/// variables: read from u, q, qd.
EmittedCode emit_kernels(const std::string& prefix, int nq, const std::vector<Input>& parameters,
                         const std::vector<Input>& variables, const std::vector<KernelSpec>& kernels);

/// The C literal for a number: round-trip precision, always a double literal ("2.0", "0.1", "-1e-05").
std::string c_number(const GiNaC::numeric& x);

}  // namespace hubbeam::gen
