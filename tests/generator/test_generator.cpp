// The generator's stages on their own: the strict printer (golden strings), the kinematics of each model
// order against MODEL.md section 3, and the shape-function integrals against closed forms.
#include <catch2/catch.hpp>

#include "emit.hpp"
#include "energy.hpp"
#include "integrals.hpp"

using namespace GiNaC;
using namespace hubbeam;
using namespace hubbeam::gen;

namespace {

/// The runtime's argument layout (c, u, q, qd) around the test's inputs, one entry each.
Signature signature(const std::vector<Input>& params, const std::vector<Input>& vars)
{
    return {{"p", static_cast<int>(params.size()), ""}, {{"u", 1, ""}, {"q", 1, ""}, {"qd", 1, ""}}, params, vars};
}

}  // namespace

TEST_CASE("numbers print as round-trip double literals", "[emit]")
{
    CHECK(c_number(numeric(2)) == "2.0");
    CHECK(c_number(numeric(1, 10)) == "0.1");
    CHECK(c_number(numeric(1, 3)) == "0.3333333333333333");
    CHECK(c_number(numeric(-1, 100000)) == "-1e-05");
    CHECK(c_number(numeric(2, 3)) == "0.6666666666666666");
}

TEST_CASE("kernels: coefficients hoisted, monomials formed once, one write per output", "[emit]")
{
    const symbol k("k"), L("L"), x("x"), y("y");
    const std::vector<Input> params = {{k, "p[0]"}, {L, "p[1]"}};
    const std::vector<Input> vars = {{x, "q[0]"}, {y, "qd[0]"}};
    const std::vector<KernelSpec> kernels = {
        {"f", "out[3]", "test", {k * pow(x, 2) * y + 3 * x - k / pow(L, 2), ex(2), 0}},
        {"g", "out[1]", "test", {k / pow(L, 2) - k * x * x * y}}};
    const EmittedCode code = emit_kernels("t", signature(params, vars), kernels);
    CHECK(code.ncoeff == 4);  // deduplicated by text, not up to sign
    CHECK(code.constant("f") == false);
    const std::string expected_f =
        "void t_f(const double* c, const double* u, const double* q, const double* qd, double* out)\n{\n"
        "    (void)u;\n"
        "    const double x = q[0];\n"
        "    const double y = qd[0];\n"
        "    const double xsq = x*x;\n"
        "    const double xsq_y = xsq*y;\n"
        "    out[0] = c[0] + 3.0*x + c[1]*xsq_y;\n"
        "    out[1] = 2.0;\n"
        "    out[2] = 0.0;\n"
        "}\n";
    INFO(code.text);
    CHECK(code.text.find(expected_f) != std::string::npos);
    CHECK(code.text.find("    c[0] = -k/(L*L);\n    c[1] = k;\n    c[2] = k/(L*L);\n    c[3] = -k;\n") !=
          std::string::npos);
    CHECK(code.text.find("    out[0] = c[2] + c[3]*xsq_y;\n") != std::string::npos);
}

TEST_CASE("the printer refuses what it cannot print exactly", "[emit]")
{
    const symbol x("x"), k("k");
    const std::vector<Input> params = {{k, "p[0]"}};
    const std::vector<Input> vars = {{x, "q[0]"}};
    auto emit = [&](const ex& e) { return emit_kernels("t", signature(params, vars), {{"f", "out[1]", "", {e}}}); };
    CHECK_THROWS_AS(emit(sin(x)), EmitError);
    CHECK_THROWS_AS(emit(sqrt(x)), EmitError);
    CHECK_THROWS_AS(emit(1 / x), EmitError);
    CHECK_THROWS_AS(emit(symbol("unknown") * x), EmitError);
    CHECK_NOTHROW(emit(k * x + 1 / k));
}

