// Polynomial decomposition and printing of the generated kernels.
#include "emit.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <sstream>

namespace hubbeam::gen {

using namespace GiNaC;

namespace {

/// numeric * prod(parameter^pe) * prod(variable^ve)
struct PolyTerm {
    numeric coeff = 1;
    std::vector<int> pe, ve;
};

class Decomposer {
public:
    Decomposer(const std::vector<Input>& params, const std::vector<Input>& vars)
    {
        for (std::size_t i = 0; i < params.size(); ++i) index_[params[i].symbol] = {true, i};
        for (std::size_t i = 0; i < vars.size(); ++i) index_[vars[i].symbol] = {false, i};
        np_ = params.size();
        nv_ = vars.size();
    }

    std::vector<PolyTerm> operator()(const ex& value) const
    {
        const ex e = value.expand();
        std::vector<PolyTerm> terms;
        if (e.is_zero()) return terms;
        for (const ex& term : is_a<add>(e) ? e : lst{e}) {
            PolyTerm t{1, std::vector<int>(np_), std::vector<int>(nv_)};
            for (const ex& f : is_a<mul>(term) ? term : lst{term}) factor(f, t);
            terms.push_back(std::move(t));
        }
        return terms;
    }

private:
    void factor(const ex& f, PolyTerm& t) const
    {
        if (is_a<numeric>(f)) {
            const numeric& n = ex_to<numeric>(f);
            if (!n.is_real()) throw EmitError("emit: non-real number " + str(f));
            t.coeff *= n;
            return;
        }
        ex base = f;
        int n = 1;
        if (is_a<power>(f)) {
            if (!is_a<numeric>(f.op(1)) || !ex_to<numeric>(f.op(1)).is_integer())
                throw EmitError("emit: cannot print non-integer power " + str(f));
            base = f.op(0);
            n = ex_to<numeric>(f.op(1)).to_int();
        }
        auto it = is_a<symbol>(base) ? index_.find(ex_to<symbol>(base)) : index_.end();
        if (it == index_.end()) throw EmitError("emit: cannot print " + str(f) + " (not a polynomial in the inputs)");
        const auto [is_param, i] = it->second;
        if (!is_param && n < 0) throw EmitError("emit: negative power of a variable " + str(f));
        (is_param ? t.pe : t.ve)[i] += n;
    }

    static std::string str(const ex& e)
    {
        std::ostringstream s;
        s << e;
        return s.str();
    }

