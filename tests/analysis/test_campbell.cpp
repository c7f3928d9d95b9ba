// Campbell diagrams that track their modes (linearize.hpp campbell, critical_speeds) against a computation of the
// modes here that shares no code with linearize.cpp: the steady stretch by Newton on the model's forces, the
// gyroscopic equations M q'' + G q' + K q = 0 by central differences of them, and the frequencies as the
// eigenvalues of a Hermitian matrix (the skew-symmetric first-order form of Meirovitch), each mode's kind by
// where its kinetic energy lies. The case, the paper's beam with Nx = 2 and Ny = 4 spinning up to 900 rad/s,
// has the veerings of a rotating beam's axial and in-plane bending modes: the first axial mode passes bending
// modes 4 and 3 where their coupling is weak (a sharp veering, stepped over by the rates), and bending mode 4
// veers from the second axial mode near 525 rad/s where it is strong.
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <complex>
#include <functional>
#include <map>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <hubbeam/linearize.hpp>
#include <hubbeam/make_model.hpp>

#include "eigen_oracles.hpp"

using namespace hubbeam;

namespace {

constexpr int nx = 2, ny = 4;

VariantKey campbell_key()
{
    return {.method = Method::amm, .nx = nx, .ny = ny, .order = Order::first, .drive = Drive::prescribed, .extras = {}};
}

/// One mode of the independent computation: frequency (rad/s) and the share of its kinetic energy in the axial
/// coordinates.
struct OracleMode {
    double rad_s, axial_share;
    std::string kind() const { return axial_share > 0.5 ? "axial" : "bending"; }
};

/// Q(q, qd) of the model spinning steadily at omega.
Eigen::VectorXd forces(const Model& model, double omega, const Eigen::VectorXd& q, const Eigen::VectorXd& qd)
{
    HubInput u;
    u.theta_dot = omega;
    Eigen::VectorXd Q(q.size());
    model.forces(u, q.data(), qd.data(), Q.data());
    return Q;
}

/// dQ/dx (x = q, or qd with rates = true) at (q, 0) by central differences.
Eigen::MatrixXd difference(const Model& model, double omega, const Eigen::VectorXd& q, bool rates)
{
    const Eigen::Index n = q.size();
    Eigen::MatrixXd J(n, n);
    for (Eigen::Index j = 0; j < n; ++j) {
        const double h = rates ? 1e-3 : 1e-6;  // Q is quadratic in the rates: their differences are exact
        Eigen::VectorXd plus = Eigen::VectorXd::Zero(n), minus = plus;
        plus[j] = h, minus[j] = -h;
        J.col(j) = rates ? (forces(model, omega, q, plus) - forces(model, omega, q, minus)) / (2 * h)
                         : (forces(model, omega, q + plus, Eigen::VectorXd::Zero(n)) -
                            forces(model, omega, q + minus, Eigen::VectorXd::Zero(n))) /
                               (2 * h);
    }
    return J;
}

/// The modes at spin rate omega, by increasing frequency.
std::vector<OracleMode> oracle_modes(const Model& model, double omega)
{
    const int n = nx + ny, a0 = coordinate_layout(model.key()).first(FieldKind::axial);
    // The steady stretch: Newton on the axial rows of Q with the beam straight.
    Eigen::VectorXd q = Eigen::VectorXd::Zero(n);
    for (int iteration = 0; iteration < 20; ++iteration) {
        const Eigen::VectorXd Q = forces(model, omega, q, Eigen::VectorXd::Zero(n));
        const Eigen::MatrixXd J = difference(model, omega, q, false);
        q.segment(a0, nx) -= J.block(a0, a0, nx, nx).lu().solve(Q.segment(a0, nx));
    }
    Eigen::MatrixXd M(n, n);
    HubInput u;
    u.theta_dot = omega;
    model.mass(u, q.data(), M.data());
    const Eigen::MatrixXd K = -difference(model, omega, q, false), C = -difference(model, omega, q, true);
    // Undamped and steady: K symmetric, C skew-symmetric (gyroscopic) to the differences' accuracy.
    REQUIRE((K - K.transpose()).norm() < 1e-5 * K.norm());
    REQUIRE((C + C.transpose()).norm() < 1e-5 * std::max(1.0, C.norm()));
    const Eigen::MatrixXd Ks = (K + K.transpose()) / 2, G = (C - C.transpose()) / 2;
    // D x' + H x = 0 for x = (q, q'), D = diag(K, M) positive definite, H = [[0, -K], [K, G]] skew-symmetric: with
    // D = L L^T and y = L^T x, y' = S y, S = -L^-1 H L^-T skew-symmetric, whose eigenvalues i w are those of the
    // Hermitian -i S.
    Eigen::MatrixXd D = Eigen::MatrixXd::Zero(2 * n, 2 * n), H = D;
    D.topLeftCorner(n, n) = Ks;
    D.bottomRightCorner(n, n) = (M + M.transpose()) / 2;
    H.topRightCorner(n, n) = -Ks;
    H.bottomLeftCorner(n, n) = Ks;
    H.bottomRightCorner(n, n) = G;
    const Eigen::LLT<Eigen::MatrixXd> llt(D);
    REQUIRE(llt.info() == Eigen::Success);  // below the axial divergence, K is positive definite
    const Eigen::MatrixXd L = llt.matrixL();
    const Eigen::MatrixXd Linv = L.triangularView<Eigen::Lower>().solve(Eigen::MatrixXd::Identity(2 * n, 2 * n));
    const Eigen::MatrixXd S = -Linv * H * Linv.transpose();
    const test::HermitianEigen eig =
        test::hermitian_eigen(std::complex<double>(0, -1) * S.cast<std::complex<double>>());
    std::vector<OracleMode> modes;
    for (Eigen::Index k = 0; k < 2 * n; ++k) {
        if (eig.values[k] <= 0.0) continue;  // each frequency's negative twin
        const Eigen::VectorXcd x = Linv.transpose().cast<std::complex<double>>() * eig.vectors.col(k);
        const Eigen::VectorXcd rates = x.tail(n);
        double axial = 0.0, total = 0.0;
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < n; ++j) {
                const double e = (std::conj(rates[i]) * M(i, j) * rates[j]).real();
                const bool ai = i >= a0 && i < a0 + nx, aj = j >= a0 && j < a0 + nx;
                if (ai && aj) axial += e;
                if (ai == aj) total += e;
            }
        modes.push_back({eig.values[k], axial / total});
    }
    std::sort(modes.begin(), modes.end(), [](const OracleMode& a, const OracleMode& b) { return a.rad_s < b.rad_s; });
    REQUIRE(modes.size() == static_cast<std::size_t>(n));
    return modes;
}

