// Stage "emit": C++ source for a variant's kernels. Every output is a polynomial in the run-time variables
// (q, qd, u) whose coefficients depend on the parameters only: those coefficients are computed once per
// parameter set by a coefficients kernel (deduplicated), monomials of the variables are formed once per
// call as const temporaries, and each output is written exactly once. The printer is strict: any node
// that is not a sum of numeric * symbol^integer products is an error, never printed approximately.
#pragma once

#include <ginac/ginac.h>

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "poly.hpp"

namespace hubbeam::gen {

struct EmitError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

/// A run-time input of the kernels: a symbol and the C expression that reads it (e.g. "q[3]").
struct Input {
    GiNaC::symbol symbol;
    std::string read;
};

/// One kernel: out[slots[i]] = values[i] (out[i] when slots is empty), documented by a shape comment.
struct KernelSpec {
    std::string name;  // suffix, e.g. "mass"
    std::string out;   // e.g. "M[81]"
    std::string doc;   // e.g. "row-major, M = d2T/dqd2"
    std::vector<GiNaC::ex> values;
    std::vector<int> slots = {};  // for a kernel that writes only some entries of out
    /// Outputs already in polynomial form (over Signature's parameter and state inputs); they come before values.
    std::vector<Poly> polys = {};
    /// > 0: a matrix-times-monomials kernel. values are K monomials m_k of the state, and the kernel writes
    /// out[i] = sum_k P(i, k) m_k for i < rows, reading its c argument as that matrix (a runtime product such as
    /// M^-1 F) instead of the coefficient pool, in groups of W = generated::folded_lanes rows: with j = i +
    /// row_offset, P(i, k) at c[(j/W)*W*K + W*k + j%W] (row_offset W - 1 keeps row 0 out of the groups).
    int rows = 0;
    int row_offset = 0;
    /// With rows > 0: which entries P(i, k) can be nonzero (row-major, rows x K); a group of rows reads the columns
    /// any of its rows allows, the others are neither read nor multiplied. Empty: every entry.
    std::vector<bool> pattern = {};
    /// Code added at the end of the kernel, after every output is written (e.g. loops that add to them), and the
    /// parameter expressions that its placeholders stand for: each "$name" becomes the expression's pool entry.
    std::string tail = {};
    std::vector<std::pair<std::string, GiNaC::ex>> tail_coefficients = {};
    /// Called at every right-hand side (the forces, the mass matrix), where a run spends its time, rather than once
    /// per Jacobian or per row: printed as tables only above EmitOptions::rhs_table_threshold, and unrolled, compiled
    /// for AVX2 as well (HUBBEAM_WIDE_KERNEL) unless it has a tail.
    bool every_right_hand_side = false;
};

struct EmittedCode {
    std::string text;  // function definitions
    int ncoeff = 0;
    bool affine = true;  // every kernel is affine in c: a coefficients_p kernel (dc/dp) was emitted
    bool constant(const std::string& kernel) const;  // the kernel's outputs depend on no variable
    std::vector<std::string> constant_kernels;
};

/// An argument array of the kernels, as the shape comments state it: name, length and, optionally, what its
/// entries are (e.g. {"p", 7, "p = (L, rho, S, I, E, a, J_oh)"}).
struct Array {
    std::string name;
    int size = 0;
    std::string doc;
};

/// The caller's names for everything the kernels read: the emitter knows no physics.
struct Signature {
    Array parameters;                     // read once, by the coefficients kernel
    std::vector<Array> state;             // read by every other kernel, in argument order after c (e.g. u, q, qd)
    std::vector<Input> parameter_inputs;  // symbols read from the parameter array ("p[1] * p[2]" may combine)
    std::vector<Input> state_inputs;      // symbols read from the state arrays
    // The parameter entries p[k], k < this, whose derivatives coefficients_p prints (the named parameters: a
    // profile's station values have none); -1: all.
    int derivative_entries = -1;

    std::vector<GiNaC::symbol> state_inputs_symbols() const
    {
        std::vector<GiNaC::symbol> s;
        for (const Input& i : state_inputs) s.push_back(i.symbol);
        return s;
    }
};

/// How a kernel's sum of terms is printed. Unrolled: one statement per output, every monomial a named temporary:
/// the fastest code, but compile time grows faster than the term count. Tables: the monomials and the terms as
/// constant integer tables walked by two short loops: compile time and code size linear in the terms, at about
/// twice the run time per term. Automatic: tables for kernels above table_threshold terms, and for the kernels of
/// every right-hand side above rhs_table_threshold: their tables cost three times the unrolled code's run time (FEM
/// at Ny = 64 under gravity, 1727 terms: 1.45 against 0.55 us a call), the compiler a second or two more.
struct EmitOptions {
    enum class Form { automatic, unrolled, tables } form = Form::automatic;
    int table_threshold = 1000;
    int rhs_table_threshold = 4000;
    /// Whether to print coefficients_p (dc/dp). The caller turns it off where dc/dp would be far larger than the
    /// rest (a pre-twist's series): the runtime then differences the model, as for order full.
    bool parameter_derivatives = true;
};

/// Emits `<prefix>_coefficients(p, c)` and `<prefix>_<kernel>(c, state..., out)` for each kernel.
EmittedCode emit_kernels(const std::string& prefix, const Signature& signature, std::vector<KernelSpec> kernels,
                         const EmitOptions& options = {});

/// The C literal for a number: round-trip precision, always a double literal ("2.0", "0.1", "-1e-05").
std::string c_number(const GiNaC::numeric& x);

}  // namespace hubbeam::gen
