// Energies by substitution of the discretized fields into the field-level energy densities and
// term-by-term integration over the beam.
#include "energy.hpp"

#include <algorithm>
#include <map>
#include <set>
#include <stdexcept>
#include <string>

#include "generator_terms.hpp"
#include "terms.hpp"

namespace hubbeam::gen {

using namespace GiNaC;

namespace {

std::vector<symbol> numbered(const std::string& stem, int n, const std::string& suffix = "")
{
    std::vector<symbol> v;
    for (int i = 1; i <= n; ++i) v.emplace_back(stem + std::to_string(i) + suffix);
    return v;
}

/// One term of a field's expansion at an abscissa: coefficient * variable monomial (over the PolyReader's
/// variables) * prod(factors)(xi).
struct Term {
    Exponents monomial;
    Coefficient coefficient;
    std::vector<Factor> factors;
};
using Expansion = std::vector<Term>;

/// The product of two parameter coefficients.
Coefficient product(const Coefficient& x, const Coefficient& y)
{
    Coefficient p;
    for (const auto& [px, nx] : x)
        for (const auto& [py, ny] : y) {
            Exponents e = px;
            for (std::size_t i = 0; i < e.size(); ++i) e[i] += py[i];
            auto [it, added] = p.emplace(std::move(e), nx * ny);
            if (!added) {
                it->second += nx * ny;
                if (it->second.is_zero()) p.erase(it);
            }
        }
    return p;
}

/// The sum of two parameter coefficients.
Coefficient sum(Coefficient x, const Coefficient& y)
{
    for (const auto& [pe, n] : y) {
        auto [it, added] = x.emplace(pe, n);
        if (!added) {
            it->second += n;
            if (it->second.is_zero()) x.erase(it);
        }
    }
    return x;
}

/// The single term of a monomial expression read as a Poly.
Term single_term(const PolyReader& read, const ex& e, std::vector<Factor> factors)
{
    const Poly p = read(e);
    if (p.terms().size() != 1) throw std::logic_error("energy: a field term is not one monomial");
    const auto& [monomial, coefficient] = *p.terms().begin();
    return {monomial, coefficient, std::move(factors)};
}

/// Integrates an energy density over the beam: int_0^L density dx with x = L xi and every field symbol
/// replaced by its expansion in shape functions, straight into a Poly (the Cartesian products of the fields'
/// expansions reach 10^5 terms for order full; as GiNaC products they cost seconds).
class DensityIntegrator {
public:
    /// found: where a first pass collects the section integrals the energies meet (Symbols::section_keys), or null.
    DensityIntegrator(const Symbols& s, const FieldSymbols& f, const VariantKey& key, ShapeIntegrals& integrals,
                      const PolyReader& read, std::set<SectionKey>* found)
        : s_(s), f_(f), integrals_(integrals), read_(read), found_(found)
    {
        const CoordinateLayout layout = coordinate_layout(key);
        expand_axial(layout);
        expand_inplane(layout);
        expand_flap(layout);
        expand_twist(layout);
        merge_symmetric_couplings();
        expand_sections(key);
        // Present (possibly empty) so that nx = 0 (or a planar variant's missing fields) makes their terms vanish.
        for (const symbol& absent : {f.ux1, f.ux1_dot, f.ux1_x, f.ux1_x_dot, f.uz, f.uz_dot, f.uz_x, f.uz_xx,
                                     f.uz_xx_dot, f.phi, f.phi_dot, f.phi_x, f.phi_x_dot})
            fields_[absent];
        if (f.offsets) fields_[f.offsets->uz_x_dot];
    }

    /// int_0^L density dx.
    Poly operator()(const ex& density) { return evaluate(density, false); }
    /// The density at x = L (a tip body's energies): no integral.
    Poly at_tip(const ex& density) { return evaluate(density, true); }

private:
    /// Adds one term of field's expansion: coef (coordinates over powers of L) times a factor of shape functions.
    void add(const symbol& field, const ex& coef, const Factor& factor)
    {
        fields_[field].push_back(single_term(read_, coef, {factor}));
    }