/// Each mode's label where every mode at that rate is clearly of one kind (60 % of its kinetic energy: the Coriolis
/// coupling grows with the spin, and at 450 rad/s the first axial mode moves a third of its energy transversely):
/// its kind and its rank among the modes of that kind. Empty where one is mixed.
std::vector<std::string> oracle_labels(const std::vector<OracleMode>& modes)
{
    std::vector<std::string> labels;
    std::map<std::string, int> count;
    for (const OracleMode& m : modes) {
        if (m.axial_share > 0.4 && m.axial_share < 0.6) return {};
        labels.push_back(m.kind() + " " + std::to_string(++count[m.kind()]));
    }
    return labels;
}

/// The rows of campbell at one rate.
std::vector<SpinMode> at_rate(const std::vector<SpinMode>& rows, double omega)
{
    std::vector<SpinMode> out;
    for (const SpinMode& r : rows)
        if (r.omega == omega) out.push_back(r);
    return out;
}

}  // namespace

TEST_CASE("tracked modes keep their shape's label where an axial mode passes bending modes", "[modes][campbell]")
{
    const Parameters p;
    const auto model = make_model(campbell_key(), p, ModelSource::generated);
    std::vector<double> omegas;
    for (double w = 0.0; w <= 450.0; w += 50.0) omegas.push_back(w);
    const std::vector<SpinMode> rows = campbell(*model, omegas);
    int clear_rates = 0;
    std::map<std::string, std::vector<int>> ranks;  // each label's frequency rank, rate by rate
    for (const double omega : omegas) {
        const std::vector<OracleMode> oracle = oracle_modes(*model, omega);
        const std::vector<SpinMode> here = at_rate(rows, omega);
        REQUIRE(here.size() == oracle.size());
        const std::vector<std::string> expected = oracle_labels(oracle);
        clear_rates += expected.empty() ? 0 : 1;
        for (std::size_t i = 0; i < here.size(); ++i) {
            INFO("Omega " << omega << " mode " << i + 1);
            CHECK(here[i].number == static_cast<int>(i + 1));
            CHECK(here[i].mode.rad_s == Approx(oracle[i].rad_s).epsilon(1e-6));
            CHECK(here[i].mode.kind == oracle[i].kind());
            if (!expected.empty()) CHECK(here[i].label == expected[i]);
            if (omega > 0.0) CHECK(here[i].mac > 0.9);  // the rates resolve every line
            ranks[here[i].label].push_back(here[i].number);
        }
    }
    CHECK(clear_rates == static_cast<int>(omegas.size()));
    // Not frequency order in disguise: the first axial mode is the fifth at rest and the third at 450 rad/s.
    CHECK(ranks["axial 1"].front() == 5);
    CHECK(ranks["axial 1"].back() == 3);
    CHECK(std::isnan(rows.front().mac));  // a line's first rate has no MAC
}

