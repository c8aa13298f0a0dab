//! The OOFEM-style `.out` text file (spec §4): per step the DOF values of the selected nodes, the
//! integration-point strains and stresses (or F and P for `nlgeo 1`), and the reaction table.

use crate::assembly::DofMap;
use crate::model::{AnalysisKind, DofId, Model};
use crate::solve::StepResult;
use std::fmt::Write;

/// Header written once at the top.
pub fn header(model: &Model) -> String {
    format!(
        "\n############################################################## www.oofem.org ###\n\
         #### hertz {} (OOFEM-compatible output)\n\
         ##################################################################################\n\n\
         Starting analysis on: {}\n{}\n",
        env!("CARGO_PKG_VERSION"),
        timestamp(),
        model.description
    )
}

/// Footer written once at the end.
pub fn footer(total_seconds: f64) -> String {
    format!(
        "\nFinishing analysis on: {}\n\nReal time consumed: {:.3} [s]\n",
        timestamp(),
        total_seconds
    )
}

/// The date as C's `ctime` writes it (OOFEM's header), in UTC: `Sun Nov 22 18:10:12 2026`.
fn timestamp() -> String {
    let secs = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map(|d| d.as_secs())
        .unwrap_or(0);
    ctime_utc(secs)
}

/// `ctime` of `secs` since the Unix epoch, in UTC (days to civil date: H. Hinnant's algorithm).
pub fn ctime_utc(secs: u64) -> String {
    const DAYS: [&str; 7] = ["Thu", "Fri", "Sat", "Sun", "Mon", "Tue", "Wed"];
    const MONTHS: [&str; 12] = [
        "Jan", "Feb", "Mar", "Apr", "May", "Jun", "Jul", "Aug", "Sep", "Oct", "Nov", "Dec",
    ];
    let days = (secs / 86_400) as i64;
    let rem = secs % 86_400;
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let day = doy - (153 * mp + 2) / 5 + 1;
    let month = if mp < 10 { mp + 3 } else { mp - 9 };
    let year = yoe + era * 400 + i64::from(month <= 2);
    format!(
        "{} {} {:2} {:02}:{:02}:{:02} {year}",
        DAYS[days.rem_euclid(7) as usize],
        MONTHS[month as usize - 1],
        day,
        rem / 3600,
        rem / 60 % 60,
        rem % 60
    )
}

/// The block of one step.
pub fn step_block(model: &Model, res: &StepResult) -> String {
    let mut s = String::new();
    match model.analysis.kind {
        AnalysisKind::NonLinearStatic => {
            let _ = write!(
                s,
                "\n\nOutput for time {}, solution step number {}\nReached load level : {:20.6} in {} iterations\n\n",
                sci(res.time, 3), res.step, 1.0, res.info.iterations
            );
        }
        _ => {
            let _ = write!(
                s,
                "\n==============================================================\nOutput for time {} \n\
                 ==============================================================\nOutput for domain   1\n",
                sci(res.time, 8)
            );
        }
    }
    s.push_str("\n\nDofManager output:\n------------------\n");
    s.push_str(&par_blocks(model.nodes.len(), |n, s| {
        node_block(model, res, n, s)
    }));
    s.push_str("\n\nElement output:\n---------------\n");
    s.push_str(&par_blocks(model.elements.len(), |e, s| {
        element_block(model, res, e, s)
    }));
    s.push_str("\n\n\tR E A C T I O N S  O U T P U T:\n\t_______________________________\n\n\n");
    let mut rows: Vec<(usize, u8, usize, f64)> = res
        .dofs
        .prescribed
        .iter()
        .zip(res.reactions)
        .filter(|((n, _, _), _)| model.output.node(n + 1))
        .map(|(&(n, d, bi), &r)| (n, d, model.dirichlet[bi].number, r))
        .collect();
    rows.sort_by_key(|r| (r.0, r.1));
    for (n, d, bc, r) in rows {
        let _ = writeln!(
            s,
            "\tNode {:8} iDof {:2} reaction {}    [bc-id: {}]",
            model.nodes[n].label,
            d,
            sci_sign(r, 4),
            bc
        );
    }
    if !res.contact.is_empty() {
        s.push_str(&contact_table(model, res));
    }
    let _ = write!(
        s,
        "\nUser time consumed by solution step {}: {:.3} [s]\n\n",
        res.step, res.info.wall_seconds
    );
    s
}

