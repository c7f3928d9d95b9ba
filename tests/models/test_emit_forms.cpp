// The generator's two printing forms (unrolled statements, and constant tables walked by loops) compute the same
// kernels: each variant here is compiled in table form and compared kernel by kernel with its unrolled form.
#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <hubbeam/on_demand.hpp>
#include <random>
#include <string>
#include <vector>

#include "generated_abi.h"
#include "models/generated_model.hpp"
#include "random_state.hpp"

using namespace hubbeam;
using namespace hubbeam::test;
namespace fs = std::filesystem;

namespace {

/// The unrolled form: built in, else from the cache (compiled now if need be; automatic form prints these small
/// variants unrolled).
const generated::Variant& unrolled(const VariantKey& key)
{
    if (const generated::Variant* v = built_in_variant(key)) return *v;
    return *compile_variant(key);
}

double max_abs(const std::vector<double>& v)
{
    double m = 0.0;
    for (double x : v) m = std::max(m, std::abs(x));
    return m;
}

}  // namespace

TEST_CASE("table form equals unrolled form, kernel by kernel", "[generated][emit]")
{
    const fs::path dir = fs::temp_directory_path() / ("hubbeam-test-forms-" + std::to_string(::getpid()));
    Parameters p;
    p.a = 0.35;
    std::mt19937 rng(3);
    for (const char* name : {"bim_nx4_ny4_torque_first", "fem_nx4_ny4_prescribed_first", "amm_nx0_ny4_prescribed_zero",
                             "amm_nx2_ny3_prescribed_full", "fem_nx2_ny4_torque_full"}) {
        SECTION(name)
        {
            const VariantKey key = VariantKey::parse(name);
            const generated::Variant& a = unrolled(key);
            const generated::Variant& b = *compile_variant_in(key, dir / name, {"--form", "tables"});
            REQUIRE(b.ncoeff >= a.ncoeff);  // tables also pool the pure numbers
            REQUIRE(a.nterms == b.nterms);
            REQUIRE(std::string(a.mass_pattern) == b.mass_pattern);
            const int n = a.nq;
            std::vector<double> ca(static_cast<std::size_t>(a.ncoeff)), cb(static_cast<std::size_t>(b.ncoeff));
            a.coefficients(p.packed().data(), ca.data());
            b.coefficients(p.packed().data(), cb.data());
            const auto check = [&](const char* kernel, generated::Kernel ka, generated::Kernel kb, std::size_t size,
                                   const double* u, const double* q, const double* qd) {
                INFO(kernel);
                REQUIRE((ka == nullptr) == (kb == nullptr));
                if (ka == nullptr) return;
                std::vector<double> oa(size, 0.0), ob(size, 0.0);
                ka(ca.data(), u, q, qd, oa.data());
                kb(cb.data(), u, q, qd, ob.data());
                double diff = 0.0;
                for (std::size_t i = 0; i < size; ++i) diff = std::max(diff, std::abs(oa[i] - ob[i]));
                CHECK(diff <= 1e-13 * std::max(max_abs(oa), 1e-300));
            };
            for (int trial = 0; trial < 3; ++trial) {
                const State s = random_state(key, rng);
                const auto u = s.u.packed();
                const double *q = s.q.data(), *qd = s.qd.data();
                const std::size_t nn = static_cast<std::size_t>(n) * n, k = static_cast<std::size_t>(a.nterms);
                check("mass", a.mass, b.mass, nn, u.data(), q, qd);
                check("mass_varying", a.mass_varying, b.mass_varying, nn, u.data(), q, qd);
                check("forces", a.forces, b.forces, static_cast<std::size_t>(n), u.data(), q, qd);
                check("forces_terms", a.forces_terms, b.forces_terms, k, u.data(), q, qd);
                check("forces_matrix", a.forces_matrix, b.forces_matrix, static_cast<std::size_t>(n) * k, u.data(),
                      nullptr, nullptr);
                check("energy", a.energy, b.energy, 4, u.data(), q, qd);
                check("momentum", a.momentum, b.momentum, 1, u.data(), q, qd);
                check("tip", a.tip, b.tip, 3, u.data(), q, q);
                check("forces_q", a.forces_q, b.forces_q, nn, u.data(), q, qd);
                check("forces_qd", a.forces_qd, b.forces_qd, nn, u.data(), q, qd);
                check("mass_q_product", a.mass_q_product, b.mass_q_product, nn, u.data(), q, qd);
                check("forces_u", a.forces_u, b.forces_u, static_cast<std::size_t>(n) * 3, u.data(), q, qd);
            }
        }
    }
    fs::remove_all(dir);
}
