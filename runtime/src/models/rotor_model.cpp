// A rotor's model from one model per blade (rotor_model.hpp): gather each blade's coordinates, evaluate its model,
// scatter its mass and forces into the rotor's.
#include "models/rotor_model.hpp"

#include <algorithm>
#include <stdexcept>

#include <hubbeam/make_model.hpp>

#include "models/modal_damping.hpp"

namespace hubbeam {

namespace {

/// The rank of a mass pattern's character: a zero, a constant, an entry that varies.
int rank(char c)
{
    return c == 'v' ? 2 : c == 'c' ? 1 : 0;
}

}  // namespace

/// The exact Jacobian of the rotor: each blade's, scattered. The torque acts on the hub once (blade 0's input).
class RotorModel::Jacobian final : public ExactJacobian {
public:
    explicit Jacobian(const RotorModel& r) : r_(r) {}

    void force_derivatives(const HubInput& u, const double* q, const double* qd, double* dQdq, double* dQdqd,
                           double* dQdu) const override
    {
        const int n = r_.nq(), nl = r_.local_;
        const std::size_t nl2 = static_cast<std::size_t>(nl) * static_cast<std::size_t>(nl);
        std::vector<double> lq(static_cast<std::size_t>(nl)), lqd(lq.size()), a(nl2), b(nl2),
            du(static_cast<std::size_t>(nl) * drive_value_count);
        std::fill_n(dQdq, n * n, 0.0);
        std::fill_n(dQdqd, n * n, 0.0);
        std::fill_n(dQdu, n * static_cast<int>(drive_value_count), 0.0);
        for (int k = 0; k < r_.blades(); ++k) {
            r_.gather(q, k, lq.data(), true);
            r_.gather(qd, k, lqd.data(), false);
            std::fill(a.begin(), a.end(), 0.0);
            std::fill(b.begin(), b.end(), 0.0);
            std::fill(du.begin(), du.end(), 0.0);
            r_.blade(k).jacobian()->force_derivatives(r_.blade_input(u, k), lq.data(), lqd.data(), a.data(), b.data(),
                                                      du.data());
            r_.scatter_add_matrix(a.data(), k, dQdq);
            r_.scatter_add_matrix(b.data(), k, dQdqd);
            for (int i = 0; i < nl; ++i)
                for (std::size_t j = 0; j < drive_value_count; ++j) {
                    // d/dtau: the torque reaches the hub through blade 0 alone.
                    if (j == index(DriveValue::tau) && k > 0) continue;
                    dQdu[static_cast<std::size_t>(r_.global_index(k, i)) * drive_value_count + j] +=
                        du[static_cast<std::size_t>(i) * drive_value_count + j];
                }
        }
    }