/// The blocks of items 0..n concatenated in order, formatted in parallel chunks.
fn par_blocks(n: usize, block: impl Fn(usize, &mut String) + Sync) -> String {
    use rayon::prelude::*;
    const CHUNK: usize = 2048;
    let parts: Vec<String> = (0..n.div_ceil(CHUNK))
        .into_par_iter()
        .map(|c| {
            let mut s = String::new();
            for i in c * CHUNK..((c + 1) * CHUNK).min(n) {
                block(i, &mut s);
            }
            s
        })
        .collect();
    parts.concat()
}

/// One node's DOF values (if the output manager selects it).
fn node_block(model: &Model, res: &StepResult, n: usize, s: &mut String) {
    if !model.output.node(n + 1) {
        return;
    }
    let node = &model.nodes[n];
    let class = if node.slave.is_some() {
        "SlaveNode"
    } else {
        "Node"
    };
    let _ = writeln!(s, "{:<8}{:8} ({:8}):", class, node.label, n + 1);
    for &(d, code) in &res.dofs.node_dofs[n] {
        let _ = write!(s, "  dof {d}   d ");
        push_sci_sign(s, res.dofs.value(res.u, code), 8);
        s.push('\n');
    }
}

/// One element's integration-point strains and stresses (F and P with `nlgeo 1`).
fn element_block(model: &Model, res: &StepResult, e: usize, s: &mut String) {
    if !model.output.element(e + 1) {
        return;
    }
    let el = &model.elements[e];
    let _ = writeln!(s, "element {} ({:8}) :", el.label, e + 1);
    for (g, st) in res.states[e].iter().enumerate() {
        let _ = write!(s, "  GP {:2}.{:<2} :", 1, g + 1);
        let values = |s: &mut String, v: &mut dyn Iterator<Item = f64>| {
            for x in v {
                s.push(' ');
                push_sci(s, x, 4);
            }
        };
        if el.nlgeo {
            const ORDER: [(usize, usize); 9] = [
                (0, 0),
                (1, 1),
                (2, 2),
                (1, 2),
                (0, 2),
                (0, 1),
                (2, 1),
                (2, 0),
                (1, 0),
            ];
            s.push_str("  F ");
            values(s, &mut ORDER.iter().map(|&(i, j)| st.f[i][j]));
            s.push_str("\n  P");
            values(s, &mut ORDER.iter().map(|&(i, j)| st.p[i][j]));
        } else {
            s.push_str("  strains ");
            values(s, &mut st.strain.iter().copied());
            s.push_str("\n              stresses");
            values(s, &mut st.stress.iter().copied());
        }
        s.push('\n');
    }
}

/// The contact table of a step: one row per contact node.
fn contact_table(model: &Model, res: &StepResult) -> String {
    let mut s =
        String::from("\n\n\tC O N T A C T   O U T P U T:\n\t___________________________\n\n");
    s.push_str("\tcondition     node          gap         force      pressure  active\n");
    for c in res.contact {
        let _ = writeln!(
            s,
            "\t{:9} {:8} {} {} {} {:>7}",
            c.condition,
            model.nodes[c.node].label,
            sci_sign(c.gap, 4),
            sci_sign(c.force, 4),
            sci_sign(c.pressure, 4),
            if c.active { "yes" } else { "no" }
        );
    }
    s
}

/// The `.contact.csv` header (one row per contact node and step).
pub const CONTACT_CSV_HEADER: &str = "step,condition,node,x,y,z,gap,force,pressure,active";

