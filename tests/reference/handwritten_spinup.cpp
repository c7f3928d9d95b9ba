// handwritten_spinup: the scene cases/spinup_omega4.toml without axial coordinates (Nx = 0), written by hand from
// docs/model.md: an oracle for hubbeam's generated equations and its row output, and the yardstick of its speed.
//
// It shares no code with hubbeam (GSL, the C++ library and the tests' own Gauss-Legendre rule only). The model,
// section by section of docs/model.md:
//   section 1, 6  a uniform beam clamped at the axis of a hub (a = 0) whose rotation is prescribed (eq. 58);
//   section 3     order "first": |r_dot|^2 keeps terms of degree <= 2, u_x2 only in 2 theta_dot^2 x u_x2;
//   section 4     AMM, Ny = 4 clamped-free cantilever modes, no axial field (u_x1 = 0);
//   section 5     Lagrange's equations, derived below from T and U;
//   section 5.4   the outputs (docs/cli.md's CSV columns).
// The integration is hubbeam's for `--stepper rk8pd` (runtime/src/simulation/run_stepping.cpp): GSL's rk8pd stepping
// freely under the standard control on y, a restart at the drive's breakpoint T_s, and rows interpolated inside the
// steps by the quintic Hermite polynomial of the positions, rates and accelerations at both ends, the steps kept short
// enough for it. So both take the same steps, and their times compare like for like.
//
// Usage: handwritten_spinup OUT.csv [--rtol X] [--atol X]     (the scene's 1e-8 and 1e-10 by default)
#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <string>
#include <vector>

#include "gauss_legendre.hpp"

