// Small scalar helpers shared by the shape-function files: exact constants and integer powers for any
// scalar type (double, Jet<double>, GiNaC::ex).
#pragma once

namespace hubbeam {

/// p/q in the scalar type T: an exact rational when T is GiNaC::ex.
template <class T> T frac(long p, long q = 1) { return T(p) / T(q); }

/// x^k for k >= 0 by repeated multiplication (keeps polynomials polynomial for every T).
template <class T> T ipow(const T& x, int k)
{
    T r = frac<T>(1);
    for (int i = 0; i < k; ++i) r = r * x;
    return r;
}

/// n choose k as an integer.
inline long binomial(int n, int k)
{
    long r = 1;
    for (int i = 1; i <= k; ++i) r = r * (n - k + i) / i;
    return r;
}

}  // namespace hubbeam