    void mass_q_product(const HubInput& u, const double* q, const double* v, double* dMv) const override
    {
        const int n = r_.nq(), nl = r_.local_;
        std::vector<double> lq(static_cast<std::size_t>(nl)), lv(lq.size()),
            a(static_cast<std::size_t>(nl) * static_cast<std::size_t>(nl));
        std::fill_n(dMv, n * n, 0.0);
        for (int k = 0; k < r_.blades(); ++k) {
            r_.gather(q, k, lq.data(), true);
            r_.gather(v, k, lv.data(), false);
            std::fill(a.begin(), a.end(), 0.0);
            r_.blade(k).jacobian()->mass_q_product(r_.blade_input(u, k), lq.data(), lv.data(), a.data());
            r_.scatter_add_matrix(a.data(), k, dMv);
        }
    }

private:
    const RotorModel& r_;
};

RotorModel::RotorModel(std::vector<std::unique_ptr<Model>> blades, std::vector<double> azimuths, const Parameters& p)
    : Model(blades.at(0)->key(), coordinate_layout(blades.at(0)->key(), static_cast<int>(blades.size())), p),
      blades_(std::move(blades)),
      azimuths_(std::move(azimuths)),
      hub_(0),
      torque_(key().drive == Drive::torque),
      local_(blades_.front()->nq())
{
    if (azimuths_.size() != blades_.size()) throw std::invalid_argument("RotorModel: one azimuth per blade");
    for (const CoordinateField& f : blades_.front()->coordinates().fields)
        if (!f.basis) hub_ = f.end();
    bool exact = true;
    for (const auto& b : blades_) {
        if (!(b->key() == key())) throw std::invalid_argument("RotorModel: blades of different variants");
        exact = exact && b->jacobian() != nullptr;
    }
    const int n = nq();
    pattern_.assign(static_cast<std::size_t>(n) * static_cast<std::size_t>(n), '0');
    blade_varying_.resize(blades_.size());
    for (int k = 0; k < this->blades(); ++k) {
        const std::string local = blade(k).mass_pattern();
        for (int i = 0; i < local_; ++i)
            for (int j = 0; j < local_; ++j) {
                const int at = global_index(k, i) * n + global_index(k, j);
                char& c = pattern_[static_cast<std::size_t>(at)];
                const char l = local[static_cast<std::size_t>(i * local_ + j)];
                if (rank(l) > rank(c)) c = l;
                if (l == 'v') blade_varying_[static_cast<std::size_t>(k)].emplace_back(i * local_ + j, at);
            }
    }
    for (int at = 0; at < n * n; ++at)
        if (pattern_[static_cast<std::size_t>(at)] == 'v') varying_.push_back(at);
    // An entry that varies for one blade and is constant for another would lose the constant part in mass_varying:
    // the blades are one variant, so their patterns agree.
    for (int k = 0; k < this->blades(); ++k)
        if (blade(k).mass_pattern() != blade(0).mass_pattern())
            throw std::invalid_argument("RotorModel: blades whose mass patterns differ");
    if (exact) jacobian_ = std::make_unique<Jacobian>(*this);
}

HubInput RotorModel::blade_input(const HubInput& u, int b) const
{
    HubInput l = u;
    l.theta += azimuths_[static_cast<std::size_t>(b)];
    if (b > 0) l.tau = 0.0;
    return l;
}

void RotorModel::gather(const double* q, int b, double* local, bool angle) const
{
    for (int i = 0; i < local_; ++i) local[i] = q[global_index(b, i)];
    if (torque_ && angle) local[0] += azimuths_[static_cast<std::size_t>(b)];
}

void RotorModel::scatter_add(const double* local, int b, double* global) const
{
    for (int i = 0; i < local_; ++i) global[global_index(b, i)] += local[i];
}

void RotorModel::scatter_add_matrix(const double* local, int b, double* global) const
{
    const int n = nq();
    for (int i = 0; i < local_; ++i)
        for (int j = 0; j < local_; ++j)
            global[global_index(b, i) * n + global_index(b, j)] += local[i * local_ + j];
}

void RotorModel::mass(const HubInput& u, const double* q, double* M) const
{
    const int n = nq();
    std::vector<double> lq(static_cast<std::size_t>(local_)),
        m(static_cast<std::size_t>(local_) * static_cast<std::size_t>(local_));
    std::fill_n(M, n * n, 0.0);
    for (int b = 0; b < blades(); ++b) {
        gather(q, b, lq.data(), true);
        blade(b).mass(blade_input(u, b), lq.data(), m.data());
        scatter_add_matrix(m.data(), b, M);
    }
}

void RotorModel::mass_varying(const HubInput& u, const double* q, double* M) const
{
    // Per thread: a model is shared by the runs of several threads, and this runs at every right-hand side.
    thread_local std::vector<double> lq, m;
    lq.resize(static_cast<std::size_t>(local_));
    m.resize(static_cast<std::size_t>(local_) * static_cast<std::size_t>(local_));
    for (int at : varying_) M[at] = 0.0;
    for (int b = 0; b < blades(); ++b) {
        gather(q, b, lq.data(), true);
        blade(b).mass_varying(blade_input(u, b), lq.data(), m.data());
        for (const auto& [local, global] : blade_varying_[static_cast<std::size_t>(b)])
            M[global] += m[static_cast<std::size_t>(local)];
    }
}

void RotorModel::summed(const HubInput& u, const double* q, const double* qd, double* out,
                        void (Model::*vector)(const HubInput&, const double*, const double*, double*) const) const
{
    thread_local std::vector<double> lq, lqd, f;  // as mass_varying's
    lq.resize(static_cast<std::size_t>(local_));
    lqd.resize(lq.size());
    f.resize(lq.size());
    std::fill_n(out, nq(), 0.0);
    for (int b = 0; b < blades(); ++b) {
        gather(q, b, lq.data(), true);
        gather(qd, b, lqd.data(), false);
        (blade(b).*vector)(blade_input(u, b), lq.data(), lqd.data(), f.data());
        scatter_add(f.data(), b, out);
    }
}

void RotorModel::forces(const HubInput& u, const double* q, const double* qd, double* Q) const
{
    summed(u, q, qd, Q, &Model::forces);
}

void RotorModel::forces_theta(const HubInput& u, const double* q, const double* qd, double* dQdtheta) const
{
    summed(u, q, qd, dQdtheta, &Model::forces_theta);
}

Energy RotorModel::energy(const HubInput& u, const double* q, const double* qd) const
{
    std::vector<double> lq(static_cast<std::size_t>(local_)), lqd(lq.size());
    Energy e;
    for (int b = 0; b < blades(); ++b) {
        gather(q, b, lq.data(), true);
        gather(qd, b, lqd.data(), false);
        const Energy x = blade(b).energy(blade_input(u, b), lq.data(), lqd.data());
        e.T2 += x.T2, e.T1 += x.T1, e.T0 += x.T0, e.U += x.U;
    }
    return e;
}

double RotorModel::momentum(const HubInput& u, const double* q, const double* qd) const
{
    std::vector<double> lq(static_cast<std::size_t>(local_)), lqd(lq.size());
    double h = 0.0;
    for (int b = 0; b < blades(); ++b) {
        gather(q, b, lq.data(), true);
        gather(qd, b, lqd.data(), false);
        h += blade(b).momentum(blade_input(u, b), lq.data(), lqd.data());
    }
    return h;
}

Tip RotorModel::blade_tip(const double* q, int b) const
{
    std::vector<double> lq(static_cast<std::size_t>(local_));
    gather(q, b, lq.data(), true);
    return blade(b).tip(lq.data());
}

std::unique_ptr<Model> make_scene_model(const Scene& scene, const ModelNote& note)
{
    return make_scene_model(scene, scene.key(), note);
}

std::unique_ptr<Model> make_scene_model(const Scene& scene, const VariantKey& key, const ModelNote& note)
{
    const Rotor& r = scene.rotor;
    if (r.blades <= 1)
        return with_modal_damping(make_model(key, scene.parameters, scene.source, note), scene, scene.parameters);
    std::vector<std::unique_ptr<Model>> blades;
    std::vector<double> azimuths;
    for (int b = 0; b < r.blades; ++b) {
        const Parameters p = r.blade(scene.parameters, b);
        blades.push_back(with_modal_damping(make_model(key, p, scene.source, b == 0 ? note : ModelNote{}), scene, p));
        azimuths.push_back(r.azimuth(b));
    }
    const std::string origin = blades.front()->origin();
    auto rotor = std::make_unique<RotorModel>(std::move(blades), std::move(azimuths), scene.parameters);
    rotor->set_origin(origin);
    return rotor;
}

Tip blade_tip(const Model& model, const double* q, int b)
{
    if (const auto* r = dynamic_cast<const RotorModel*>(&model)) return r->blade_tip(q, b);
    if (b != 0) throw std::out_of_range("blade_tip: a single blade's model has blade 0 only");
    return model.tip(q);
}

int blade_count(const Model& model)
{
    const auto* r = dynamic_cast<const RotorModel*>(&model);
    return r ? r->blades() : 1;
}

}  // namespace hubbeam
