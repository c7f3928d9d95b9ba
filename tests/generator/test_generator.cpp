// The generator's stages on their own: the strict printer (golden strings), the kinematics of each model
// order against docs/model.md section 3, the shape-function integrals against closed forms, and the Poly route of
// Lagrange's equations against GiNaC's differentiation.
#include <catch2/catch.hpp>
#include <algorithm>

#include "emit.hpp"
#include "energy.hpp"
#include "integrals.hpp"
#include "lagrange.hpp"

using namespace GiNaC;
using namespace hubbeam;
using namespace hubbeam::gen;

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
    const Signature sig{{"p", 2, "p = (k, L)"}, {{"u", 3, ""}, {"q", 1, ""}, {"qd", 1, ""}}, {{k, "p[0]"}, {L, "p[1]"}},
                        {{x, "q[0]"}, {y, "qd[0]"}}};
    const std::vector<KernelSpec> kernels = {
        {"f", "out[3]", "test", {k * pow(x, 2) * y + 3 * x - k / pow(L, 2), ex(2), 0}},
        {"g", "out[1]", "test", {k / pow(L, 2) - k * x * x * y}}};
    const EmittedCode code = emit_kernels("t", sig, kernels);
    CHECK(code.ncoeff == 2);  // -k/L^2 and k/L^2 share c[0], k and -k share c[1]
    CHECK(code.constant("f") == false);
    const std::string expected_f =
        "void t_f(const double* c, const double* u, const double* q, const double* qd, double* out)\n{\n"
        "    (void)u;\n"
        "    const double x = q[0];\n"
        "    const double y = qd[0];\n"
        "    const double xsq = x*x;\n"
        "    const double xsq_y = xsq*y;\n"
        "    out[0] = -c[0] + 3.0*x + c[1]*xsq_y;\n"
        "    out[1] = 2.0;\n"
        "    out[2] = 0.0;\n"
        "}\n";
    INFO(code.text);
    CHECK(code.text.find(expected_f) != std::string::npos);
    CHECK(code.text.find("    c[0] = k/(L*L);\n    c[1] = k;\n}\n") != std::string::npos);
    CHECK(code.text.find("    out[0] = c[0] - c[1]*xsq_y;\n") != std::string::npos);
}

TEST_CASE("a kernel of every right-hand side stays unrolled up to its own threshold", "[emit]")
{
    const symbol k("k"), x("x"), y("y");
    const Signature sig{{"p", 1, ""}, {{"q", 1, ""}, {"qd", 1, ""}}, {{k, "p[0]"}}, {{x, "q[0]"}, {y, "qd[0]"}}};
    const ex five_terms = k * x + k * y + k * x * y + k * x * x + k * y * y;
    EmitOptions options;
    options.table_threshold = 4;
    options.rhs_table_threshold = 5;
    const auto tables = [&](bool every_right_hand_side, int rhs_threshold) {
        KernelSpec spec{"f", "out[1]", "", {five_terms}};
        spec.every_right_hand_side = every_right_hand_side;
        options.rhs_table_threshold = rhs_threshold;
        const EmittedCode code = emit_kernels("t", sig, {spec}, options);
        return code.text.find("Table form") != std::string::npos;
    };
    CHECK(tables(false, 5));  // five terms, above the threshold of 4
    CHECK_FALSE(tables(true, 5));
    CHECK(tables(true, 4));
}

TEST_CASE("the printer refuses what it cannot print exactly", "[emit]")
{
    const symbol x("x"), k("k");
    const Signature sig{{"p", 1, ""}, {{"q", 1, ""}}, {{k, "p[0]"}}, {{x, "q[0]"}}};
    auto emit = [&](const ex& e) { return emit_kernels("t", sig, {{"f", "out[1]", "", {e}}}); };
    CHECK_THROWS_AS(emit(sin(x)), EmitError);
    CHECK_THROWS_AS(emit(sqrt(x)), EmitError);
    CHECK_THROWS_AS(emit(1 / x), EmitError);
    CHECK_THROWS_AS(emit(symbol("unknown") * x), EmitError);
    CHECK_NOTHROW(emit(k * x + 1 / k));
}