    std::map<symbol, std::pair<bool, std::size_t>, ex_is_less> index_;
    std::size_t np_ = 0, nv_ = 0;
};

/// "x*x*y" for exponents {2,1} over names {x,y}; empty for the constant monomial.
std::string product(const std::vector<int>& e, const std::vector<std::string>& names, bool positive)
{
    std::string s;
    for (std::size_t i = 0; i < e.size(); ++i)
        for (int r = 0; r < (positive ? e[i] : -e[i]); ++r) s += (s.empty() ? "" : "*") + names[i];
    return s;
}

/// sum of "c*monomial" terms, with signs folded: "a*x - b*y".
std::string signed_sum(const std::vector<std::pair<numeric, std::string>>& terms)
{
    std::string s;
    for (const auto& [c, mono] : terms) {
        const bool negative = c < 0;
        const numeric mag = negative ? numeric(-c) : c;
        std::string t;
        if (mono.empty()) t = c_number(mag);
        else if (mag == 1) t = mono;
        else t = c_number(mag) + "*" + mono;
        if (s.empty()) s = negative ? "-" + t : t;
        else s += (negative ? " - " : " + ") + t;
    }
    return s.empty() ? "0.0" : s;
}

std::string monomial_name(const std::vector<int>& e, const std::vector<std::string>& names)
{
    std::string s;
    for (std::size_t i = 0; i < e.size(); ++i) {
        if (e[i] == 0) continue;
        s += (s.empty() ? "" : "_") + names[i];
        if (e[i] == 2) s += "sq";
        else if (e[i] > 2) s += "p" + std::to_string(e[i]);
    }
    return s;
}

int degree(const std::vector<int>& e)
{
    int d = 0;
    for (int x : e) d += x;
    return d;
}

/// Reading order of monomials: by degree, then in the order of the variables (A1 before A2 before B1).
bool reads_before(const std::vector<int>& x, const std::vector<int>& y)
{
    if (degree(x) != degree(y)) return degree(x) < degree(y);
    return x > y;
}

}  // namespace

std::string c_number(const numeric& x)
{
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.17g", x.to_double());
    std::string s = buf;
    // Shortest of %.15g/%.16g/%.17g that round-trips, for readable literals.
    for (int p : {15, 16}) {
        std::snprintf(buf, sizeof buf, "%.*g", p, x.to_double());
        if (std::strtod(buf, nullptr) == x.to_double()) {
            s = buf;
            break;
        }
    }
    if (s.find_first_of(".en") == std::string::npos) s += ".0";
    return s;
}

bool EmittedCode::constant(const std::string& kernel) const
{
    return std::find(constant_kernels.begin(), constant_kernels.end(), kernel) != constant_kernels.end();
}

EmittedCode emit_kernels(const std::string& prefix, int nq, const std::vector<Input>& parameters,
                         const std::vector<Input>& variables, const std::vector<KernelSpec>& kernels)
{
    const Decomposer decompose(parameters, variables);
    std::vector<std::string> pnames, vnames;
    for (const Input& p : parameters) pnames.push_back(p.symbol.get_name());
    for (const Input& v : variables) vnames.push_back(v.symbol.get_name());

    std::map<std::string, int> coeff_index;  // printed coefficient -> c[k]
    std::vector<std::string> coeff_text;
    std::vector<int> params_used(parameters.size());
    EmittedCode code;
    // Kernel functions wait for the coefficient count, which their shape comments state.
    struct Body {
        const KernelSpec* spec;
        std::string function;
    };
    std::vector<Body> bodies;

    for (const KernelSpec& k : kernels) {
        // For each output: var monomial -> coefficient as (number, parameter monomial) terms.
        std::vector<std::map<std::vector<int>, std::vector<std::pair<numeric, std::vector<int>>>>> outputs;
        std::set<std::vector<int>> monomials;  // variable monomials used by this kernel
        bool constant = true;
        for (const ex& v : k.values) {
            auto& grouped = outputs.emplace_back();
            for (PolyTerm& t : decompose(v)) {
                grouped[t.ve].emplace_back(t.coeff, t.pe);
                if (degree(t.ve) > 0) {
                    monomials.insert(t.ve);
                    constant = false;
                }
            }
        }
        if (constant) code.constant_kernels.push_back(k.name);

        // Monomials are built from their prefixes (drop one factor of the last variable) so that each
        // product is formed once: B1_B2 = B1*B2, then theta_dot_B1_B2 = ... reuses what exists.
        std::map<std::vector<int>, std::string> names;  // emitted monomial -> temporary name
        std::vector<std::string> lines;
        std::vector<bool> var_used(variables.size());
        auto ensure = [&](auto&& self, const std::vector<int>& e) -> std::string {
            if (auto it = names.find(e); it != names.end()) return it->second;
            std::size_t last = e.size();
            while (e[--last] == 0) {
            }
            if (degree(e) == 1) {
                var_used[last] = true;
                return names[e] = vnames[last];
            }
            std::vector<int> rest = e;
            --rest[last];
            std::vector<int> single(e.size());
            single[last] = 1;
            const std::string a = self(self, rest), b = self(self, single);
            const std::string name = monomial_name(e, vnames);
            lines.push_back("    const double " + name + " = " + a + "*" + b + ";\n");
            return names[e] = name;
        };
        std::vector<std::vector<int>> ordered(monomials.begin(), monomials.end());
        std::sort(ordered.begin(), ordered.end(), reads_before);
        for (const auto& e : ordered) ensure(ensure, e);

        std::ostringstream out_lines;
        bool uses_c = false;
        for (std::size_t i = 0; i < outputs.size(); ++i) {
            std::vector<std::pair<numeric, std::string>> terms;
            std::vector<std::vector<int>> order;
            for (const auto& entry : outputs[i]) order.push_back(entry.first);
            std::sort(order.begin(), order.end(), reads_before);
            for (const std::vector<int>& ve : order) {
                auto& coeff_terms = outputs[i][ve];
                std::sort(coeff_terms.begin(), coeff_terms.end(),
                          [](const auto& x, const auto& y) { return x.second < y.second; });
                const std::string mono = degree(ve) == 0 ? "" : names.at(ve);
                const bool pure_number = coeff_terms.size() == 1 &&
                                         std::all_of(coeff_terms[0].second.begin(), coeff_terms[0].second.end(),
                                                     [](int x) { return x == 0; });
                if (pure_number) {
                    terms.emplace_back(coeff_terms[0].first, mono);
                    continue;
                }
                std::vector<std::pair<numeric, std::string>> parts;
                for (const auto& [c, pe] : coeff_terms) {
                    for (std::size_t j = 0; j < pe.size(); ++j) params_used[j] |= pe[j] != 0;
                    const std::string num = product(pe, pnames, true), den = product(pe, pnames, false);
                    std::string m = num;
                    if (!den.empty()) m = (m.empty() ? "1.0" : m) + "/(" + den + ")";
                    parts.emplace_back(c, m);
                }
                const std::string text = signed_sum(parts);
                auto [it, added] = coeff_index.emplace(text, static_cast<int>(coeff_text.size()));
                if (added) coeff_text.push_back(text);
                const std::string ck = "c[" + std::to_string(it->second) + "]";
                terms.emplace_back(1, mono.empty() ? ck : ck + "*" + mono);
                uses_c = true;
            }
            out_lines << "    out[" << i << "] = " << signed_sum(terms) << ";\n";
        }

        std::ostringstream f;
        f << "void " << prefix << "_" << k.name
          << "(const double* c, const double* u, const double* q, const double* qd, double* out)\n{\n";
        std::string reads;
        for (std::size_t v = 0; v < variables.size(); ++v)
            if (var_used[v]) reads += "    const double " + vnames[v] + " = " + variables[v].read + ";\n";
        for (const char* arr : {"c", "u", "q", "qd"}) {
            const std::string a = arr;
            const bool used = a == "c" ? uses_c : reads.find(" = " + a + "[") != std::string::npos;
            if (!used) f << "    (void)" << a << ";\n";
        }
        f << reads;
        for (const std::string& l : lines) f << l;
        f << out_lines.str() << "}\n";
        bodies.push_back({&k, f.str()});
    }

    std::ostringstream text;
    text << "\n/* coefficients:(p[7])->(c[" << coeff_text.size()
         << "]) p = (L, rho, S, I, E, a, J_oh); once per parameter set */\n";
    text << "void " << prefix << "_coefficients(const double* p, double* c)\n{\n";
    bool any = false;
    for (std::size_t j = 0; j < parameters.size(); ++j)
        if (params_used[j]) {
            text << "    const double " << pnames[j] << " = " << parameters[j].read << ";\n";
            any = true;
        }
    if (!any) text << "    (void)p;\n";
    if (coeff_text.empty()) text << "    (void)c;\n";
    for (std::size_t i = 0; i < coeff_text.size(); ++i) text << "    c[" << i << "] = " << coeff_text[i] << ";\n";
    text << "}\n";
    for (const Body& b : bodies)
        text << "\n/* " << b.spec->name << ":(c[" << coeff_text.size() << "],u[3],q[" << nq << "],qd[" << nq << "])->("
             << b.spec->out << ") " << b.spec->doc << " */\n"
             << b.function;
    code.text = text.str();
    code.ncoeff = static_cast<int>(coeff_text.size());
    return code;
}

}  // namespace hubbeam::gen