namespace {

constexpr int ny = 4;  // transverse coordinates B_1..B_4; the state is y = (B, B_dot)
constexpr int n = 2 * ny;
using Vec = std::array<double, ny>;
using Mat = std::array<Vec, ny>;

// cases/spinup_omega4.toml
constexpr double L = 8.0, rho = 2.7667e3, S = 7.2968e-5, I = 8.2189e-9, E = 6.8952e10;  // [beam]; [hub] a = 0
constexpr double omega0 = 4.0, T_s = 15.0;                                              // [motion] spin-up
constexpr double t_end = 30.0, rows_per_second = 100.0;                                 // [output] dt_out = 0.01
// [hub] gives no inertia: hubbeam's default J_oh (docs/scene.md, hub.inertia) is in the rows' T, h and Jacobi
// integral (section 3: T = 1/2 J_oh theta_dot^2 + ...), though a prescribed rotation's motion does not depend on it.
constexpr double J_oh = 30.0;
constexpr double h0 = 1e-4;  // hubbeam's default first step (docs/scene.md, solver.h0)
constexpr double m = rho * S, EI = E * I;
constexpr double pi = std::numbers::pi;

/// The prescribed rotation, paper eq. 58 (docs/model.md section 6): theta, theta_dot, theta_ddot at t.
struct Drive {
    double theta, theta_dot, theta_ddot;
};
Drive drive(double t)
{
    if (t > T_s) return {omega0 * (t - T_s / 2), omega0, 0.0};
    const double w = 2 * pi / T_s;
    return {omega0 * (t * t / (2 * T_s) + T_s * (std::cos(w * t) - 1) / (4 * pi * pi)),
            omega0 * (t / T_s - std::sin(w * t) / (2 * pi)), omega0 / T_s * (1 - std::cos(w * t))};
}

/// Gauss-Legendre nodes and weights on [0, 1], from the tests' own rule on [-1, 1] (tests/gauss_legendre.hpp,
/// which no hubbeam code uses).
struct Rule {
    std::vector<double> x, w;
};
Rule gauss_legendre(int k)
{
    const hubbeam::test::GaussRule on_symmetric = hubbeam::test::gauss_legendre(k);
    Rule r;
    for (std::size_t i = 0; i < on_symmetric.x.size(); ++i) {
        r.x.push_back(0.5 * (1 - on_symmetric.x[i]));
        r.w.push_back(0.5 * on_symmetric.w[i]);
    }
    return r;
}

/// beta_i L: the i-th positive root of 1 + cos z cosh z = 0 (section 4), by Newton's method on cos z + 1/cosh z,
/// which has the same roots and no exponential growth, from (i - 1/2) pi.
double cantilever_root(int i)
{
    double z = (i - 0.5) * pi;
    for (int it = 0; it < 50; ++it) {
        const double f = std::cos(z) + 1 / std::cosh(z), df = -std::sin(z) - std::tanh(z) / std::cosh(z);
        const double dz = f / df;
        z -= dz;
        if (std::abs(dz) < 1e-15 * z) break;
    }
    return z;
}

/// A clamped-free mode phi(xi) = cos(b xi) - cosh(b xi) + g (sin(b xi) - sinh(b xi)), g = -(cos b + cosh b)/(sin b +
/// sinh b) (section 4), with its first and second derivatives by xi. At b < 11 the cancellation between cosh
/// and sinh costs under 1e-11.
struct Mode {
    double b, g;
    explicit Mode(double root) : b(root), g(-(std::cos(root) + std::cosh(root)) / (std::sin(root) + std::sinh(root))) {}
    double phi(double xi) const
    {
        const double z = b * xi;
        return std::cos(z) - std::cosh(z) + g * (std::sin(z) - std::sinh(z));
    }
    double d1(double xi) const
    {
        const double z = b * xi;
        return b * (-std::sin(z) - std::sinh(z) + g * (std::cos(z) - std::cosh(z)));
    }
    double d2(double xi) const
    {
        const double z = b * xi;
        return b * b * (-std::cos(z) - std::cosh(z) + g * (-std::sin(z) - std::sinh(z)));
    }
};

/// The constant matrices of docs/model.md section 5.2 at a = 0 and Nx = 0, and the tip's values (section 5.4).
/// With x = L xi, dx = L dxi and d/dx = (1/L) d/dxi:
///   M2  = int m Phi^T Phi dx                      = m L    int phi_i phi_j dxi
///   K2  = int EI Phi''^T Phi'' dx                 = EI/L^3 int phi_i'' phi_j'' dxi
///   G   = D = int m (L^2 - x^2)/2 Phi'^T Phi' dx  = m L/2  int (1 - xi^2) phi_i' phi_j' dxi
///   S_y = int m x Phi dx                          = m L^2  int xi phi_i dxi
///   H(L) = int_0^L Phi'^T Phi' dx                 = 1/L    int phi_i' phi_j' dxi
///   J_ob = int m x^2 dx                           = m L^3/3
struct Beam {
    Mat M2{}, K2{}, G{}, H_L{}, M2_minus_G{};
    Vec S_y{}, Phi_L{};
    double J_ob = m * L * L * L / 3;
};
Beam beam_matrices()
{
    std::vector<Mode> modes;
    for (int i = 1; i <= ny; ++i) modes.emplace_back(cantilever_root(i));
    // 16 panels of 20 points: the integrands are entire functions growing as e^(2 b xi), b < 11, which a 20-point
    // rule on panels of 1/16 integrates to round-off.
    const Rule rule = gauss_legendre(20);
    const int panels = 16;
    Beam beam;
    for (int p = 0; p < panels; ++p)
        for (std::size_t k = 0; k < rule.x.size(); ++k) {
            const double xi = (p + rule.x[k]) / panels, w = rule.w[k] / panels;
            Vec phi, d1, d2;
            for (int i = 0; i < ny; ++i) {
                phi[i] = modes[i].phi(xi);
                d1[i] = modes[i].d1(xi);
                d2[i] = modes[i].d2(xi);
            }
            for (int i = 0; i < ny; ++i) {
                beam.S_y[i] += w * m * L * L * xi * phi[i];
                for (int j = 0; j < ny; ++j) {
                    beam.M2[i][j] += w * m * L * phi[i] * phi[j];
                    beam.K2[i][j] += w * EI / (L * L * L) * d2[i] * d2[j];
                    beam.G[i][j] += w * m * L / 2 * (1 - xi * xi) * d1[i] * d1[j];
                    beam.H_L[i][j] += w / L * d1[i] * d1[j];
                }
            }
        }
    for (int i = 0; i < ny; ++i) {
        beam.Phi_L[i] = modes[i].phi(1.0);
        for (int j = 0; j < ny; ++j) beam.M2_minus_G[i][j] = beam.M2[i][j] - beam.G[i][j];
    }
    return beam;
}

/// The inverse of a symmetric positive definite matrix (M2) by Gauss-Jordan elimination; no pivoting needed.
Mat inverse(Mat a)
{
    Mat x{};
    for (int i = 0; i < ny; ++i) x[i][i] = 1.0;
    for (int c = 0; c < ny; ++c) {
        const double pivot = a[c][c];
        for (int j = 0; j < ny; ++j) {
            a[c][j] /= pivot;
            x[c][j] /= pivot;
        }
        for (int r = 0; r < ny; ++r) {
            if (r == c) continue;
            const double f = a[r][c];
            for (int j = 0; j < ny; ++j) {
                a[r][j] -= f * a[c][j];
                x[r][j] -= f * x[c][j];
            }
        }
    }
    return x;
}

Mat product(const Mat& a, const Mat& b)
{
    Mat c{};
    for (int i = 0; i < ny; ++i)
        for (int j = 0; j < ny; ++j)
            for (int k = 0; k < ny; ++k) c[i][j] += a[i][k] * b[k][j];
    return c;
}

double quadratic(const Mat& a, const double* u, const double* v)
{
    double s = 0.0;
    for (int i = 0; i < ny; ++i)
        for (int j = 0; j < ny; ++j) s += u[i] * a[i][j] * v[j];
    return s;
}

/// The equations of motion, derived from the energies (docs/model.md sections 2, 3, 5.2 with a = 0, u_x1 = 0).
/// At first order |r_dot|^2 = theta_dot^2 (x^2 + 2 x u_x2 + u_y^2) + 2 theta_dot x u_y_dot + u_y_dot^2, and with
/// u_y = Phi B, int m x u_x2 dx = -1/2 B^T D B = -1/2 B^T G B:
///   T = 1/2 theta_dot^2 (J_oh + J_ob + B^T (M2 - G) B) + theta_dot S_y B_dot + 1/2 B_dot^T M2 B_dot
///   U = 1/2 B^T K2 B
/// Lagrange: d/dt dT/dB_dot = M2 B_ddot + theta_ddot S_y^T, dT/dB = theta_dot^2 (M2 - G) B, dU/dB = K2 B, so
///   M2 B_ddot = theta_dot^2 (M2 - G) B - K2 B - theta_ddot S_y^T        (eq. 57 with Nx = 0)
/// M2 is constant: B_ddot = theta_dot^2 P B - Q B - theta_ddot s with P = M2^-1 (M2 - G), Q = M2^-1 K2,
/// s = M2^-1 S_y^T, formed once.
struct Equations {
    Mat P{}, Q{};
    Vec s{};
    long evaluations = 0;
    explicit Equations(const Beam& beam)
    {
        const Mat Minv = inverse(beam.M2);
        P = product(Minv, beam.M2_minus_G);
        Q = product(Minv, beam.K2);
        for (int i = 0; i < ny; ++i)
            for (int j = 0; j < ny; ++j) s[i] += Minv[i][j] * beam.S_y[j];
    }
    void rhs(double t, const double* y, double* f)
    {
        ++evaluations;
        const Drive d = drive(t);
        const double w2 = d.theta_dot * d.theta_dot;
        for (int i = 0; i < ny; ++i) {
            double acc = -d.theta_ddot * s[i];
            for (int j = 0; j < ny; ++j) acc += (w2 * P[i][j] - Q[i][j]) * y[j];
            f[i] = y[ny + i];
            f[ny + i] = acc;
        }
    }
};

int gsl_rhs(double t, const double y[], double f[], void* equations)
{
    static_cast<Equations*>(equations)->rhs(t, y, f);
    return GSL_SUCCESS;
}

/// Quintic Hermite interpolation on the step [t0, t1] of the positions (values, rates and accelerations at both
/// ends) and of the rates (its derivative); s = (t - t0)/h.
void interpolate(double t0, const double* y0, const double* f0, double t1, const double* y1, const double* f1, double t,
                 double* y)
{
    const double h = t1 - t0, s = (t - t0) / h, s2 = s * s, s3 = s2 * s, s4 = s3 * s, s5 = s4 * s;
    // Basis functions of p(0), h p'(0), h^2 p''(0), p(1), h p'(1), h^2 p''(1), and their derivatives by s.
    const double b[6] = {1 - 10 * s3 + 15 * s4 - 6 * s5, s - 6 * s3 + 8 * s4 - 3 * s5, (s2 - 3 * s3 + 3 * s4 - s5) / 2,
                         10 * s3 - 15 * s4 + 6 * s5,     -4 * s3 + 7 * s4 - 3 * s5,    (s3 - 2 * s4 + s5) / 2};
    const double db[6] = {
        -30 * s2 + 60 * s3 - 30 * s4, 1 - 18 * s2 + 32 * s3 - 15 * s4, (2 * s - 9 * s2 + 12 * s3 - 5 * s4) / 2,
        30 * s2 - 60 * s3 + 30 * s4,  -12 * s2 + 28 * s3 - 15 * s4,    (3 * s2 - 8 * s3 + 5 * s4) / 2};
    for (int i = 0; i < ny; ++i) {
        const double c[6] = {y0[i], h * y0[ny + i], h * h * f0[ny + i], y1[i], h * y1[ny + i], h * h * f1[ny + i]};
        y[i] = y[ny + i] = 0.0;
        for (int k = 0; k < 6; ++k) {
            y[i] += b[k] * c[k];
            y[ny + i] += db[k] * c[k] / h;
        }
    }
}

/// How far the interpolant's acceleration at the step's middle, p''(1/2)/h^2, is from the equations' there, as a
/// position error (that difference times h^2/24) over the tolerance atol + rtol |B_i|, the largest over i. The
/// basis's second derivatives by s at s = 1/2 are (0, -3/2, -1/4, 0, 3/2, -1/4).
double interpolation_error(double h, const double* y0, const double* f0, const double* y1, const double* f1,
                           const double* y_mid, const double* f_mid, double atol, double rtol)
{
    double worst = 0.0;
    for (int i = 0; i < ny; ++i) {
        const double p2 = (-1.5 * y0[ny + i] + 1.5 * y1[ny + i]) / h - 0.25 * f0[ny + i] - 0.25 * f1[ny + i];
        worst = std::max(worst, std::abs(p2 - f_mid[ny + i]) * h * h / 24 / (atol + rtol * std::abs(y_mid[i])));
    }
    return worst;
}

/// One CSV row: t, theta, theta_dot, tip_uy, tip_ux1, tip_ux, kinetic, potential, momentum, jacobi (docs/cli.md;
/// docs/model.md sections 5.4 and 7), each number in its shortest round-trip form.
void write_row(std::string& out, const Beam& beam, double t, const double* y)
{
    const Drive d = drive(t);
    const double* B = y;
    const double* Bd = y + ny;
    double tip_uy = 0.0, S_y_Bd = 0.0;
    for (int i = 0; i < ny; ++i) {
        tip_uy += beam.Phi_L[i] * B[i];
        S_y_Bd += beam.S_y[i] * Bd[i];
    }
    const double spin_inertia = J_oh + beam.J_ob + quadratic(beam.M2_minus_G, B, B);  // d2T/dtheta_dot2
    const double T2 = 0.5 * quadratic(beam.M2, Bd, Bd), T1 = d.theta_dot * S_y_Bd,
                 T0 = 0.5 * spin_inertia * d.theta_dot * d.theta_dot, U = 0.5 * quadratic(beam.K2, B, B);
    const double values[] = {t,
                             d.theta,
                             d.theta_dot,
                             tip_uy,
                             0.0,                                    // tip_ux1: no axial coordinate
                             0.0 - 0.5 * quadratic(beam.H_L, B, B),  // tip_ux = u_x2(L), +0 at B = 0
                             T2 + T1 + T0,                           // kinetic
                             U,                                      // potential
                             spin_inertia * d.theta_dot + S_y_Bd,    // momentum dT/dtheta_dot
                             T2 - T0 + U};                           // jacobi
    char buffer[32];
    for (std::size_t k = 0; k < std::size(values); ++k) {
        const auto result = std::to_chars(buffer, buffer + sizeof buffer, values[k]);
        out.append(buffer, result.ptr);
        out += k + 1 < std::size(values) ? ',' : '\n';
    }
}

double positive_number(const char* text, const char* option)
{
    char* end = nullptr;
    const double x = std::strtod(text, &end);
    if (end == text || *end != '\0' || !(x > 0.0) || !std::isfinite(x)) {
        std::fprintf(stderr, "handwritten_spinup: %s expects a number > 0, not '%s'\n", option, text);
        std::exit(2);
    }
    return x;
}

}  // namespace

