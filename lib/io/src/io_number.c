/* Number text of meshtopo::io, read and written. Coordinates: plain decimals
 * with at most 19 significant digits are read exactly without strtod:
 * Clinger's fast path (one exact IEEE multiplication or division) when the
 * significand fits in 53 bits and |exponent| <= 22, else the Eisel-Lemire
 * algorithm (one or two 64x128-bit products with a table of powers of five,
 * io_pow5.c; Lemire, "Number parsing at a gigabyte per second", 2021),
 * which gives the correctly rounded double or declines. Anything declined
 * (more digits, subnormal or out-of-range results, hex, inf, nan) goes to
 * strtod, so every value is bit-identical to strtod's. Hand-written because
 * strtod is locale-aware and several times slower, and no Debian C package
 * offers this. Doubles are written as the shortest of %.15g/%.16g/%.17g
 * that reads back bit for bit; counts are plain digits. All under the C
 * locale, so that '.' is always the decimal point. */
#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "io_internal.h"

const double mt__pow10_exact[23] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                    1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
                                    1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};

static int parse_with_strtod(const unsigned char *s, size_t len, double *out)
{
    char small[128];
    char *buf = small;
    if (len == 0) return 0;
    if (len >= sizeof small) {
        buf = malloc(len + 1);
        if (!buf) return 0;
    }
    memcpy(buf, s, len);
    buf[len] = '\0';
    char *end = NULL;
    errno = 0;
    double v = strtod(buf, &end);
    int ok = end == buf + len; /* ERANGE gives +-inf or a (sub)normal rounding: kept */
    if (buf != small) free(buf);
    if (ok) *out = v;
    return ok;
}

/* The high and low 64 bits of a * b. */
static inline void mul_64x64(uint64_t a, uint64_t b, uint64_t *hi, uint64_t *lo)
{
#if defined(__SIZEOF_INT128__)
    unsigned __int128 r = (unsigned __int128)a * b;
    *hi = (uint64_t)(r >> 64);
    *lo = (uint64_t)r;
#else
    uint64_t a0 = (uint32_t)a, a1 = a >> 32, b0 = (uint32_t)b, b1 = b >> 32;
    uint64_t p00 = a0 * b0, p01 = a0 * b1, p10 = a1 * b0, p11 = a1 * b1;
    uint64_t mid = (p00 >> 32) + (uint32_t)p01 + (uint32_t)p10;
    *hi = p11 + (p01 >> 32) + (p10 >> 32) + (mid >> 32);
    *lo = (mid << 32) | (uint32_t)p00;
#endif
}

static inline int leading_zeros(uint64_t x)
{
#if defined(__GNUC__)
    return __builtin_clzll(x);
#else
    int n = 0;
    while (!(x & (1ull << 63))) {
        x <<= 1;
        n++;
    }
    return n;
#endif
}

/* Eisel-Lemire: the double nearest to w * 10^q (w != 0, exact), as
 * fast_float computes it; 0 when it cannot tell the rounding cheaply or the
 * result is subnormal, zero or infinite (strtod then decides). */
int mt__eisel_lemire(uint64_t w, int64_t q, int neg, double *out)
{
    if (q < MT__POW5_SMALLEST || q > MT__POW5_LARGEST) return 0;
    int lz = leading_zeros(w);
    w <<= lz;
    const uint64_t *p5 = mt__pow5_128[q - MT__POW5_SMALLEST];
    uint64_t hi, lo;
    mul_64x64(w, p5[0], &hi, &lo);
    if ((hi & 0x1ff) == 0x1ff) { /* the low bits may carry: add the next 64 bits */
        uint64_t hi2, lo2;
        mul_64x64(w, p5[1], &hi2, &lo2);
        lo += hi2;
        if (hi2 > lo) hi++;
    }
    /* An approximation this close to a carry is left to strtod outside the
     * exponents where the table's values are exact (5^q < 2^128, or a
     * reciprocal of 5^-q < 2^64). */
    if (lo == UINT64_MAX && (q < -27 || q > 55)) return 0;
    int upperbit = (int)(hi >> 63);
    int shift = upperbit + 64 - 52 - 3;
    uint64_t mantissa = hi >> shift;
    /* floor(log2(10^q)) + 63 by a fixed-point multiplication, floor division */
    int64_t t = (152170 + 65536) * q;
    int64_t log2_10q = t >= 0 ? t / 65536 : -((-t + 65535) / 65536);
    int64_t power2 = log2_10q + 63 + upperbit - lz + 1023;
    if (power2 <= 0) return 0; /* subnormal or zero */
    /* Exactly halfway between two doubles: round to even. */
    if (lo <= 1 && q >= -4 && q <= 23 && (mantissa & 3) == 1 && (mantissa << shift) == hi)
        mantissa &= ~1ull;
    mantissa += mantissa & 1;
    mantissa >>= 1;
    if (mantissa >= (2ull << 52)) {
        mantissa = 1ull << 52;
        power2++;
    }
    mantissa &= ~(1ull << 52);
    if (power2 >= 0x7ff) return 0; /* infinite */
    uint64_t bits = mantissa | (uint64_t)power2 << 52 | (uint64_t)(neg != 0) << 63;
    memcpy(out, &bits, sizeof bits);
    return 1;
}