TEST_CASE("through a veering the rates resolve, a tracked mode follows its branch as its shape turns", "[modes][campbell]")
{
    const Parameters p;
    const auto model = make_model(campbell_key(), p, ModelSource::generated);
    // The oracle shows the veering: modes 5 and 6 come within a small gap between 450 and 650 rad/s without
    // crossing, and exchange their kinds.
    std::vector<double> omegas, gaps;
    for (double w = 450.0; w <= 650.0; w += 5.0) {
        omegas.push_back(w);
        const std::vector<OracleMode> m = oracle_modes(*model, w);
        gaps.push_back(m[5].rad_s - m[4].rad_s);
    }
    const auto narrowest = std::min_element(gaps.begin(), gaps.end()) - gaps.begin();
    REQUIRE(narrowest > 0);
    REQUIRE(narrowest + 1 < static_cast<long>(gaps.size()));
    REQUIRE(gaps[static_cast<std::size_t>(narrowest)] > 0.0);
    REQUIRE(oracle_modes(*model, omegas.front())[4].kind() == "bending");
    REQUIRE(oracle_modes(*model, omegas.back())[4].kind() == "axial");
    // hubbeam's lines stay on the branches: the fifth mode keeps its label all the way, and its kind turns.
    const std::vector<SpinMode> rows = campbell(*model, omegas);
    std::string label;
    for (const SpinMode& r : rows) {
        if (r.number != 5) continue;
        INFO("Omega " << r.omega);
        if (label.empty()) label = r.label;
        CHECK(r.label == label);
        if (r.omega > omegas.front()) CHECK(r.mac > 0.5);
    }
    CHECK(label.rfind("bending ", 0) == 0);
    CHECK(at_rate(rows, omegas.back())[4].mode.kind == "axial");
}

