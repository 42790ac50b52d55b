//! Number parsing for ASCII STL.
//!
//! Why a hand-written fast path: `str::parse::<f64>` is correct but costs a UTF-8 check and a
//! general algorithm per coordinate, and ASCII STL is mostly coordinates. STL writers print
//! plain decimals (`-12.5`, `1.234567e+01`) whose digits fit in 2^53 and whose decimal exponent
//! is at most 22; for those, one IEEE multiplication or division of two exact values is the
//! correctly rounded result, i.e. exactly what `str::parse` returns. Everything else (long
//! mantissas, big exponents, `nan`, `inf`, garbage) goes to `str::parse`.

/// Exact powers of ten representable in an f64.
const POW10: [f64; 23] = [
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20,
    1e21, 1e22,
];

/// Largest mantissa the fast path accepts (every integer up to it is exact in an f64).
const MAX_EXACT: u64 = 1 << 53;

/// Parses a number token; `None` when it is not a number `str::parse::<f64>` accepts.
pub(super) fn parse_f64(token: &[u8]) -> Option<f64> {
    match fast(token) {
        Some(value) => Some(value),
        None => std::str::from_utf8(token).ok()?.parse().ok(),
    }
}

/// Appends the decimal digits at `token[*i..]` to `mantissa`, returning how many there were;
/// `None` when the mantissa would need more than 19 digits (the caller falls back to std).
fn take_digits(token: &[u8], i: &mut usize, mantissa: &mut u64, digits: &mut u32) -> Option<u32> {
    let start = *digits;
    while let Some(&b) = token.get(*i) {
        let d = b.wrapping_sub(b'0');
        if d > 9 {
            break;
        }
        if *digits == 19 {
            return None;
        }
        *mantissa = *mantissa * 10 + u64::from(d);
        *digits += 1;
        *i += 1;
    }
    Some(*digits - start)
}

/// The fast path: `[+-]digits[.digits][(e|E)[+-]digits]` with a small mantissa and exponent.
fn fast(token: &[u8]) -> Option<f64> {
    let mut i = 0;
    let negative = match token.first()? {
        b'-' => {
            i = 1;
            true
        }
        b'+' => {
            i = 1;
            false
        }
        _ => false,
    };
    let mut mantissa: u64 = 0;
    let mut digits = 0u32;
    take_digits(token, &mut i, &mut mantissa, &mut digits)?;
    let mut exponent: i32 = 0;
    if token.get(i) == Some(&b'.') {
        i += 1;
        exponent = -(take_digits(token, &mut i, &mut mantissa, &mut digits)? as i32);
    }
    if digits == 0 {
        return None;
    }
    if let Some(&b) = token.get(i)
        && b | 0x20 == b'e'
    {
        i += 1;
        let negative_exponent = match token.get(i) {
            Some(b'-') => {
                i += 1;
                true
            }
            Some(b'+') => {
                i += 1;
                false
            }
            _ => false,
        };
        let mut value: i32 = 0;
        let start = i;
        while let Some(&b) = token.get(i) {
            let d = b.wrapping_sub(b'0');
            if d > 9 || i - start == 4 {
                break;
            }
            value = value * 10 + i32::from(d);
            i += 1;
        }
        if i == start {
            return None;
        }
        exponent += if negative_exponent { -value } else { value };
    }
    if i != token.len() || mantissa > MAX_EXACT {
        return None;
    }
    let m = mantissa as f64;
    let magnitude = if exponent >= 0 {
        m * *POW10.get(usize::try_from(exponent).ok()?)?
    } else {
        m / *POW10.get(usize::try_from(-exponent).ok()?)?
    };
    Some(if negative { -magnitude } else { magnitude })
}

#[cfg(test)]
mod tests {
    use super::parse_f64;

    fn std_parse(s: &str) -> Option<f64> {
        s.parse().ok()
    }

    #[test]
    fn agrees_with_std_on_typical_and_odd_tokens() {
        let cases = [
            "0",
            "-0",
            "+0",
            "1",
            "-1",
            "0.5",
            ".5",
            "5.",
            "1.5e+01",
            "1E-3",
            "1e22",
            "1e23",
            "-12.345678",
            "1.234567e+01",
            "9007199254740993",
            "123456789012345678901",
            "0.000000000000000000000000001",
            "1e-400",
            "1e400",
            "nan",
            "NaN",
            "inf",
            "-inf",
            "infinity",
            "",
            "-",
            "+",
            ".",
            "e5",
            "1e",
            "1e+",
            "1.2.3",
            "0x10",
            "1,5",
            "blah",
            "1e99999",
            "00000000000000000001",
            "3.14159265358979323846",
        ];
        for c in cases {
            let ours = parse_f64(c.as_bytes());
            let theirs = std_parse(c);
            match (ours, theirs) {
                (Some(a), Some(b)) if a.is_nan() && b.is_nan() => {}
                (Some(a), Some(b)) => assert_eq!(a.to_bits(), b.to_bits(), "{c}"),
                (a, b) => assert_eq!(a, b, "{c}"),
            }
        }
    }

    #[test]
    fn agrees_with_std_on_generated_decimals() {
        // A small deterministic generator (xorshift) keeps this test free of dependencies.
        let mut state: u64 = 0x9E37_79B9_7F4A_7C15;
        for _ in 0..200_000 {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            let int = state % 100_000;
            let frac = (state >> 20) % 1_000_000;
            let exp = ((state >> 40) % 61) as i32 - 30;
            let sign = if state & 1 == 0 { "" } else { "-" };
            for s in [
                format!("{sign}{int}.{frac:06}"),
                format!("{sign}{int}.{frac}e{exp}"),
                format!("{sign}{}E{exp:+}", f64::from_bits(state >> 2)),
            ] {
                let theirs = std_parse(&s);
                let ours = parse_f64(s.as_bytes());
                match (ours, theirs) {
                    (Some(a), Some(b)) if a.is_nan() && b.is_nan() => {}
                    (Some(a), Some(b)) => assert_eq!(a.to_bits(), b.to_bits(), "{s}"),
                    (a, b) => assert_eq!(a, b, "{s}"),
                }
            }
        }
    }
}
