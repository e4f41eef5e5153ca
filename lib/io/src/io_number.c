/* Number text of meshtopo::io, read and written. Coordinates: plain decimals
 * with at most 19 significant digits and a small exponent are read exactly
 * (Clinger's fast path: one exact IEEE multiplication or division); anything
 * else goes to strtod. Doubles are written as the shortest of %.15g/%.16g/
 * %.17g that reads back bit for bit; counts are plain digits. All under the C
 * locale, so that '.' is always the decimal point. */
#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "io_internal.h"

static const double pow10_exact[23] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
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

size_t mt__scan_decimal(const unsigned char *s, const unsigned char *end, double *out)
{
#if FLT_EVAL_METHOD == 0
    const unsigned char *p = s;
    int neg = 0;
    if (p < end && (*p == '-' || *p == '+')) neg = *p++ == '-';
    uint64_t mant = 0;
    int sig = 0, digits = 0, exact = 1;
    int64_t exp10 = 0;
    for (; p < end && (unsigned)*p - '0' <= 9; p++) {
        unsigned d = (unsigned)*p - '0';
        digits++;
        if (mant == 0 && d == 0) continue;
        if (sig < 19) {
            mant = mant * 10 + d;
            sig++;
        } else {
            exp10++;
            if (d) exact = 0;
        }
    }
    if (p < end && *p == '.') {
        for (p++; p < end && (unsigned)*p - '0' <= 9; p++) {
            unsigned d = (unsigned)*p - '0';
            digits++;
            if (mant == 0 && d == 0) {
                exp10--;
                continue;
            }
            if (sig < 19) {
                mant = mant * 10 + d;
                sig++;
                exp10--;
            } else if (d) {
                exact = 0;
            }
        }
    }
    if (digits == 0) return 0;
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
    if (exact && mant <= (1ull << 53) && exp10 >= -22 && exp10 <= 22) {
        double v = (double)mant;
        v = exp10 < 0 ? v / pow10_exact[-exp10] : v * pow10_exact[exp10];
        *out = neg ? -v : v;
        return (size_t)(p - s);
    }
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
