// GeneratedModel: a Model that calls one variant's generated kernels through the table row of
// generated_abi.h, with the parameter-only coefficients computed once.
#include "models/generated_model.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "generated_abi.h"
#include "models/section_integrals.hpp"
#include "terms.hpp"

namespace hubbeam {

namespace {

class GeneratedModel final : public Model, TermForces, FoldedForceKernel, ExactJacobian, ParameterDerivatives {
public:
    GeneratedModel(const VariantKey& key, const generated::Variant& v, const Parameters& p)
        : Model(key, p),
          v_(v),
          c_(static_cast<std::size_t>(v.ncoeff)),
          pattern_(v.mass_pattern),
          reads_angle_(kernels_read_angle(key)),
          torque_(key.drive == Drive::torque)
    {
        // A profile variant reads its section integrals after the parameters (model/interface.hpp).
        std::vector<double> packed = p.packed();
        const std::vector<double> sections = section_integrals(key, v.section_integrals, v.nsection, p);
        packed.insert(packed.end(), sections.begin(), sections.end());
        v_.coefficients(packed.data(), c_.data());
        if (v_.coefficients_p != nullptr) {
            // The entries of p the variant reads (generator/variant_source.cpp, read_parameter_names): the paper's
            // seven, or all with extra terms; the derivatives by the named ones are kept.
            const std::size_t read = key.params_read();
            std::vector<double> all(read * c_.size());
            v_.coefficients_p(packed.data(), all.data());
            dcdp_.assign(param_count * c_.size(), 0.0);
            std::copy_n(all.begin(), std::min(read, param_count) * c_.size(), dcdp_.begin());
            zero_c_.assign(c_.size(), 0.0);
        }
        // The kernels write M's upper triangle: these lower entries are mirrored from it.
        const int n = v.nq;
        for (int i = 0; i < n; ++i)
            for (int j = i + 1; j < n; ++j) {
                const char kind = pattern_[static_cast<std::size_t>(i * n + j)];
                if (kind != '0') mirrored_.push_back({i * n + j, j * n + i});
                if (kind == 'v') mirrored_varying_.push_back({i * n + j, j * n + i});
            }
    }

    const char* source() const override { return "generated"; }
    bool mass_is_constant() const override { return pattern_.find('v') == std::string::npos; }
    std::string mass_pattern() const override { return pattern_; }

    void mass(const HubInput& u, const double* q, double* M) const override
    {
        std::fill_n(M, nq() * nq(), 0.0);
        call_without_angle(v_.mass, u, q, q, M);
        for (const auto& [upper, lower] : mirrored_) M[lower] = M[upper];
    }
    void mass_varying(const HubInput& u, const double* q, double* M) const override
    {
        mass_varying_upper(u, q, M);
        for (const auto& [upper, lower] : mirrored_varying_) M[lower] = M[upper];  // none without a kernel
    }
    void mass_varying_upper(const HubInput& u, const double* q, double* M) const override
    {
        if (v_.mass_varying != nullptr) call_without_angle(v_.mass_varying, u, q, q, M);
    }
    const TermForces* term_forces() const override
    {
        return v_.nterms > 0 && v_.forces_terms != nullptr && v_.forces_matrix != nullptr ? this : nullptr;
    }
    const FoldedForceKernel* folded_kernel() const override { return v_.forces_folded != nullptr ? this : nullptr; }
    const ExactJacobian* jacobian() const override { return this; }
    const ParameterDerivatives* parameter_derivatives() const override { return dcdp_.empty() ? nullptr : this; }