/// CSV rows of one step's contact states.
pub fn contact_csv_rows(model: &Model, res: &StepResult) -> String {
    let mut s = String::new();
    for c in res.contact {
        let _ = writeln!(
            s,
            "{},{},{},{:e},{:e},{:e},{:e},{:e},{:e},{}",
            res.step,
            c.condition,
            model.nodes[c.node].label,
            c.x[0],
            c.x[1],
            c.x[2],
            c.gap,
            c.force,
            c.pressure,
            u8::from(c.active)
        );
    }
    s
}

/// Columns of the per-step history CSV: the step, its Newton effort, and for every DOF a
/// `BoundaryCondition` prescribes, the mean prescribed value and the summed reaction.
pub fn history_csv_header(model: &Model, dofs: &DofMap) -> String {
    let mut s = String::from("step,time,iterations,substeps,residual");
    for (bc, d) in prescribed_groups(dofs) {
        let n = model.dirichlet[bc].number;
        let _ = write!(s, ",bc{n}.u{d},bc{n}.r{d}");
    }
    s.push('\n');
    s
}

/// The (Dirichlet index, DOF id) pairs of the prescribed DOFs, in first-seen order.
fn prescribed_groups(dofs: &DofMap) -> Vec<(usize, DofId)> {
    let mut groups = Vec::new();
    for &(_, d, bc) in &dofs.prescribed {
        if !groups.contains(&(bc, d)) {
            groups.push((bc, d));
        }
    }
    groups
}

/// One row of the history CSV (see [`history_csv_header`]).
pub fn history_csv_row(res: &StepResult) -> String {
    let info = res.info;
    let mut s = format!(
        "{},{:e},{},{},{:e}",
        res.step,
        res.time,
        info.iterations,
        info.substeps,
        info.residual_history.last().copied().unwrap_or(0.0)
    );
    let nf = res.dofs.n_free;
    for (bc, d) in prescribed_groups(res.dofs) {
        let (mut u, mut r, mut n) = (0.0, 0.0, 0usize);
        for (i, &(_, di, bi)) in res.dofs.prescribed.iter().enumerate() {
            if (bi, di) == (bc, d) {
                u += res.u[nf + i];
                r += res.reactions[i];
                n += 1;
            }
        }
        let _ = write!(s, ",{:e},{:e}", u / n as f64, r);
    }
    s.push('\n');
    s
}

/// Header of the Newton residual CSV.
pub const NEWTON_CSV_HEADER: &str = "step,iteration,residual";

/// Rows of the Newton residual CSV: the step's residual history, iteration 0 first.
pub fn newton_csv_rows(res: &StepResult) -> String {
    let mut s = String::new();
    for (k, r) in res.info.residual_history.iter().enumerate() {
        let _ = writeln!(s, "{},{k},{r:e}", res.step);
    }
    s
}

/// C `%.Ne` formatting (exponent with sign and at least two digits).
pub fn sci(v: f64, prec: usize) -> String {
    let mut s = String::with_capacity(prec + 8);
    push_sci(&mut s, v, prec);
    s
}

