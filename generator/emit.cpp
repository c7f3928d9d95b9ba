// Polynomial decomposition and printing of the generated kernels.
#include "emit.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include "generated_abi.h"
#include "monomial_order.hpp"

namespace hubbeam::gen {

using namespace GiNaC;

namespace {

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
        if (mono.empty())
            t = c_number(mag);
        else if (mag == 1)
            t = mono;
        else
            t = c_number(mag) + "*" + mono;
        if (s.empty())
            s = negative ? "-" + t : t;
        else
            s += (negative ? " - " : " + ") + t;
    }
    return s.empty() ? "0.0" : s;
}

std::string monomial_name(const std::vector<int>& e, const std::vector<std::string>& names)
{
    std::string s;
    for (std::size_t i = 0; i < e.size(); ++i) {
        if (e[i] == 0) continue;
        s += (s.empty() ? "" : "_") + names[i];
        if (e[i] == 2)
            s += "sq";
        else if (e[i] > 2)
            s += "p" + std::to_string(e[i]);
    }
    return s;
}

/// The index of a monomial's last variable (of nonzero exponent): its prefix, in the order monomials are built,
/// has one factor of it fewer. The monomial must not be constant.
std::size_t last_variable(const std::vector<int>& e)
{
    std::size_t last = e.size();
    while (e[--last] == 0) {
    }
    return last;
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

namespace {

/// One output as a polynomial in the state: state monomial (exponents over the state inputs) -> coefficient.
using Output = std::map<Exponents, Coefficient>;

/// Stage "decompose": each output of a kernel as a polynomial in the state with parameter coefficients (given as
/// Polys, or read from expressions).
std::vector<Output> decompose_outputs(const PolyReader& read, KernelSpec& k)
{
    std::vector<Output> outputs;
    for (Poly& p : k.polys) outputs.push_back(std::move(p).release());
    for (const ex& v : k.values) {
        try {
            outputs.push_back(read(v).terms());
        } catch (const std::invalid_argument& e) {
            throw EmitError(std::string("emit: cannot print: ") + e.what());
        }
    }
    return outputs;
}

/// Stage "plan monomials": every state monomial a kernel uses, formed once as a const temporary from its
/// prefixes (drop one factor of the last variable): B1_B2 = B1*B2, then theta_dot_B1_B2 reuses B1_B2.
struct MonomialPlan {
    std::map<std::vector<int>, std::string> names;  // monomial -> the variable or temporary holding it
    std::vector<std::string> lines;                 // the temporaries' definitions, in reading order
    std::vector<bool> variable_used;
};

MonomialPlan plan_monomials(const std::vector<Output>& outputs, const std::vector<std::string>& vnames)
{
    MonomialPlan plan;
    plan.variable_used.assign(vnames.size(), false);
    std::set<std::vector<int>> monomials;
    for (const Output& o : outputs)
        for (const auto& entry : o)
            if (degree(entry.first) > 0) monomials.insert(entry.first);
    auto ensure = [&](auto&& self, const std::vector<int>& e) -> std::string {
        if (auto it = plan.names.find(e); it != plan.names.end()) return it->second;
        const std::size_t last = last_variable(e);
        if (degree(e) == 1) {
            plan.variable_used[last] = true;
            return plan.names[e] = vnames[last];
        }
        std::vector<int> rest = e;
        --rest[last];
        std::vector<int> single(e.size());
        single[last] = 1;
        const std::string a = self(self, rest), b = self(self, single);
        const std::string name = monomial_name(e, vnames);
        plan.lines.push_back("    const double " + name + " = " + a + "*" + b + ";\n");
        return plan.names[e] = name;
    };
    std::vector<std::vector<int>> ordered(monomials.begin(), monomials.end());
    sort_reading(ordered);
    for (const auto& e : ordered) ensure(ensure, e);
    return plan;
}

/// An output's terms in reading order (pointers into it, no copies).
std::vector<const Output::value_type*> reading_order(const Output& o)
{
    std::vector<const Output::value_type*> terms;
    terms.reserve(o.size());
    for (const auto& entry : o) terms.push_back(&entry);
    std::vector<const Output::value_type*> order;
    order.reserve(terms.size());
    for (std::size_t i :
         reading_permutation(terms, [](const Output::value_type* t) -> const Exponents& { return t->first; }))
        order.push_back(terms[i]);
    return order;
}

/// Stage "pool coefficients": every coefficient that is not a pure number becomes one entry c[k] of the
/// coefficients kernel, shared by all kernels of the variant (equal text, one entry).
class CoefficientPool {
public:
    explicit CoefficientPool(std::vector<std::string> pnames) : pnames_(std::move(pnames)), params_used_(pnames_.size())
    {
    }

    /// The pure number of a coefficient without parameters, or nullopt.
    static std::optional<numeric> pure_number(const Coefficient& c)
    {
        const auto& [pe, number] = *c.begin();
        if (c.size() != 1 || std::any_of(pe.begin(), pe.end(), [](int x) { return x != 0; })) return std::nullopt;
        return number;
    }

    /// The coefficient as sign * c[k], adding c[k] to the pool if it is new. A coefficient and its negative
    /// share one entry: the entry holds the form whose first term is positive.
    std::pair<int, std::string> reference(Coefficient c)
    {
        const int sign = c.begin()->second < 0 ? -1 : 1;
        // Equal doubles print equal text (c_number is the shortest round-trip form), so the doubles find an entry
        // without printing it: order full has 10^5 references.
        std::vector<std::pair<Exponents, double>> key;
        for (const auto& [pe, number] : c) key.emplace_back(pe, sign * number.to_double());
        if (auto found = by_value_.find(key); found != by_value_.end())
            return {sign, "c[" + std::to_string(found->second) + "]"};
        std::vector<std::pair<numeric, std::string>> parts;
        for (const auto& [pe, number] : c) {
            for (std::size_t j = 0; j < pe.size(); ++j) params_used_[j] = params_used_[j] || pe[j] != 0;
            const std::string num = product(pe, pnames_, true), den = product(pe, pnames_, false);
            std::string m = num;
            if (!den.empty()) m = (m.empty() ? "1.0" : m) + "/(" + den + ")";
            parts.emplace_back(sign * number, m);
        }
        const std::string text = signed_sum(parts);
        auto [it, added] = index_.emplace(text, static_cast<int>(texts_.size()));
        if (added) {
            texts_.push_back(text);
            for (auto& term : c) term.second *= sign;
            entries_.push_back(std::move(c));
        }
        by_value_.emplace(std::move(key), it->second);
        return {sign, "c[" + std::to_string(it->second) + "]"};
    }

    const std::vector<std::string>& texts() const { return texts_; }
    /// Entry k as a sum of number * parameter monomial (texts()[k] printed).
    const std::vector<Coefficient>& entries() const { return entries_; }
    const std::vector<std::string>& parameter_names() const { return pnames_; }
    bool parameter_used(std::size_t j) const { return params_used_[j]; }

private:
    std::vector<std::string> pnames_;
    std::vector<bool> params_used_;
    std::map<std::string, int> index_;
    std::map<std::vector<std::pair<Exponents, double>>, int> by_value_;
    std::vector<std::string> texts_;
    std::vector<Coefficient> entries_;
};

/// Stage "print": "out[slot] = ...;" for each output, monomials in reading order.
std::string print_outputs(const std::vector<Output>& outputs, const std::vector<int>& slots, const MonomialPlan& plan,
                          CoefficientPool& pool, bool& uses_c)
{
    std::ostringstream lines;
    for (std::size_t i = 0; i < outputs.size(); ++i) {
        std::vector<std::pair<numeric, std::string>> terms;
        for (const auto* entry : reading_order(outputs[i])) {
            const Exponents& ve = entry->first;
            const Coefficient& c = entry->second;
            const std::string mono = degree(ve) == 0 ? "" : plan.names.at(ve);
            if (const auto number = CoefficientPool::pure_number(c)) {
                terms.emplace_back(*number, mono);
                continue;
            }
            const auto [sign, ck] = pool.reference(c);
            terms.emplace_back(sign, mono.empty() ? ck : ck + "*" + mono);
            uses_c = true;
        }
        lines << "    out[" << (slots.empty() ? static_cast<int>(i) : slots[i]) << "] = " << signed_sum(terms) << ";\n";
    }
    return lines.str();
}

/// Stage "print" of a matrix-times-monomials kernel: out[i] = sum_k P(i, k) m_k over the entries pattern allows (all
/// when empty), in increasing k, every m_k a monomial with coefficient 1 (KernelSpec::rows). The rows go in groups of
/// W = generated::folded_lanes, the lanes of one AVX2 register (two SSE2 ones): with j = i + offset (offset W - 1
/// puts row 0 alone, beside padding), P's entry (i, k) is read at c[(j/W)*W*K + W*k + j%W], so that a group's
/// entries of a column are one load; each lane adds its own row's terms in the scalar order (an entry outside its
/// row's pattern is zero and adds nothing), so the sums are the scalar ones to the bit. A row without a partner is
/// scalar.
/// The names print_matrix_product multiplies P's columns by: each monomial's (1.0 for the constant one), which must
/// have coefficient 1.
std::vector<std::string> monomial_names(const std::vector<Output>& monomials, const MonomialPlan& plan)
{
    std::vector<std::string> names;
    for (const Output& m : monomials) {
        if (m.size() != 1 || CoefficientPool::pure_number(m.begin()->second) != numeric(1))
            throw EmitError("emit: a matrix-times-monomials kernel takes monomials with coefficient 1");
        names.push_back(degree(m.begin()->first) == 0 ? "1.0" : plan.names.at(m.begin()->first));
    }
    return names;
}

/// The rows of a matrix-times-monomials kernel in groups of W lanes (print_matrix_product): which row each lane
/// slot holds, and which entries of P its pattern allows.
struct LaneGroups {
    static constexpr int W = generated::folded_lanes;
    int rows, offset;
    const std::vector<bool>& pattern;
    std::size_t K;

    /// Row of lane slot j (-1: padding).
    int row(int j) const { return j - offset >= 0 && j - offset < rows ? j - offset : -1; }
    /// Whether P's entry (i, k) can be nonzero.
    bool allowed(int i, std::size_t k) const
    {
        return i >= 0 && (pattern.empty() || pattern[static_cast<std::size_t>(i) * K + k]);
    }
    /// The rows of group g's slots.
    std::vector<int> group_rows(int g) const
    {
        std::vector<int> r;
        for (int l = 0; l < W; ++l)
            if (row(g * W + l) >= 0) r.push_back(row(g * W + l));
        return r;
    }
    /// Whether column k is read by any of group g's rows.
    bool reads(int g, std::size_t k) const
    {
        for (int l = 0; l < W; ++l)
            if (allowed(row(g * W + l), k)) return true;
        return false;
    }
    int count() const { return (rows + offset + W - 1) / W; }
    /// Whether any group of more than one row reads a column: the kernel then needs the lane types.
    bool any_vector() const
    {
        bool vectors = false;
        for (int g = 0; g < count() && !vectors; ++g)
            if (group_rows(g).size() > 1)
                for (std::size_t k = 0; k < K && !vectors; ++k) vectors = reads(g, k);
        return vectors;
    }
};

/// Row i alone in group g (beside padding): a scalar sum in its lane's entries; whether it read c.
bool print_scalar_row(std::ostringstream& lines, const LaneGroups& groups, int g, int i,
                      const std::vector<std::string>& names)
{
    constexpr int W = LaneGroups::W;
    const std::size_t base = static_cast<std::size_t>(g) * W * groups.K;
    const int lane = i + groups.offset - g * W;
    lines << "    out[" << i << "] =";
    bool first = true;
    for (std::size_t k = 0; k < groups.K; ++k) {
        if (!groups.allowed(i, k)) continue;
        lines << (first ? " " : " + ") << "c[" << base + W * k + static_cast<std::size_t>(lane) << "]*" << names[k];
        first = false;
    }
    lines << (first ? " 0.0;\n" : ";\n");
    return !first;
}

/// The rows in of group g: one vector sum over the columns the group reads, each lane written to its row; whether it
/// read c.
bool print_lane_group(std::ostringstream& lines, const LaneGroups& groups, int g, const std::vector<int>& in,
                      const std::vector<std::string>& names)
{
    constexpr int W = LaneGroups::W;
    bool first = true;
    for (std::size_t k = 0; k < groups.K; ++k) {
        if (!groups.reads(g, k)) continue;
        // A vector times a scalar multiplies every lane by it (GCC's vector extension).
        const std::string term =
            "column[" + std::to_string(static_cast<std::size_t>(g) * groups.K + k) + "] * " + names[k];
        lines << (first ? "    {\n        lanes s = " : "        s += ") << term << ";\n";
        first = false;
    }
    if (first) {
        for (const int i : in) lines << "    out[" << i << "] = 0.0;\n";
        return false;
    }
    for (const int i : in) lines << "        out[" << i << "] = s[" << i + groups.offset - g * W << "];\n";
    lines << "    }\n";
    return true;
}

std::string print_matrix_product(const std::vector<Output>& monomials, int rows, int offset,
                                 const std::vector<bool>& pattern, const MonomialPlan& plan, bool& uses_c)
{
    constexpr int W = generated::folded_lanes;
    const std::vector<std::string> names = monomial_names(monomials, plan);
    const std::size_t K = names.size();
    if (!pattern.empty() && pattern.size() != static_cast<std::size_t>(rows) * K)
        throw EmitError("emit: a matrix-times-monomials kernel's pattern has " + std::to_string(pattern.size()) +
                        " entries for " + std::to_string(rows) + " x " + std::to_string(K));
    const LaneGroups groups{rows, offset, pattern, K};
    std::ostringstream lines;
    uses_c = false;
    if (groups.any_vector())
        lines << "    typedef double lanes __attribute__((vector_size(" << 8 * W << ")));\n"
              << "    typedef double lanes_at __attribute__((vector_size(" << 8 * W << "), aligned(8), may_alias));\n"
              << "    // column[g*" << K << " + k]: group g's entries of column k.\n"
              << "    const lanes_at* const column = reinterpret_cast<const lanes_at*>(c);\n";
    for (int g = 0; g < groups.count(); ++g) {
        const std::vector<int> in = groups.group_rows(g);
        if (in.empty()) continue;
        const bool read_c = in.size() == 1 ? print_scalar_row(lines, groups, g, in[0], names)
                                           : print_lane_group(lines, groups, g, in, names);
        uses_c = uses_c || read_c;
    }
    return lines.str();
}

/// Number of terms of a kernel's outputs (what unrolled code would print).
std::size_t term_count(const std::vector<Output>& outputs)
{
    std::size_t n = 0;
    for (const Output& o : outputs) n += o.size();
    return n;
}

/// The monomials of a table-form kernel, in reading order, each built from one before it: m[0] = 1 and
/// m[k + 1] = m[a] * v[b], chain line k = "{a, b}"; index maps each monomial's exponents to its k + 1 (1 to 0).
struct MonomialChain {
    std::vector<std::vector<int>> ordered;
    std::map<std::vector<int>, int> index;
    std::string chain;
};

MonomialChain monomial_chain(const std::vector<Output>& outputs, std::size_t variables)
{
    // Monomials in reading order, each after its prefix (one factor of its last variable fewer).
    std::set<std::vector<int>> all;
    for (const Output& o : outputs)
        for (const auto& entry : o)
            for (std::vector<int> e = entry.first; degree(e) > 0;) {
                if (!all.insert(e).second) break;
                --e[last_variable(e)];
            }
    MonomialChain c;
    c.ordered.assign(all.begin(), all.end());
    sort_reading(c.ordered);
    c.index.emplace(std::vector<int>(variables), 0);
    std::ostringstream chain;
    for (const std::vector<int>& e : c.ordered) {
        const std::size_t last = last_variable(e);
        std::vector<int> rest = e;
        --rest[last];
        chain << "        {" << c.index.at(rest) << ", " << last << "},\n";
        c.index.emplace(e, static_cast<int>(c.index.size()));
    }
    c.chain = chain.str();
    return c;
}

/// The tables' text of a table-form kernel: terms (pairs signed coefficient entry, monomial), first (each written
/// entry's first term, then the count) and written (the output slots).
struct TermTables {
    std::string terms, first, written;
    std::size_t nterms = 0;
};

TermTables term_tables(const KernelSpec& k, const std::vector<Output>& outputs,
                       const std::map<std::vector<int>, int>& index, CoefficientPool& pool)
{
    std::ostringstream terms, first, written;
    std::size_t nterms = 0;
    for (std::size_t i = 0; i < outputs.size(); ++i) {
        const char* sep = i == 0 ? "" : i % 16 == 0 ? ",\n        " : ", ";
        written << sep << (k.slots.empty() ? static_cast<int>(i) : k.slots[i]);
        first << sep << nterms;
        for (const auto* entry : reading_order(outputs[i])) {
            const Exponents& ve = entry->first;
            // Pure numbers are pool entries too, so that a term is two integers: the signed entry and the monomial.
            const auto [sign, ck] = pool.reference(entry->second);
            const int coef = std::stoi(ck.substr(2));  // "c[k]"
            terms << (nterms % 8 == 0 ? "\n        " : " ") << (sign > 0 ? coef : -coef - 1) << ", " << index.at(ve)
                  << ",";
            ++nterms;
        }
    }
    first << (outputs.empty() ? "" : ", ") << nterms;
    return {terms.str(), first.str(), written.str(), nterms};
}

/// Stage "print" in table form: the kernel's monomials m[k] built by the chain m[k + 1] = m[a] * v[b] from
/// m[0] = 1, then each written entry as a sum over its run of terms (scale * c[coef] * m[mono]), accumulated in a
/// register: rows of a sparse matrix in compressed form.
std::string print_tables(const std::string& prefix, const KernelSpec& k, const Signature& sig,
                         const std::vector<Output>& outputs, CoefficientPool& pool)
{
    const MonomialChain chain = monomial_chain(outputs, sig.state_inputs.size());
    const TermTables t = term_tables(k, outputs, chain.index, pool);
    const std::vector<std::vector<int>>& ordered = chain.ordered;
    // Up to 64 KB of monomials on the stack; beyond, one buffer per thread.
    const std::size_t nm = ordered.size() + 1;
    std::ostringstream f;
    f << "void " << prefix << "_" << k.name << "(const double* c";
    for (const Array& a : sig.state) f << ", const double* " << a.name;
    f << ", double* out)\n{\n";
    f << "    // Table form (" << t.nterms << " terms, " << ordered.size()
      << " monomials): m[0] = 1, m[k + 1] = m[chain[k][0]] * v[chain[k][1]];\n"
      << "    // out[written[i]] = sum over terms t = first[i] .. first[i + 1] - 1 of c[k] * m[terms[2t + 1]], k = "
         "terms[2t],\n"
      << "    // negated for k < 0 (entry -k - 1).\n";
    if (ordered.empty()) {  // a state-free kernel reads no state (its callers may pass null pointers)
        for (const Array& a : sig.state) f << "    (void)" << a.name << ";\n";
        f << "    const double m[1] = {1.0};\n";
    } else {
        f << "    static const int chain[][2] = {\n" << chain.chain << "    };\n";
        f << "    const double v[] = {";
        for (std::size_t v = 0; v < sig.state_inputs.size(); ++v) f << (v ? ", " : "") << sig.state_inputs[v].read;
        f << "};\n";
        f << "    " << (nm > 8192 ? "static thread_local " : "") << "double m[" << nm << "];\n    m[0] = 1.0;\n";
        f << "    for (int k = 0; k < " << ordered.size() << "; ++k) m[k + 1] = m[chain[k][0]] * v[chain[k][1]];\n";
    }
    if (outputs.empty()) {
        f << "    (void)c;\n    (void)m;\n    (void)out;  // every entry is zero\n}\n";
        return f.str();
    }
    if (t.nterms > 0)
        f << "    static const int terms[] = {" << t.terms << "\n    };\n";
    else
        f << "    static const int terms[2] = {0, 0};  // no term: every written entry is zero\n    (void)m;\n";
    f << "    static const int written[] = {" << t.written << "};\n";
    f << "    static const int first[] = {" << t.first << "};\n";
    f << "    for (int i = 0; i < " << outputs.size() << "; ++i) {\n        double sum = 0.0;\n"
      << "        for (int t = first[i]; t < first[i + 1]; ++t) {\n"
      << "            const int k = terms[2 * t];\n"
      << "            sum += (k >= 0 ? c[k] : -c[-k - 1]) * m[terms[2 * t + 1]];\n        }\n"
      << "        out[written[i]] = sum;\n    }\n}\n";
    return f.str();
}

/// The function of one kernel: reads of the state it uses, its monomials, its outputs.
std::string print_kernel(const std::string& prefix, const KernelSpec& k, const Signature& sig, const MonomialPlan& plan,
                         const std::string& outputs, bool uses_c)
{
    std::ostringstream f;
    // A matrix-times-monomials kernel's lanes run four wide where the processor has AVX2 (generated_abi.h); a
    // right-hand side's unrolled sums take AVX's three-operand forms there, without the copies SSE2's two-operand
    // forms need (FEM Nx = 16, Ny = 64: the controlled hub's run 0.78 of the time). Not kernels with point loops
    // (order full's tails), whose clones ran 1.64 times slower, nor constant ones, called once.
    const bool wide = k.rows > 0 || (k.every_right_hand_side && k.tail.empty() && !plan.names.empty());
    f << (wide ? "HUBBEAM_WIDE_KERNEL " : "") << "void " << prefix << "_" << k.name << "(const double* c";
    for (const Array& a : sig.state) f << ", const double* " << a.name;
    f << ", double* out)\n{\n";
    std::string reads;
    for (std::size_t v = 0; v < sig.state_inputs.size(); ++v)
        if (plan.variable_used[v])
            reads +=
                "    const double " + sig.state_inputs[v].symbol.get_name() + " = " + sig.state_inputs[v].read + ";\n";
    if (!uses_c) f << "    (void)c;\n";
    if (outputs.empty()) f << "    (void)out;  // every entry is zero\n";
    for (const Array& a : sig.state)
        if (reads.find(" = " + a.name + "[") == std::string::npos) f << "    (void)" << a.name << ";\n";
    f << reads;
    for (const std::string& l : plan.lines) f << l;
    f << outputs << "}\n";
    return f.str();
}

/// The coefficients kernel: c[k] from the parameters, once per parameter set.
std::string print_coefficients(const std::string& prefix, const Signature& sig, const CoefficientPool& pool,
                               bool tables)
{
    const Array& p = sig.parameters;
    std::ostringstream text;
    text << "\n/* coefficients:(" << p.name << "[" << p.size << "])->(c[" << pool.texts().size() << "]) " << p.doc
         << "; once per parameter set */\n";
    text << "HUBBEAM_ONCE_KERNEL void " << prefix << "_coefficients(const double* " << p.name << ", double* c)\n{\n";
    bool any = false;
    for (std::size_t j = 0; j < sig.parameter_inputs.size(); ++j)
        if (pool.parameter_used(j)) {
            text << "    const double " << sig.parameter_inputs[j].symbol.get_name() << " = "
                 << sig.parameter_inputs[j].read << ";\n";
            any = true;
        }
    if (!any) text << "    (void)" << p.name << ";\n";
    if (pool.texts().empty()) text << "    (void)c;\n";
    if (tables) {
        // The distinct parameter monomials pm[j], unrolled (a few), then c[k] += number * pm[j] from a table.
        std::map<std::vector<int>, int> monomials;
        std::ostringstream terms;
        std::size_t nterms = 0;
        for (std::size_t k = 0; k < pool.entries().size(); ++k)
            for (const auto& [pe, number] : pool.entries()[k]) {
                const int j = monomials.emplace(pe, static_cast<int>(monomials.size())).first->second;
                terms << "        {" << k << ", " << j << ", " << c_number(number) << "},\n";
                ++nterms;
            }
        std::vector<std::string> pm(monomials.size());
        for (const auto& [pe, j] : monomials) {
            const std::string num = product(pe, pool.parameter_names(), true),
                              den = product(pe, pool.parameter_names(), false);
            pm[static_cast<std::size_t>(j)] = (num.empty() ? "1.0" : num) + (den.empty() ? "" : "/(" + den + ")");
        }
        text << "    // Table form (" << nterms
             << " terms): c[t.entry] += t.number * pm[t.monomial] for each term t.\n";
        text << "    const double pm[] = {";
        for (std::size_t j = 0; j < pm.size(); ++j) text << (j ? ", " : "") << pm[j];
        text << "};\n    struct Term {\n        int entry, monomial;\n        double number;\n    };\n";
        text << "    static const Term terms[] = {\n" << terms.str() << "    };\n";
        text << "    for (int k = 0; k < " << pool.texts().size() << "; ++k) c[k] = 0.0;\n";
        text << "    for (const Term& t : terms) c[t.entry] += t.number * pm[t.monomial];\n";
    } else {
        for (std::size_t i = 0; i < pool.texts().size(); ++i)
            text << "    c[" << i << "] = " << pool.texts()[i] << ";\n";
    }
    text << "}\n";
    return text.str();
}

/// The p entry of "p[i]", or -1 for any other text.
int entry_of(const std::string& r)
{
    if (r.size() < 4 || r.compare(0, 2, "p[") != 0 || r.back() != ']') return -1;
    return std::stoi(r.substr(2, r.size() - 3));
}

/// For a read "std::cos(ARG)" or "std::sin(ARG)" with ARG "p[i]" or "K * p[i]" (a pitch's, a precone's): i and the C
/// text of the read's derivative by p[i]; {-1, ""} for any other read.
std::pair<int, std::string> trigonometric_derivative(const std::string& read)
{
    const bool cos = read.rfind("std::cos(", 0) == 0, sin = read.rfind("std::sin(", 0) == 0;
    if ((!cos && !sin) || read.back() != ')') return {-1, ""};
    const std::string arg = read.substr(9, read.size() - 10);
    const std::size_t star = arg.find(" * ");
    const std::string factor = star == std::string::npos ? "" : arg.substr(0, star) + " * ";
    const int i = entry_of(star == std::string::npos ? arg : arg.substr(star + 3));
    if (i < 0) return {-1, ""};
    return {i, cos ? "-" + factor + "std::sin(" + arg + ")" : factor + "std::cos(" + arg + ")"};
}

/// The p entries an input reads and, for each, the C text of d(input)/d(p entry): an input's read is "p[i]", a
/// product "p[i] * p[j]" (m = rho S), whose derivative by one factor is the product of the others ("1" alone), or the
/// cosine or sine of one entry (trigonometric_derivative).
std::vector<std::pair<int, std::string>> read_derivatives(const std::string& read)
{
    if (const auto [i, d] = trigonometric_derivative(read); i >= 0) return {{i, d}};
    std::vector<std::string> factors;
    for (std::size_t at = 0; at <= read.size();) {
        const std::size_t star = read.find(" * ", at);
        factors.push_back(read.substr(at, star == std::string::npos ? std::string::npos : star - at));
        if (star == std::string::npos) break;
        at = star + 3;
    }
    std::vector<std::pair<int, std::string>> out;
    for (std::size_t f = 0; f < factors.size(); ++f) {
        const int entry = entry_of(factors[f]);
        if (entry < 0) throw EmitError("emit: cannot differentiate the parameter read " + read);
        std::string rest;
        for (std::size_t g = 0; g < factors.size(); ++g)
            if (g != f) {
                if (!rest.empty()) rest += '*';
                rest += factors[g];
            }
        out.emplace_back(entry, rest);
    }
    return out;
}

/// The coefficients' derivatives by the parameters, dc/dp, from the pool's entries (sums of number * parameter
/// monomial) by the chain rule through the inputs' reads; written by p entry then c entry, nonzero entries only.
std::string print_coefficients_p(const std::string& prefix, const Signature& sig, const CoefficientPool& pool)
{
    const Array& p = sig.parameters;
    const std::vector<std::string>& names = pool.parameter_names();
    const std::size_t nc = pool.texts().size();
    // (p entry, c entry) -> terms number * text
    std::map<std::pair<int, std::size_t>, std::vector<std::pair<numeric, std::string>>> terms;
    std::vector<bool> used(names.size());
    for (std::size_t i = 0; i < nc; ++i)
        for (const auto& [pe, number] : pool.entries()[i])
            for (std::size_t j = 0; j < pe.size(); ++j) {
                if (pe[j] == 0) continue;
                std::vector<std::pair<int, std::string>> by = read_derivatives(sig.parameter_inputs[j].read);
                std::erase_if(by, [&](const auto& kd) {
                    return sig.derivative_entries >= 0 && kd.first >= sig.derivative_entries;
                });
                if (by.empty()) continue;
                std::vector<int> e = pe;
                --e[j];
                for (std::size_t l = 0; l < e.size(); ++l) used[l] = used[l] || e[l] != 0;
                const std::string num = product(e, names, true), den = product(e, names, false);
                for (const auto& [k, d] : by) {
                    std::string mono = num;
                    if (!d.empty()) mono = mono.empty() ? d : mono + "*" + d;
                    if (!den.empty()) mono = (mono.empty() ? "1.0" : mono) + "/(" + den + ")";
                    terms[{k, i}].emplace_back(number * pe[j], mono);
                }
            }
    std::ostringstream text;
    text << "\n/* coefficients_p:(" << p.name << "[" << p.size << "])->(dcdp[" << p.size << "*" << nc << "]) out[k*"
         << nc << " + i] = dc_i/dp_k, by the chain rule on the coefficients above; nonzero entries "
         << "only */\n";
    text << "HUBBEAM_ONCE_KERNEL void " << prefix << "_coefficients_p(const double* " << p.name
         << ", double* out)\n{\n";
    bool reads_p = false;
    for (std::size_t j = 0; j < names.size(); ++j)
        if (used[j]) {
            text << "    const double " << names[j] << " = " << sig.parameter_inputs[j].read << ";\n";
            reads_p = true;
        }
    for (const auto& [at, parts] : terms) {
        for (const auto& part : parts) reads_p = reads_p || part.second.find(p.name + "[") != std::string::npos;
        text << "    out[" << static_cast<std::size_t>(at.first) * nc + at.second << "] = " << signed_sum(parts)
             << ";\n";
    }
    if (!reads_p) text << "    (void)" << p.name << ";\n";
    if (terms.empty()) text << "    (void)out;\n";
    text << "}\n";
    return text.str();
}

/// A kernel's body with its tail before the closing brace, the tail's placeholders replaced by pool entries.
std::string with_tail(std::string body, const KernelSpec& k, const PolyReader& read, CoefficientPool& pool)
{
    if (k.tail.empty()) return body;
    std::string tail = k.tail;
    for (const auto& [name, value] : k.tail_coefficients) {
        const std::map<Exponents, Coefficient> terms = read(value).terms();
        if (terms.size() != 1 || degree(terms.begin()->first) != 0)
            throw EmitError("emit: the tail coefficient " + name + " is not free of the state");
        const Coefficient& c = terms.begin()->second;
        std::string text;
        if (const auto number = CoefficientPool::pure_number(c))
            text = c_number(*number);
        else {
            const auto [sign, ck] = pool.reference(c);
            text = sign < 0 ? "(-" + ck + ")" : ck;
        }
        for (std::size_t at = tail.find(name); at != std::string::npos; at = tail.find(name, at + text.size()))
            tail.replace(at, name.size(), text);
    }
    const std::size_t close = body.rfind("}\n");
    return body.insert(close, tail);
}

std::vector<std::string> names_of(const std::vector<Input>& inputs)
{
    std::vector<std::string> names;
    for (const Input& i : inputs) names.push_back(i.symbol.get_name());
    return names;
}

}  // namespace

EmittedCode emit_kernels(const std::string& prefix, const Signature& sig, std::vector<KernelSpec> kernels,
                         const EmitOptions& options)
{
    using Form = EmitOptions::Form;
    std::vector<symbol> parameters;
    for (const Input& i : sig.parameter_inputs) parameters.push_back(i.symbol);
    const PolyReader read(parameters, sig.state_inputs_symbols());
    CoefficientPool pool(names_of(sig.parameter_inputs));
    EmittedCode code;
    std::vector<std::string> bodies;  // printed after the coefficients kernel, whose size they state
    for (KernelSpec& k : kernels) {
        const std::vector<Output> outputs = decompose_outputs(read, k);
        if (!k.slots.empty() && k.slots.size() != outputs.size())
            throw EmitError("emit: kernel " + k.name + " has " + std::to_string(outputs.size()) + " values but " +
                            std::to_string(k.slots.size()) + " slots");
        const int threshold = k.every_right_hand_side ? options.rhs_table_threshold : options.table_threshold;
        const bool tables = k.rows == 0 && (options.form == Form::tables ||
                                            (options.form == Form::automatic &&
                                             term_count(outputs) > static_cast<std::size_t>(threshold)));
        if (tables) {
            bool constant = true;
            for (const Output& o : outputs)
                for (const auto& entry : o) constant = constant && degree(entry.first) == 0;
            if (constant && k.tail.empty()) code.constant_kernels.push_back(k.name);
            bodies.push_back(with_tail(print_tables(prefix, k, sig, outputs, pool), k, read, pool));
            continue;
        }
        const MonomialPlan plan = plan_monomials(outputs, names_of(sig.state_inputs));
        if (plan.names.empty() && k.tail.empty()) code.constant_kernels.push_back(k.name);
        bool uses_c = false;
        const std::string lines = k.rows > 0
                                      ? print_matrix_product(outputs, k.rows, k.row_offset, k.pattern, plan, uses_c)
                                      : print_outputs(outputs, k.slots, plan, pool, uses_c);
        bodies.push_back(with_tail(print_kernel(prefix, k, sig, plan, lines, uses_c), k, read, pool));
    }
    std::ostringstream text;
    std::size_t coefficient_terms = 0;
    for (const Coefficient& c : pool.entries()) coefficient_terms += c.size();
    const bool coefficient_tables =
        !pool.texts().empty() &&
        (options.form == Form::tables ||
         (options.form == Form::automatic && coefficient_terms > static_cast<std::size_t>(options.table_threshold)));
    text << print_coefficients(prefix, sig, pool, coefficient_tables);
    // Every kernel printed from polynomials reads each term's coefficient as one c[k] (or a pure number): it is
    // affine in c, so its derivative by p_k is itself at c = dc/dp_k less itself at c = 0. Hand-written tails
    // (order full's quadrature points) multiply coefficients: they have no such derivative.
    code.affine = options.parameter_derivatives &&
                  std::none_of(kernels.begin(), kernels.end(), [](const KernelSpec& k) { return !k.tail.empty(); });
    if (code.affine) text << print_coefficients_p(prefix, sig, pool);
    for (std::size_t i = 0; i < kernels.size(); ++i) {
        text << "\n/* " << kernels[i].name << ":(c[" << pool.texts().size() << "]";
        for (const Array& a : sig.state) text << "," << a.name << "[" << a.size << "]";
        text << ")->(" << kernels[i].out << ") " << kernels[i].doc << " */\n" << bodies[i];
    }
    code.text = text.str();
    code.ncoeff = static_cast<int>(pool.texts().size());
    return code;
}

}  // namespace hubbeam::gen
