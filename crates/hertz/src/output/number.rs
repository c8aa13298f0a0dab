//! Numbers as C's `printf("%.Ne")` writes them, exactly and fast: the hot loop of the output
//! files (a 400 × 200 block's `.out` holds 4 million of them).
//!
//! The fast path scales `|v|` by a power of ten into `[10^N, 10^(N+1))` in one rounded
//! multiplication and rounds that to an integer. The product is within `2^-52` relative of the
//! exact one, so the rounding is the exact value's unless the fraction lies within that error of
//! one half; those values (and ties, subnormals, huge exponents, 15 digits and more) are formatted
//! by the exact decimal expansion of `{:.Ne}`.

use std::sync::OnceLock;

/// C `%.Ne` (exponent with its sign and at least two digits).
pub fn sci(v: f64, prec: usize) -> String {
    let mut s = String::with_capacity(prec + 8);
    push_sci(&mut s, v, prec);
    s
}

/// C `% .Ne` (a space in place of the plus sign).
pub fn sci_sign(v: f64, prec: usize) -> String {
    let mut s = String::with_capacity(prec + 9);
    push_sci_sign(&mut s, v, prec);
    s
}

/// Append C's `% .Ne` of `v` (a space in place of the plus sign).
pub fn push_sci_sign(s: &mut String, v: f64, prec: usize) {
    if !v.is_sign_negative() || v.is_nan() {
        s.push(' ');
    }
    push_sci(s, v, prec);
}

/// Append C's `%.Ne` of `v` to `s`.
pub fn push_sci(s: &mut String, v: f64, prec: usize) {
    if !v.is_finite() {
        s.push_str(if v.is_nan() {
            "nan"
        } else if v > 0.0 {
            "inf"
        } else {
            "-inf"
        });
        return;
    }
    if !push_sci_fast(s, v, prec) {
        push_sci_exact(s, v, prec);
    }
}

/// Most significant digits the fast path writes: at 14 the product's error (`10^14 · 2^-52`,
/// 0.02) still leaves most fractions clear of one half.
const MAX_FAST_DIGITS: usize = 14;
/// Powers of ten in the table: `10^-POW10_SPAN ..= 10^POW10_SPAN`.
const POW10_SPAN: i32 = 310;
/// Magnitudes beyond which the fast path steps aside (the table's reach, and subnormals).
const FAST_RANGE: (f64, f64) = (1e-290, 1e290);

/// `10^n` rounded to the nearest double (as the literal `1eN` parses).
fn pow10(n: i32) -> f64 {
    static TABLE: OnceLock<Vec<f64>> = OnceLock::new();
    let table = TABLE.get_or_init(|| {
        (-POW10_SPAN..=POW10_SPAN)
            .map(|k| format!("1e{k}").parse().expect("a power of ten"))
            .collect()
    });
    table[(n + POW10_SPAN) as usize]
}

/// The fast path; `false` (nothing written) where only the exact expansion can decide.
fn push_sci_fast(s: &mut String, v: f64, prec: usize) -> bool {
    let keep = prec + 1;
    if keep > MAX_FAST_DIGITS {
        return false;
    }
    let a = v.abs();
    let (mantissa, exp) = if a == 0.0 {
        (0, 0)
    } else {
        if !(FAST_RANGE.0..=FAST_RANGE.1).contains(&a) {
            return false;
        }
        // a ∈ [2^e2, 2^(e2+1)), so its decimal exponent is k or k + 1.
        let e2 = ((a.to_bits() >> 52) as i32) - 1023;
        let k = (f64::from(e2) * std::f64::consts::LOG10_2).floor() as i32;
        let upper = pow10(keep as i32);
        let mut exp = k;
        let mut scaled = a * pow10(keep as i32 - 1 - exp);
        if scaled >= upper {
            exp += 1;
            scaled = a * pow10(keep as i32 - 1 - exp);
        }
        let whole = scaled as u64;
        let frac = scaled - whole as f64;
        if (frac - 0.5).abs() <= upper * 4.5e-16 {
            return false;
        }
        let mut mantissa = whole + u64::from(frac > 0.5);
        if mantissa as f64 >= upper {
            // 9.99..9 rounded up: 1.00..0 with the next exponent.
            mantissa /= 10;
            exp += 1;
        }
        if (mantissa as f64) < pow10(keep as i32 - 1) {
            return false;
        }
        (mantissa, exp)
    };
    // "-d.ddddddddddddde+308": at most 1 + MAX_FAST_DIGITS + 1 + 5 bytes.
    let mut buf = [b'0'; MAX_FAST_DIGITS + 7];
    let mut n = 0;
    if v.is_sign_negative() {
        buf[0] = b'-';
        n = 1;
    }
    let first = n;
    n += keep + usize::from(keep > 1);
    let mut m = mantissa;
    for at in (first + 1..n).rev() {
        if at == first + 1 {
            buf[at] = b'.';
        } else {
            buf[at] = b'0' + (m % 10) as u8;
            m /= 10;
        }
    }
    buf[first] = b'0' + m as u8;
    buf[n] = b'e';
    buf[n + 1] = if exp < 0 { b'-' } else { b'+' };
    let e = exp.unsigned_abs();
    n += 2;
    if e >= 100 {
        buf[n] = b'0' + (e / 100) as u8;
        n += 1;
    }
    buf[n] = b'0' + (e / 10 % 10) as u8;
    buf[n + 1] = b'0' + (e % 10) as u8;
    s.push_str(std::str::from_utf8(&buf[..n + 2]).expect("ASCII"));
    true
}