TEST_CASE("critical speeds are where a tracked mode meets n times the spin rate", "[modes][campbell]")
{
    const Parameters p;
    const auto model = make_model(campbell_key(), p, ModelSource::generated);
    std::vector<double> omegas;
    for (double w = 0.0; w <= 450.0; w += 50.0) omegas.push_back(w);
    const std::vector<CriticalSpeed> speeds = critical_speeds(*model, campbell(*model, omegas), {1, 2, 3});
    // The oracle's: bisection on the frequency of the lowest mode (bending 1, with nothing near it) and of the
    // mode whose kinetic energy is mostly axial (axial 1), minus n Omega.
    const auto crossing = [&](const std::function<double(double)>& frequency, int n, double lo, double hi) {
        for (int k = 0; k < 60; ++k) {
            const double mid = 0.5 * (lo + hi);
            ((frequency(lo) - n * lo) * (frequency(mid) - n * mid) <= 0.0 ? hi : lo) = mid;
        }
        return 0.5 * (lo + hi);
    };
    const auto lowest = [&](double w) { return oracle_modes(*model, w).front().rad_s; };
    const auto axial = [&](double w) {
        for (const OracleMode& m : oracle_modes(*model, w))
            if (m.kind() == "axial") return m.rad_s;
        return 0.0;
    };
    std::vector<std::pair<std::string, int>> expected = {{"bending 1", 1}, {"bending 1", 2}, {"bending 1", 3},
                                                         {"axial 1", 3}};
    for (const auto& [label, n] : expected) {
        INFO(label << " meets " << n << "P");
        const auto found = std::find_if(speeds.begin(), speeds.end(),
                                        [&](const CriticalSpeed& c) { return c.label == label && c.harmonic == n; });
        REQUIRE(found != speeds.end());
        const double omega = label == "axial 1" ? crossing(axial, n, 350.0, 450.0) : crossing(lowest, n, 0.0, 50.0);
        CHECK(found->omega == Approx(omega).epsilon(1e-7));
        CHECK(found->rad_s == Approx(n * omega).epsilon(1e-7));
    }
    // bending 2 stays above 3 Omega up to 450 rad/s once past its crossing at about 9.7 rad/s, and the others
    // stay above it: every other crossing is one of bending 2's at low speed.
    for (const CriticalSpeed& c : speeds)
        if (std::find(expected.begin(), expected.end(), std::pair{c.label, c.harmonic}) == expected.end()) {
            INFO(c.label << " " << c.harmonic << "P at " << c.omega);
            CHECK(c.label == "bending 2");
        }
}

namespace {

/// The largest sum of scores over the matchings of min(rows, cols) pairs, by trying every one.
double best_sum(const Eigen::MatrixXd& score, Eigen::Index row, std::vector<bool>& used)
{
    if (row == score.rows()) return 0.0;
    double best = -1.0;
    for (Eigen::Index c = 0; c < score.cols(); ++c) {
        if (used[static_cast<std::size_t>(c)]) continue;
        used[static_cast<std::size_t>(c)] = true;
        best = std::max(best, score(row, c) + best_sum(score, row + 1, used));
        used[static_cast<std::size_t>(c)] = false;
    }
    if (score.rows() > score.cols()) best = std::max(best, best_sum(score, row + 1, used));  // the row left over
    return best;
}

}  // namespace

TEST_CASE("the modes' pairing is the assignment of the largest total MAC, square or not", "[campbell]")
{
    std::mt19937 random(7);
    std::uniform_real_distribution<double> mac(0.0, 1.0);
    for (int trial = 0; trial < 500; ++trial) {
        const auto rows = static_cast<Eigen::Index>(1 + random() % 6), cols = static_cast<Eigen::Index>(1 + random() % 6);
        Eigen::MatrixXd score(rows, cols);
        for (Eigen::Index i = 0; i < rows; ++i)
            for (Eigen::Index j = 0; j < cols; ++j) score(i, j) = mac(random);
        const std::vector<int> column = best_assignment(score);
        REQUIRE(column.size() == static_cast<std::size_t>(rows));
        std::vector<bool> taken(static_cast<std::size_t>(cols), false);
        double sum = 0.0;
        int pairs = 0;
        for (Eigen::Index i = 0; i < rows; ++i) {
            const int c = column[static_cast<std::size_t>(i)];
            if (c < 0) continue;
            REQUIRE(c < cols);
            CHECK_FALSE(taken[static_cast<std::size_t>(c)]);  // each column once
            taken[static_cast<std::size_t>(c)] = true;
            sum += score(i, c);
            ++pairs;
        }
        CHECK(pairs == std::min(rows, cols));
        std::vector<bool> used(static_cast<std::size_t>(cols), false);
        CHECK(sum == Approx(best_sum(score, 0, used)).epsilon(1e-12));
    }
}