    /// The axial field's expansion: u_x1, its rate and their slopes.
    void expand_axial(const CoordinateLayout& layout)
    {
        const Symbols& s = s_;
        const FieldSymbols& f = f_;
        using K = Factor::Kind;
        const ex inv_L = 1 / s.L;
        for (int i = 0; i < layout.count(FieldKind::axial); ++i) {
            add(f.ux1, s.A[i], {K::axial, i, 0, 0});
            add(f.ux1_dot, s.A_dot[i], {K::axial, i, 0, 0});
            add(f.ux1_x, s.A[i] * inv_L, {K::axial, i, 0, 1});
            add(f.ux1_x_dot, s.A_dot[i] * inv_L, {K::axial, i, 0, 1});
        }
    }

    /// The in-plane field's expansion: u_y, its rate, slopes and curvatures, and its foreshortening u_x2.
    void expand_inplane(const CoordinateLayout& layout)
    {
        const Symbols& s = s_;
        const FieldSymbols& f = f_;
        using K = Factor::Kind;
        const ex inv_L = 1 / s.L;
        const int ny = layout.count(FieldKind::inplane);
        for (int j = 0; j < ny; ++j) {
            add(f.uy, s.B[j], {K::transverse, j, 0, 0});
            add(f.uy_dot, s.B_dot[j], {K::transverse, j, 0, 0});
            add(f.uy_xx, s.B[j] * pow(inv_L, 2), {K::transverse, j, 0, 2});
            add(f.uy_x, s.B[j] * inv_L, {K::transverse, j, 0, 1});
            add(f.uy_x_dot, s.B_dot[j] * inv_L, {K::transverse, j, 0, 1});
            add(f.uy_xx_dot, s.B_dot[j] * pow(inv_L, 2), {K::transverse, j, 0, 2});
            // u_x2 = -1/2 B^T H(x) B with H in x units = H_xi / L; its rate is -B^T H B_dot (H symmetric).
            for (int k = 0; k < ny; ++k) {
                add(f.ux2, -s.B[j] * s.B[k] * inv_L / 2, {K::coupling, j, k, 0});
                add(f.ux2_dot, -s.B[j] * s.B_dot[k] * inv_L, {K::coupling, j, k, 0});
            }
        }
    }

    /// The flapwise field's expansion (docs/model.md section 12).
    void expand_flap(const CoordinateLayout& layout)
    {
        const Symbols& s = s_;
        const FieldSymbols& f = f_;
        using K = Factor::Kind;
        const ex inv_L = 1 / s.L;
        // Like the in-plane one, and its slope shortens the beam too.
        const int nz = layout.count(FieldKind::flap);
        for (int j = 0; j < nz; ++j) {
            add(f.uz, s.Z[j], {K::flap, j, 0, 0});
            add(f.uz_dot, s.Z_dot[j], {K::flap, j, 0, 0});
            add(f.uz_x, s.Z[j] * inv_L, {K::flap, j, 0, 1});
            add(f.uz_xx, s.Z[j] * pow(inv_L, 2), {K::flap, j, 0, 2});
            add(f.uz_xx_dot, s.Z_dot[j] * pow(inv_L, 2), {K::flap, j, 0, 2});
            if (f.offsets) add(f.offsets->uz_x_dot, s.Z_dot[j] * inv_L, {K::flap, j, 0, 1});
            for (int k = 0; k < nz; ++k) {
                add(f.ux2, -s.Z[j] * s.Z[k] * inv_L / 2, {K::flap_coupling, j, k, 0});
                add(f.ux2_dot, -s.Z[j] * s.Z_dot[k] * inv_L, {K::flap_coupling, j, k, 0});
            }
        }
    }