/// The exact decimal expansion rounded to `prec` places, with C's exponent.
fn push_sci_exact(s: &mut String, v: f64, prec: usize) {
    use std::fmt::Write as _;
    let start = s.len();
    let _ = write!(s, "{v:.prec$e}");
    let at = start + s[start..].rfind('e').expect("exponent");
    let e: i32 = s[at + 1..].parse().expect("integer exponent");
    s.truncate(at + 1);
    push_exponent(s, e);
}

/// `+05`, `-12`, `+100`: the sign and at least two digits, as C prints exponents.
fn push_exponent(s: &mut String, e: i32) {
    s.push(if e < 0 { '-' } else { '+' });
    let e = e.unsigned_abs();
    if e >= 100 {
        s.push(char::from(b'0' + (e / 100) as u8));
    }
    s.push(char::from(b'0' + (e / 10 % 10) as u8));
    s.push(char::from(b'0' + (e % 10) as u8));
}

#[cfg(test)]
mod tests {
    #[test]
    fn sci_matches_c_printf() {
        assert_eq!(super::sci(-1.5625, 8), "-1.56250000e+00");
        assert_eq!(super::sci(4.975e6, 4), "4.9750e+06");
        assert_eq!(super::sci(1.2e-12, 4), "1.2000e-12");
        assert_eq!(super::sci(f64::NAN, 4), "nan");
        assert_eq!(super::sci(f64::NEG_INFINITY, 4), "-inf");
        assert_eq!(super::sci_sign(2.5, 2), " 2.50e+00");
        assert_eq!(super::sci_sign(-0.0, 2), "-0.00e+00");
        assert_eq!(super::sci_sign(f64::NAN, 2), " nan");
        assert_eq!(super::sci(1e100, 1), "1.0e+100");
        assert_eq!(super::sci(9.99995, 4), "1.0000e+01");
        assert_eq!(super::sci(0.0, 4), "0.0000e+00");
    }

    /// The fast formatter agrees with exact rounding (Rust's `{:.Ne}`, as C's printf) on values
    /// of every magnitude, on decimal ties, at powers of ten and on carries.
    #[test]
    fn fast_sci_equals_exact_rounding() {
        let exact = |v: f64, prec: usize| {
            let t = format!("{v:.prec$e}");
            let (m, e) = t.split_once('e').unwrap();
            let e: i32 = e.parse().unwrap();
            format!("{m}e{}{:02}", if e < 0 { '-' } else { '+' }, e.abs())
        };
        let mut x: u64 = 0x9E37_79B9_7F4A_7C15;
        let mut values = vec![
            0.5,
            1.5,
            2.5,
            1.23455,
            1.234_45,
            0.000_125,
            5e-324,
            f64::MAX,
            -0.0,
        ];
        for _ in 0..200_000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let v = f64::from_bits(x);
            if v.is_finite() {
                values.push(v);
            }
            // Short decimals, where ties of the shortest digits happen.
            values.push((x % 2_000_001) as f64 / 10f64.powi((x % 9) as i32) - 100.0);
        }
        // Around powers of ten (where the decimal exponent changes) and their roundings up.
        for k in -300..=300 {
            let p: f64 = format!("1e{k}").parse().unwrap();
            for q in [p, p * (1.0 - 5e-5), p * (1.0 - 5e-9), p * (1.0 - 5e-13)] {
                values.extend([
                    q,
                    f64::from_bits(q.to_bits() + 1),
                    f64::from_bits(q.to_bits() - 1),
                ]);
            }
        }
        for v in values {
            for prec in [0, 2, 3, 4, 8, 12, 13, 14] {
                assert_eq!(super::sci(v, prec), exact(v, prec), "{v:e} at {prec}");
            }
        }
    }
}