TEST_CASE("|r_dot|^2 per model order matches MODEL.md section 3", "[energy]")
{
    const FieldSymbols f;
    const symbol w("w");
    const ex X = f.X, u1 = f.ux1, u2 = f.ux2, uy = f.uy, u1d = f.ux1_dot, u2d = f.ux2_dot, uyd = f.uy_dot;
    const ex first = pow(w, 2) * (pow(X, 2) + 2 * X * (u1 + u2) + pow(u1, 2) + pow(uy, 2)) +
                     2 * w * ((X + u1) * uyd - uy * u1d) + pow(u1d, 2) + pow(uyd, 2);
    CHECK((velocity_squared(Order::first, f, w) - first).expand().is_zero());
    CHECK((velocity_squared(Order::zero, f, w) - first.subs(u2 == 0)).expand().is_zero());
    const ex ux = u1 + u2, uxd = u1d + u2d;
    const ex full = pow(w, 2) * (pow(X + ux, 2) + pow(uy, 2)) + 2 * w * ((X + ux) * uyd - uy * uxd) + pow(uxd, 2) +
                    pow(uyd, 2);
    CHECK((velocity_squared(Order::full, f, w) - full).expand().is_zero());
}

TEST_CASE("exact integrals equal closed forms", "[integrals]")
{
    using K = Factor::Kind;
    SECTION("Bernstein products: int J_{m,i} J_{m,j} = C(m,i) C(m,j) / (C(2m,i+j) (2m+1))")
    {
        const int ny = 5, m = ny + 1;
        ShapeIntegrals in({Method::bim, Field::axial, 0}, {Method::bim, Field::transverse, ny});
        for (int i = 0; i < ny; ++i)
            for (int j = 0; j < ny; ++j) {
                const int a = i + 2, b = j + 2;  // the kept members J_{m,2..m}
                const numeric expected = numeric(binomial(m, a) * binomial(m, b)) / (binomial(2 * m, a + b) * (2 * m + 1));
                CHECK(in.integrate({{K::transverse, i, 0, 0}, {K::transverse, j, 0, 0}}, 0) == expected);
            }
    }
    SECTION("Hermite element mass: l/420 (156, 22 l, 54, -13 l, 4 l^2, -3 l^2)")
    {
        // One element (n = 1, l = 1 in xi): the root node is removed, so functions 0, 1 are N3, N4.
        ShapeIntegrals in({Method::fem, Field::axial, 0}, {Method::fem, Field::transverse, 2});
        CHECK(in.integrate({{K::transverse, 0, 0, 0}, {K::transverse, 0, 0, 0}}, 0) == numeric(156, 420));
        CHECK(in.integrate({{K::transverse, 0, 0, 0}, {K::transverse, 1, 0, 0}}, 0) == numeric(-22, 420));
        CHECK(in.integrate({{K::transverse, 1, 0, 0}, {K::transverse, 1, 0, 0}}, 0) == numeric(4, 420));
        // Element stiffness int N'' N'': 12/l^3, -6/l^2, 4/l.
        CHECK(in.integrate({{K::transverse, 0, 0, 2}, {K::transverse, 0, 0, 2}}, 0) == 12);
        CHECK(in.integrate({{K::transverse, 0, 0, 2}, {K::transverse, 1, 0, 2}}, 0) == -6);
        CHECK(in.integrate({{K::transverse, 1, 0, 2}, {K::transverse, 1, 0, 2}}, 0) == 4);
    }
    SECTION("coupling H: int_0^1 xi^p H_jk = int_0^1 (1 - xi^(p+1))/(p+1) phi_j' phi_k' (order swapped)")
    {
        for (Method method : {Method::fem, Method::bsim, Method::amm}) {
            const int ny = method == Method::fem ? 4 : 5;
            ShapeIntegrals in({method, Field::axial, 0}, {method, Field::transverse, ny});
            for (int p : {0, 1})
                for (int j = 0; j < ny; ++j)
                    for (int k = j; k < ny; ++k) {
                        const numeric lhs = in.integrate({{K::coupling, j, k, 0}}, p);
                        const numeric rhs = (in.integrate({{K::transverse, j, 0, 1}, {K::transverse, k, 0, 1}}, 0) -
                                             in.integrate({{K::transverse, j, 0, 1}, {K::transverse, k, 0, 1}}, p + 1)) /
                                            (p + 1);
                        INFO(to_string(method) << " p=" << p << " j=" << j << " k=" << k);
                        if (method == Method::amm) CHECK(std::abs((lhs - rhs).to_double()) < 1e-12 * std::abs(rhs.to_double()) + 1e-13);
                        else CHECK(lhs == rhs);
                    }
        }
    }
}