    /// The twist field's expansion: phi, its rate and their slopes.
    void expand_twist(const CoordinateLayout& layout)
    {
        const Symbols& s = s_;
        const FieldSymbols& f = f_;
        using K = Factor::Kind;
        const ex inv_L = 1 / s.L;
        for (int i = 0; i < layout.count(FieldKind::twist); ++i) {
            add(f.phi, s.P[i], {K::twist, i, 0, 0});
            add(f.phi_dot, s.P_dot[i], {K::twist, i, 0, 0});
            add(f.phi_x, s.P[i] * inv_L, {K::twist, i, 0, 1});
            add(f.phi_x_dot, s.P_dot[i] * inv_L, {K::twist, i, 0, 1});
        }
    }

    /// The couplings' terms merged where H's symmetry makes two one.
    void merge_symmetric_couplings()
    {
        using K = Factor::Kind;
        // H is symmetric: B_j B_k H_jk and B_k B_j H_kj are one term (halves u_x2's expansion, quarters its square).
        for (auto& [field, expansion] : fields_) {
            std::map<std::pair<Exponents, std::vector<Factor>>, Coefficient> merged;
            for (Term& t : expansion) {
                for (Factor& factor : t.factors)
                    if ((factor.kind == K::coupling || factor.kind == K::flap_coupling) && factor.i > factor.j)
                        std::swap(factor.i, factor.j);
                Coefficient& c = merged[{t.monomial, t.factors}];
                c = sum(c, t.coefficient);
            }
            expansion.clear();
            for (auto& [key, c] : merged)
                if (!c.empty()) expansion.push_back({key.first, c, key.second});
        }
    }

    /// A profile's distributions along the beam, or a pre-twist's cos and sin: each a factor whose integrals against
    /// the basis are run-time data.
    void expand_sections(const VariantKey& key)
    {
        const FieldSymbols& f = f_;
        using D = SectionDistribution;
        const auto distribution = [&](const symbol& field, D d) {
            add(field, 1, {Factor::Kind::section, static_cast<int>(d), 0, 0});
        };
        if (key.extras.twist) {
            distribution(f.cos_2twist_x, D::cos_2twist);
            distribution(f.sin_2twist_x, D::sin_2twist);
        }
        if (!key.extras.profile()) return;
        distribution(f.m_x, D::m);
        distribution(f.EI_x, D::EI);
        distribution(f.ES_x, D::ES);
        if (!s_.o) return;
        distribution(f.EI_flap_x, D::EI_flap);
        distribution(f.GJ_x, D::GJ);
        distribution(f.j_p_x, D::j_p);
        distribution(f.EI_cos_x, D::EI_cos);
        distribution(f.EI_sin_x, D::EI_sin);
        distribution(f.j_cos_x, D::j_cos);
        distribution(f.j_sin_x, D::j_sin);
        if (!key.extras.offsets) return;
        distribution(f.offsets->mass_offset_cos_x, D::mass_offset_cos);
        distribution(f.offsets->mass_offset_sin_x, D::mass_offset_sin);
        distribution(f.offsets->tension_offset_cos_x, D::tension_offset_cos);
        distribution(f.offsets->tension_offset_sin_x, D::tension_offset_sin);
        distribution(f.offsets->mass_offset2_x, D::mass_offset2);
        distribution(f.offsets->mass_offset2_cos_x, D::mass_offset2_cos);
        distribution(f.offsets->mass_offset2_sin_x, D::mass_offset2_sin);
    }

    Poly evaluate(const ex& density, bool tip)
    {
        const symbol& xi = f_.xi;
        const ex d = density.subs(f_.X == s_.a + s_.L * xi).subs(xi == (tip ? ex(1) : ex(xi))).expand();
        Poly sum;
        for (const ex& term : is_a<GiNaC::add>(d) ? d : lst{d}) {
            ex coef = tip ? ex(1) : ex(s_.L);  // dx = L dxi
            int xi_power = 0;
            std::vector<const Expansion*> occurrences;
            for (const ex& factor : is_a<mul>(term) ? term : lst{term}) {
                const ex base = is_a<power>(factor) ? factor.op(0) : factor;
                const int n = is_a<power>(factor) ? ex_to<numeric>(factor.op(1)).to_int() : 1;
                if (base.is_equal(xi)) {
                    xi_power += n;
                } else if (auto it = fields_.find(base); it != fields_.end()) {
                    for (int r = 0; r < n; ++r) occurrences.push_back(&it->second);
                } else {
                    coef *= factor;
                }
            }
            // Every combination of one term per occurring field: monomials multiply, shape factors integrate.
            Term start = single_term(read_, coef, {});
            std::vector<std::size_t> chosen;
            expand(sum, occurrences, start, tip ? -1 : xi_power, chosen);
        }
        return sum;
    }