    // Each kernel is affine in c (generated_abi.h): its derivative by p_k is itself at c = dc/dp_k less itself at 0.
    // The part at 0 goes to an array of the call's own: a model is shared by the runs of several threads.
    void mass_p(Param k, const HubInput& u, const double* q, double* dM) const override
    {
        std::vector<double> at_zero(static_cast<std::size_t>(nq()) * nq());
        mass_at(zero_c_.data(), u, q, at_zero.data());
        mass_derivative(dc(k), u, q, at_zero.data(), dM);
    }
    void forces_p(Param k, const HubInput& u, const double* q, const double* qd, double* dQ) const override
    {
        const std::array<double, kernel_input_count> in = inputs(u, q);
        std::vector<double> at_zero(static_cast<std::size_t>(nq()));
        forces_at(zero_c_.data(), in, q, qd, at_zero.data());
        forces_derivative(dc(k), in, q, qd, at_zero.data(), dQ);
    }
    void derivatives_p(const Param* ks, int count, int n, const HubInput& u, const double* q, const double* qd,
                       double* dM, double* dQ) const override
    {
        // M and Q at c = 0 once for all the parameters.
        const int nn = n * n;
        std::vector<double> at_zero(static_cast<std::size_t>(nn + n));
        const std::array<double, kernel_input_count> in = inputs(u, q);
        mass_at(zero_c_.data(), u, q, at_zero.data());
        forces_at(zero_c_.data(), in, q, qd, at_zero.data() + nn);
        for (int j = 0; j < count; ++j) {
            mass_derivative(dc(ks[j]), u, q, at_zero.data(), dM + static_cast<std::ptrdiff_t>(j) * nn);
            forces_derivative(dc(ks[j]), in, q, qd, at_zero.data() + nn, dQ + static_cast<std::ptrdiff_t>(j) * n);
        }
    }
    Tip tip_p(Param k, const double* q) const override
    {
        double t[5] = {}, t0[5] = {};
        const std::array<double, kernel_input_count> in{};
        v_.tip(dc(k), in.data(), q, q, t);
        v_.tip(zero_c_.data(), in.data(), q, q, t0);
        return {t[0] - t0[0], t[1] - t0[1], t[2] - t0[2], t[3] - t0[3], t[4] - t0[4]};
    }
    bool term_matrix_p(Param k, double* dF) const override
    {
        if (term_forces() == nullptr) return false;
        const int n = nq() * v_.nterms;
        std::fill_n(dF, n, 0.0);
        std::vector<double> at_zero(static_cast<std::size_t>(n), 0.0);
        const std::array<double, kernel_input_count> in{};
        v_.forces_matrix(dc(k), in.data(), nullptr, nullptr, dF);
        v_.forces_matrix(zero_c_.data(), in.data(), nullptr, nullptr, at_zero.data());
        for (int i = 0; i < n; ++i) dF[i] -= at_zero[static_cast<std::size_t>(i)];
        return true;
    }

    int term_count() const override { return v_.nterms; }
    void terms(const HubInput& u, const double* q, const double* qd, double* m) const override
    {
        call(v_.forces_terms, u, q, qd, m);
    }
    void term_matrix(double* F) const override
    {
        std::fill_n(F, nq() * v_.nterms, 0.0);
        call(v_.forces_matrix, HubInput{}, nullptr, nullptr, F);
    }
    void accelerations(const double* P, const HubInput& u, const double* q, const double* qd, double* y) const override
    {
        v_.forces_folded(P, inputs(u, q).data(), q, qd, y);
    }
    void forces(const HubInput& u, const double* q, const double* qd, double* Q) const override
    {
        call(v_.forces, u, q, qd, Q);
    }
    Energy energy(const HubInput& u, const double* q, const double* qd) const override
    {
        double e[4];
        call(v_.energy, u, q, qd, e);
        return {e[0], e[1], e[2], e[3]};
    }
    double momentum(const HubInput& u, const double* q, const double* qd) const override
    {
        double h;
        call(v_.momentum, u, q, qd, &h);
        return h;
    }

    Tip tip(const double* q) const override
    {
        double t[5] = {};  // a planar variant's kernel writes the first three (generated_abi.h)
        call(v_.tip, HubInput{}, q, q, t);
        return {t[0], t[1], t[2], t[3], t[4]};
    }

    void force_derivatives(const HubInput& u, const double* q, const double* qd, double* dQdq, double* dQdqd,
                           double* dQdu) const override
    {
        // The kernels write their nonzero entries only.
        std::fill_n(dQdq, nq() * nq(), 0.0);
        std::fill_n(dQdqd, nq() * nq(), 0.0);
        std::fill_n(dQdu, nq() * static_cast<int>(drive_value_count), 0.0);
        call(v_.forces_q, u, q, qd, dQdq);
        call(v_.forces_qd, u, q, qd, dQdqd);
        call(v_.forces_u, u, q, qd, dQdu);
    }
    void forces_theta(const HubInput& u, const double* q, const double* qd, double* dQdtheta) const override
    {
        std::fill_n(dQdtheta, nq(), 0.0);
        if (!reads_angle_ || torque_) return;
        // Q is affine in (sin theta, cos theta) (U's weight and a moving hub's T hold them linearly, and the prescribed
        // angle's d/dt turns one into the other): dQ/dtheta = cos dQ/dsin - sin dQ/dcos is Q at (cos theta, -sin theta)
        // less Q at (0, 0).
        std::array<double, kernel_input_count> k = inputs(u, q);
        const double s = k[index(AngleValue::sin_theta)], c = k[index(AngleValue::cos_theta)];
        std::vector<double> base(static_cast<std::size_t>(nq()));
        k[index(AngleValue::sin_theta)] = c;
        k[index(AngleValue::cos_theta)] = -s;
        v_.forces(c_.data(), k.data(), q, qd, dQdtheta);
        k[index(AngleValue::sin_theta)] = k[index(AngleValue::cos_theta)] = 0.0;
        v_.forces(c_.data(), k.data(), q, qd, base.data());
        for (int i = 0; i < nq(); ++i) dQdtheta[i] -= base[static_cast<std::size_t>(i)];
    }
    void mass_q_product(const HubInput& u, const double* q, const double* v, double* dMv) const override
    {
        // The generator emits no kernel for a constant M (dM/dq = 0).
        std::fill_n(dMv, nq() * nq(), 0.0);
        if (v_.mass_q_product != nullptr) call_without_angle(v_.mass_q_product, u, q, v, dMv);
    }

private:
    void call(generated::Kernel k, const HubInput& u, const double* q, const double* qd, double* out) const
    {
        k(c_.data(), inputs(u, q).data(), q, qd, out);
    }

