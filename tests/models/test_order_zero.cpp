// Order zero is the conventional linear model (docs/model.md section 3): it has no foreshortening u_x2, so its
// axial displacement is the stretch alone, u_x = u_x1, at the tip (generated and assembled) and along the beam.
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <filesystem>
#include <fstream>
#include <hubbeam/field_recorder.hpp>
#include <hubbeam/fields.hpp>
#include <hubbeam/make_model.hpp>
#include <hubbeam/simulate.hpp>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "csv_file.hpp"
#include "models/generated_model.hpp"
#include "random_state.hpp"
#include "runs.hpp"

using namespace hubbeam;

namespace {

using test::Csv;
using test::read_csv;

/// 1/2 B^T H(L) B of the state q: how far the tip of a foreshortened model would be pulled in.
double tip_foreshortening(const VariantKey& key, const Parameters& p, const Eigen::VectorXd& q)
{
    const Eigen::VectorXd B = q.segment(coordinate_layout(key).first(FieldKind::inplane), key.ny);
    return 0.5 * B.dot(BeamFields(key, p).H_L() * B);
}

}  // namespace

TEST_CASE("order zero's tip has no foreshortening: u_x = u_x1, generated and assembled", "[order-zero]")
{
    const Parameters p;
    std::mt19937 rng(16);
    int zero_variants = 0;
    for (const std::string& name : generated_variant_names()) {
        const VariantKey key = VariantKey::parse(name);
        if (key.order != Order::zero) continue;
        ++zero_variants;
        for (ModelSource source : {ModelSource::generated, ModelSource::assembled}) {
            const auto model = make_model(key, p, source);
            REQUIRE(std::string(model->source()) == to_string(source));
            for (int trial = 0; trial < 5; ++trial) {
                const test::State s = test::random_state(key, rng);
                const Tip tip = model->tip(s.q.data());
                INFO(name << " " << model->source() << " trial " << trial);
                // A state whose u_x2(L) would be far above round-off, so that a foreshortened u_x shows.
                REQUIRE(tip_foreshortening(key, p, s.q) > 1e-6);
                CHECK(tip.ux == Approx(tip.ux1).epsilon(1e-14).margin(1e-18));
            }
        }
    }
    CHECK(zero_variants > 0);
}

TEST_CASE("an order-zero run's fields CSV has u_x = u_x1 along the beam", "[order-zero][fields]")
{
    // Torque 10 N m on the paper's beam with axial coordinates: u_x1 and the bending both nonzero.
    for (ModelSource source : {ModelSource::generated, ModelSource::assembled}) {
        Scene scene = test::paper_scene(Method::bim, 4, 4, test::torque(10.0));
        scene.variant.order = Order::zero;
        scene.source = source;
        scene.output.t_end = 2.0;
        scene.output.dt_out = 0.5;
        const VariantKey key = scene.key();
        const std::string path =
            (std::filesystem::temp_directory_path() / ("hubbeam_order_zero_fields_" + to_string(source) + ".csv")).string();
        Simulation sim(scene);
        REQUIRE(std::string(sim.model().source()) == to_string(source));
        FieldRecorder recorder(key, scene.parameters, {1.0, 2.0}, 9, path);
        std::map<double, Eigen::VectorXd> states;
        sim.observe_states([&](double t, const double* q) {
            recorder.state(t, q);
            states[t] = Eigen::Map<const Eigen::VectorXd>(q, key.nq());
        });
        std::vector<Row> rows;
        const RunSummary summary = sim.run([&](const Row& r) { rows.push_back(r); });
        INFO(to_string(source) << ": " << summary.failure);
        REQUIRE(summary.completed);
        REQUIRE(recorder.finish());
        for (const Row& r : rows) CHECK(r.tip_ux == r.tip_ux1);

        const Csv csv = read_csv(path);
        std::filesystem::remove(path);
        const std::size_t t = csv.column("t"), x = csv.column("x"), ux = csv.column("ux");
        const BeamFields fields(key, scene.parameters);
        REQUIRE(csv.rows.size() >= 18);
        double largest_ux1 = 0.0;
        for (const std::vector<double>& row : csv.rows) {
            INFO("t = " << row[t] << " x = " << row[x]);
            REQUIRE(states.count(row[t]) == 1);
            const Eigen::VectorXd& q = states.at(row[t]);
            const double ux1 = fields.ux1(q.data() + coordinate_layout(key).first(FieldKind::axial), row[x]);
            const double ux2 = fields.foreshortening(q.data() + coordinate_layout(key).first(FieldKind::inplane), {row[x]})[0];
            CHECK(row[ux] == ux1);
            // Where the beam is bent, the foreshortening a first-order model adds is thousands of times round-off.
            if (row[x] > 0.5 * scene.parameters.L) CHECK(std::abs(ux2) > 1e3 * 1e-16 * std::abs(ux1) + 1e-12);
            largest_ux1 = std::max(largest_ux1, std::abs(ux1));
        }
        CHECK(largest_ux1 > 0.0);
    }
}