    /// Adds every combination of one term per remaining occurrence. A field that occurs r times (u_x2^2) is
    /// expanded as a multiset, chosen indices non-decreasing, each combination weighted by its number of orderings.
    /// xi_power -1: the product at the tip instead of the integral.
    void expand(Poly& sum, const std::vector<const Expansion*>& occurrences, const Term& partial, int xi_power,
                std::vector<std::size_t>& chosen)
    {
        const std::size_t next = chosen.size();
        if (next == occurrences.size() && has_section(partial.factors)) {
            add_section_integral(sum, partial, xi_power, orderings(occurrences, chosen));
            return;
        }
        if (next == occurrences.size()) {
            const numeric shape =
                xi_power < 0 ? integrals_.at_tip(partial.factors) : integrals_.integrate(partial.factors, xi_power);
            const numeric value = shape * orderings(occurrences, chosen);
            if (!value.is_zero()) sum.add(partial.monomial, partial.coefficient, value);
            return;
        }
        const bool repeat = next > 0 && occurrences[next] == occurrences[next - 1];
        const Expansion& e = *occurrences[next];
        for (std::size_t i = repeat ? chosen.back() : 0; i < e.size(); ++i) {
            const Term& t = e[i];
            Term p{partial.monomial, product(partial.coefficient, t.coefficient), partial.factors};
            for (std::size_t v = 0; v < p.monomial.size(); ++v) p.monomial[v] += t.monomial[v];
            p.factors.insert(p.factors.end(), t.factors.begin(), t.factors.end());
            chosen.push_back(i);
            expand(sum, occurrences, p, xi_power, chosen);
            chosen.pop_back();
        }
    }

    static bool has_section(const std::vector<Factor>& factors)
    {
        return std::any_of(factors.begin(), factors.end(),
                           [](const Factor& f) { return f.kind == Factor::Kind::section; });
    }

    /// A term whose integral holds a section distribution: its run-time integral's symbol s_n times the term's
    /// coefficient (or, in the first pass, the integral's key collected).
    void add_section_integral(Poly& sum, const Term& partial, int xi_power, const numeric& weight)
    {
        if (xi_power < 0) throw std::logic_error("energy: a section distribution at the tip");
        SectionKey key{-1, xi_power, {}};
        for (const Factor& f : partial.factors) {
            if (f.kind != Factor::Kind::section) {
                key.factors.push_back(f);
            } else if (key.distribution >= 0) {
                throw std::logic_error("energy: a product of two section distributions");
            } else {
                key.distribution = f.i;
            }
        }
        std::sort(key.factors.begin(), key.factors.end());
        if (!integrals_.overlaps(key.factors)) return;
        if (found_) {
            found_->insert(std::move(key));
            return;
        }
        const auto it = s_.section_index.find(key);
        if (it == s_.section_index.end()) throw std::logic_error("energy: a section integral the first pass missed");
        const Term s = single_term(read_, s_.section[it->second], {});
        sum.add(partial.monomial, product(partial.coefficient, s.coefficient), weight);
    }

    /// The number of orderings of the chosen indices within each run of repeated occurrences: r! / prod(count!).
    static numeric orderings(const std::vector<const Expansion*>& occurrences, const std::vector<std::size_t>& chosen)
    {
        numeric n = 1;
        for (std::size_t start = 0; start < chosen.size();) {
            std::size_t end = start + 1;
            while (end < chosen.size() && occurrences[end] == occurrences[start]) ++end;
            n *= factorial(numeric(static_cast<int>(end - start)));
            for (std::size_t i = start; i < end;) {
                std::size_t same = i + 1;
                while (same < end && chosen[same] == chosen[i]) ++same;
                n /= factorial(numeric(static_cast<int>(same - i)));
                i = same;
            }
            start = end;
        }
        return n;
    }

