/* The binary interface between generated kernels and the runtime: one signature for every kernel and one
 * table row per variant. Generated code includes this header and nothing else of the project. */
#pragma once

namespace hubbeam::generated {

/* The version of this interface. Every table row starts with the version of the generator that wrote it, and a
 * loader refuses a row of any other version before calling one of its kernels (an on-demand object outlives the
 * generator that made it). Raise it with any change to Variant, Kernel or CoefficientsKernel below. */
inline constexpr int abi_version = 6;

/* forces_folded's lanes: the rows of P go in groups of this many, one group's entries of a column side by side. */
inline constexpr int folded_lanes = 4;

/* out = f(c, u, q, qd). c: the variant's coefficients (from its coefficients kernel, once per parameter set);
 * u: the drive, indexed by DriveValue of model/interface.hpp (a torque variant reads tau, a prescribed variant
 * theta_dot and theta_ddot); q, qd: generalized coordinates and rates of the variant. */
using Kernel = void (*)(const double* c, const double* u, const double* q, const double* qd, double* out);
/* c = f(p), p: the physical parameters in SI units, indexed by Param of model/interface.hpp. */
using CoefficientsKernel = void (*)(const double* p, double* c);

/* A profile variant's run-time section integrals (docs/model.md section 11.2): entry n is
 *   int_0^1 xi^power d(xi) prod_f factor_f(xi) dxi,
 * d the SectionDistribution `distribution` of model/interface.hpp (linear between the table's stations) and each factor
 * a shape function's derivative, a coupling function H or the section itself, named by the kinds below. The runtime
 * computes them from the run's table and passes them to the coefficients kernel after the parameters. */
enum SectionFactorKind { axial_factor, transverse_factor, coupling_factor, flap_factor, flap_coupling_factor,
                         twist_factor };
/* phi_i^(deriv) of the field of `kind`; a coupling H_ij (deriv 0) of the in-plane or flapwise field. */
struct SectionFactor {
    int kind, i, j, deriv;
};
inline constexpr int max_section_factors = 6;
struct SectionIntegral {
    int distribution, power, count; /* count: the factors used of `factors` */
    SectionFactor factors[max_section_factors];
};

/* One variant's row, filled by designated initializers (field names, not positions) in the generated source. */
struct Variant {
    int abi_version;          /* first, where every version of this struct has it: the generator's abi_version */
    const char* name;         /* VariantKey::name(), e.g. "bim_nx4_ny4_torque_first" */
    int nq;                   /* number of generalized coordinates */
    int ncoeff;               /* length of c */
    int nterms;               /* K, the number of state monomials of Q (forces_terms) */
    const char* mass_pattern; /* nq*nq characters, row-major: '0' zero, 'c' constant, 'v' depends on q */
    CoefficientsKernel coefficients;
    CoefficientsKernel coefficients_p; /* dcdp[np*ncoeff] = dc/dp, out[k*ncoeff + i] = dc_i/dp_k over the np entries of
                                        * p the variant reads; nonzero entries only. Every other kernel except
                                        * forces_folded is affine in c, so its derivative by p_k is itself at
                                        * c = dc/dp_k less itself at c = 0. A null pointer where a kernel is not
                                        * (order full's sums over quadrature points) */
    Kernel mass;              /* M[nq*nq] = d2T/dqd2, symmetric: writes the upper triangle's nonzero entries only */
    Kernel mass_varying;      /* as mass, the 'v' entries only; a null pointer when M is constant */
    Kernel forces;            /* Q[nq]: tau e_theta + dT/dq - d(dT/dqd)/dt|_(qdd=0) - dU/dq */
    Kernel forces_terms;      /* m[nterms]: the state monomials of Q (the runtime folds the constant part of M^-1
                               * into F) */
    Kernel forces_matrix;     /* F[nq*nterms], row-major, free of the state: Q = F m */
    Kernel energy;            /* E[4] = (T2, T1, T0, U), T split by degree in qd */
    Kernel momentum;          /* h[1] = dT/dtheta_dot */
    /* The Jacobian pieces for implicit integrators, derivatives of the M and Q above (docs/model.md section 5.1);
     * each writes its nonzero entries only, the caller zero-fills. */
    Kernel forces_q;          /* dQdq[nq*nq], row-major: out[i*nq+k] = dQ_i/dq_k */
    Kernel forces_qd;         /* dQdqd[nq*nq], row-major: out[i*nq+k] = dQ_i/dqd_k */
    Kernel mass_q_product;    /* dMv[nq*nq], row-major, v passed in the qd slot: out[i*nq+k] = sum_j dM_ij/dq_k v_j;
                               * a null pointer when M is constant (then dM/dq = 0) */
    Kernel forces_u;          /* dQdu[nq*3], row-major: out[i*3+j] = dQ_i/du_j, u indexed by DriveValue; columns of
                               * drive values the variant does not read are zero */
    Kernel tip;               /* tip[3] = (u_y(L), u_x1(L), u_x(L)), u_x = u_x1 - 1/2 B^T H(L) B; a variant that
                               * leaves the plane writes tip[5], adding (u_z(L), phi(L)) (docs/model.md section 12) */
    Kernel forces_folded;     /* y[nq] = P m for the runtime's folded P (nq x nterms) in the c slot, by groups of
                               * W = folded_lanes rows: P(i, k) at c[(j/W)*W*nterms + W*k + j%W], j = i for a
                               * constant M, i + W - 1 else (row 0 alone), padding rows zero.
                               * P = M^-1 F for a constant M; with M varying in the hub's row only, the constant
                               * block's inverse folded into its rows of F and the hub's row F_0 - b^T C^-1 F_C (b
                               * its constant couplings). Reads only the entries that can be nonzero; a null pointer
                               * for other mass patterns or beyond a size where unrolling pays */
    int nsection;             /* a profile variant's number of section integrals (0 without a profile) */
    const SectionIntegral* section_integrals; /* their definitions, nsection of them; a null pointer without */
};

/* Marks forces_folded, the unrolled kernels of every right-hand side (and the runtime's band solve): GCC compiles
 * them for AVX2 (four lanes in one register, three-operand forms) and for the baseline (two registers of two), and
 * the loader picks. AVX2 without FMA rounds as SSE2 does, so both give the same bits. */
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define HUBBEAM_WIDE_KERNEL __attribute__((target_clones("avx2", "default")))
#else
#define HUBBEAM_WIDE_KERNEL
#endif

/* Marks coefficients and coefficients_p, which run once per parameter set (a model's construction), not per step:
 * compiled without optimization. They are long straight-line sums (AMM at Ny = 16 with four terms: 850 KB of the
 * 1.1 MB source), whose optimization took most of an on-demand compilation (31.5 s with it, 5.9 s without, one
 * measurement on a loaded machine) for no gain a run could see. Without -ffast-math or FMA, unoptimized code rounds as optimized code
 * does: the coefficients are the same bits. */
#if defined(__clang__)
#define HUBBEAM_ONCE_KERNEL __attribute__((optnone))
#elif defined(__GNUC__)
#define HUBBEAM_ONCE_KERNEL __attribute__((optimize("O0")))
#else
#define HUBBEAM_ONCE_KERNEL
#endif

extern const Variant* const variants[];
extern const int variant_count;

}  // namespace hubbeam::generated
