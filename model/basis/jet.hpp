// Second-order forward-mode jet: a value with its first two derivatives, so one templated shape-function
// source serves the runtime (values, slopes, curvatures) and the generator (GiNaC expressions).
#pragma once

#include <cmath>

namespace hubbeam {

/// f, f' and f'' of a function of one variable, carried through arithmetic by the chain rule.
template <class T>
struct Jet {
    T v{}, d1{}, d2{};
    Jet() = default;
    Jet(T value) : v(value) {}  // NOLINT(google-explicit-constructor): constants mix freely with jets
    Jet(T value, T slope, T curvature) : v(value), d1(slope), d2(curvature) {}
};

template <class T> Jet<T> operator+(const Jet<T>& a, const Jet<T>& b) { return {a.v + b.v, a.d1 + b.d1, a.d2 + b.d2}; }
template <class T> Jet<T> operator-(const Jet<T>& a, const Jet<T>& b) { return {a.v - b.v, a.d1 - b.d1, a.d2 - b.d2}; }
template <class T> Jet<T> operator-(const Jet<T>& a) { return {-a.v, -a.d1, -a.d2}; }
template <class T> Jet<T> operator*(const Jet<T>& a, const Jet<T>& b)
{
    return {a.v * b.v, a.d1 * b.v + a.v * b.d1, a.d2 * b.v + T(2) * a.d1 * b.d1 + a.v * b.d2};
}
template <class T> Jet<T> operator/(const Jet<T>& a, const Jet<T>& b)
{
    // (a/b)'' from q = a/b: q' = (a' - q b')/b, q'' = (a'' - 2 q' b' - q b'')/b
    const T q = a.v / b.v;
    const T q1 = (a.d1 - q * b.d1) / b.v;
    return {q, q1, (a.d2 - T(2) * q1 * b.d1 - q * b.d2) / b.v};
}
template <class T> Jet<T> cos(const Jet<T>& a)
{
    using std::cos, std::sin;
    const T c = cos(a.v), s = sin(a.v);
    return {c, -s * a.d1, -c * a.d1 * a.d1 - s * a.d2};
}
template <class T> Jet<T> sin(const Jet<T>& a)
{
    using std::cos, std::sin;
    const T c = cos(a.v), s = sin(a.v);
    return {s, c * a.d1, -s * a.d1 * a.d1 + c * a.d2};
}
template <class T> Jet<T> exp(const Jet<T>& a)
{
    using std::exp;
    const T e = exp(a.v);
    return {e, e * a.d1, e * (a.d1 * a.d1 + a.d2)};
}

/// The independent variable x itself at a point: value x, slope 1, curvature 0.
inline Jet<double> variable(double x) { return {x, 1.0, 0.0}; }

}  // namespace hubbeam