int main(int argc, char** argv)
{
    std::string out_path;
    double rtol = 1e-8, atol = 1e-10;  // [solver] of the scene
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if ((arg == "--rtol" || arg == "--atol") && i + 1 < argc) {
            (arg == "--rtol" ? rtol : atol) = positive_number(argv[i + 1], argv[i]);
            ++i;
        } else if (!arg.empty() && arg[0] != '-' && out_path.empty())
            out_path = arg;
        else {
            std::fprintf(stderr, "usage: handwritten_spinup OUT.csv [--rtol X] [--atol X]\n");
            return 2;
        }
    }
    if (out_path.empty()) {
        std::fprintf(stderr, "usage: handwritten_spinup OUT.csv [--rtol X] [--atol X]\n");
        return 2;
    }

    gsl_set_error_handler_off();  // a failed step comes back as a status, reported below, not as abort()
    const Beam beam = beam_matrices();
    Equations equations(beam);
    gsl_odeiv2_system system{gsl_rhs, nullptr, n, &equations};
    // hubbeam's control: GSL's standard one on y (atol + rtol |y_i|), through a driver that owns step and evolve.
    gsl_odeiv2_driver* driver = gsl_odeiv2_driver_alloc_y_new(&system, gsl_odeiv2_step_rk8pd, h0, atol, rtol);

    std::string csv = "t,theta,theta_dot,tip_uy,tip_ux1,tip_ux,kinetic,potential,momentum,jacobi\n";
    double t = 0.0, h = h0;
    double y[n] = {}, y0[n], f0[n], f1[n], y_mid[n], f_mid[n], yi[n];
    write_row(csv, beam, t, y);
    const long last_row = std::lround(t_end * rows_per_second);
    const auto row_time = [](long i) { return static_cast<double>(i) / rows_per_second; };
    constexpr double same_instant = 1e-12;  // relative: a row this close to a step's end is that end's state
    double h_max = INFINITY;                // the longest step whose interpolated rows stay within the tolerance
    bool have_f0 = false;
    bool breakpoint_passed = false;
    unsigned long steps = 0, rejected = 0;  // GSL counts them again from a reset
    long row = 1;
    while (row <= last_row) {
        // The drive's derivatives jump at T_s: steps end there and the stepper starts again (docs/model.md section 9).
        const double target = breakpoint_passed ? t_end : T_s;
        const double t0 = t;
        std::copy_n(y, n, y0);
        h = std::min(h, h_max);
        const int status = gsl_odeiv2_evolve_apply(driver->e, driver->c, driver->s, &system, &t, target, &h, y);
        if (status != GSL_SUCCESS) {
            std::fprintf(stderr, "handwritten_spinup: rk8pd failed at t = %g s (GSL status %d)\n", t, status);
            return 1;
        }
        bool have_f1 = false;
        const auto ends = [&] {
            if (!have_f0) equations.rhs(t0, y0, f0);
            if (!have_f1) equations.rhs(t, y, f1);
            have_f0 = have_f1 = true;
        };
        if (row_time(row) < t * (1 - same_instant)) {
            // A row inside the step: the interpolant's error at the middle bounds the next steps (error ~ h^6).
            ends();
            const double t_mid = 0.5 * (t0 + t);
            interpolate(t0, y0, f0, t, y, f1, t_mid, y_mid);
            equations.rhs(t_mid, y_mid, f_mid);
            const double ratio = interpolation_error(t - t0, y0, f0, y, f1, y_mid, f_mid, atol, rtol);
            h_max = (t - t0) * std::min(4.0, 0.9 * std::pow(std::max(ratio, 1e-12), -1.0 / 6.0));
        }
        for (; row <= last_row && row_time(row) <= t * (1 + same_instant); ++row) {
            const double ti = row_time(row);
            if (std::abs(ti - t) > same_instant * ti) {
                ends();
                interpolate(t0, y0, f0, t, y, f1, ti, yi);
                write_row(csv, beam, ti, yi);
            } else {
                write_row(csv, beam, ti, y);
            }
        }
        std::copy_n(f1, n, f0);  // this step's end starts the next
        have_f0 = have_f1;
        if (!breakpoint_passed && t >= T_s) {
            breakpoint_passed = true;
            steps += driver->e->count;
            rejected += driver->e->failed_steps;
            gsl_odeiv2_driver_reset(driver);
            h = std::min(h, h0);
        }
    }
    steps += driver->e->count;
    rejected += driver->e->failed_steps;
    gsl_odeiv2_driver_free(driver);

    // Written beside the target and renamed over it: a reader never sees half a file.
    const std::string temporary = out_path + ".tmp";
    std::FILE* file = std::fopen(temporary.c_str(), "wb");
    if (file == nullptr || std::fwrite(csv.data(), 1, csv.size(), file) != csv.size() || std::fclose(file) != 0 ||
        std::rename(temporary.c_str(), out_path.c_str()) != 0) {
        std::fprintf(stderr, "handwritten_spinup: cannot write %s\n", out_path.c_str());
        std::remove(temporary.c_str());
        return 1;
    }
    std::printf("steps       %lu accepted, %lu rejected by the error test\nRHS evals   %ld\n", steps, rejected,
                equations.evaluations);
    return 0;
}