TEST_CASE("|r_dot|^2 per model order matches docs/model.md sections 3 and 12", "[energy]")
{
    // The reference is derived here, not transcribed: r = Theta(theta) p with p = a i + (x + u_x) e1 + u_y e2 + u_z e3,
    // e1 = cos(b) i + sin(b) k, e3 = -sin(b) i + cos(b) k (docs/model.md sections 2 and 12, b the precone),
    // differentiated in time by GiNaC through the chain rule, d/dt = sum_k qdot_k d/dq_k over
    // q = (theta, u_x1, u_y, u_z, u_x2) with rates (w, u_x1_dot, u_y_dot, u_z_dot, u_x2_dot); X = a + x is fixed.
    const FieldSymbols f;
    const symbol theta("theta"), w("w"), a("a"), b("b");
    const ex ux = f.ux1 + f.ux2;
    const ex p[3] = {a + (f.X - a + ux) * cos(b) - f.uz * sin(b), f.uy, (f.X - a + ux) * sin(b) + f.uz * cos(b)};
    const ex c = cos(theta), s = sin(theta);
    const ex r[3] = {c * p[0] - s * p[1], s * p[0] + c * p[1], p[2]};
    const std::pair<symbol, ex> rates[] = {
        {theta, w}, {f.ux1, f.ux1_dot}, {f.uy, f.uy_dot}, {f.uz, f.uz_dot}, {f.ux2, f.ux2_dot}};
    ex v2 = 0;
    for (int i = 0; i < 3; ++i) {
        ex r_dot = 0;
        for (const auto& [coordinate, rate] : rates) r_dot += r[i].diff(coordinate) * rate;
        v2 += pow(r_dot, 2);
    }
    // cos^2 + sin^2 = 1 applied to theta and to the precone: what remains must be free of theta.
    const auto simplified = [](const ex& e, const ex& angle) {
        return e.expand().subs(pow(sin(angle), 2) == 1 - pow(cos(angle), 2), subs_options::algebraic).expand();
    };
    const ex v2_cone = simplified(simplified(v2, theta), b);
    REQUIRE_FALSE(v2_cone.has(theta));
    // Order `first` keeps degrees 0..2 in the deformation, u_x1, u_y, u_z and their rates counting 1, u_x2 and its
    // rate 2 (docs/model.md sections 3 and 12); order `zero` is `first` without the foreshortening.
    const symbol eps("eps");
    const auto first = [&](const ex& e) {
        const ex scaled = e.subs(lst{f.ux1 == eps * f.ux1, f.uy == eps * f.uy, f.uz == eps * f.uz,
                                     f.ux1_dot == eps * f.ux1_dot, f.uy_dot == eps * f.uy_dot, f.uz_dot == eps * f.uz_dot,
                                     f.ux2 == pow(eps, 2) * f.ux2, f.ux2_dot == pow(eps, 2) * f.ux2_dot})
                             .expand();
        ex kept = 0;
        for (int k = 0; k <= 2; ++k) kept += scaled.coeff(eps, k);
        return kept;
    };
    const auto zero = [&](const ex& e) { return e.subs(lst{f.ux2 == 0, f.ux2_dot == 0}); };
    const Cone cone{cos(b), sin(b), a};
    const auto same = [&b](const ex& x, const ex& y) {
        return (x - y).expand().subs(pow(sin(b), 2) == 1 - pow(cos(b), 2), subs_options::algebraic).expand().is_zero();
    };
    CHECK(same(velocity_squared(Order::full, f, w, cone), v2_cone));
    CHECK(same(velocity_squared(Order::first, f, w, cone), first(v2_cone)));
    CHECK(same(velocity_squared(Order::zero, f, w, cone), zero(first(v2_cone))));

    // The plane (b = 0, u_z = 0): section 3's integrand. The truncation drops something (the terms section 3
    // lists), and the foreshortening reaches `first` only through the centrifugal term 2 w^2 X u_x2.
    const ex v2_full = v2_cone.subs(lst{b == 0, f.uz == 0, f.uz_dot == 0});
    INFO("|r_dot|^2 = " << v2_full);
    const ex v2_first = first(v2_full), v2_zero = zero(v2_first);
    REQUIRE_FALSE((v2_full - v2_first).expand().is_zero());
    CHECK((v2_first - v2_zero - 2 * pow(w, 2) * f.X * f.ux2).expand().is_zero());
    const auto planar = [&](const ex& e) { return e.subs(lst{f.uz == 0, f.uz_dot == 0}); };
    CHECK((planar(velocity_squared(Order::full, f, w)) - v2_full).expand().is_zero());
    CHECK((planar(velocity_squared(Order::first, f, w)) - v2_first).expand().is_zero());
    CHECK((planar(velocity_squared(Order::zero, f, w)) - v2_zero).expand().is_zero());
    // With no precone the flapwise rate only adds its own square (no -Omega^2 softening, section 12).
    CHECK((velocity_squared(Order::first, f, w) - planar(velocity_squared(Order::first, f, w)) - pow(f.uz_dot, 2))
              .expand()
              .is_zero());
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

TEST_CASE("AMM integrals that vanish by orthogonality are exact zeros, the others are kept", "[integrals]")
{
    // Clamped-free modes are orthonormal in L2 and their second derivatives orthogonal (docs/model.md
    // section 4): quadrature leaves ~1e-17 there, which the cancellation bound turns into an exact zero, so
    // that M2 and K2 come out diagonal. Integrals with a weight (xi, the coupling H) are not zero and stay.
    using K = Factor::Kind;
    ShapeIntegrals in({Method::amm, Field::axial, 4}, {Method::amm, Field::transverse, 6});
    for (int i = 0; i < 6; ++i)
        for (int j = 0; j < 6; ++j) {
            INFO("i=" << i << " j=" << j);
            const numeric mass = in.integrate({{K::transverse, i, 0, 0}, {K::transverse, j, 0, 0}}, 0);
            const numeric stiffness = in.integrate({{K::transverse, i, 0, 2}, {K::transverse, j, 0, 2}}, 0);
            if (i == j) {
                CHECK(std::abs(mass.to_double() - 1.0) < 1e-12);
                CHECK(stiffness.to_double() > 0.0);
            } else {
                CHECK(mass.is_zero());
                CHECK(stiffness.is_zero());
                CHECK_FALSE(in.integrate({{K::transverse, i, 0, 0}, {K::transverse, j, 0, 0}}, 1).is_zero());
            }
        }
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            CHECK(in.integrate({{K::axial, i, 0, 0}, {K::axial, j, 0, 0}}, 0).is_zero() == (i != j));
    CHECK_FALSE(in.integrate({{K::coupling, 0, 1, 0}}, 0).is_zero());
}

TEST_CASE("Lagrange's equations on Polys equal GiNaC's differentiation of the same energies", "[poly][lagrange]")
{
    // The generator differentiates Polys (poly.cpp); GiNaC's diff of the same T and U is the oracle. Exact equality:
    // both are exact rational arithmetic.
    for (const char* name : {"bim_nx2_ny3_torque_full", "fem_nx2_ny4_prescribed_full", "amm_nx1_ny2_prescribed_first"}) {
        INFO(name);
        const hubbeam::VariantKey key = hubbeam::VariantKey::parse(name);
        const Symbols s(key);
        const bool torque = key.drive == hubbeam::Drive::torque;
        const std::vector<symbol> parameters = {s.L, s.m, s.EI, s.ES, s.a, s.J_oh};
        std::vector<symbol> variables;
        if (torque) variables = {s.tau};
        else variables = {s.theta_dot, s.theta_ddot};
        variables.insert(variables.end(), s.q.begin(), s.q.end());
        variables.insert(variables.end(), s.qd.begin(), s.qd.end());
        const auto index = [&](const symbol& x) {
            return static_cast<int>(std::find_if(variables.begin(), variables.end(), [&](const symbol& v) { return v == x; }) -
                                    variables.begin());
        };
        const PolyReader read(parameters, variables);
        const Energies en = derive_energies(key, s, read);

        PolyCoordinates pc;
        Coordinates ec;
        for (const symbol& x : s.q) pc.q.push_back(index(x));
        for (const symbol& x : s.qd) pc.qd.push_back(index(x));
        ec.q = s.q;
        ec.qd = s.qd;
        pc.force.resize(s.q.size());
        ec.force.assign(s.q.size(), 0);
        if (torque) {
            pc.force[0] = read(s.tau);
            ec.force[0] = s.tau;
            pc.spin = index(s.theta_dot);
        } else {
            pc.driven.emplace_back(index(s.theta_dot), index(s.theta_ddot));
            ec.driven.emplace_back(s.theta_dot, s.theta_ddot);
            pc.spin = index(s.theta_dot);
        }
        ec.spin = s.theta_dot;
        const PolyEquations p = lagrange(en.T, en.U, pc);
        const Equations e = lagrange(to_ex(en.T, parameters, variables), to_ex(en.U, parameters, variables), ec);
        const auto same = [&](const Poly& x, const ex& y) { return (to_ex(x, parameters, variables) - y).expand().is_zero(); };
        for (std::size_t i = 0; i < e.M.size(); ++i) CHECK(same(p.M[i], e.M[i]));
        for (std::size_t i = 0; i < e.Q.size(); ++i) CHECK(same(p.Q[i], e.Q[i]));
        CHECK(same(p.T2, e.T2));
        CHECK(same(p.T1, e.T1));
        CHECK(same(p.T0, e.T0));
        CHECK(same(p.momentum, e.momentum));
        // and the energies themselves are nontrivial
        CHECK(!p.Q.back().is_zero());
        CHECK(!p.T2.is_zero());
    }
}
