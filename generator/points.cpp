// Order full's foreshortening terms at quadrature points: the rule, the tables of shape values and H(x_g), and the
// kernels' loops, from the density's derivatives by the chain rule through the point fields.
#include "points.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <sstream>
#include <stdexcept>

#include "basis/quadrature.hpp"
#include "emit.hpp"
#include "interface.hpp"
#include "terms.hpp"

namespace hubbeam::gen {

using namespace GiNaC;

namespace {

/// The polynomial pieces of both fields: their common break points on [0, 1].
std::vector<double> piece_cuts(const FieldBasis& axial, const FieldBasis& transverse)
{
    std::vector<double> cuts{0.0, 1.0};
    for (const FieldBasis* f : {&axial, &transverse})
        if (f->size() > 0)
            for (int k = 1; k < f->intervals(); ++k) cuts.push_back(static_cast<double>(k) / f->intervals());
    std::sort(cuts.begin(), cuts.end());
    cuts.erase(std::unique(cuts.begin(), cuts.end(), [](double a, double b) { return b - a < 1e-14; }), cuts.end());
    return cuts;
}

/// The point fields of the density (docs/model.md section 2): their symbols and how each depends on the state.
/// A gradient is a list of (vector, sign): the vectors are theta (the hub's unit entry), a = Phi_x(x_g)^T (A block),
/// p = Phi_y(x_g)^T, h = H(x_g) B and k = H(x_g) B_dot (B block); H in x units.
struct PointField {
    symbol sym;
    std::vector<std::pair<std::string, int>> dq, dqd;
    /// sum_j qd_j d2(field)/dq_j dqd: the rate of the qd-gradient along the motion.
    std::vector<std::pair<std::string, int>> mixed;
    ex rate;  // sum_j qd_j d(field)/dq_j: the field's time derivative at qdd = 0
    bool rate_field = false;  // linear in qd (M's entries come from these)
};

/// The symbols the emitted loop names, with their C spellings.
struct LoopSymbols {
    FieldSymbols f;
    symbol w{"w"}, w_dot{"w_dot"}, ux2_ddot{"u_x2_ddot"};
    std::map<ex, std::string, ex_is_less> names;
    LoopSymbols()
    {
        names = {{f.ux1, "f.u_x1"}, {f.ux1_dot, "f.u_x1_dot"}, {f.uy, "f.u_y"},         {f.uy_dot, "f.u_y_dot"},
                 {f.ux2, "f.u_x2"}, {f.ux2_dot, "f.u_x2_dot"}, {ux2_ddot, "f.u_x2_ddot"}, {w, "w"},
                 {w_dot, "w_dot"}};
    }
};

/// A polynomial in the loop's symbols as C: "2.0*f.u_x1*f.u_x2 + f.u_x2*f.u_x2". Factors and terms are sorted by
/// their C text, so that the output does not depend on GiNaC's order of terms (its symbols' creation order), and the
/// same variant is emitted byte for byte alike by every run.
std::string c_expression(const ex& e, const LoopSymbols& ls)
{
    const ex x = e.expand();
    if (x.is_zero()) return "0.0";
    std::vector<std::pair<std::string, numeric>> terms;  // the product of named factors, its coefficient
    for (const ex& term : is_a<add>(x) ? x : lst{x}) {
        numeric c = 1;
        std::vector<std::string> factors;
        for (const ex& factor : is_a<mul>(term) ? term : lst{term}) {
            if (is_a<numeric>(factor)) {
                c *= ex_to<numeric>(factor);
                continue;
            }
            const ex base = is_a<power>(factor) ? factor.op(0) : factor;
            const ex exponent = is_a<power>(factor) ? factor.op(1) : ex(1);
            const auto it = ls.names.find(base);
            if (it == ls.names.end() || !is_a<numeric>(exponent) || !ex_to<numeric>(exponent).is_pos_integer())
                throw EmitError("points: cannot print a term of the density's derivatives");
            for (int r = 0; r < ex_to<numeric>(exponent).to_int(); ++r) factors.push_back(it->second);
        }
        std::sort(factors.begin(), factors.end());
        std::string product;
        for (const std::string& f : factors) product += (product.empty() ? "" : "*") + f;
        terms.emplace_back(product, c);
    }
    std::sort(terms.begin(), terms.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    std::string s;
    for (const auto& [product, c] : terms) {
        const bool negative = c < 0;
        const numeric mag = negative ? -c : c;
        std::string t = product.empty() ? c_number(mag) : mag == 1 ? product : c_number(mag) + "*" + product;
        s += s.empty() ? (negative ? "-" + t : t) : (negative ? " - " : " + ") + t;
    }
    return s;
}

}  // namespace

std::vector<double> coupling_at(const FieldBasis& t, double xi)
{
    const int n = t.size();
    std::vector<double> H(static_cast<std::size_t>(n * n), 0.0);
    std::vector<double> cuts;
    int points = 0;
    if (t.polynomial()) {
        for (double c : piece_cuts(t, t))
            if (c < xi) cuts.push_back(c);
        points = t.degree();
    } else {
        const int panels = transcendental_panels(n);
        for (int k = 0; k < panels && static_cast<double>(k) / panels < xi; ++k) cuts.push_back(static_cast<double>(k) / panels);
        points = transcendental_points;
    }
    cuts.push_back(xi);
    const QuadratureRule rule = composite_gauss_legendre(cuts, points);
    std::vector<double> slope(static_cast<std::size_t>(n));
    for (std::size_t r = 0; r < rule.nodes.size(); ++r) {
        for (int j = 0; j < n; ++j) slope[static_cast<std::size_t>(j)] = t.at(j, rule.nodes[r]).d1;
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < n; ++j)
                H[static_cast<std::size_t>(i * n + j)] += rule.weights[r] * slope[static_cast<std::size_t>(i)] * slope[static_cast<std::size_t>(j)];
    }
    return H;
}

namespace {

/// How many coordinates the variant's field of this kind holds.
int field_count(const VariantKey& key, FieldKind kind) { return coordinate_layout(key).count(kind); }

/// Order full's |r_dot|^2 less order first's, halved (T = 1/2 int m |r_dot|^2): every term holds u_x2 or its rate.
ex point_density(const VariantKey& key, const LoopSymbols& ls)
{
    const FieldSymbols& f = ls.f;
    ex e = ((velocity_squared(Order::full, f, ls.w) - velocity_squared(Order::first, f, ls.w)) / 2).expand();
    if (field_count(key, FieldKind::axial) == 0) e = e.subs(lst{f.ux1 == 0, f.ux1_dot == 0}).expand();
    for (const symbol& other : {f.X, f.uy_x, f.uy_xx, f.ux1_x})
        if (e.has(other)) throw std::logic_error("points: the density holds " + other.get_name());
    return e;
}

/// The degree in xi of the density on one polynomial piece: the fields' degrees summed over its heaviest term.
int density_degree(const ex& e, const VariantKey& key, const LoopSymbols& ls)
{
    const int dy = key.transverse_basis().degree(), dx = field_count(key, FieldKind::axial) > 0 ? key.axial_basis().degree() : 0;
    const FieldSymbols& f = ls.f;
    const std::vector<std::pair<symbol, int>> degrees = {{f.ux1, dx}, {f.ux1_dot, dx},         {f.uy, dy},
                                                         {f.uy_dot, dy}, {f.ux2, 2 * dy - 1}, {f.ux2_dot, 2 * dy - 1}};
    int most = 0;
    for (const ex& term : is_a<add>(e) ? e : lst{e}) {
        int d = 0;
        for (const auto& [sym, deg] : degrees) d += term.degree(sym) * deg;
        most = std::max(most, d);
    }
    return most;
}

std::vector<PointField> point_fields(const VariantKey& key, const LoopSymbols& ls)
{
    const FieldSymbols& f = ls.f;
    std::vector<PointField> fields;
    if (key.drive == Drive::torque) fields.push_back({ls.w, {}, {{"theta", 1}}, {}, 0, true});
    if (field_count(key, FieldKind::axial) > 0) {
        fields.push_back({f.ux1, {{"a", 1}}, {}, {}, f.ux1_dot, false});
        fields.push_back({f.ux1_dot, {}, {{"a", 1}}, {}, 0, true});
    }
    fields.push_back({f.uy, {{"p", 1}}, {}, {}, f.uy_dot, false});
    fields.push_back({f.uy_dot, {}, {{"p", 1}}, {}, 0, true});
    // u_x2 = -1/2 B^T H B, u_x2_dot = -B^T H B_dot: d/dB = -H B, -H B_dot; d/dB_dot of the rate = -H B.
    fields.push_back({f.ux2, {{"h", -1}}, {}, {}, f.ux2_dot, false});
    fields.push_back({f.ux2_dot, {{"k", -1}}, {{"h", -1}}, {{"k", -1}}, ls.ux2_ddot, true});
    return fields;
}

/// The field of q a vector lives in (theta: the hub angle, a: the axial field, the others: the in-plane field) as
/// its index in layout.fields, and its entry i as C.
int field_index(const CoordinateLayout& layout, const std::string& v)
{
    const FieldKind kind = v == "theta" ? FieldKind::hub_angle : v == "a" ? FieldKind::axial : FieldKind::inplane;
    return static_cast<int>(layout.find(kind) - layout.fields.data());
}
std::string entry(const std::string& v, const std::string& i)
{
    if (v == "theta") return "";
    if (v == "a") return "point_phi_x[g][" + i + "]";
    if (v == "p") return "point_phi_y[g][" + i + "]";
    return "f." + v + "[" + i + "]";
}

/// Whether code names the identifier (not as part of a longer name or a member).
bool names(const std::string& code, const std::string& id)
{
    const auto part = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.'; };
    for (std::size_t at = code.find(id); at != std::string::npos; at = code.find(id, at + 1)) {
        const bool before = at > 0 && part(code[at - 1]), after = at + id.size() < code.size() && part(code[at + id.size()]);
        if (!before && !after) return true;
    }
    return false;
}

/// The loop over the points around body: fields, weight, drive values as the body needs them; the vectors k and
/// u_x2_ddot only where the body names them.
std::string point_loop(const VariantKey& key, const std::string& body, bool tip)
{
    const bool vectors = body.find("f.k[") != std::string::npos || body.find("u_x2_ddot") != std::string::npos;
    const bool torque = key.drive == Drive::torque;
    const CoordinateLayout layout = coordinate_layout(key);
    const CoordinateField &axial = *layout.find(FieldKind::axial), &inplane = *layout.find(FieldKind::inplane);
    const std::string a = std::to_string(axial.first), b = std::to_string(inplane.first);
    const std::string A = axial.count > 0 ? "q + " + a : "nullptr", A_dot = axial.count > 0 ? "qd + " + a : "nullptr";
    std::ostringstream s;
    s << "    // Order full's foreshortening terms, summed over the quadrature points (point_fields above).\n"
      << "    const PointVectors& HB = point_products(q + " << b << ");\n"
      << "    for (int g = 0; g < point_count; ++g) {\n"
      << "        PointFields f;\n"
      << "        point_fields<" << (vectors ? "true" : "false") << ">(g, $inv_L, HB[g], " << A << ", q + " << b << ", " << A_dot
      << ", qd + " << b << ", f);\n";
    if (tip) s << "        const double W = g < beam_points ? $m_L * point_weight[g] : $m_tip;\n";
    else s << "        const double W = $m_L * point_weight[g];\n";
    if (names(body, "w"))
        s << "        const double w = " << (torque ? std::string("qd[0]") : "u[" + std::to_string(index(DriveValue::theta_dot)) + "]") << ";\n";
    if (names(body, "w_dot")) s << "        const double w_dot = u[" << index(DriveValue::theta_ddot) << "];\n";
    s << body << "    }\n";
    return s.str();
}

}  // namespace

bool foreshortening_at_points(const VariantKey& key)
{
    // Below Ny = 8 the expanded form is the cheaper: AMM torque, instructions per right-hand side, expanded against
    // points: 5.5 against 20 thousand at Ny = 4, 79 against 58 at Ny = 8, 2870 against 229 at Ny = 16.
    // The points' code knows the planar fields of a uniform section only: a beam that leaves the plane, or whose
    // section a term shapes (a taper, a profile), takes the expanded form.
    return key.order == Order::full && field_count(key, FieldKind::inplane) >= 8 && !shaped_section(key) &&
           !key.out_of_plane() && !key.extras.hub;
}

PointRule point_rule(const VariantKey& key)
{
    const FieldBasis axial = key.axial_basis(), transverse = key.transverse_basis();
    PointRule r;
    QuadratureRule q;
    if (transverse.polynomial() && axial.polynomial()) {
        const LoopSymbols ls;
        const int degree = density_degree(point_density(key, ls), key, ls);
        q = composite_gauss_legendre(piece_cuts(axial, transverse), degree / 2 + 1);
        r.exact = true;
    } else {
        // The highest modes' products oscillate about 4 b_n / (2 pi) times on [0, 1]; 4 n + 16 points reach
        // round-off with a margin (3.5 n + 16 do, measured from n = 4 to 32).
        int most = 0;  // the largest count of a beam field
        for (const CoordinateField& f : coordinate_layout(key).fields)
            if (f.basis) most = std::max(most, f.count);
        q = gauss_legendre(4 * most + 16);
    }
    r.xi = q.nodes;
    r.weight = q.weights;
    return r;
}

namespace {

/// Lagrange's equations of T_points = sum_g W_g e(fields(x_g)) by the chain rule, per vector (Q) and pair of vectors
/// (M) of the point fields' gradients:
///   M = sum e_ab dqd(a) dqd(b)^T over the rate fields,
///   Q = sum e_a dq(a) - D_a dqd(a) - e_a mixed(a),  D_a = sum_b e_ab rate(b) [+ de_a/dw w_dot, prescribed].
struct PointTerms {
    std::map<std::string, ex> Q;
    std::map<std::pair<std::string, std::string>, ex> M;
};
PointTerms point_terms(const ex& e, const std::vector<PointField>& fields, const LoopSymbols& ls, bool torque)
{
    PointTerms terms;
    std::map<std::string, ex>& Q = terms.Q;
    for (const PointField& a : fields) {
        const ex ea = e.diff(a.sym);
        ex D = torque ? ex(0) : ea.diff(ls.w) * ls.w_dot;
        for (const PointField& b : fields) D += ea.diff(b.sym) * b.rate;
        for (const auto& [v, sign] : a.dq) Q[v] += sign * ea;
        for (const auto& [v, sign] : a.dqd) Q[v] -= sign * D;
        for (const auto& [v, sign] : a.mixed) Q[v] -= sign * ea;
        if (!a.rate_field) continue;
        for (const PointField& b : fields) {
            if (!b.rate_field) continue;
            const ex eab = ea.diff(b.sym);
            for (const auto& [u, su] : a.dqd)
                for (const auto& [v, sv] : b.dqd) terms.M[{u, v}] += su * sv * eab;
        }
    }
    return terms;
}

/// Where the blocks of q (its fields, numbered by their place in the layout) lie in the kernels' arrays, as C text,
/// and their sizes.
struct Blocks {
    CoordinateLayout layout;
    int nq, nx, ny;
    std::string B0, n;
    explicit Blocks(const VariantKey& key)
        : layout(coordinate_layout(key)), nq(layout.size()), nx(layout.count(FieldKind::axial)),
          ny(layout.count(FieldKind::inplane)), B0(std::to_string(layout.first(FieldKind::inplane))),
          n(std::to_string(nq))
    {
    }
    const CoordinateField& field(int block) const { return layout.fields[static_cast<std::size_t>(block)]; }
    /// The block of the hub angle (one entry, at q[0]).
    bool hub(int block) const { return field(block).kind == FieldKind::hub_angle; }
    std::string offset(int block) const { return std::to_string(field(block).first); }
    int size(int block) const { return field(block).count; }
    /// The block a vector of the point terms lives in.
    int block(const std::string& v) const { return field_index(layout, v); }
};

/// The forces' loop body: one scalar per vector, then one loop per block.
std::string forces_body(const std::map<std::string, ex>& Q, const Blocks& b, const LoopSymbols& ls)
{
    std::ostringstream body, lines;
    std::map<int, std::vector<std::string>> by_block;
    for (const auto& [v, c] : Q) {
        if (c.expand().is_zero()) continue;
        lines << "        const double q_" << v << " = W * (" << c_expression(c, ls) << ");\n";
        by_block[b.block(v)].push_back(v);
    }
    body << lines.str();
    for (const auto& [block, vs] : by_block) {
        std::string sum;
        for (const std::string& v : vs) sum += (sum.empty() ? "" : " + ") + ("q_" + v + (v == "theta" ? "" : " * " + entry(v, "i")));
        if (b.hub(block)) body << "        out[0] += " << sum << ";\n";
        else
            body << "        for (int i = 0; i < " << b.size(block) << "; ++i) out[" << b.offset(block) << " + i] += " << sum << ";\n";
    }
    return body.str();
}

/// The mass kernel's code: declarations before the loop over the points, the loop's body, the sums after it.
struct MassCode {
    std::ostringstream before, body, after;
};

/// The sum of the terms of the vector pairs of the blocks (bu, bv) at entry (i, j).
std::string mass_sum(const std::vector<std::pair<std::string, std::string>>& pairs, int bu, int bv)
{
    std::string sum;
    for (const auto& [u, v] : pairs) {
        std::string t = "m_" + u + "_" + v;
        const auto times = [](const std::string& x) { return x.empty() ? std::string() : " * " + x; };
        if (bu == bv && u != v)
            t += " * (" + entry(u, "i") + " * " + entry(v, "j") + " + " + entry(v, "i") + " * " + entry(u, "j") + ")";
        else t += times(entry(u, "i")) + times(entry(v, "j"));
        sum += (sum.empty() ? "" : " + ") + t;
    }
    return sum;
}

/// sum_g m_h_h(g) h_g h_g^T as a product of the points' vectors after the loop, a row by four columns at a time in
/// registers: two thirds of the instructions of a rank-one update per point.
void outer_h_mass(MassCode& m, const Blocks& b)
{
    const std::string c = "m_h_h", B0 = b.B0;
    m.before << "    double h_at[point_count][NY], scaled_h_at[point_count][NY];  // h_g and " << c << "(g) h_g\n";
    m.body << "        for (int i = 0; i < NY; ++i) {\n"
           << "            h_at[g][i] = f.h[i];\n"
           << "            scaled_h_at[g][i] = " << c << " * f.h[i];\n"
           << "        }\n";
    // Four named sums, not an array: GCC kept an array's sums on the stack, a store and a reload on every point's
    // dependency chain (two thirds of the mass kernel's time, AMM at Ny = 16).
    m.after << "    for (int i = 0; i < NY; ++i)\n"
            << "        for (int j = i / 4 * 4; j < NY; j += 4) {\n"
            << "            double s0 = 0.0, s1 = 0.0, s2 = 0.0, s3 = 0.0;\n"
            << "            for (int g = 0; g < point_count; ++g) {\n"
            << "                const double a = scaled_h_at[g][i];\n"
            << "                const double* h = h_at[g] + j;\n"
            << "                s0 += a * h[0];\n"
            << "                s1 += a * h[1];\n"
            << "                s2 += a * h[2];\n"
            << "                s3 += a * h[3];\n"
            << "            }\n"
            << "            const double s[4] = {s0, s1, s2, s3};\n"
            << "            for (int col = 0; col < 4; ++col)\n"
            << "                if (j + col >= i) out[(" << B0 << " + i) * " << b.n << " + " << B0 << " + j + col] += s[col];\n"
            << "        }\n";
}

/// A diagonal block (A or B) summed in a local square over the points (a loop the compiler vectorizes), its upper
/// triangle added at the end.
void square_mass_block(MassCode& m, int block, const std::string& sum, const Blocks& b)
{
    const std::string name = "block_" + b.field(block).symbol, nb = std::to_string(b.size(block));
    m.before << "    double " << name << "[" << nb << " * " << nb << "] = {};  // this block's terms, square\n";
    m.body << "        for (int i = 0; i < " << nb << "; ++i)\n"
           << "            for (int j = 0; j < " << nb << "; ++j) " << name << "[i * " << nb << " + j] += " << sum << ";\n";
    m.after << "    for (int i = 0; i < " << nb << "; ++i)\n"
            << "        for (int j = i; j < " << nb << "; ++j) out[(" << b.offset(block) << " + i) * " << b.n << " + "
            << b.offset(block) << " + j] += " << name << "[i * " << nb << " + j];\n";
}

/// The code that adds the vector pairs of the blocks (bu, bv) to M's upper triangle.
void mass_block(MassCode& m, int bu, int bv, const std::vector<std::pair<std::string, std::string>>& pairs,
                const Blocks& b)
{
    const std::string sum = mass_sum(pairs, bu, bv);
    if (b.hub(bu) && b.hub(bv)) {
        m.body << "        out[0] += " << sum << ";\n";
    } else if (b.hub(bu)) {
        m.body << "        for (int j = 0; j < " << b.size(bv) << "; ++j) out[" << b.offset(bv) << " + j] += " << sum << ";\n";
    } else if (bu != bv) {
        m.body << "        for (int i = 0; i < " << b.size(bu) << "; ++i)\n"
               << "            for (int j = 0; j < " << b.size(bv) << "; ++j) out[(" << b.offset(bu) << " + i) * " << b.n
               << " + " << b.offset(bv) << " + j] += " << sum << ";\n";
    } else if (pairs.size() == 1 && pairs[0].first == pairs[0].second && pairs[0].first == "h" && b.ny % 4 == 0) {
        outer_h_mass(m, b);
    } else {
        square_mass_block(m, bu, sum, b);
    }
}

/// M's point terms: the upper triangle, one scalar per unordered pair of vectors; entries collects the entries
/// (row-major) they add to.
std::string mass_code(const PointTerms& terms, const Blocks& b, const LoopSymbols& ls, const VariantKey& key,
                      std::vector<int>& entries)
{
    MassCode m;
    std::map<std::pair<int, int>, std::vector<std::pair<std::string, std::string>>> by_blocks;
    for (const auto& [uv, c] : terms.M) {
        const auto& [u, v] = uv;
        if (c.expand().is_zero() || b.block(u) > b.block(v)) continue;
        if (b.block(u) == b.block(v) && u > v) continue;  // (v, u) carries it: same coefficient, both orders below
        m.body << "        const double m_" << u << "_" << v << " = W * (" << c_expression(c, ls) << ");\n";
        by_blocks[{b.block(u), b.block(v)}].push_back({u, v});
    }
    for (const auto& [blocks, pairs] : by_blocks) {
        const auto [bu, bv] = blocks;
        for (int i = 0; i < b.size(bu); ++i)
            for (int j = bu == bv ? i : 0; j < b.size(bv); ++j)
                entries.push_back((std::stoi(b.offset(bu)) + i) * b.nq + std::stoi(b.offset(bv)) + j);
        mass_block(m, bu, bv, pairs, b);
    }
    return m.before.str() + point_loop(key, m.body.str(), key.extras.tip) + m.after.str();
}

/// A Jacobian piece by the chain rule: sum c(fields) u v^T over vectors u, v, plus c_H H(x_g)/L on the B block,
/// where a vector holds the state (dh/dB = H/L, dk/dB_dot = H/L).
struct Matrix {
    std::map<std::pair<std::string, std::string>, ex> outer;
    ex H = 0;
};

/// Adds the gradient of c (the coefficient of row) in q, or in the rates, to out.
void add_gradient(const ex& c, bool rates, const std::string& row, const std::vector<PointField>& fields,
                  const LoopSymbols& ls, Matrix& out)
{
    for (const PointField& f : fields) {
        const ex dc = c.diff(f.sym);
        if (dc.is_zero()) continue;
        for (const auto& [v, sign] : rates ? f.dqd : f.dq) out.outer[{row, v}] += sign * dc;
    }
    // u_x2_ddot = -B_dot^T H B_dot / L: its gradient in the rates is -2 k.
    if (rates) out.outer[{row, "k"}] += -2 * c.diff(ls.ux2_ddot);
}

/// dQ/dq, dQ/dqd and sum_j dM_ij/dq_k z_j of the point terms.
struct Jacobians {
    Matrix dQdq, dQdqd, dMv;
};
Jacobians jacobians(const PointTerms& terms, const std::vector<PointField>& fields, const LoopSymbols& ls)
{
    Jacobians J;
    for (const auto& [v, c] : terms.Q) {
        add_gradient(c, false, v, fields, ls, J.dQdq);
        add_gradient(c, true, v, fields, ls, J.dQdqd);
        if (v == "h") J.dQdq.H += c;
        if (v == "k") J.dQdqd.H += c;
    }
    // sum_j dM_ij/dq_k z_j with z in the qd slot, so that the point fields of the rates are products with z: for
    // M = sum m_uv u v^T it is sum_uv u d(m_uv (v . z))/dq + m_uv (v . z) du/dq, where a . z = u_x1_dot, p . z = u_y_dot,
    // h . z = -u_x2_dot (whose q-gradient -k carries dh/dq z).
    const std::map<std::string, ex> dot = {{"theta", ls.w}, {"a", ls.f.ux1_dot}, {"p", ls.f.uy_dot}, {"h", -ls.f.ux2_dot}};
    for (const auto& [uv, m] : terms.M) {
        const auto& [u, v] = uv;
        if (m.expand().is_zero()) continue;
        add_gradient(m * dot.at(v), false, u, fields, ls, J.dMv);
        if (u == "h") J.dMv.H += m * dot.at(v);
    }
    return J;
}

/// A Jacobian piece's loop body: one scalar per pair of vectors, one loop nest per pair of blocks, then H's term.
std::string matrix_body(const Matrix& J, const std::string& stem, const Blocks& b, const LoopSymbols& ls)
{
    std::ostringstream body;
    std::map<std::pair<int, int>, std::string> sums;
    for (const auto& [uv, c] : J.outer) {
        if (c.expand().is_zero()) continue;
        const auto& [u, v] = uv;
        const std::string name = stem + "_" + u + "_" + v;
        body << "        const double " << name << " = W * (" << c_expression(c, ls) << ");\n";
        std::string t = name;
        if (!entry(u, "i").empty()) t += " * " + entry(u, "i");
        if (!entry(v, "j").empty()) t += " * " + entry(v, "j");
        std::string& sum = sums[{b.block(u), b.block(v)}];
        sum += (sum.empty() ? "" : " + ") + t;
    }
    for (const auto& [blocks, sum] : sums) {
        const auto [bu, bv] = blocks;
        const std::string row = b.hub(bu) ? "0" : "(" + b.offset(bu) + " + i) * " + b.n, col = b.hub(bv) ? "0" : b.offset(bv) + " + j";
        std::string indent = "        ";
        if (!b.hub(bu)) {
            body << indent << "for (int i = 0; i < " << b.size(bu) << "; ++i)\n";
            indent += "    ";
        }
        if (!b.hub(bv)) {
            body << indent << "for (int j = 0; j < " << b.size(bv) << "; ++j)\n";
            indent += "    ";
        }
        body << indent << "out[" << row << " + " << col << "] += " << sum << ";\n";
    }
    if (!J.H.expand().is_zero())
        body << "        const double " << stem << "_H = W * (" << c_expression(J.H, ls) << ") * $inv_L;\n"
             << "        for (int i = 0; i < NY; ++i)\n"
             << "            for (int j = 0; j < NY; ++j) out[(" << b.B0 << " + i) * " << b.n << " + " << b.B0 << " + j] += "
             << stem << "_H * point_H[g][i * NY + j];\n";
    return body.str();
}

/// dQ/du's loop body: the prescribed drive's theta_dot and theta_ddot (a torque variant's point terms hold no tau).
std::string drive_body(const std::map<std::string, ex>& Q, const Blocks& b, const LoopSymbols& ls)
{
    std::ostringstream body;
    for (const auto& [v, c] : Q)
        for (const auto& [input, column] : {std::pair{ex(ls.w), index(DriveValue::theta_dot)}, std::pair{ex(ls.w_dot), index(DriveValue::theta_ddot)}}) {
            const ex dc = c.diff(ex_to<symbol>(input)).expand();
            if (dc.is_zero()) continue;
            const std::string name = "du_" + v + "_" + std::to_string(column);
            body << "        const double " << name << " = W * (" << c_expression(dc, ls) << ");\n";
            if (b.hub(b.block(v))) body << "        out[" << column << "] += " << name << ";\n";
            else
                body << "        for (int i = 0; i < " << b.size(b.block(v)) << "; ++i) out[(" << b.offset(b.block(v))
                     << " + i) * " << drive_value_count << " + " << column << "] += " << name << " * " << entry(v, "i") << ";\n";
        }
    return body.str();
}

/// The energy's loop body: the density split by degree in the rates (out[0] the quadratic part).
std::string energy_body(const ex& e, const std::vector<PointField>& fields, const LoopSymbols& ls)
{
    const symbol lambda("lambda");
    exmap scale;
    for (const PointField& f : fields)
        if (f.rate_field) scale[f.sym] = lambda * f.sym;
    const ex el = e.subs(scale).expand();
    std::ostringstream body;
    for (int d = 2; d >= 0; --d)
        if (!el.coeff(lambda, d).is_zero())
            body << "        out[" << 2 - d << "] += W * (" << c_expression(el.coeff(lambda, d), ls) << ");\n";
    return body.str();
}

/// A row of a C table: the numbers, comma-separated.
std::string number_row(const std::vector<double>& v)
{
    std::string r;
    for (std::size_t i = 0; i < v.size(); ++i) r += (i ? ", " : "") + c_number(numeric(v[i]));
    return r;
}

/// The tables' head: what they are, the sizes and the rule's weights.
void point_table_head(std::ostream& t, const VariantKey& key, const PointRule& rule, std::size_t point_count)
{
    const bool tip = key.extras.tip;
    t << "// Order full's foreshortening terms at " << rule.xi.size() << " Gauss-Legendre points x_g = L xi_g ("
      << (rule.exact ? "exact for these polynomial integrands" : "converged to round-off for these modes") << ")"
      << (tip ? ", then the tip body at xi = 1" : "") << ":\n"
      << "// T += sum_g W_g e(fields at x_g), W_g = m L w_g" << (tip ? " (m_tip at the tip)" : "")
      << ", e = 1/2 (|r_dot|^2 of order full - of order first).\n"
      << (key.nx > 0 ? "constexpr int NX = " + std::to_string(key.nx) + ";\n" : std::string()) << "constexpr int NY = " << key.ny << ";\n"
      << "constexpr int beam_points = " << rule.xi.size() << ", point_count = " << point_count << ";\n";
    t << "constexpr double point_weight[beam_points] = {" << number_row(rule.weight) << "};\n";
}

/// A basis's values at every point, as the table `name`[point_count][count].
void shape_table(std::ostream& t, const char* name, const char* count, const FieldBasis& basis, int n,
                 const std::vector<double>& xi)
{
    t << "constexpr double " << name << "[point_count][" << count << "] = {\n";
    for (double x : xi) {
        std::vector<double> v;
        for (int i = 0; i < n; ++i) v.push_back(basis.at(i, x).v);
        t << "    {" << number_row(v) << "},\n";
    }
    t << "};\n";
}

/// Rows from to to of H times vector into out, width at a time: in registers, the sum over j unrolled (GCC and
/// Clang read the pragma). The sums are named variables: GCC kept an array of them on the stack, a store and a
/// reload on every step of the sum's dependency chain.
void h_rows(std::ostream& t, const std::string& indent, const std::string& from, const std::string& to, int width,
            const std::string& vector, const std::string& out)
{
    t << indent << "for (int i = " << from << "; i < " << to << "; i += " << width << ") {\n" << indent << "    double";
    for (int r = 0; r < width; ++r) t << (r ? ", " : " ") << "s" << r << " = 0.0";
    t << ";\n"
      << "#pragma GCC unroll 32\n"
      << indent << "    for (int j = 0; j < NY; ++j) {\n"
      << indent << "        const double v = " << vector << "[j];\n"
      << indent << "        const double* h = H + j * NY + i;\n";
    for (int r = 0; r < width; ++r) t << indent << "        s" << r << " += h[" << r << "] * v;\n";
    t << indent << "    }\n";
    for (int r = 0; r < width; ++r) t << indent << "    " << out << "[i + " << r << "] = s" << r << ";\n";
    t << indent << "}\n";
}

/// H times vector into out: four entries at a time over H's rows (H is symmetric), then the rest one by one. Copies
/// of B and fixed-length inner loops keep them free of aliasing, so that the compiler vectorizes them at -O2; the
/// loop's own instructions would cost half as much again.
void h_product(std::ostream& t, int ny, const std::string& vector, const std::string& out)
{
    const int blocked = ny / 4 * 4;
    if (blocked > 0) h_rows(t, "        ", "0", std::to_string(blocked), 4, vector, out);
    if (blocked < ny) h_rows(t, "        ", std::to_string(blocked), "NY", 1, vector, out);
}

/// point_products(B): H_xi(x_g) B at every point, kept for the last B.
void point_products_code(std::ostream& t, int ny)
{
    t << "using PointVectors = double[point_count][NY];\n\n"
      << "/// H_xi(x_g) B at every point, for the last B this thread asked for: the mass and the forces of one right-hand\n"
      << "/// side are evaluated at the same B and share these G Ny^2 products.\n"
      << "const PointVectors& point_products(const double* B)\n{\n"
      << "    thread_local double last[NY];\n"
      << "    thread_local PointVectors products;\n"
      << "    thread_local bool valid = false;\n"
      << "    bool same = valid;\n"
      << "    for (int i = 0; i < NY; ++i) same = same && B[i] == last[i];\n"
      << "    if (same) return products;\n"
      << "    double b[NY];\n"
      << "    for (int i = 0; i < NY; ++i) b[i] = last[i] = B[i];\n"
      << "    for (int g = 0; g < point_count; ++g) {\n"
      << "        const double* H = point_H[g];\n";
    h_product(t, ny, "b", "products[g]");
    t << "    }\n    valid = true;\n    return products;\n}\n\n";
}

/// point_fields<vectors>(g, ...): the point fields at point g from the state.
void point_fields_code(std::ostream& t, int nx, int ny)
{
    t << "/// The fields at point g (docs/model.md section 2): u_x1, u_y, u_x2 = -1/2 B^T H B and their rates, with\n"
      << "/// h = H B (from HB = H_xi(x_g) B) and (vectors) k = H B_dot and u_x2_ddot = -B_dot^T H B_dot, the rate of u_x2_dot\n"
      << "/// at B_ddot = 0; H in x units (H_xi / L).\n"
      << "struct PointFields {\n    double u_x1 = 0.0, u_x1_dot = 0.0, u_y = 0.0, u_y_dot = 0.0, u_x2 = 0.0, u_x2_dot = 0.0, "
         "u_x2_ddot = 0.0;\n    double h[NY], k[NY];\n};\n"
      << "template <bool vectors>\n"
      << "void point_fields(int g, double inv_L, const double* HB, const double* A, const double* B, const double* A_dot,\n"
      << "                  const double* B_dot, PointFields& f)\n{\n";
    if (nx > 0)
      t << "    for (int i = 0; i < NX; ++i) {\n"
        << "        f.u_x1 += point_phi_x[g][i] * A[i];\n"
        << "        f.u_x1_dot += point_phi_x[g][i] * A_dot[i];\n    }\n";
    else t << "    (void)A;\n    (void)A_dot;\n";
    t << "    double b[NY], b_dot[NY], k[NY];\n"
      << "    for (int i = 0; i < NY; ++i) {\n"
      << "        b[i] = B[i];\n"
      << "        b_dot[i] = B_dot[i];\n"
      << "    }\n"
      << "    if constexpr (vectors) {\n"
      << "        const double* H = point_H[g];\n";
    h_product(t, ny, "b_dot", "k");
    t << "    }\n"
      << "    double u_y = 0.0, u_y_dot = 0.0, u_x2 = 0.0, u_x2_dot = 0.0, u_x2_ddot = 0.0;\n"
      << "    for (int i = 0; i < NY; ++i) {\n"
      << "        u_y += point_phi_y[g][i] * b[i];\n"
      << "        u_y_dot += point_phi_y[g][i] * b_dot[i];\n"
      << "        u_x2 += b[i] * HB[i];\n"
      << "        u_x2_dot += b_dot[i] * HB[i];\n"
      << "        f.h[i] = HB[i] * inv_L;\n"
      << "    }\n"
      << "    if constexpr (vectors)\n"
      << "        for (int i = 0; i < NY; ++i) {\n"
      << "            u_x2_ddot += b_dot[i] * k[i];\n"
      << "            f.k[i] = k[i] * inv_L;\n"
      << "        }\n"
      << "    f.u_y = u_y;\n"
      << "    f.u_y_dot = u_y_dot;\n"
      << "    f.u_x2 = -0.5 * u_x2 * inv_L;\n"
      << "    f.u_x2_dot = -u_x2_dot * inv_L;\n"
      << "    f.u_x2_ddot = -u_x2_ddot * inv_L;\n"
      << "}\n";
}

/// The tables: the rule's points (then the tip), shape values and H at each; then point_products and point_fields.
std::string point_tables(const VariantKey& key, const PointRule& rule)
{
    std::vector<double> xi = rule.xi;
    if (key.extras.tip) xi.push_back(1.0);
    const FieldBasis axial = key.axial_basis(), transverse = key.transverse_basis();
    std::ostringstream t;
    point_table_head(t, key, rule, xi.size());
    if (key.nx > 0) shape_table(t, "point_phi_x", "NX", axial, key.nx, xi);
    shape_table(t, "point_phi_y", "NY", transverse, key.ny, xi);
    t << "// H_xi(xi_g) = int_0^xi_g Phi_y'^T Phi_y' dxi, row-major.\nconstexpr double point_H[point_count][NY * NY] = {\n";
    for (double x : xi) t << "    {" << number_row(coupling_at(transverse, x)) << "},\n";
    t << "};\n\n";
    point_products_code(t, key.ny);
    point_fields_code(t, key.nx, key.ny);
    return t.str();
}

}  // namespace

PointCode point_code(const VariantKey& key, const Symbols& s)
{
    const LoopSymbols ls;
    const ex e = point_density(key, ls);
    const bool torque = key.drive == Drive::torque, tip = key.extras.tip;
    const std::vector<PointField> fields = point_fields(key, ls);
    const PointRule rule = point_rule(key);  // its symbols made first: GiNaC orders symbols by creation
    const PointTerms terms = point_terms(e, fields, ls, torque);
    const Blocks blocks(key);

    PointCode code;
    code.forces = point_loop(key, forces_body(terms.Q, blocks, ls), tip);
    code.mass = mass_code(terms, blocks, ls, key, code.mass_entries);
    const Jacobians J = jacobians(terms, fields, ls);
    code.forces_q = point_loop(key, matrix_body(J.dQdq, "dq", blocks, ls), tip);
    code.forces_qd = point_loop(key, matrix_body(J.dQdqd, "dqd", blocks, ls), tip);
    code.mass_q_product = point_loop(key, matrix_body(J.dMv, "dm", blocks, ls), tip);
    if (!torque) code.forces_u = point_loop(key, drive_body(terms.Q, blocks, ls), tip);
    // The energy split by degree in the rates, and the angular momentum de/dw.
    code.energy = point_loop(key, energy_body(e, fields, ls), tip);
    code.momentum = point_loop(key, "        out[0] += W * (" + c_expression(e.diff(ls.w), ls) + ");\n", tip);
    code.tables = point_tables(key, rule);
    code.coefficients = {{"$m_L", s.m * s.L}, {"$inv_L", 1 / s.L}};
    if (tip) code.coefficients.emplace_back("$m_tip", s.m_tip);
    return code;
}

}  // namespace hubbeam::gen