/* The digits of a decimal with more than 19 of them, one at a time: the
 * first 19 significant ones make the significand, and the value is exact
 * (*exact set) when every later one is 0. Returns past the digits, with
 * *digits counted. */
static const unsigned char *scan_long_digits(const unsigned char *p, const unsigned char *end,
                                             uint64_t *out_mant, int64_t *exp10, int *exact,
                                             int *digits)
{
    uint64_t mant = 0;
    int sig = 0;
    for (; p < end && (unsigned)*p - '0' <= 9; p++) {
        unsigned d = (unsigned)*p - '0';
        ++*digits;
        if (mant == 0 && d == 0) continue;
        if (sig < 19) {
            mant = mant * 10 + d;
            sig++;
        } else {
            ++*exp10;
            if (d) *exact = 0;
        }
    }
    if (p < end && *p == '.') {
        for (p++; p < end && (unsigned)*p - '0' <= 9; p++) {
            unsigned d = (unsigned)*p - '0';
            ++*digits;
            if (mant == 0 && d == 0) {
                --*exp10;
                continue;
            }
            if (sig < 19) {
                mant = mant * 10 + d;
                sig++;
                --*exp10;
            } else if (d) {
                *exact = 0;
            }
        }
    }
    *out_mant = mant;
    return p;
}

size_t mt__scan_decimal(const unsigned char *s, const unsigned char *end, double *out)
{
#if FLT_EVAL_METHOD == 0
    const unsigned char *p = s;
    int neg = 0;
    if (p < end && (*p == '-' || *p == '+')) neg = *p++ == '-';
    const unsigned char *first = p;
    /* Every digit into a 64-bit significand (leading zeros add nothing),
     * eight at a time where the platform allows; exact up to 19
     * significant digits, else read again one at a time. */
    uint64_t mant = 0;
    while (p < end && (unsigned)*p - '0' <= 9) mant = mant * 10 + (uint64_t)(*p++ - '0');
    int digits = (int)(p - first);
    int64_t exp10 = 0;
    if (p < end && *p == '.') {
        const unsigned char *frac = ++p;
        while (end - p >= 8) {
            uint64_t chunk = mt__load8(p);
            if (!mt__is_8digits(chunk)) break;
            mant = mant * 100000000 + mt__parse_8digits(chunk);
            p += 8;
        }
        while (p < end && (unsigned)*p - '0' <= 9) mant = mant * 10 + (uint64_t)(*p++ - '0');
        digits += (int)(p - frac);
        exp10 = -(int64_t)(p - frac);
    }
    if (digits == 0) return 0;
    int exact = 1;
    if (digits > 19) {
        int zeros = 0;
        for (const unsigned char *z = first; z < p && (*z == '0' || *z == '.'); z++)
            zeros += *z == '0';
        if (digits - zeros > 19) {
            exp10 = 0;
            digits = 0;
            p = scan_long_digits(first, end, &mant, &exp10, &exact, &digits);
        }
    }
    if (p < end && (*p == 'e' || *p == 'E')) {
        const unsigned char *q = p + 1;
        int eneg = 0;
        if (q < end && (*q == '-' || *q == '+')) eneg = *q++ == '-';
        if (q < end && (unsigned)*q - '0' <= 9) {
            int64_t e = 0;
            for (; q < end && (unsigned)*q - '0' <= 9; q++)
                if (e < 100000) e = e * 10 + (*q - '0');
            exp10 += eneg ? -e : e;
            p = q;
        }
    }
    if (mant == 0) {
        *out = neg ? -0.0 : 0.0;
        return (size_t)(p - s);
    }
    if (!exact) return 0;
    if (mant <= (1ull << 53) && exp10 >= -22 && exp10 <= 22) {
        double v = (double)mant;
        if (exp10 < 0)
            v /= mt__pow10_exact[-exp10];
        else if (exp10 > 0)
            v *= mt__pow10_exact[exp10];
        *out = neg ? -v : v;
        return (size_t)(p - s);
    }
    if (mt__eisel_lemire(mant, exp10, neg, out)) return (size_t)(p - s);
#else
    (void)s;
    (void)end;
    (void)out;
#endif
    return 0;
}