/// Append C's `%.Ne` of `v` to `s` (the output files' hot loop).
///
/// Fast and exact: the shortest round-trip digits of `v` (`{:e}`) rounded to N + 1 digits give
/// what rounding the exact binary value gives, except when the dropped digits are exactly `5`
/// (a tie between the shortest digits and the value): then the exact `{:.Ne}` decides. (Were a
/// shorter midpoint strictly between `v` and its shortest digits, it would be shorter still.)
pub fn push_sci(s: &mut String, v: f64, prec: usize) {
    use std::fmt::Write as _;
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
    // Shortest digits: "-d.ddde-x" -> sign, digits, exponent.
    let mut buf = ShortBuf::default();
    let _ = write!(buf, "{v:e}");
    let text = buf.as_str();
    let (mantissa, exp) = text.split_once('e').expect("exponent");
    let mut exp: i32 = exp.parse().expect("integer exponent");
    let negative = mantissa.starts_with('-');
    let mut digits = [b'0'; 24];
    let mut n = 0;
    for b in mantissa.bytes().filter(u8::is_ascii_digit) {
        digits[n] = b;
        n += 1;
    }
    let keep = prec + 1;
    // The argument needs the double's spacing far below the last printed digit: not so for
    // subnormals or for 16 digits and more.
    let exact_only = keep >= 16 || (v != 0.0 && v.abs() < f64::MIN_POSITIVE);
    if exact_only || n > keep {
        let dropped = &digits[keep.min(n)..n];
        if exact_only || dropped == b"5" {
            // A tie in the shortest digits: only the exact value can break it.
            let start = s.len();
            let _ = write!(s, "{v:.prec$e}");
            let at = start + s[start..].rfind('e').expect("exponent");
            let e: i32 = s[at + 1..].parse().expect("integer exponent");
            s.truncate(at + 1);
            push_exponent(s, e);
            return;
        }
        if dropped[0] >= b'5' {
            let mut i = keep;
            loop {
                if i == 0 {
                    // 9.99..9 rounded up: 1.00..0 with the next exponent.
                    digits[0] = b'1';
                    digits[1..keep].fill(b'0');
                    exp += 1;
                    break;
                }
                i -= 1;
                if digits[i] == b'9' {
                    digits[i] = b'0';
                } else {
                    digits[i] += 1;
                    break;
                }
            }
        }
    } else {
        digits[n..keep].fill(b'0');
    }
    if negative {
        s.push('-');
    }
    s.push(digits[0] as char);
    if keep > 1 {
        s.push('.');
        s.push_str(std::str::from_utf8(&digits[1..keep]).expect("ASCII digits"));
    }
    s.push('e');
    push_exponent(s, exp);
}

/// `+05`, `-12`, `+100`: the sign and at least two digits, as C prints exponents.
fn push_exponent(s: &mut String, e: i32) {
    use std::fmt::Write as _;
    s.push(if e < 0 { '-' } else { '+' });
    let e = e.unsigned_abs();
    if e < 10 {
        s.push('0');
    }
    let _ = write!(s, "{e}");
}

/// A stack buffer for one shortest float (at most 24 bytes: "-1.2345678901234567e-308").
#[derive(Default)]
struct ShortBuf {
    bytes: [u8; 32],
    len: usize,
}

impl ShortBuf {
    fn as_str(&self) -> &str {
        std::str::from_utf8(&self.bytes[..self.len]).expect("formatted text")
    }
}

impl std::fmt::Write for ShortBuf {
    fn write_str(&mut self, t: &str) -> std::fmt::Result {
        let end = self.len + t.len();
        if end > self.bytes.len() {
            return Err(std::fmt::Error);
        }
        self.bytes[self.len..end].copy_from_slice(t.as_bytes());
        self.len = end;
        Ok(())
    }
}

/// Append C's `% .Ne` of `v` (a space in place of the plus sign).
pub fn push_sci_sign(s: &mut String, v: f64, prec: usize) {
    if !v.is_sign_negative() || v.is_nan() {
        s.push(' ');
    }
    push_sci(s, v, prec);
}

/// C `% .Ne` (a space in place of the plus sign).
pub fn sci_sign(v: f64, prec: usize) -> String {
    let mut s = String::with_capacity(prec + 9);
    push_sci_sign(&mut s, v, prec);
    s
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
    /// of every magnitude, on ties of the shortest digits and on carries.
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
        for v in values {
            for prec in [0, 2, 3, 4, 8] {
                assert_eq!(super::sci(v, prec), exact(v, prec), "{v:e} at {prec}");
            }
        }
    }

    /// Dates as `date -u -d @SECS '+%a %b %e %T %Y'` prints them (C's ctime layout).
    #[test]
    fn ctime_matches_the_c_library() {
        assert_eq!(super::ctime_utc(0), "Thu Jan  1 00:00:00 1970");
        assert_eq!(super::ctime_utc(951_782_400), "Tue Feb 29 00:00:00 2000");
        assert_eq!(super::ctime_utc(1_795_370_501), "Sun Nov 22 18:01:41 2026");
        assert_eq!(super::ctime_utc(4_107_542_399), "Sun Feb 28 23:59:59 2100");
    }
}
