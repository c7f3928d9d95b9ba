// The shortest round-trip text of a double, as std::to_chars(first, last, double) writes it, in a fraction of its
// instructions: a run's CSV is mostly this text, and libstdc++'s to_chars spent about 490 instructions a number.
//
// The digits come from the Schubfach method (R. Giulietti, "The Schubfach way to render doubles", 2020): the
// rounding interval of v is scaled by a 128-bit approximation of 10^-k, and the shortest decimal in it is found by
// comparing the scaled bounds with one or two candidates, no loop over digits. The text around the digits follows
// libstdc++'s choice: the plain form (123.45, 0.001, 12300000) when it is no longer than the scientific one
// (1.2345e-05, 1e+15), exponents with a sign and at least two digits. Values this code does not meet in a run's
// rows (zero aside, subnormals, |v| >= 2^53, inf and nan) are handed to std::to_chars itself: libstdc++ writes an
// integer of 2^53 or more in the plain form with all its exact digits (123456789012345683968), not the shortest.
#include <hubbeam/shortest.hpp>

#include <array>
#include <bit>
#include <charconv>
#include <cstdint>
#include <cstring>
#include <stdexcept>

namespace hubbeam {

namespace {

using u64 = std::uint64_t;
using u128 = unsigned __int128;

/// floor(e log2(10)), for 0 <= e <= 325 (checked against the exact powers in make_table).
constexpr int floor_log2_pow10(int e) { return (e * 1741647) >> 19; }
/// floor(q log10(2)) for -1074 <= q <= 0 (checked in make_table).
constexpr int floor_log10_pow2(int q) { return static_cast<int>((q * std::int64_t{661971961083}) >> 41); }
/// floor(log10(3/4 2^q)) for -1074 <= q <= 0 (checked in make_table): the interval of a power of two is narrower
/// below it than above.
constexpr int floor_log10_three_quarters_pow2(int q)
{
    return static_cast<int>((q * std::int64_t{661971961083} - 274743187321) >> 41);
}

constexpr int max_e = 325;  // 10^325 scales the smallest normal double's interval: q = -1074 gives k = -324, -325

/// g(e) = floor(10^e 2^(127 - floor(log2 10^e))) + 1, a 128-bit number in [2^127, 2^128): 10^e with its top bit at
/// bit 127, rounded up. Rounded up, the error of g cp (cp < 2^60) stays below the 64 bits rop() ignores.
struct Pow10 {
    u64 hi, lo;
};

/// A little-endian number in base 2^32, enough for 3 10^325 (about 1081 bits).
struct Big {
    std::array<std::uint32_t, 36> w{};
    int size = 1;