int mt__parse_double(const unsigned char *s, size_t len, double *out)
{
    if (len && mt__scan_decimal(s, s + len, out) == len) return 1;
    return parse_with_strtod(s, len, out);
}

mt__num mt__parse_count(const unsigned char *s, size_t len, uint64_t *out)
{
    const unsigned char *p = s, *end = s + len;
    if (p < end && *p == '+') p++;
    if (p == end) return MT__NUM_BAD;
    uint64_t v = 0;
    int big = 0;
    for (; p < end; p++) {
        unsigned d = (unsigned)*p - '0';
        if (d > 9) return MT__NUM_BAD;
        if (v > (UINT64_MAX - d) / 10)
            big = 1;
        else
            v = v * 10 + d;
    }
    if (big) return MT__NUM_RANGE;
    *out = v;
    return MT__NUM_OK;
}

size_t mt__format_i64(int64_t v, char *buf)
{
    char tmp[24];
    size_t n = 0, o = 0;
    uint64_t u = v < 0 ? (uint64_t)0 - (uint64_t)v : (uint64_t)v;
    do {
        tmp[n++] = (char)('0' + u % 10);
        u /= 10;
    } while (u);
    if (v < 0) buf[o++] = '-';
    while (n) buf[o++] = tmp[--n];
    buf[o] = '\0';
    return o;
}

size_t mt__format_double(double v, char *buf)
{
    if (isnan(v)) {
        memcpy(buf, signbit(v) ? "-nan" : "nan", signbit(v) ? 5 : 4);
        return signbit(v) ? 4 : 3;
    }
    if (isinf(v)) {
        memcpy(buf, v < 0 ? "-inf" : "inf", v < 0 ? 5 : 4);
        return v < 0 ? 4 : 3;
    }
    /* Small integers (the common 0, 1, -2 ...) print exactly as integers. */
    if (fabs(v) < 1e15 && v == (double)(int64_t)v && !(v == 0 && signbit(v)))
        return mt__format_i64((int64_t)v, buf);
    int n = 0;
    for (int precision = 15; precision <= 17; precision++) {
        n = snprintf(buf, 32, "%.*g", precision, v);
        if (precision == 17 || n <= 0) break;
        /* Read it back exactly: the fast exact path, else strtod. */
        double back;
        const unsigned char *text = (const unsigned char *)buf;
        if (mt__scan_decimal(text, text + n, &back) != (size_t)n) back = strtod(buf, NULL);
        if (back == v) break;
    }
    return n > 0 ? (size_t)n : 0;
}

void mt__c_locale_enter(mt__locale_state *state)
{
    state->c_locale = (locale_t)0;
    state->saved = (locale_t)0;
    locale_t c = newlocale(LC_ALL_MASK, "C", (locale_t)0);
    if (c == (locale_t)0) return; /* the process locale is used: C assumed */
    locale_t old = uselocale(c);
    if (old == (locale_t)0) {
        freelocale(c);
        return;
    }
    state->c_locale = c;
    state->saved = old;
}

void mt__c_locale_leave(mt__locale_state *state)
{
    if (!state->c_locale) return;
    uselocale(state->saved);
    freelocale(state->c_locale);
    state->c_locale = (locale_t)0;
}