    const Symbols& s_;
    const FieldSymbols& f_;
    ShapeIntegrals& integrals_;
    const PolyReader& read_;
    std::set<SectionKey>* found_;
    std::map<ex, Expansion, ex_is_less> fields_;
};

/// derive_energies, or with found its first pass over a profile variant: the section integrals the energies meet.
Energies energies(const VariantKey& key, const Symbols& s, const PolyReader& read, bool without_point_terms,
                  std::set<SectionKey>* found);

}  // namespace

Symbols::Symbols(const VariantKey& key)
{
    // Every coordinate's symbol, then every rate's (GiNaC orders terms by the symbols' creation, which the
    // generated code's text follows), then the profile's.
    const CoordinateLayout layout = coordinate_layout(key);
    for (const CoordinateField& f : layout.fields)
        if (f.basis) coordinates(f.kind) = numbered(f.symbol, f.count);
    for (const CoordinateField& f : layout.fields)
        if (f.basis) rates(f.kind) = numbered(f.symbol, f.count, "_dot");
    if (key.out_of_plane()) o = std::make_shared<const OutOfPlane>();
    if (key.extras.hub) h = std::make_shared<const MovingHub>();
    for (const TermInfo* t : carried_terms(key.extras))
        for (const TermInput& i : generator_part(*t).inputs) inputs.emplace_back(i, symbol(i.symbol));
    for (const CoordinateField& f : layout.fields) {
        if (f.kind == FieldKind::hub_angle) {
            q.push_back(theta);
            qd.push_back(theta_dot);
            continue;
        }
        if (f.kind == FieldKind::hub_x || f.kind == FieldKind::hub_y) {
            q.push_back(f.kind == FieldKind::hub_x ? h->x : h->y);
            qd.push_back(f.kind == FieldKind::hub_x ? h->x_dot : h->y_dot);
            continue;
        }
        q.insert(q.end(), coordinates(f.kind).begin(), coordinates(f.kind).end());
        qd.insert(qd.end(), rates(f.kind).begin(), rates(f.kind).end());
    }
    if (!has_section_integrals(key)) return;
    // The first pass: the energies over every symbol they can hold, keeping only which section integrals they meet.
    std::vector<symbol> variables = {tau, theta_dot, theta_ddot, sin_theta, cos_theta};
    for (const symbol& x : q)
        if (!x.is_equal(theta)) variables.push_back(x);
    variables.push_back(theta);
    for (const symbol& x : qd)
        if (!x.is_equal(theta_dot)) variables.push_back(x);
    std::set<SectionKey> found;
    energies(key, *this, PolyReader(parameters(), variables), false, &found);
    section_keys.assign(found.begin(), found.end());
    for (std::size_t n = 0; n < section_keys.size(); ++n) {
        section.emplace_back("s_" + std::to_string(n));
        section_index.emplace(section_keys[n], n);
    }
}

std::vector<symbol> Symbols::parameters() const
{
    std::vector<symbol> p = {L, m, EI, ES, a, J_oh, m_tip, J_tip, g, alpha, beta, tip_ratio};
    if (o)
        p.insert(p.end(), {o->EI_flap, o->GJ, o->j_n, o->j_c, o->cos_2pitch, o->sin_2pitch, o->twist, o->cos_cone,
                           o->sin_cone, o->g_axis});
    for (const auto& [i, x] : inputs) p.push_back(x);
    p.insert(p.end(), section.begin(), section.end());
    return p;
}

const symbol& Symbols::input(std::string_view name) const
{
    for (const auto& [i, x] : inputs)
        if (name == i.symbol) return x;
    throw std::logic_error("energy: no carried term has the input " + std::string(name));
}

std::vector<symbol>& Symbols::coordinates(FieldKind kind)
{
    switch (kind) {
        case FieldKind::axial:
            return A;
        case FieldKind::inplane:
            return B;
        case FieldKind::flap:
            return Z;
        case FieldKind::twist:
            return P;
        default:
            throw std::logic_error("energy: the hub angle is one symbol, theta");
    }
}

std::vector<symbol>& Symbols::rates(FieldKind kind)
{
    switch (kind) {
        case FieldKind::axial:
            return A_dot;
        case FieldKind::inplane:
            return B_dot;
        case FieldKind::flap:
            return Z_dot;
        case FieldKind::twist:
            return P_dot;
        default:
            throw std::logic_error("energy: the hub angle's rate is one symbol, theta_dot");
    }
}

Position position(Order order, const FieldSymbols& f, const Cone& cone)
{
    const bool shortening = order != Order::zero;
    const ex ux = f.ux1 + (shortening ? ex(f.ux2) : ex(0));
    const ex ux_dot = f.ux1_dot + (shortening ? ex(f.ux2_dot) : ex(0));
    // X = a + x: the root at a i, the axis along e1 = cos i + sin k, the flapwise direction e3 = -sin i + cos k.
    const ex along = f.X - cone.a + ux;
    return {cone.a + along * cone.cos - f.uz * cone.sin, f.uy,     along * cone.sin + f.uz * cone.cos,
            ux_dot * cone.cos - f.uz_dot * cone.sin,     f.uy_dot, ux_dot * cone.sin + f.uz_dot * cone.cos};
}

ex velocity_squared(Order order, const FieldSymbols& f, const ex& w, const Cone& cone)
{
    // In the frame turning with w about k: |r_dot|^2 = (p_i' - w p_j)^2 + (p_j' + w p_i)^2 + p_k'^2.
    const Position p = position(order, f, cone);
    ex v2 = pow(p.i_dot - w * p.j, 2) + pow(p.j_dot + w * p.i, 2) + pow(p.k_dot, 2);
    if (order == Order::full) return v2.expand();
    // Keep terms up to 2nd order in the deformation: u_x1, u_y, u_z and rates 1st order, u_x2 and its rate 2nd.
    const symbol eps("eps");
    v2 = v2.subs(lst{f.ux1 == eps * f.ux1, f.uy == eps * f.uy, f.ux1_dot == eps * f.ux1_dot, f.uy_dot == eps * f.uy_dot,
                     f.uz == eps * f.uz, f.uz_dot == eps * f.uz_dot, f.ux2 == pow(eps, 2) * f.ux2,
                     f.ux2_dot == pow(eps, 2) * f.ux2_dot})
             .expand();
    ex kept = 0;
    for (int k = 0; k <= 2; ++k) kept += v2.coeff(eps, k);
    return kept;
}

Cone cone_of(const VariantKey& key, const Symbols& s)
{
    if (!key.extras.cone) return {1, 0, 0};
    return {s.o->cos_cone, s.o->sin_cone, s.a};
}

std::pair<ex, ex> turned_by_pitch(const VariantKey& key, const Symbols& s, const ex& c, const ex& sn)
{
    if (!key.extras.pitch) return {c, sn};
    // cos 2 (pitch + beta) = cos 2 pitch cos 2 beta - sin 2 pitch sin 2 beta, and sin 2 (pitch + beta) likewise.
    const ex cp = s.o->cos_2pitch, sp = s.o->sin_2pitch;
    return {cp * c - sp * sn, sp * c + cp * sn};
}

std::pair<ex, ex> chord_angle(const VariantKey& key, const Symbols& s, const FieldSymbols& f)
{
    if (!key.extras.twist) return turned_by_pitch(key, s, 1, 0);
    // The pre-twist's cos and sin are section distributions: the runtime integrates them against the basis for any
    // twist, where a series in twist xi held only for small ones.
    const auto [cos_2beta, sin_2beta] = turned_by_pitch(key, s, f.cos_2twist_x, f.sin_2twist_x);
    return {cos_2beta.expand(), sin_2beta.expand()};
}

bool has_section_integrals(const VariantKey& key)
{
    return key.extras.profile() || key.extras.twist;
}

ex bending_density(const VariantKey& key, const BeamSection& b, const ex& y2, const ex& z2)
{
    if (!key.out_of_plane()) return b.bending * pow(y2, 2);
    // EI_edge kappa_c^2 + EI_flap kappa_n^2, kappa_c = cos beta y'' + sin beta z'', kappa_n = -sin beta y'' + cos beta
    // z'': mean (y''^2 + z''^2) + deviator (cos 2 beta (y''^2 - z''^2) + 2 sin 2 beta y'' z'').
    return pow(y2, 2) * (b.bend_mean + b.bend_cos) + pow(z2, 2) * (b.bend_mean - b.bend_cos) + 2 * y2 * z2 * b.bend_sin;
}

ex section_rotation(const VariantKey& key, const Symbols& s, const FieldSymbols& f, const BeamSection& b)
{
    if (key.nt == 0) return 0;
    // T_sec = 1/2 [j_p (phi_dot + w sin beta_c)^2 + w^2 cos^2 beta_c (j_c sin^2 psi + j_n cos^2 psi)], psi = beta +
    // phi, to second order in phi (docs/model.md section 12).
    const Cone cone = cone_of(key, s);
    const ex w = s.theta_dot;
    const ex about_k = b.polar / 2 + b.inertia_cos - 2 * (b.inertia_sin * f.phi + b.inertia_cos * pow(f.phi, 2));
    return (b.polar * pow(f.phi_dot + w * cone.sin, 2) + pow(w * cone.cos, 2) * about_k) / 2;
}

Energies derive_energies(const VariantKey& key, const Symbols& s, const PolyReader& read, bool without_point_terms)
{
    return energies(key, s, read, without_point_terms, nullptr);
}

namespace {

Energies energies(const VariantKey& key, const Symbols& s, const PolyReader& read, bool without_point_terms,
                  std::set<SectionKey>* found)
{
    if (const std::string why = key.dof_problem(); !why.empty()) throw std::invalid_argument(key.name() + ": " + why);
    const Extras& x = key.extras;
    ShapeIntegrals integrals(key.axial_basis(), key.transverse_basis(), key.flap_basis(), key.twist_basis());
    FieldSymbols fields;
    if (x.offsets || x.tip_body) fields.offsets = std::make_shared<const FieldSymbols::Offsets>();
    const FieldSymbols& f = fields;
    DensityIntegrator integrate(s, f, key, integrals, read, found);
    // The distributions along the span: the root's values, or a section term's (a taper, a profile).
    const std::vector<const TermInfo*> carried = carried_terms(x);
    BeamSection beam = uniform_section(key, s, f);
    for (const TermInfo* t : carried)
        if (generator_part(*t).section) beam = generator_part(*t).section(key, s, f);
    const ex v2 = velocity_squared(without_point_terms ? Order::first : key.order, f, s.theta_dot, cone_of(key, s));
    Energies e;
    e.T = read(s.J_oh * pow(s.theta_dot, 2) / 2);
    e.T += integrate(beam.mass * v2 / 2);
    e.U = integrate((beam.axial * pow(f.ux1_x, 2) + bending_density(key, beam, f.uy_xx, f.uz_xx)) / 2);
    if (key.nt > 0) {
        e.T += integrate(section_rotation(key, s, f, beam));
        e.U += integrate(beam.torsion * pow(f.phi_x, 2) / 2);
    }
    // The terms' energies and dissipation (docs/model.md section 11), in registry order.
    const TermContext context{key,
                              s,
                              f,
                              beam,
                              v2,
                              [&](const ex& d) { return integrate(d); },
                              [&](const ex& d) { return integrate.at_tip(d); }};
    for (const TermInfo* t : carried)
        if (generator_part(*t).energies) generator_part(*t).energies(context, e);
    return e;
}

}  // namespace

}  // namespace hubbeam::gen