    constexpr void multiply(std::uint32_t m)
    {
        u64 carry = 0;
        for (int i = 0; i < size; ++i) {
            const u64 p = u64{w[i]} * m + carry;
            w[i] = static_cast<std::uint32_t>(p);
            carry = p >> 32;
        }
        if (carry != 0) w[size++] = static_cast<std::uint32_t>(carry);
    }
    constexpr int bits() const { return (size - 1) * 32 + std::bit_width(w[size - 1]); }
    constexpr int bit(int b) const { return b < 0 ? 0 : static_cast<int>((w[b / 32] >> (b % 32)) & 1u); }
};

/// The table of g(e), e = 0..max_e, computed exactly from 10^e at compile time, and the three floor-log formulas
/// checked against the same exact powers (a formula wrong for one exponent is a compile error).
constexpr std::array<Pow10, max_e + 1> make_table()
{
    std::array<Pow10, max_e + 1> table{};
    std::array<int, max_e + 1> log2_pow10{}, log2_three_pow10{};  // floor(log2 10^e), floor(log2 3 10^e)
    Big p, three;
    p.w[0] = 1;
    three.w[0] = 3;
    for (int e = 0; e <= max_e; ++e) {
        if (e > 0) {
            p.multiply(10);
            three.multiply(10);
        }
        const int n = p.bits();
        log2_pow10[e] = n - 1;
        log2_three_pow10[e] = three.bits() - 1;
        if (floor_log2_pow10(e) != n - 1) throw std::logic_error("floor_log2_pow10");
        u128 g = 0;
        for (int b = n - 1; b >= n - 128; --b) g = (g << 1) | static_cast<u128>(p.bit(b));
        table[e] = {static_cast<u64>((g + 1) >> 64), static_cast<u64>(g + 1)};
    }
    // 10^-m <= 2^q < 10^(1-m) with m = -floor_log10_pow2(q): 2^-q <= 10^m (exactly equal only for q = m = 0, else
    // 10^m is no power of two) and 10^(m-1) < 2^-q. Likewise with 3/4 2^q, i.e. 2^(2-q) against 3 10^m.
    for (int q = -1074; q <= 0; ++q) {
        const int m = -floor_log10_pow2(q), n = -q;
        if (m < 0 || m > max_e || (m == 0 ? n != 0 : n > log2_pow10[m]) || (m > 0 && log2_pow10[m - 1] >= n))
            throw std::logic_error("floor_log10_pow2");
        const int m3 = -floor_log10_three_quarters_pow2(q), n3 = 2 - q;
        if (m3 < 0 || m3 > max_e || n3 > log2_three_pow10[m3] || (m3 > 0 && log2_three_pow10[m3 - 1] >= n3))
            throw std::logic_error("floor_log10_three_quarters_pow2");
    }
    return table;
}

constexpr std::array<Pow10, max_e + 1> pow10_table = make_table();

/// floor(g cp / 2^128), rounded to odd by the bits from 2^64 up: an exact integer stays even (g's rounding error
/// stays below 2^64), an inexact one becomes odd, so it never equals a multiple of 4 it is compared with.
inline u64 rop(const Pow10& g, u64 cp)
{
    const u128 hi = static_cast<u128>(g.hi) * cp;
    const u128 lo = static_cast<u128>(g.lo) * cp;
    const u128 m = hi + (lo >> 64);
    return static_cast<u64>(m >> 64) | static_cast<u64>(static_cast<u64>(m) != 0);
}

constexpr char digit_pairs[] =
    "00010203040506070809101112131415161718192021222324252627282930313233343536373839"
    "40414243444546474849505152535455565758596061626364656667686970717273747576777879"
    "8081828384858687888990919293949596979899";

/// Writes the two digits of d < 100 at p.
inline void write_pair(char* p, u64 d) { std::memcpy(p, digit_pairs + 2 * d, 2); }

/// Writes the 8 digits of y < 10^8 at p, leading zeros included. y 2^52 / 10^6, rounded up, holds the first pair
/// above bit 52 and the rest as a binary fraction; each multiplication by 100 brings up the next pair. The rounding
/// (less than y < 2^27 in 2^52 / 10^6 > 2^32) never reaches the next multiple of 10^-6.
inline void write_8_digits(char* p, u64 y)
{
    constexpr u64 mask = (u64{1} << 52) - 1;
    u64 f = y * 4503599628u;  // ceil(2^52 / 10^6)
    write_pair(p, f >> 52);
    f = (f & mask) * 100;
    write_pair(p + 2, f >> 52);
    f = (f & mask) * 100;
    write_pair(p + 4, f >> 52);
    f = (f & mask) * 100;
    write_pair(p + 6, f >> 52);
}

/// Writes f's n decimal digits (10^(n-1) <= f < 10^n, n <= 17) at out.
[[gnu::always_inline]] inline void write_digits(char* out, u64 f, int n)
{
    if (n > 8) {  // most numbers of a run: 16 or 17 digits
        const u64 hi = f / 100000000;
        write_8_digits(out + n - 8, f - hi * 100000000);
        f = hi;
        n -= 8;
        if (n == 9) {
            *out++ = static_cast<char>('0' + f / 100000000);
            f %= 100000000;
            n = 8;
        }
        if (n == 8) {
            write_8_digits(out, f);
            return;
        }
    }
    char* p = out + n;
    while (f >= 100) {
        const u64 q = f / 100;
        p -= 2;
        write_pair(p, f - 100 * q);
        f = q;
    }
    if (f >= 10) write_pair(p - 2, f);
    else *--p = static_cast<char>('0' + f);
}

constexpr u64 powers_of_10[] = {1ull,
                                10ull,
                                100ull,
                                1000ull,
                                10000ull,
                                100000ull,
                                1000000ull,
                                10000000ull,
                                100000000ull,
                                1000000000ull,
                                10000000000ull,
                                100000000000ull,
                                1000000000000ull,
                                10000000000000ull,
                                100000000000000ull,
                                1000000000000000ull,
                                10000000000000000ull,
                                100000000000000000ull,
                                1000000000000000000ull,
                                10000000000000000000ull};

/// The number of decimal digits of f > 0.
inline int digit_count(u64 f)
{
    const int guess = (std::bit_width(f) * 1233) >> 12;  // floor(log10 2^bits), one below or at the count
    return guess + (f >= powers_of_10[guess]);
}

/// Writes f 10^e (f > 0, at most 17 digits) at out in to_chars's form; returns the end. The digits are written
/// once, into a local buffer, and moved into place with fixed-size copies (cheaper than counted ones): so up to
/// shortest_room - 1 bytes at out are touched.
[[gnu::always_inline]] inline char* write_decimal(char* out, u64 f, int e)
{
    // The shortest digits: f without its trailing zeros.
    if (f % 10 == 0) {
        while (f % 100000000 == 0) f /= 100000000, e += 8;
        if (f % 10000 == 0) f /= 10000, e += 4;
        if (f % 100 == 0) f /= 100, e += 2;
        if (f % 10 == 0) f /= 10, e += 1;
    }
    const int n = digit_count(f);
    char d[32];
    std::memset(d, '0', sizeof d);  // an integer's zeros after its digits
    write_digits(d, f, n);
    const int x = e + n - 1;  // the scientific exponent: d.ddd 10^x
    const int scientific = n + (n > 1) + (x >= 100 || x <= -100 ? 5 : 4);
    const int plain = x >= n - 1 ? x + 1 : x >= 0 ? n + 1 : n + 1 - x;
    if (plain <= scientific) {  // so x <= 21, and x >= -4 (0.0001234 against 1.234e-04)
        if (x >= n - 1) {  // an integer: the digits, then zeros
            std::memcpy(out, d, 24);
            return out + x + 1;
        }
        if (x >= 0) {  // the point among the digits (x <= 15)
            std::memcpy(out, d, 16);
            out[x + 1] = '.';
            std::memcpy(out + x + 2, d + x + 1, 16);
            return out + n + 1;
        }
        std::memcpy(out, "0.000000", 8);  // below 1: 0.000ddd (at most 3 zeros)
        std::memcpy(out + 1 - x, d, 24);
        return out + n + 1 - x;
    }
    out[0] = d[0];
    out[1] = '.';
    std::memcpy(out + 2, d + 1, 16);
    char* p = out + (n > 1 ? n + 1 : 1);
    *p++ = 'e';
    *p++ = x < 0 ? '-' : '+';
    const unsigned a = static_cast<unsigned>(x < 0 ? -x : x);
    if (a >= 100) *p++ = static_cast<char>('0' + a / 100);
    write_pair(p, a % 100);
    return p + 2;
}

}  // namespace

char* write_shortest(char* out, double v) noexcept
{
    const u64 bits = std::bit_cast<u64>(v);
    const int be = static_cast<int>((bits >> 52) & 0x7ff);
    const u64 t = bits & ((u64{1} << 52) - 1);
    // Zero, subnormals, |v| >= 2^53, inf and nan: see the top of the file.
    if (be == 0 || be >= 1023 + 53) {
        if ((bits << 1) == 0) {
            if (bits != 0) *out++ = '-';
            *out++ = '0';
            return out;
        }
        return std::to_chars(out, out + max_shortest_chars, v).ptr;
    }
    if (bits >> 63) *out++ = '-';
    const u64 c = t | (u64{1} << 52);
    const int q = be - 1075;  // |v| = c 2^q, -1074 <= q <= 0
    u64 f = 0;
    int e = 0;
    if (q >= -52 && (c & ((u64{1} << -q) - 1)) == 0) {  // an integer
        f = c >> -q;
    } else {
        // The rounding interval [cbl, cbr] 2^(q-2), closed when c is even (ties round to even), scaled by 10^-k so
        // that it is at least 1 wide: vbl, vb, vbr are 4 times the bounds and v in units of 10^k, rounded to odd.
        const bool irregular = t == 0 && be > 1;  // a power of two: the gap below is half the gap above
        const u64 open = c & 1;
        const u64 cb = c << 2, cbr = cb + 2, cbl = irregular ? cb - 1 : cb - 2;
        e = irregular ? floor_log10_three_quarters_pow2(q) : floor_log10_pow2(q);
        const Pow10& g = pow10_table[-e];
        const int h = q + floor_log2_pow10(-e) + 1;  // 1..4
        const u64 vb = rop(g, cb << h), vbl = rop(g, cbl << h), vbr = rop(g, cbr << h);
        // The interval is narrower than 10^(e+1): at most one multiple of 10^(e+1) in it, the shortest if there is.
        const u64 s = vb >> 2;  // >= 2^52 for a normal v
        const u64 sp10 = s / 10 * 10, tp10 = sp10 + 10;
        const bool upin = vbl + open <= sp10 << 2, wpin = (tp10 << 2) + open <= vbr;
        const u64 s1 = s + 1;
        const bool uin = vbl + open <= s << 2, win = (s1 << 2) + open <= vbr;
        const u64 mid = (s + s1) << 1;
        if (upin != wpin) f = upin ? sp10 : tp10;
        // Else one or both of the multiples of 10^e around v: the nearer, ties to even.
        else if (uin != win) f = uin ? s : s1;
        else f = vb < mid || (vb == mid && (s & 1) == 0) ? s : s1;
    }
    return write_decimal(out, f, e);
}

}  // namespace hubbeam