    /// A kernel of M: M depends on no drive value, and on the angle only where the hub translates (its velocity in
    /// the blade's frame turns with theta, a coordinate: docs/model.md section 13); elsewhere the sine and cosine
    /// are not computed for it.
    void call_without_angle(generated::Kernel k, const HubInput& u, const double* q, const double* qd,
                            double* out) const
    {
        k(c_.data(), mass_inputs(u, q).data(), q, qd, out);
    }
    std::array<double, kernel_input_count> mass_inputs(const HubInput& u, const double* q) const
    {
        if (mass_reads_angle(key())) return inputs(u, q);
        return {u.tau, u.theta_dot, u.theta_ddot, 0.0, 0.0};
    }

    /// M's kernel at the coefficients c (its entries; the mirrored ones zero).
    void mass_at(const double* c, const HubInput& u, const double* q, double* M) const
    {
        std::fill_n(M, nq() * nq(), 0.0);
        v_.mass(c, mass_inputs(u, q).data(), q, q, M);
    }
    /// dM/dp_k, both triangles: M's kernel at c = dc/dp_k less at_zero, its mass_at at c = 0.
    void mass_derivative(const double* c, const HubInput& u, const double* q, const double* at_zero, double* dM) const
    {
        mass_at(c, u, q, dM);
        for (int i = 0; i < nq() * nq(); ++i) dM[i] -= at_zero[i];
        for (const auto& [upper, lower] : mirrored_) dM[lower] = dM[upper];
    }
    /// Q's kernel at the coefficients c, the kernels' inputs in.
    void forces_at(const double* c, const std::array<double, kernel_input_count>& in, const double* q,
                   const double* qd, double* Q) const
    {
        std::fill_n(Q, nq(), 0.0);
        v_.forces(c, in.data(), q, qd, Q);
    }
    /// dQ/dp_k: Q's kernel at c = dc/dp_k less at_zero, its forces_at at c = 0.
    void forces_derivative(const double* c, const std::array<double, kernel_input_count>& in, const double* q,
                           const double* qd, const double* at_zero, double* dQ) const
    {
        forces_at(c, in, q, qd, dQ);
        for (int i = 0; i < nq(); ++i) dQ[i] -= at_zero[i];
    }

    /// The kernels' u: the drive values, then where U reads it (gravity) sin and cos of the angle (a torque variant's
    /// q[0]; q is null only for the state-free F, which holds no angle).
    std::array<double, kernel_input_count> inputs(const HubInput& u, const double* q) const
    {
        const std::array<double, drive_value_count> d = u.packed();
        std::array<double, kernel_input_count> k{d[0], d[1], d[2], 0.0, 0.0};
        if (reads_angle_) {
            const double theta = torque_ ? (q != nullptr ? q[0] : 0.0) : u.theta;
            k[index(AngleValue::sin_theta)] = std::sin(theta);
            k[index(AngleValue::cos_theta)] = std::cos(theta);
        }
        return k;
    }

    const double* dc(Param k) const { return dcdp_.data() + index(k) * c_.size(); }

    const generated::Variant& v_;
    std::vector<double> c_;
    std::vector<double> dcdp_, zero_c_;  // dc/dp by Param, param_count x ncoeff (empty without coefficients_p); 0
    std::string pattern_;
    std::vector<std::pair<int, int>> mirrored_, mirrored_varying_;  // (upper, lower) entry pairs of M
    bool reads_angle_, torque_;  // whether U reads the hub angle (terms.hpp), whether it is q[0]
};

}  // namespace

std::unique_ptr<Model> make_generated_model(const VariantKey& key, const generated::Variant& v, const Parameters& p,
                                            std::string origin)
{
    auto m = std::make_unique<GeneratedModel>(key, v, p);
    m->set_origin(std::move(origin));
    return m;
}

}  // namespace hubbeam
